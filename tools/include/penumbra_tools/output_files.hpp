// output_files.hpp — the files of one emission as penumbra-gen writes them: every shader file
// (Emission::files(), in layout order), then layout.json, the manifest, last. The one list both
// penumbra-gen (write_files.hpp) and the WebAssembly emitter (wasm/) hand out.
#pragma once

#include <penumbra/emit.hpp>

#include <string>
#include <vector>

namespace penumbra_gen {

struct OutputFile {
    std::string name; // relative to the output directory, no slashes
    std::string text;
};

std::vector<OutputFile> output_files(const penumbra::Emission& emission);

} // namespace penumbra_gen
