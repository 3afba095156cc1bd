// penumbra/detail/shadow_map/emit_depth.hpp — the depth pass of shadowmap, pcf and pcss: the scene
// from the light into a depth texture, depth stored linearly along the light axis and pushed away
// from the light by the configured slope-scaled bias.
#pragma once

#include "../alpha_test.hpp"
#include "parameters.hpp"

namespace penumbra::detail {

constexpr Text shadow_depth_vertex(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "shadow map depth pass, vertex stage");
    out.chunk("shadow_depth_inputs");
    out.line(stage_variable(out, config, "in", 0, "vec3", "penumbra_position", true), " // world space (scene units)");
    out.line(stage_variable(out, config, "out", 0, "float", "penumbra_depth", has_varying_locations(config)),
             " // depth along the light axis (scene units)");
    write_alpha_test_vertex_inputs(out, config);
    declare_builtin(out, config, false, "position", "vec4", clip_position(config));
    out.blank();
    int binding = 0;
    write_params(out, config, shadow_depth_params(), "PenumbraShadowDepth", binding);
    out.chunk("shadow_depth_vertex_main");
    write_caster_vertex_main(out, config, "penumbra_shadowClipFromWorld", "the map's");
    return out.take();
}

constexpr Text shadow_depth_fragment(const Config& config) {
    const ShadowMapParams& sm = config.shadow_map;
    LineWriter out;
    write_preamble(out, config, "shadow map depth pass, fragment stage (depth test LESS, clear depth to 1)");
    out.chunk("shadow_depth_outputs");
    out.line(stage_variable(out, config, "in", 0, "float", "penumbra_depth", has_varying_locations(config)));
    write_alpha_test_fragment_inputs(out, config);
    declare_builtin(out, config, false, "frag_depth", "float", frag_depth(config));
    out.blank();
    int binding = 0;
    write_params(out, config, shadow_depth_params(), "PenumbraShadowDepth", binding);
    write_alpha_test_params(out, config, binding);
    out.chunk("shadow_depth_fragment_main");
    out.line(main_signature(config));
    out.line("{");
    write_alpha_test_discard(out, config);
    write_light_plane_clip(out, config);
    out.comment("slope-scaled bias in scene units: constant + factor * depth change across one shadow-map texel");
    out.comment("(the pass is drawn at the shadow map's resolution, so the derivatives are per texel)");
    out.line(value(config, "float", "slope",
                   cat("max(abs(", builtin(config, "dFdx"), "(penumbra_depth)), abs(", builtin(config, "dFdy"), "(penumbra_depth)))")));
    out.line(value(config, "float", "biased",
                   cat("penumbra_depth + ", format_float(sm.constant_bias), " + ", format_float(sm.slope_bias), " * slope")));
    out.line(value(config, "vec2", "range", "penumbra_shadowDepthRange"));
    out.line(frag_depth(config), " = clamp((biased - range.x) / (range.y - range.x), 0.0, 1.0);");
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

} // namespace penumbra::detail
