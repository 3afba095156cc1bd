#include "shader_folder.hpp"

#include <penumbra_tools/bounded_read.hpp>
#include <penumbra_tools/file_transaction.hpp>

#include <algorithm>
#include <functional>
#include <system_error>

namespace penumbra::playground {

namespace {

std::size_t text_hash(const std::string& text) { return std::hash<std::string>{}(text); }

// A watched file's text, read only when it is a regular file within the limit (an editor or a
// stray `cp /dev/zero` must not make the playground read gigabytes).
penumbra_gen::BoundedRead read_text(const std::filesystem::path& path) {
    return penumbra_gen::read_bounded_file(path.string(), penumbra_gen::shader_file_limit);
}

} // namespace

ShaderFolder::ShaderFolder(std::filesystem::path directory, Clock::duration debounce)
    : directory_(std::move(directory)), debounce_(debounce) {}

std::string ShaderFolder::write_file(const std::string& file_name, const std::string& text) {
    const std::filesystem::path target = path(file_name);
    if (std::string e = penumbra_gen::write_file_atomically(target, text); !e.empty()) return e;
    Entry& entry = files_[file_name];
    std::error_code ec;
    entry.seen_time = std::filesystem::last_write_time(target, ec);
    entry.seen_size = std::filesystem::file_size(target, ec);
    entry.reported_hash = text_hash(text);
    entry.pending = false;
    return {};
}

std::string ShaderFolder::write_generated(const std::vector<ShaderFile>& files) {
    std::error_code ec;
    std::filesystem::create_directories(directory_, ec);
    if (ec) return "cannot create " + directory_.string() + ": " + ec.message();
    std::map<std::string, Entry> previous = std::move(files_);
    files_.clear();
    for (const ShaderFile& file : files) {
        files_[file.file_name].generated = file.text;
        if (std::string e = write_file(file.file_name, file.text); !e.empty()) return e;
        previous.erase(file.file_name);
    }
    // Stale files of the previous configuration (another filter writes other passes): remove
    // them so that nobody edits a file that no longer does anything.
    for (const auto& [name, entry] : previous) std::filesystem::remove(path(name), ec);
    return {};
}

std::string ShaderFolder::restore(const std::string& file_name) {
    auto it = files_.find(file_name);
    if (it == files_.end()) return "no generated file " + file_name;
    // poll() sees the save like any other.
    return penumbra_gen::write_file_atomically(path(file_name), it->second.generated);
}

std::vector<std::string> ShaderFolder::hand_edited() const {
    std::vector<std::string> out;
    for (const auto& [name, entry] : files_) {
        const penumbra_gen::BoundedRead read = read_text(path(name));
        const bool missing = !read.text && read.problem == "no such file";
        if (!missing && (!read.text || *read.text != entry.generated)) out.push_back(name);
    }
    return out;
}

std::vector<ShaderFolder::Change> ShaderFolder::poll(Clock::time_point now) {
    std::vector<Change> changes;
    for (auto& [name, entry] : files_) {
        const std::filesystem::path file = path(name);
        std::error_code ec;
        const auto time = std::filesystem::last_write_time(file, ec);
        if (ec) continue; // deleted or being replaced: wait for it to come back
        const std::uintmax_t size = std::filesystem::file_size(file, ec);
        if (ec) continue;
        if (time != entry.seen_time || size != entry.seen_size) {
            entry.seen_time = time;
            entry.seen_size = size;
            penumbra_gen::BoundedRead read = read_text(file);
            if (!read.text && read.problem == "no such file") continue; // replaced right now
            // A file that cannot be read (too large, not a regular file) is reported with its
            // problem instead of its text, once per problem.
            std::string text = read.text ? std::move(*read.text) : std::string();
            entry.pending_problem = read.text ? std::string() : std::move(read.problem);
            if (!entry.pending_problem.empty()) text = "\n(unreadable) " + entry.pending_problem;
            // Each save restarts the debounce, so a burst of saves is reported once. The quiet
            // time counts from the save itself (its mtime), not from when this poll noticed it:
            // with slow frames a save that is already old enough is reported at once.
            entry.pending = text_hash(text) != entry.reported_hash;
            const auto age = std::chrono::system_clock::now() - std::chrono::file_clock::to_sys(time);
            entry.pending_since = now - std::clamp(std::chrono::duration_cast<Clock::duration>(age),
                                                   Clock::duration::zero(), debounce_);
            entry.pending_text = std::move(text);
        }
        if (entry.pending && now - entry.pending_since >= debounce_) {
            entry.pending = false;
            entry.reported_hash = text_hash(entry.pending_text);
            const std::string problem = std::move(entry.pending_problem);
            changes.push_back({name, problem.empty() ? std::move(entry.pending_text) : std::string(),
                               std::chrono::time_point_cast<std::chrono::system_clock::duration>(
                                   std::chrono::file_clock::to_sys(entry.seen_time)),
                               problem});
        }
    }
    return changes;
}

bool ShaderFolder::has_pending() const {
    for (const auto& [name, entry] : files_)
        if (entry.pending) return true;
    return false;
}

ShaderFolder::Clock::duration ShaderFolder::time_to_settle(Clock::time_point now) const {
    Clock::duration longest = Clock::duration::zero();
    for (const auto& [name, entry] : files_)
        if (entry.pending) longest = std::max(longest, entry.pending_since + debounce_ - now);
    return longest;
}

} // namespace penumbra::playground
