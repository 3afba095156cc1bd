#include "output_files.hpp"

namespace penumbra_gen {

std::vector<OutputFile> output_files(const penumbra::Emission& emission) {
    std::vector<OutputFile> files;
    for (const penumbra::ShaderFile& f : emission.files()) files.push_back({f.file_name, f.text});
    files.push_back({"layout.json", penumbra::to_json(emission.layout)});
    return files;
}

} // namespace penumbra_gen
