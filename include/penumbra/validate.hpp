// penumbra/validate.hpp — is a configuration something Penumbra can emit for its target?
//
//   for (const penumbra::ConfigError& e : penumbra::validate(config)) std::puts(e.message.c_str());
//
// Every message names the field, the value given and what is allowed. Nothing is clamped. Each
// technique checks its own fields (detail/<technique>/validate.hpp, through its descriptor: detail/techniques.hpp).
#pragma once

#include "config.hpp"
#include "detail/techniques.hpp"

#include <string>
#include <vector>

namespace penumbra {

// allowed_slices, the slice counts a configuration may have: detail/occlusion/validate.hpp.

// ConfigError (one error: field, value, message): config.hpp.

namespace detail {

// The techniques whose descriptors write WGSL, for the message of one that does not.
constexpr Text techniques_writing_wgsl() {
    Text names;
    for (std::size_t i = 0; i < EnumNames<Technique>::names.size(); ++i)
        if (technique_descriptor(static_cast<Technique>(i)).writes_wgsl)
            names += cat(names.empty() ? "" : ", ", EnumNames<Technique>::names[i]);
    return names;
}

// The techniques whose descriptors write HLSL, for the message of one that does not.
constexpr Text techniques_writing_hlsl() {
    Text names;
    for (std::size_t i = 0; i < EnumNames<Technique>::names.size(); ++i)
        if (technique_descriptor(static_cast<Technique>(i)).writes_hlsl)
            names += cat(names.empty() ? "" : ", ", EnumNames<Technique>::names[i]);
    return names;
}

constexpr std::vector<Problem> find_problems(const Config& config) {
    std::vector<Problem> problems;
    check_known(problems, "technique", config.technique);
    if (!problems.empty()) return problems;
    const TechniqueDescriptor technique = technique_descriptor(config.technique);
    // Metal is SPIRV-Cross's translation of the vulkan target, made where SPIRV-Cross is linked.
    if (config.target == Target::msl) {
        add_problem(problems, "target", Text("msl"),
                 Text("is translated from the vulkan target's SPIR-V by SPIRV-Cross, which this header-only "
                      "emitter does not link; write it with penumbra-gen --target msl, "
                      "penumbra_generate_shaders(... TARGET_API msl) or penumbra::emit_msl (penumbra/msl.hpp, "
                      "CMake target penumbra::msl); targets emitted here: glsl330, glsl450, essl300, vulkan, "
                      "wgsl, hlsl"));
        return problems;
    }
    if (config.target == Target::wgsl && !technique.writes_wgsl)
        add_problem(problems, "target", Text("wgsl"),
                    cat("is not written for technique '", to_string(config.technique),
                        "' yet; allowed with target wgsl: technique ", techniques_writing_wgsl(),
                        "; other targets: glsl330, glsl450, essl300, vulkan"));
    if (config.target == Target::hlsl && !technique.writes_hlsl)
        add_problem(problems, "target", Text("hlsl"),
                    cat("is not written for technique '", to_string(config.technique),
                        "' yet; allowed with target hlsl: technique ", techniques_writing_hlsl(),
                        "; other targets: glsl330, glsl450, essl300, vulkan, wgsl"));
    if (!problems.empty()) return problems;
    return technique.problems(config);
}

} // namespace detail

// True when `config` can be emitted. Usable in constant expressions.
constexpr bool is_valid(const Config& config) { return detail::find_problems(config).empty(); }

// Every problem with `config`, in field order; empty when it is valid.
inline std::vector<ConfigError> validate(const Config& config) {
    std::vector<ConfigError> errors;
    for (const detail::Problem& problem : detail::find_problems(config))
        errors.push_back({std::string(problem.field), problem.value.str(), problem.message.str()});
    return errors;
}

} // namespace penumbra
