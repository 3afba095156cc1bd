// penumbra/detail/evsm/emit_passes.hpp — the programs of exponential variance shadow maps (EVSM;
// Lauritzen & McCool 2008, "Layered variance shadow maps"; Unity HDRP's area-light shadows):
//   evsm_moments  the shadow map's depth d in [0, 1], warped by two exponentials of d' = 2d - 1,
//                 e^(c+ d') and -e^(-c- d'), and their squares: the four moments (one texel per texel)
//   evsm_blur_x   a box blur of the moments along the map's x axis (the light's width), then
//   evsm_blur_y   along y (its height): together a box over the light's footprint. Its half-width
//                 follows the light: blur_fraction of the widest penumbra the light casts across the
//                 scene (a blocker on the near plane over a receiver on the far one), clamped to
//                 max_blur_texels; the taps are spread over it, so their count is fixed
//   penumbraVisibility  the blurred moments under the receiver, one bilinear lookup: the one-tailed
//                 Chebyshev bound of each warp, the light-bleeding reduction, the smaller of the two
// Exponents, tap offsets, counts and clamps are literals; the taps are written out one line each.
#pragma once

#include "../shadow_map/emit_visibility.hpp"
#include "parameters.hpp"

namespace penumbra::detail {

// Offset of blur tap i of `taps`, in half-widths: the midpoints of `taps` equal parts of [-1, 1], so
// the taps average the box without weighting its ends twice.
constexpr double evsm_tap_offset(int i, int taps) { return (2.0 * i + 1.0) / taps - 1.0; }

// penumbra_evsmWarp: the two exponential warps of a stored depth, as the moments pass and the lookup
// both compute them.
constexpr void write_warp_function(LineWriter& out, const Config& config) {
    const EvsmParams& e = config.evsm;
    out.chunk("evsm_warp");
    out.comment("the depth as stored, (z - near) / (far - near), warped: x = e^(c+ d), y = -e^(-c- d), d = 2 depth - 1");
    out.comment("(d in [-1, 1] spreads the 32-bit floats' precision over both ends)");
    out.line(signature(config, "vec2", "penumbra_evsmWarp", {{"float", "depth"}}));
    out.line("{");
    out.line(value(config, "float", "d", "2.0 * clamp(depth, 0.0, 1.0) - 1.0"));
    out.line("return vec2(exp(", format_float(e.positive_exponent), " * d), -exp(", format_float(-e.negative_exponent),
             " * d));");
    out.line("}");
    out.blank();
}

// penumbra_evsmSample: the moments at a point in texel units (texel centres at .5), bilinear.
constexpr void write_sample_function(LineWriter& out, const Config& config) {
    const int R = config.shadow_map.resolution;
    out.chunk("evsm_sample");
    if (evsm_filters_in_hardware(config)) {
        out.comment("the moments at a point in texel units (texel centres at .5), filtered bilinearly by the hardware");
        out.line(signature(config, "vec4", "penumbra_evsmSample", {{"sampler2D", "moments"}, {"vec2", "texel"}}));
        out.line("{");
        out.line("return ", sample_level(config, "moments", cat("texel * ", format_float(1.0 / R)), "0.0"), ";");
        out.line("}");
        out.blank();
        return;
    }
    out.comment("one texel's moments: the bits of 32-bit floats (RGBA32UI, colour-renderable in core ES 3.0, where");
    out.comment("rendering to a float texture needs EXT_color_buffer_float); clamped to the map, as CLAMP_TO_EDGE");
    out.line(signature(config, "vec4", "penumbra_evsmLoad", {{"usampler2D", "moments"}, {"ivec2", "texel"}}));
    out.line("{");
    out.line("return ", uint_bits_to_float(config, "vec4",
                                             fetch(config, "moments",
                                                   cat("clamp(texel, ", construct(config, "ivec2", "0"), ", ",
                                                       construct(config, "ivec2", format_int(R - 1)), ")"),
                                                   "0")),
             ";");
    out.line("}");
    out.blank();
    out.comment("the moments at a point in texel units (texel centres at .5), filtered bilinearly by hand: integer");
    out.comment("textures are never filtered");
    out.line(signature(config, "vec4", "penumbra_evsmSample", {{"usampler2D", "moments"}, {"vec2", "texel"}}));
    out.line("{");
    const std::string_view ivec2 = type_name(config, "ivec2");
    out.line(value(config, "vec2", "p", "texel - 0.5"));
    out.line(value(config, "ivec2", "i", construct(config, "ivec2", "floor(p)")));
    out.line(value(config, "vec2", "f", "p - floor(p)"));
    out.line(value(config, "vec4", "bottom",
                   cat("mix(penumbra_evsmLoad(moments, i), penumbra_evsmLoad(moments, i + ", ivec2, "(1, 0)), f.x)")));
    out.line(value(config, "vec4", "top",
                   cat("mix(penumbra_evsmLoad(moments, i + ", ivec2, "(0, 1)), penumbra_evsmLoad(moments, i + ", ivec2,
                       "(1, 1)), f.x)")));
    out.line("return mix(bottom, top, f.y);");
    out.line("}");
    out.blank();
}

// The colour output of the moments and blur passes (and the fragment coordinate they read), and how a
// vec4 of moments is written to it.
constexpr void write_evsm_output(LineWriter& out, const Config& config) {
    if (evsm_filters_in_hardware(config))
        out.line(stage_variable(out, config, "out", 0, "vec4", "penumbra_out", true));
    else
        out.line(stage_variable(out, config, "out", 0, "uvec4", "penumbra_out", true), " // the bits of 32-bit floats");
    declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
}
constexpr Text evsm_store(const Config& config, std::string_view value) {
    if (evsm_filters_in_hardware(config)) return cat("penumbra_out = ", value, ";");
    return cat("penumbra_out = ", float_bits(config, "uvec4", value), ";");
}

constexpr Text evsm_moments_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "evsm: moments of the warped depth, fragment stage (drawn at the shadow map's size)");
    write_evsm_output(out, config);
    out.blank();
    int binding = 0;
    write_params(out, config, {evsm_depth_param()}, "PenumbraPass", binding);
    write_warp_function(out, config);
    out.chunk("evsm_moments_main");
    out.line(main_signature(config));
    out.line("{");
    out.comment("the texel of the depth map under this fragment (the pass covers the map one texel per fragment)");
    out.line(value(config, "float", "depth",
                   fetch_depth(config, "penumbra_shadowDepth", construct(config, "ivec2", cat(frag_coord(config), ".xy")))));
    out.line(value(config, "vec2", "warped", "penumbra_evsmWarp(depth)"));
    out.line(evsm_store(config, "vec4(warped.x, warped.x * warped.x, warped.y, warped.y * warped.y)"));
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

