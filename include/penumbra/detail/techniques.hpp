// penumbra/detail/techniques.hpp — the one place that knows which folder implements which
// technique. emit, describe_layout and validate ask it for a technique's functions; each folder
// detail/<technique>/ provides them:
//   programs        its programs in pass order (layout.hpp)
//   param_groups    a program's parameters, in the declaration groups of its emitted text (layout.hpp)
//   describe_layout its textures and passes, shadow and screen phases (layout.hpp)
//   problems        what is wrong with its fields for the target (validate.hpp)
// A new technique: a new folder with these four, and one case below.
#pragma once

#include "erosion/layout.hpp"
#include "erosion/validate.hpp"
#include "occlusion/layout.hpp"
#include "occlusion/validate.hpp"
#include "oim/layout.hpp"
#include "oim/validate.hpp"
#include "shadow_map/layout.hpp"
#include "shadow_map/validate.hpp"

namespace penumbra::detail {

struct TechniqueFunctions {
    std::vector<ProgramPlan> (*programs)(const Config&);
    std::vector<ParamGroup> (*param_groups)(const Config&, std::string_view program);
    void (*describe_layout)(LayoutBuilder&, const Config&);
    std::vector<Problem> (*problems)(const Config&);
};

// Precondition: `technique` is a known value (validate checks it first).
constexpr TechniqueFunctions technique_functions(Technique technique) {
    switch (technique) {
    case Technique::occlusion:
        return {occlusion_programs, occlusion_param_groups, describe_occlusion_layout, occlusion_problems};
    case Technique::shadowmap:
    case Technique::pcf:
    case Technique::pcss:
        return {shadow_map_programs, shadow_map_param_groups, describe_shadow_map_layout, shadow_map_problems};
    case Technique::oim: return {oim_programs, oim_param_groups, describe_oim_layout, oim_problems};
    case Technique::erosion: return {erosion_programs, erosion_param_groups, describe_erosion_layout, erosion_problems};
    }
    return technique_functions(Technique::occlusion); // not reached for a known technique
}

// Programs in the order their passes run.
constexpr std::vector<ProgramPlan> program_plan(const Config& config) {
    return technique_functions(config.technique).programs(config);
}

// Every file of the configuration, each once, snippet last.
constexpr std::vector<Artifact> artifacts(const Config& config) {
    std::vector<Artifact> files;
    for (const ProgramPlan& program : program_plan(config))
        for (Artifact stage : program.stages) {
            bool seen = false;
            for (Artifact f : files) seen = seen || f == stage;
            if (!seen) files.push_back(stage);
        }
    files.push_back(Artifact::visibility_snippet);
    return files;
}

} // namespace penumbra::detail
