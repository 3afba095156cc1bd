// penumbra/detail/techniques.hpp — the registry: which folder's descriptor implements which
// technique (detail/technique.hpp says what a descriptor holds). emit, describe_layout, validate,
// the files' headers and the cost model ask it; a new technique is one case below.
#pragma once

#include "erosion/technique.hpp"
#include "evsm/technique.hpp"
#include "occlusion/technique.hpp"
#include "oim/technique.hpp"
#include "shadow_map/technique.hpp"
#include "smrt/technique.hpp"

namespace penumbra::detail {

constexpr TechniqueDescriptor technique_descriptor(Technique technique) {
    switch (technique) {
    case Technique::occlusion: return occlusion_technique();
    case Technique::shadowmap:
    case Technique::pcf:
    case Technique::pcss: return shadow_map_technique();
    case Technique::oim: return oim_technique();
    case Technique::erosion: return erosion_technique();
    case Technique::evsm: return evsm_technique();
    case Technique::smrt: return smrt_technique();
    }
    return occlusion_technique(); // not reached for a known technique
}

// Programs in the order their passes run.
constexpr std::vector<ProgramPlan> program_plan(const Config& config) {
    return technique_descriptor(config.technique).programs(config);
}

constexpr ShaderFileSpec visibility_snippet_file(const Config& config) {
    return {visibility_snippet_name, Stage::fragment, technique_descriptor(config.technique).visibility_snippet};
}

// Every file of the configuration, each once, in pass order; the snippet last.
constexpr std::vector<ShaderFileSpec> shader_files(const Config& config) {
    std::vector<ShaderFileSpec> files;
    for (const ProgramPlan& program : program_plan(config))
        for (const ShaderFileSpec& stage : program.stages) {
            bool seen = false;
            for (const ShaderFileSpec& f : files) seen = seen || f == stage;
            if (!seen) files.push_back(stage);
        }
    files.push_back(visibility_snippet_file(config));
    return files;
}

} // namespace penumbra::detail