// One blur pass: `axis` 0 along x (the light's width, reading the moments), 1 along y (its height,
// reading the x pass's result).
constexpr Text evsm_blur_fragment(const Config& config, int axis) {
    const EvsmParams& e = config.evsm;
    const int R = config.shadow_map.resolution;
    const std::string_view source = axis == 0 ? evsm_moments_texture : evsm_blur_x_texture;
    const std::string_view component = axis == 0 ? "x" : "y";
    LineWriter out;
    write_preamble(out, config,
                   axis == 0 ? "evsm: box blur of the moments along x (the light's width), fragment stage"
                             : "evsm: box blur of the moments along y (the light's height), fragment stage");
    write_evsm_output(out, config);
    out.blank();
    int binding = 0;
    write_params(out, config, evsm_blur_params(config, source), "PenumbraPass", binding);
    write_sample_function(out, config);
    out.chunk(axis == 0 ? "evsm_blur_x_main" : "evsm_blur_y_main");
    out.line(main_signature(config));
    out.line("{");
    out.line(value(config, "vec2", "range", "penumbra_shadowDepthRange"));
    out.comment("the widest penumbra the light casts across the map, in uv: a blocker on the near plane over a receiver");
    if (config.light == Light::rect) {
        out.comment("on the far plane (the light's size on the near plane, times 1 - near / far)");
        out.line(value(config, "float", "widest", cat("penumbra_lightSizeUV.", component, " * (1.0 - range.x / range.y)")));
    } else {
        out.comment("on the far plane (the sun's cone grows the footprint by penumbra_lightSizeUV per unit of depth)");
        out.line(value(config, "float", "widest", cat("penumbra_lightSizeUV.", component, " * (range.y - range.x)")));
    }
    out.line("// the box's half-width in texels: half of ", format_float(e.blur_fraction), " of it, at most ",
             format_int(e.max_blur_texels), " texels");
    out.line(value(config, "float", "radius",
                   cat("min(widest * ", format_float(0.5 * e.blur_fraction * R), ", ",
                       format_float(static_cast<double>(e.max_blur_texels)), ")")));
    out.line(value(config, "vec2", "centre", cat(frag_coord(config), ".xy")));
    out.line(variable(config, "vec4", "sum", "vec4(0.0)"));
    for (int i = 0; i < e.blur_taps; ++i) {
        const Text offset = cat(format_float(evsm_tap_offset(i, e.blur_taps)), " * radius");
        const Text step = choose(axis == 0, cat("vec2(", offset, ", 0.0)"), cat("vec2(0.0, ", offset, ")"));
        out.line("sum += penumbra_evsmSample(", source, ", centre + ", step, "); // tap ", format_int(i + 1), " of ",
                 format_int(e.blur_taps), ", at ", format_float(evsm_tap_offset(i, e.blur_taps)), " of the half-width");
    }
    out.line(evsm_store(config, cat("sum * ", format_float(1.0 / e.blur_taps))));
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

constexpr Text evsm_blur_x_fragment(const Config& config) { return evsm_blur_fragment(config, 0); }
constexpr Text evsm_blur_y_fragment(const Config& config) { return evsm_blur_fragment(config, 1); }

// penumbra_evsmBound: the one-tailed Chebyshev bound of one warp, with the light-bleeding reduction.
constexpr void write_bound_function(LineWriter& out, const Config& config) {
    const double reduction = config.evsm.light_bleeding_reduction;
    out.chunk("evsm_bound");
    out.comment("Chebyshev's one-tailed bound (Donnelly & Lauritzen 2006) on the share of the filtered occluders");
    out.comment("farther from the light than the receiver: moments.x mean, moments.y mean square, t the receiver");
    out.line(signature(config, "float", "penumbra_evsmBound", {{"vec2", "moments"}, {"float", "t"}, {"float", "minVariance"}}));
    out.line("{");
    out.line(value(config, "float", "variance", "max(moments.y - moments.x * moments.x, minVariance)"));
    out.line(value(config, "float", "d", "t - moments.x"));
    out.line(variable(config, "float", "bound", "variance / (variance + d * d)"));
    if (reduction > 0.0) {
        out.comment(cat("light-bleeding reduction (Lauritzen 2007): bounds below ", format_float(reduction),
                        " are taken as shadow, the rest rescaled to [0, 1]"));
        out.line("bound = clamp((bound - ", format_float(reduction), ") * ", format_float(1.0 / (1.0 - reduction)),
                 ", 0.0, 1.0);");
    }
    out.comment("nearer than the mean occluder: lit");
    out.line("return ", conditional(config, "t <= moments.x", "1.0", "bound"), ";");
    out.line("}");
    out.blank();
}

// Declarations and functions of penumbraVisibility for EVSM.
constexpr void write_evsm_visibility(LineWriter& out, const Config& config, int& next_binding) {
    const EvsmParams& e = config.evsm;
    write_params(out, config, evsm_visibility_params(config), "PenumbraVisibility", next_binding);
    write_shadow_coord_function(out, config);
    write_warp_function(out, config);
    write_sample_function(out, config);
    write_bound_function(out, config);
    out.chunk("visibility");
    out.comment("Fraction of the light visible from worldPos: 1 lit, 0 in shadow (evsm: the smaller bound of the two");
    out.comment("warps, from the blurred moments under the point).");
    out.line(signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    out.line("{");
    out.line(value(config, "vec4", "coord", "penumbra_shadowCoord(worldPos)"));
    out.line(value(config, "vec4", "moments",
                   cat("penumbra_evsmSample(", evsm_moments_texture, ", coord.xy * ",
                       format_float(static_cast<double>(config.shadow_map.resolution)), ")")));
    out.line(value(config, "vec2", "t", "penumbra_evsmWarp(coord.z)"));
    out.line("// the least variance: a depth spread of ", format_float(e.variance_bias),
             " (of the depth range) through each warp's slope, 2 c e^(c d)");
    out.line(value(config, "vec2", "spread",
                   cat("vec2(", format_float(2.0 * e.variance_bias * e.positive_exponent), ", ",
                       format_float(2.0 * e.variance_bias * e.negative_exponent), ") * abs(t)")));
    out.line(value(config, "float", "positive", "penumbra_evsmBound(moments.xy, t.x, spread.x * spread.x)"));
    out.line(value(config, "float", "negative", "penumbra_evsmBound(moments.zw, t.y, spread.y * spread.y)"));
    out.line("return min(positive, negative);");
    out.line("}");
    out.blank();
    out.comment("The same with the receiver's normal, so that shaders written for the occlusion technique's tangent");
    out.comment("clip compile unchanged; the filtered moments have no use for it.");
    out.line(signature(config, "float", visibility_with_normal(config), {{"vec3", "worldPos"}, {"vec3", "worldNormal"}}));
    out.line("{");
    out.line("return penumbraVisibility(worldPos);");
    out.line("}");
}

// The includable snippet penumbra_visibility.glsl: no #version, declarations from binding 0; on ES
// its own precision statements (usampler2D has no default), so `#version 300 es` + it compiles.
constexpr Text evsm_visibility_snippet(const Config& config) {
    LineWriter out;
    write_snippet_header(out, config, signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    out.blank();
    write_precision(out, config);
    int binding = 0;
    write_evsm_visibility(out, config, binding);
    return out.take();
}

} // namespace penumbra::detail
