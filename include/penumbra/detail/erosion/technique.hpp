// penumbra/detail/erosion/technique.hpp — erosion (Klein et al.) as a descriptor: the shadow map's
// depth pass, then screen passes (hard shadow, edges, min-max chain, erosion, blur) in place of the
// deferred shading.
#pragma once

#include "../shadow_map/technique.hpp"
#include "fields.hpp"
#include "layout.hpp"
#include "validate.hpp"

namespace penumbra::detail {

inline constexpr ShaderFileSpec erosion_hard_frag{"penumbra_erosion_hard.frag", Stage::fragment,
                                                  [](const Config& c) { return erosion_fragment(c, "erosion_hard"); }};
inline constexpr ShaderFileSpec erosion_edges_frag{"penumbra_erosion_edges.frag", Stage::fragment,
                                                   [](const Config& c) { return erosion_fragment(c, "erosion_edges"); }};
inline constexpr ShaderFileSpec erosion_reduce_frag{"penumbra_erosion_reduce.frag", Stage::fragment,
                                                    [](const Config& c) { return erosion_fragment(c, "erosion_reduce"); }};
inline constexpr ShaderFileSpec erosion_erode_frag{"penumbra_erosion_erode.frag", Stage::fragment,
                                                   [](const Config& c) { return erosion_fragment(c, "erosion_erode"); }};
inline constexpr ShaderFileSpec erosion_blur_frag{"penumbra_erosion_blur.frag", Stage::fragment,
                                                  [](const Config& c) { return erosion_fragment(c, "erosion_blur"); }};

// Depth, the screen passes instead of shading_deferred, the example.
constexpr std::vector<ProgramPlan> erosion_programs(const Config&) {
    return {shadow_depth_program(),
            {"erosion_hard", {fullscreen_vert, erosion_hard_frag}},
            {"erosion_edges", {fullscreen_vert, erosion_edges_frag}},
            {"erosion_reduce", {fullscreen_vert, erosion_reduce_frag}},
            {"erosion_erode", {fullscreen_vert, erosion_erode_frag}},
            {"erosion_blur", {fullscreen_vert, erosion_blur_frag}},
            shading_example_program()};
}

constexpr bool erosion_reads_normal(const Config&) { return false; }

constexpr Text erosion_summary(const Config& config) {
    return cat(describe_shadow_map(config), " | erosion search at most ", format_int(config.erosion.max_search_radius),
               " px, edge threshold ", format_float(config.erosion.edge_threshold), ", ",
               format_int(config.erosion.search_taps), " search / ", format_int(config.erosion.blur_taps),
               " blur taps", describe_light_and_target(config));
}

// The screen passes' taps: about a blur's; the example's point lookup one hard-shadow tap.
inline long long erosion_texels_per_fragment(const Config&, const PassDesc& pass) {
    return pass.program.starts_with("erosion_") ? 16 : 1;
}

inline constexpr auto erosion_field_rows = erosion_fields();

constexpr TechniqueDescriptor erosion_technique() {
    TechniqueDescriptor erosion = shadow_map_technique();
    erosion.fields = erosion_field_rows;
    erosion.programs = erosion_programs;
    erosion.reads_normal = erosion_reads_normal;
    erosion.param_groups = erosion_param_groups;
    erosion.describe_layout = describe_erosion_layout;
    erosion.problems = erosion_problems;
    erosion.summary = erosion_summary;
    erosion.texels_per_fragment = erosion_texels_per_fragment;
    erosion.reads_shared_section = "shadow_map";
    return erosion;
}

} // namespace penumbra::detail
