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
    out.line("layout(location = 0) in vec3 penumbra_position; // world space (scene units)");
    out.line(varying(config, "out", 0, "float", "penumbra_depth"), " // depth along the light axis (scene units)");
    write_alpha_test_vertex_inputs(out, config);
    out.blank();
    int binding = 0;
    write_params(out, config, shadow_depth_params(), "PenumbraShadowDepth", binding);
    out.chunk("shadow_depth_vertex_main");
    out.block(R"(
void main()
{
    vec4 world = vec4(penumbra_position, 1.0);
    penumbra_depth = (penumbra_lightFromWorld * world).z;
    gl_Position = penumbra_shadowClipFromWorld * world;
)");
    write_alpha_test_vertex_copy(out, config);
    out.line("}");
    return out.take();
}

constexpr Text shadow_depth_fragment(const Config& config) {
    const ShadowMapParams& sm = config.shadow_map;
    LineWriter out;
    write_preamble(out, config, "shadow map depth pass, fragment stage (depth test LESS, clear depth to 1)");
    out.chunk("shadow_depth_outputs");
    out.line(varying(config, "in", 0, "float", "penumbra_depth"));
    write_alpha_test_fragment_inputs(out, config);
    out.blank();
    int binding = 0;
    write_params(out, config, shadow_depth_params(), "PenumbraShadowDepth", binding);
    write_alpha_test_params(out, config, binding);
    out.chunk("shadow_depth_fragment_main");
    out.line("void main()");
    out.line("{");
    write_alpha_test_discard(out, config);
    out.comment("slope-scaled bias in scene units: constant + factor * depth change across one shadow-map texel");
    out.comment("(the pass is drawn at the shadow map's resolution, so the derivatives are per texel)");
    out.line("float slope = max(abs(dFdx(penumbra_depth)), abs(dFdy(penumbra_depth)));");
    out.line("float biased = penumbra_depth + ", format_float(sm.constant_bias), " + ", format_float(sm.slope_bias),
             " * slope;");
    out.line("vec2 range = penumbra_shadowDepthRange;");
    out.line("gl_FragDepth = clamp((biased - range.x) / (range.y - range.x), 0.0, 1.0);");
    out.line("}");
    return out.take();
}

} // namespace penumbra::detail
