// write_files.hpp — the emitted files into the output directory, all or nothing as far as the
// file system allows.
#pragma once

#include <string>
#include <vector>

namespace penumbra_gen {

struct OutputFile {
    std::string name; // relative to the output directory, no slashes
    std::string text;
};

// Creates `dir` with its parents, writes every file to a temporary name in `dir`, then renames
// them all into place (so a failure while writing leaves the previous files, not a mix). Returns
// an error message, or an empty string on success. Refuses an existing `dir` that is not a
// directory.
std::string write_files(const std::string& dir, const std::vector<OutputFile>& files);

} // namespace penumbra_gen
