// playground/src/window/shader_folder.hpp — the watched folder of emitted shader files.
//
// The playground writes every emitted file here; the user edits them in any editor. poll()
// notices a save by modification time and size, confirms it by a content hash (a touch or a
// save of identical text is not a change) and debounces bursts: a file is reported once it has
// been quiet for `debounce`. A file is read only when it is a regular file of at most 1 MiB;
// otherwise the change carries the problem instead of the text. Files are written all or nothing
// (file_transaction.hpp). No GL here: the caller compiles on the render thread.
#pragma once

#include <penumbra/program.hpp>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace penumbra::playground {

class ShaderFolder {
public:
    using Clock = std::chrono::steady_clock;

    struct Change {
        std::string file_name;
        std::string text;
        std::chrono::system_clock::time_point saved_at; // the file's modification time
        std::string problem; // set when the file cannot be read (over 1 MiB, not a regular file); text is empty
    };

    explicit ShaderFolder(std::filesystem::path directory,
                          Clock::duration debounce = std::chrono::milliseconds(100));

    const std::filesystem::path& directory() const { return directory_; }

    // Writes every file (creating the folder) and forgets files of an earlier set that are not
    // part of this one (deleting them from disk). Empty string on success, else what failed.
    std::string write_generated(const std::vector<ShaderFile>& files);

    // Writes one file's generated text back ("restore"); the next poll() reports it as a change
    // when the text on disk differed. Empty string on success.
    std::string restore(const std::string& file_name);

    // Files whose text on disk differs from what was generated: saving a new configuration
    // would overwrite someone's edits.
    std::vector<std::string> hand_edited() const;

    // Changed files whose new text has been stable for the debounce time.
    std::vector<Change> poll(Clock::time_point now = Clock::now());

    // True while a save has been seen but not yet reported (debouncing).
    bool has_pending() const;
    // How long until every pending save has been quiet for the debounce time (zero if none).
    Clock::duration time_to_settle(Clock::time_point now = Clock::now()) const;

    bool contains(const std::string& file_name) const { return files_.count(file_name) != 0; }
    const std::string& generated_text(const std::string& file_name) const {
        return files_.at(file_name).generated;
    }
    std::filesystem::path path(const std::string& file_name) const { return directory_ / file_name; }

private:
    struct Entry {
        std::string generated;
        std::size_t reported_hash = 0;               // content last reported or written by us
        std::filesystem::file_time_type seen_time{}; // last stat seen
        std::uintmax_t seen_size = 0;
        bool pending = false; // changed, waiting for the debounce
        Clock::time_point pending_since{};
        std::string pending_text;
        std::string pending_problem; // why the pending file cannot be read, when it cannot
    };

    std::string write_file(const std::string& file_name, const std::string& text);

    std::filesystem::path directory_;
    Clock::duration debounce_;
    std::map<std::string, Entry> files_;
};

} // namespace penumbra::playground
