// penumbra/generic.hpp — the generic reference: the deferred visibility pass of the same model
// with nothing specialized (loops and constants are uniforms, no unrolling, no baked constants).
//
//   penumbra::Result<penumbra::GenericShading> generic = penumbra::emit_generic(config);
//   // compile generic.value->program; set every generic.value->values[i] as a uniform,
//   // the light uniforms as for the specialized program (penumbra_lightFromWorld, ...),
//   // and bind generic.value->samplers[i].texture to texture unit samplers[i].binding.
//
// It is the yardstick that shows what specialization buys, and a second witness of correctness:
// on the same textures it must give the specialized program's images. Its text depends only on
// filter, packing, light, target and tangent clip (shares_generic_program), so one program serves every slice
// count, resolution, fusion rule and fade setting. It reads the textures of the configuration's
// layout (describe_layout) after the usual slicing and prefilter passes; with the tangent clip it
// also reads the caller's world-normal G-buffer.
#pragma once

#include "detail/occlusion/emit_generic.hpp"
#include "emit.hpp"
#include "validate.hpp"

#include <cassert>
#include <iterator>
#include <string>
#include <vector>

namespace penumbra {

// A uniform value the generic program needs, derived from the configuration.
struct GenericValue {
    std::string name;    // GLSL uniform, e.g. "penumbra_sliceCount"
    std::string type;    // "int" or "float"
    double value = 0.0;  // set as an int when type is "int"
    std::string meaning; // one line, with units where they matter
};

// A sampler of the generic program and what to bind to it. Arrays are listed element by element.
struct GenericSampler {
    std::string name;    // GLSL uniform: "penumbra_sat", or one element "penumbra_levelAtlases[3]"
    std::string type;    // "sampler2D", "sampler2DArray", "sampler3D"
    int binding = 0;     // OpenGL: texture unit. Vulkan: descriptor binding (arrays: element `element`)
    int element = 0;     // array element, 0 for a single sampler
    std::string texture; // layout texture (describe_layout); "penumbra_worldPositions" and
                         // "penumbra_worldNormals" for the caller's G-buffer; empty for an array
                         // element this configuration does not use
};

struct GenericShading {
    Program program;                      // "shading_generic": full-screen vertex + deferred fragment
    std::vector<GenericValue> values;     // the configuration's values, to set as uniforms
    std::vector<GenericSampler> samplers; // in binding order, the G-buffer last
};

// True when `a` and `b` get the same generic program text (their values differ).
constexpr bool shares_generic_program(const Config& a, const Config& b) {
    return a.filter == b.filter && a.packing == b.packing && a.light == b.light && a.target == b.target &&
           clips_to_tangent_plane(a) == clips_to_tangent_plane(b) &&
           weighs_irradiance(a) == weighs_irradiance(b);
}

// The uniform values of a valid configuration.
inline std::vector<GenericValue> generic_values(const Config& config) {
    const int T = texture_count(config);
    const double in_param_order[] = { // the order of detail::generic_value_params()
        double(config.slices), double(config.resolution), double(max_level(config)), double(T), 1.0 / T,
        double(static_cast<int>(config.fusion)), config.self_shadow_fade ? 1.0 : 0.0, config.fade_ramp,
        config.tangent_clip_offset, config.clip_footprint ? double(1 + leak_fix_reach(config)) : 0.0,
        reduces_levels(config) ? double(config.level_reduction) : 99.0,
    };
    std::vector<GenericValue> values;
    const std::vector<detail::Param> params = detail::generic_value_params();
    assert(params.size() == std::size(in_param_order));
    for (std::size_t i = 0; i < params.size(); ++i)
        values.push_back({params[i].name.str(), std::string(params[i].type), in_param_order[i], std::string(params[i].meaning)});
    return values;
}

// The samplers of a valid configuration and the layout texture each one reads.
inline std::vector<GenericSampler> generic_samplers(const Config& config) {
    const int L = max_level(config), T = texture_count(config);
    std::vector<GenericSampler> samplers;
    int binding = detail::is_vulkan(config) ? 1 : 0; // Vulkan: the value block takes binding 0
    for (const detail::GenericSamplerDecl& decl : detail::generic_samplers_decl(config)) {
        const std::string name = decl.name.str();
        for (int e = 0; e < decl.count; ++e) {
            GenericSampler s{decl.count > 1 ? name + "[" + std::to_string(e) + "]" : name, std::string(decl.type),
                             detail::is_vulkan(config) ? binding : binding + e, e, name};
            if (name == "penumbra_levelAtlases") s.texture = e <= L ? detail::atlas_level_name(e).str() : "";
            if (name == "penumbra_volumes") s.texture = e < T ? detail::volume_name(e).str() : "";
            samplers.push_back(std::move(s));
        }
        binding += detail::is_vulkan(config) ? 1 : decl.count;
    }
    return samplers;
}

inline Result<GenericShading> emit_generic(const Config& config) {
    Result<GenericShading> result;
    result.errors = validate(config);
    if (config.slice_placement == SlicePlacement::adaptive)
        result.errors.push_back(
            {"slice_placement", "adaptive",
             "slice_placement: adaptive is not implemented by the generic reference (its slices "
             "are uniform, from penumbra_sliceDepths); allowed: uniform"});
    if (config.near_field)
        result.errors.push_back(
            {"near_field", "true",
             "near_field is not implemented by the generic reference (it has no rays through the "
             "slices' nearest depths); allowed: false"});
    if (config.target == Target::wgsl)
        result.errors.push_back({"target", "wgsl",
                                 "target: wgsl is not written by the generic reference (a GLSL program for the desktop "
                                 "runtime); allowed: glsl330, glsl450, essl300, vulkan"});
    if (config.target == Target::hlsl)
        result.errors.push_back(
            {"target", "hlsl",
             "target: hlsl is not written by the generic reference (a GLSL program for the desktop "
             "runtime); allowed: glsl330, glsl450, essl300, vulkan"});
    if (!result.errors.empty()) return result;
    Program program{"shading_generic",
                    {{"penumbra_generic.vert", Stage::vertex, detail::generic_vertex(config).str()},
                     {"penumbra_generic.frag", Stage::fragment, detail::generic_fragment(config).str()}}};
    result.value = GenericShading{std::move(program), generic_values(config), generic_samplers(config)};
    return result;
}

} // namespace penumbra
