// write_files.hpp — the emitted files into the output directory, all or nothing
// (file_transaction.hpp).
#pragma once

#include "output_files.hpp"

#include <string>
#include <vector>

namespace penumbra_gen {

// Creates `dir` with its parents and writes every file into it, all or nothing: on any failure
// the folder is as it was (previous files restored, created directories removed). Files that the
// previous emission there listed in its layout.json and this one does not are removed in the same
// transaction, so that the folder holds exactly the files the new layout.json lists (plus any file
// Penumbra did not write). Returns an error message, or an empty string on success. Refuses an
// existing `dir` that is not a directory.
std::string write_files(const std::string& dir, const std::vector<OutputFile>& files);

} // namespace penumbra_gen
