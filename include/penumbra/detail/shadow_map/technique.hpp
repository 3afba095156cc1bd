// penumbra/detail/shadow_map/technique.hpp — the shadow map techniques (shadowmap, pcf, pcss) as one
// descriptor: one depth map from the light, then the deferred shading with the technique's filter.
// Erosion (erosion/technique.hpp) starts from the same depth pass and header.
#pragma once

#include "../technique.hpp"
#include "fields.hpp"
#include "layout.hpp"
#include "validate.hpp"

namespace penumbra::detail {

inline constexpr ShaderFileSpec shadow_depth_vert{"penumbra_shadow_depth.vert", Stage::vertex, shadow_depth_vertex,
                                                  VertexInputs::caster};
inline constexpr ShaderFileSpec shadow_depth_frag{"penumbra_shadow_depth.frag", Stage::fragment, shadow_depth_fragment};

constexpr ProgramPlan shadow_depth_program() { return {"shadow_depth", {shadow_depth_vert, shadow_depth_frag}}; }

// Depth, shading.
constexpr std::vector<ProgramPlan> shadow_map_programs(const Config&) {
    return {shadow_depth_program(), shading_example_program(), shading_deferred_program()};
}

// The includable snippet penumbra_visibility.glsl: no #version, declarations from binding 0.
constexpr Text shadow_visibility_snippet(const Config& config) {
    LineWriter out;
    write_snippet_header(out, config, signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    if (config.target == Target::essl300) out.comment("ES: declare precision highp sampler2DShadow before it.");
    out.blank();
    write_hlsl_names(out, config);
    int binding = 0;
    write_shadow_visibility(out, config, binding);
    return out.take();
}

constexpr bool shadow_map_reads_normal(const Config& config) {
    return offsets_along_normal(config) || tilts_taps_to_receiver_plane(config);
}

// The start of the header's configuration line of every technique on the shadow map: the map and
// its biases.
constexpr Text describe_shadow_map(const Config& config) {
    const ShadowMapParams& sm = config.shadow_map;
    Text out = cat("technique ", to_string(config.technique), " | shadow map ", format_int(sm.resolution), "x",
                   format_int(sm.resolution), " | bias ", format_float(sm.constant_bias), " scene units + ",
                   format_float(sm.slope_bias), " x slope");
    if (offsets_along_normal(config)) out += cat(" | normal offset ", format_float(sm.normal_offset), " texels");
    if (tilts_taps_to_receiver_plane(config)) out += " | receiver-plane depth bias";
    return out;
}

constexpr Text describe_light_and_target(const Config& config) {
    return cat(" | light ", to_string(config.light), " | target ", to_string(config.target));
}

constexpr Text shadow_map_summary(const Config& config) {
    Text out = describe_shadow_map(config);
    if (config.technique == Technique::pcf)
        out += cat(" | pcf ", to_string(config.pcf.pattern), " ", format_int(pcf_taps(config.pcf)), " taps, radius ",
                   format_float(config.pcf.radius), ", rotation ", on_off(config.pcf.rotate));
    if (config.technique == Technique::pcss)
        out += cat(" | pcss ", format_int(config.pcss.blocker_samples), " blocker / ",
                   format_int(config.pcss.filter_samples), " filter samples, filter at most ",
                   format_int(config.pcss.max_filter_texels), " texels, rotation ", on_off(config.pcss.rotate));
    return out += describe_light_and_target(config), out;
}

constexpr Text shadow_map_storage_note(const Config&) {
    return Text("Shadow map depth stored as (z - near) / (far - near) along the light axis.");
}

constexpr std::vector<std::string_view> shadow_map_es_samplers(const Config&) { return {"sampler2DShadow"}; }

// Texels the deferred pass's fragment reads besides its G-buffer: every comparison or depth tap a
// bilinear footprint (4 texels).
constexpr long long shadow_map_tap_texels(const Config& c) {
    if (c.technique == Technique::pcf) return 4LL * pcf_taps(c.pcf);
    if (c.technique == Technique::pcss) return 4LL * (c.pcss.blocker_samples + c.pcss.filter_samples);
    return 4;
}

inline long long shadow_map_texels_per_fragment(const Config& config, const PassDesc& pass) {
    if (pass.program == "shading_deferred") return g_buffer_texels(config) + shadow_map_tap_texels(config);
    return 1;
}

inline constexpr auto shadow_map_field_rows = shadow_map_fields();

constexpr TechniqueDescriptor shadow_map_technique() {
    return {
        .fields = shadow_map_field_rows,
        .programs = shadow_map_programs,
        .visibility_snippet = shadow_visibility_snippet,
        .visibility_params = shadow_visibility_params,
        .write_visibility = write_shadow_visibility,
        .reads_normal = shadow_map_reads_normal,
        .param_groups = shadow_map_param_groups,
        .describe_layout = describe_shadow_map_layout,
        .problems = shadow_map_problems,
        .summary = shadow_map_summary,
        .storage_note = shadow_map_storage_note,
        .es_sampler_precision = shadow_map_es_samplers,
        .texels_per_fragment = shadow_map_texels_per_fragment,
        .writes_wgsl = true,
        .writes_hlsl = true,
    };
}

} // namespace penumbra::detail
