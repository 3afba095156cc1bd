// file_transaction.hpp — output files written all or nothing: the one file writer of both tools
// (penumbra-gen's output directory; the playground's PNG, PFM and JSON files, its screenshots and
// its watched shader folder).
//
// Every file is first written to a temporary name next to its destination (so in the same file
// system), every write and the close checked; only when all are complete are they renamed into
// place. If anything fails — a full disk, a destination that is a directory, a file another user
// owns in a sticky directory — every file already renamed is rolled back (a file that existed
// before gets its previous version back), the temporaries are removed, the directories this call
// created are removed again, and the message names the real destination and the system's reason,
// never a temporary name.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace penumbra_gen {

struct FileWrite {
    std::filesystem::path path; // the destination
    std::string bytes;
};

struct FileChanges {
    std::vector<FileWrite> writes;
    std::vector<std::filesystem::path> removals; // files to delete in the same transaction (missing: ignored)
    bool create_directories = false;              // create missing parent directories (removed again on failure)
};

// Empty on success; otherwise one line, e.g. "cannot write 'out/layout.json': No space left on
// device", with nothing changed on disk.
std::string commit(const FileChanges& changes);

// One file, all or nothing (its parent directory must exist).
std::string write_file_atomically(const std::filesystem::path& path, std::string bytes);

} // namespace penumbra_gen
