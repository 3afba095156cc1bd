#include "write_files.hpp"

#include "bounded_read.hpp"
#include "file_transaction.hpp"
#include "printable.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>

namespace penumbra_gen {
namespace fs = std::filesystem;
namespace {

// The files an earlier emission wrote into `dir` that this one does not: the "files" of the
// layout.json there (Penumbra's manifest), plain names only. Anything else in the folder is not
// Penumbra's and stays; so does everything when there is no readable manifest.
std::vector<fs::path> stale_files(const fs::path& dir, const std::vector<OutputFile>& files) {
    std::vector<fs::path> stale;
    const BoundedRead previous = read_bounded_file((dir / "layout.json").string(), 16u << 20);
    if (!previous.text) return stale;
    const nlohmann::json manifest = nlohmann::json::parse(*previous.text, nullptr, /*allow_exceptions=*/false);
    if (!manifest.is_object() || !manifest.contains("config") || !manifest.contains("files") ||
        !manifest["files"].is_array())
        return stale;
    for (const nlohmann::json& entry : manifest["files"]) {
        if (!entry.is_string()) continue;
        const std::string& name = entry.get_ref<const std::string&>();
        const bool plain = !name.empty() && name != "." && name != ".." &&
                           name.find_first_of("/\\") == std::string::npos && name.find('\0') == std::string::npos;
        const bool still_written =
            std::any_of(files.begin(), files.end(), [&](const OutputFile& f) { return f.name == name; });
        if (plain && !still_written && fs::is_regular_file(fs::symlink_status(dir / name))) stale.push_back(dir / name);
    }
    return stale;
}

} // namespace

std::string write_files(const std::string& dir, const std::vector<OutputFile>& files) {
    std::error_code ec;
    const fs::file_status status = fs::status(dir, ec);
    if (fs::exists(status) && !fs::is_directory(status))
        return "--out: '" + printable(dir) + "' exists and is not a directory; allowed: a directory or a new path";
    FileChanges changes;
    for (const OutputFile& file : files) changes.writes.push_back({fs::path(dir) / file.name, file.text});
    changes.removals = stale_files(dir, files);
    changes.create_directories = true;
    if (std::string error = commit(changes); !error.empty()) return "--out: " + error + "; nothing was written";
    return {};
}

} // namespace penumbra_gen
