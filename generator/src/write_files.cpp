#include "write_files.hpp"

#include "arguments.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

namespace penumbra_gen {
namespace fs = std::filesystem;

std::string write_files(const std::string& dir, const std::vector<OutputFile>& files) {
    const std::string shown = printable(dir);
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        return "--out: '" + shown + "' exists and is not a directory; allowed: a directory or a new path";
    fs::create_directories(dir, ec);
    if (ec) return "--out: cannot create directory '" + shown + "': " + ec.message();

    // Every file to a temporary name first; on any failure remove the temporaries and stop.
    const std::string suffix = ".tmp-" + std::to_string(::getpid());
    std::vector<fs::path> written;
    auto abandon = [&](const std::string& message) {
        for (const fs::path& temp : written) fs::remove(temp, ec);
        return message;
    };
    for (const OutputFile& file : files) {
        const fs::path temp = fs::path(dir) / ("." + file.name + suffix);
        std::ofstream out(temp, std::ios::binary | std::ios::trunc);
        if (!out)
            return abandon("--out: cannot write '" + printable(temp.string()) + "': " + std::strerror(errno));
        written.push_back(temp);
        out.write(file.text.data(), static_cast<std::streamsize>(file.text.size()));
        out.close();
        if (!out) return abandon("--out: cannot write '" + printable(temp.string()) + "'");
    }
    // Then rename them into place; layout.json last when it is last in `files` (the manifest).
    for (std::size_t i = 0; i < files.size(); ++i) {
        fs::rename(written[i], fs::path(dir) / files[i].name, ec);
        if (ec) {
            written.erase(written.begin(), written.begin() + static_cast<std::ptrdiff_t>(i));
            return abandon("--out: cannot rename into '" +
                           printable((fs::path(dir) / files[i].name).string()) + "': " + ec.message());
        }
    }
    return {};
}

} // namespace penumbra_gen
