// penumbra/detail/oim/technique.hpp — occlusion interval maps (GPU Gems ch. 13) as a descriptor: no
// pass before shading (the maps come from a bake), a G-buffer of texture coordinates.
#pragma once

#include "../technique.hpp"
#include "layout.hpp"
#include "validate.hpp"

namespace penumbra::detail {

inline constexpr ShaderFileSpec oim_shading_vert{"penumbra_oim_shading.vert", Stage::vertex, oim_example_vertex,
                                                 VertexInputs::receiver_with_uv};
inline constexpr ShaderFileSpec oim_shading_frag{"penumbra_oim_shading.frag", Stage::fragment, oim_example_fragment};
inline constexpr ShaderFileSpec oim_deferred_frag{"penumbra_oim_deferred.frag", Stage::fragment, oim_deferred_fragment};

// Shading only.
constexpr std::vector<ProgramPlan> oim_programs(const Config&) {
    return {{"shading_example", {oim_shading_vert, oim_shading_frag}},
            {"shading_deferred", {fullscreen_vert, oim_deferred_frag}}};
}

constexpr bool oim_reads_normal(const Config&) { return false; }

constexpr Text oim_summary(const Config& config) {
    const OimParams& o = config.oim;
    return cat("technique oim | interval maps ", format_int(o.resolution), "x", format_int(o.resolution), " | ",
               format_int(o.intervals), " intervals in ", format_int(oim_pairs(o)), " rise/fall pair(s) | ",
               format_int(o.samples), " bake samples along the path | target ", to_string(config.target));
}

constexpr Text oim_storage_note(const Config&) {
    return Text("Rise and fall times are path times t in [0, 1] (the sun's path over the day), baked offline.");
}

constexpr std::vector<std::string_view> oim_es_samplers(const Config&) { return {}; }

// The deferred pass reads its G-buffer texel (the maps' nearest texels are not counted).
inline long long oim_texels_per_fragment(const Config&, const PassDesc&) { return 1; }

constexpr TechniqueDescriptor oim_technique() {
    return {
        .programs = oim_programs,
        .visibility_snippet = oim_visibility_snippet,
        .visibility_params = oim_visibility_params,
        .write_visibility = write_oim_visibility,
        .reads_normal = oim_reads_normal,
        .param_groups = oim_param_groups,
        .describe_layout = describe_oim_layout,
        .problems = oim_problems,
        .summary = oim_summary,
        .storage_note = oim_storage_note,
        .es_sampler_precision = oim_es_samplers,
        .texels_per_fragment = oim_texels_per_fragment,
    };
}

} // namespace penumbra::detail
