// penumbra/detail/shadow_map/emit_visibility.hpp — float penumbraVisibility(vec3 worldPos) for the
// shadow map techniques:
//   shadowmap  one hardware comparison tap (bilinear, 2x2 texels): hard shadows;
//   pcf        a fixed kernel of comparison taps, radius in scene units on the receiver;
//   pcss       Fernando 2005: blocker search over the region the light subtends, parallel-planes
//              penumbra estimate, PCF over that width (clamped to pcss.max_filter_texels).
// Tap counts, tap offsets (poisson.hpp), radii and clamps are literals; the tap loops are written out
// tap by tap, one comment per group of taps, no loop statement.
#pragma once

#include "parameters.hpp"
#include "poisson.hpp"

namespace penumbra::detail {

// The blocker search uses its own pattern, so it does not sample where the filter does.
inline constexpr std::uint64_t blocker_seed = 0xB10C4E5ull;

constexpr Text shadow_taps_label(const Config& config) {
    switch (config.technique) {
    case Technique::pcf:
        return cat(format_int(pcf_taps(config.pcf)), " ", to_string(config.pcf.pattern), " taps, radius ",
                   format_float(config.pcf.radius), " scene units, rotation ", on_off(config.pcf.rotate));
    case Technique::pcss:
        return cat(format_int(config.pcss.blocker_samples), " blocker / ", format_int(config.pcss.filter_samples),
                   " filter taps, filter at most ", format_int(config.pcss.max_filter_texels), " texels, rotation ",
                   on_off(config.pcss.rotate));
    default: return Text("1 comparison tap");
    }
}

// penumbra_shadowCoord: xy shadow-map uv, z the depth as the map stores it, w depth along the light axis.
constexpr void write_shadow_coord_function(LineWriter& out, const Config& config) {
    out.chunk("shadow_coord");
    out.comment("xy: shadow-map uv, z: depth as stored, (z - near) / (far - near), w: depth along the light axis");
    out.line(signature(config, "vec4", "penumbra_shadowCoord", {{"vec3", "worldPos"}}));
    out.line("{");
    out.line(
        variable(config, "vec3", "p",
                 cat("(", transform(config, "penumbra_lightFromWorld", "vec4(worldPos, 1.0)"), ").xyz")));
    if (config.light == Light::rect) {
        out.line("p.z = max(p.z, 1e-6); // points on or behind the light plane");
        out.comment("perspective from the light centre, square frustum");
        out.line(value(config, "vec2", "uv", "0.5 + p.xy / (2.0 * penumbra_shadowTanHalfFov * p.z)"));
    } else {
        out.comment("orthographic along the sun's direction");
        out.line(value(config, "vec2", "uv", "0.5 + p.xy / (2.0 * penumbra_windowHalfSize)"));
    }
    out.line(value(config, "vec2", "range", "penumbra_shadowDepthRange"));
    out.line("return vec4(uv, (p.z - range.x) / (range.y - range.x), p.z);");
    out.line("}");
    out.blank();
    if (config.technique == Technique::shadowmap) return;
    out.comment("shadow-map uv per scene unit, measured on the receiver at depth z");
    out.line(signature(config, "float", "penumbra_uvPerUnit", {{"float", "z"}}));
    out.line("{");
    if (config.light == Light::rect)
        out.line("return 1.0 / (2.0 * penumbra_shadowTanHalfFov * z);");
    else
        out.line("return 1.0 / (2.0 * penumbra_windowHalfSize);");
    out.line("}");
    out.blank();
}

constexpr bool rotates(const Config& config) {
    return (config.technique == Technique::pcf && config.pcf.rotate) ||
           (config.technique == Technique::pcss && config.pcss.rotate);
}

constexpr void write_rotation_function(LineWriter& out, const Config& config) {
    if (!rotates(config)) return;
    out.chunk("rotation");
    // An integer hash of the position's bits (a PCG step, Jarzynski & Olano 2020), not fract(sin(x)·k):
    // sin of large arguments differs between drivers and even between one driver's GLSL and SPIR-V
    // paths, so the same pixel got another pattern on another API.
    out.comment("per-pixel rotation of the tap pattern: an angle from an integer hash of the world position's bits,");
    out.comment("the same on every API and GPU");
    out.line(signature(config, "mat2", "penumbra_rotation", {{"vec3", "worldPos"}}));
    out.line("{");
    out.line(value(config, "uvec3", "bits", float_bits(config, "uvec3", "worldPos")));
    // WGSL does not mix * and ^ without parentheses
    out.line(variable(config, "uint", "h",
                      choose(is_wgsl(config), Text("(bits.x * 0x8da6b343u) ^ (bits.y * 0xd8163841u) ^ (bits.z * 0xcb1ab31fu)"),
                             Text("bits.x * 0x8da6b343u ^ bits.y * 0xd8163841u ^ bits.z * 0xcb1ab31fu"))));
    out.line("h = h * 747796405u + 2891336453u;");
    out.line("h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;");
    out.line("h = (h >> 22u) ^ h;");
    out.line(value(config, "float", "angle", cat("6.283185307 * ", construct(config, "float", "h >> 8u"), " * (1.0 / 16777216.0)")));
    out.line(value(config, "float", "c", "cos(angle)"));
    out.line(value(config, "float", "s", "sin(angle)"));
    out.line("return ", construct(config, "mat2", "c, s, -s, c"), ";");
    out.line("}");
    out.blank();
}

constexpr Text tap_offset(const Config& config, const Tap& tap, std::string_view scale) {
    const Text v = cat("vec2(", format_float(tap.x), ", ", format_float(tap.y), ")");
    return choose(rotates(config), cat(transform(config, "penumbra_rot", v), " * ", scale),
                  cat(v, " * ", scale));
}

// One line per tap (the blocker search: two), a comment before each group of `group` taps.
template <class WriteTap>
constexpr void write_taps(LineWriter& out, const std::vector<Tap>& taps, int group, std::string_view what,
                          WriteTap write_tap) {
    for (int i = 0; i < static_cast<int>(taps.size()); ++i) {
        if (i % group == 0) {
            const int last = i + group - 1 < static_cast<int>(taps.size()) - 1 ? i + group - 1
                                                                                : static_cast<int>(taps.size()) - 1;
            out.line("// ", what, " ", format_int(i), choose(last > i, cat(" to ", format_int(last)), Text()));
        }
        write_tap(taps[static_cast<std::size_t>(i)]);
    }
}

// With the receiver-plane depth bias, the depth a tap compares against: the receiver's, plus the
// tangent plane's rise over the tap's offset. The offset is linear in the literal tap, so the plane's
// slope is turned into the pattern's frame once per pixel (`tilt`) and each tap adds one dot product.
constexpr Text tap_depth(const Config& config, const Tap& tap, std::string_view tilt) {
    if (!tilts_taps_to_receiver_plane(config)) return Text("coord.z");
    return cat("coord.z + dot(vec2(", format_float(tap.x), ", ", format_float(tap.y), "), ", tilt, ")");
}

// tilt = the stored depth's change per unit of the literal tap offset: rot^T (slope * scale).
constexpr void write_tilt(LineWriter& out, const Config& config, std::string_view tilt, std::string_view scale) {
    if (!tilts_taps_to_receiver_plane(config)) return;
    out.line(value(config, "vec2", tilt,
                   choose(rotates(config),
                          transform_row(config, cat("(depthSlope * ", scale, ")"), "penumbra_rot"),
                          cat("depthSlope * ", scale))),
             " // depth change per unit of tap offset");
}

constexpr void write_comparison_taps(LineWriter& out, const Config& config, const std::vector<Tap>& taps, int group,
                                     std::string_view what, std::string_view scale) {
    write_tilt(out, config, "tilt", scale);
    out.line(variable(config, "float", "penumbra_lit", "0.0"));
    write_taps(out, taps, group, what, [&](const Tap& tap) {
        out.line("penumbra_lit += ", sample_compare(config, shadow_map_texture, cat("coord.xy + ", tap_offset(config, tap, scale)),
                                                    tap_depth(config, tap, "tilt")), ";");
    });
    out.line("return penumbra_lit * ", format_float(1.0 / static_cast<double>(taps.size())), ";");
}

constexpr void write_pcss_body(LineWriter& out, const Config& config) {
    const PcssParams& pcss = config.pcss;
    const bool rect = config.light == Light::rect;
    out.comment("Fernando 2005, step 1: blocker search over the region the light subtends on the near plane");
    if (rect)
        out.line(value(config, "vec2", "search", "min(0.5 * penumbra_lightSizeUV * (coord.w - penumbra_shadowDepthRange.x) / coord.w, vec2(0.5))"));
    else
        out.line(value(config, "vec2", "search", "min(0.5 * penumbra_lightSizeUV * (coord.w - penumbra_shadowDepthRange.x), vec2(0.5))"));
    out.comment("a blocker is strictly nearer than the receiver: a receiver on the far plane, whose biased depth");
    out.comment("the map clamps to 1, is not its own blocker");
    out.line(variable(config, "vec2", "penumbra_blocker", "vec2(0.0)"), " // x: sum of blocker depths (as stored), y: blocker count");
    out.line(variable(config, "float", "d"));
    write_tilt(out, config, "searchTilt", "search");
    write_taps(out, poisson_disk(pcss.blocker_samples, blocker_seed), 4, "blocker taps", [&](const Tap& tap) {
        out.line("d = ", sample_depth(config, "penumbra_shadowDepth", cat("coord.xy + ", tap_offset(config, tap, "search"))), ";");
        out.line("penumbra_blocker += ", construct(config, "float", cat("d < ", tap_depth(config, tap, "searchTilt"))), " * vec2(d, 1.0);");
    });
    out.comment("no blocker: fully lit (a real branch: the filter is skipped)");
    out.line(if_then(config, "penumbra_blocker.y == 0.0", "return 1.0;"));
    out.line(value(config, "vec2", "range", "penumbra_shadowDepthRange"));
    out.line(value(config, "float", "zBlocker", "range.x + penumbra_blocker.x / penumbra_blocker.y * (range.y - range.x)"));
    out.comment("step 2, parallel planes: w_p = (d_receiver - d_blocker) * w_light / d_blocker, on the receiver");
    if (rect)
        out.line(value(config, "vec2", "penumbraWidth", "(coord.w - zBlocker) * penumbra_lightSize / zBlocker"));
    else
        out.line(value(config, "vec2", "penumbraWidth", "vec2(2.0 * (coord.w - zBlocker) * penumbra_tanAngularRadius)"));
    out.line("// step 3: PCF over half that width each side, in shadow-map uv, at most ",
             format_int(pcss.max_filter_texels), " texels");
    out.line(value(config, "vec2", "filterUV",
                   cat("min(0.5 * penumbraWidth * penumbra_uvPerUnit(coord.w), vec2(",
                       format_float(static_cast<double>(pcss.max_filter_texels) / config.shadow_map.resolution), "))")));
    write_comparison_taps(out, config, poisson_disk(pcss.filter_samples), 4, "filter taps", "filterUV");
}

// Normal-offset bias (ShadowMapParams::normal_offset; Filament, Unity, Holbert 2011): the receiver
// moves along its normal by k shadow-map texels, measured at the receiver, times the sine of its angle
// to the light. A curved receiver then looks up the map a texel's worth outside its own surface, where
// the depth bias alone would have to grow with the slope (and detach the shadows of near occluders).
// A surface facing the light moves not at all; one edge-on to it by the whole offset.
constexpr void write_normal_offset(LineWriter& out, const Config& config) {
    if (config.light == Light::rect) {
        out.comment("cosine to the direction towards the light centre; a texel spans 2 tan(fov/2) z / R at depth z");
        out.line(value(config, "float", "cosine", "dot(nLight, -normalize(p))"));
        out.line(value(config, "float", "texel",
                       cat("2.0 * penumbra_shadowTanHalfFov * p.z * ", format_float(1.0 / config.shadow_map.resolution))));
    } else {
        out.comment("cosine to the direction towards the sun; a texel spans 2 h / R of the orthographic window");
        out.line(value(config, "float", "cosine", "-nLight.z"));
        out.line(value(config, "float", "texel",
                       cat("2.0 * penumbra_windowHalfSize * ", format_float(1.0 / config.shadow_map.resolution))));
    }
    out.line(value(config, "float", "sine", "sqrt(max(1.0 - cosine * cosine, 0.0))"));
}

// Receiver-plane depth bias (ShadowMapParams::receiver_plane_bias; Isidoro 2006, as in Filament's and
// Unity's wide filters): depthSlope is the stored depth's change per unit of shadow-map uv along the
// receiver's tangent plane. It comes from the normal rather than from screen-space derivatives, so it
// holds at silhouettes, where neighbouring pixels lie on other surfaces. Near edge-on to the light the
// slope grows without bound; it is capped at a rise of 10 per lateral unit (84 degrees), and a
// receiver facing away from the light gets none.
constexpr void write_receiver_plane_slope(LineWriter& out, const Config& config) {
    if (config.light == Light::rect) {
        out.comment("the tangent plane's depth along the ray through uv: z(uv) = dot(n, p) / dot(n, dir(uv)),");
        out.comment("dir = p / p.z at the receiver; its change per lateral scene unit is n.xy / -dot(n, dir)");
        out.line(value(config, "float", "facing", "-dot(nLight, p / p.z)"));
    } else {
        out.comment("the tangent plane's depth across the orthographic window changes by n.xy / -n.z per scene unit");
        out.line(value(config, "float", "facing", "-nLight.z"));
    }
    out.line(value(config, "vec2", "rise", conditional(config, "facing > 0.0", "nLight.xy / max(facing, 0.1)", "vec2(0.0)")));
    out.line(value(config, "vec2", "depthRange", "penumbra_shadowDepthRange"));
    out.comment("per uv instead of per scene unit on the receiver, then depth as stored: (z - near) / (far - near)");
    out.line(value(config, "vec2", "depthSlope", "rise / (penumbra_uvPerUnit(p.z) * (depthRange.y - depthRange.x))"));
}

// penumbraVisibility(worldPos, worldNormal) with what the normal is for: the normal offset, the
// receiver-plane depth bias, both, or (neither) nothing.
constexpr void write_normal_visibility(LineWriter& out, const Config& config) {
    const bool offset = offsets_along_normal(config);
    const bool tilt = tilts_taps_to_receiver_plane(config);
    if (!offset && !tilt) {
        out.comment("The same with the receiver's normal, so that shaders written for the occlusion technique's");
        out.comment("tangent clip compile unchanged; without the normal offset or the receiver-plane bias a depth");
        out.comment("map has no use for it.");
        out.line(signature(config, "float", visibility_with_normal(config), {{"vec3", "worldPos"}, {"vec3", "worldNormal"}}));
        out.line("{");
        out.line("return penumbraVisibility(worldPos);");
        out.line("}");
        return;
    }
    Text uses;
    if (offset) uses = cat("the normal-offset bias of ", format_float(config.shadow_map.normal_offset), " shadow-map texels");
    if (offset && tilt) uses += " and ";
    if (tilt) uses += "the receiver-plane depth bias";
    out.comment(cat("With the receiver's normal (the side being lit): ", uses, ", then the lookup above."));
    out.line(signature(config, "float", visibility_with_normal(config), {{"vec3", "worldPos"}, {"vec3", "worldNormal"}}));
    out.line("{");
    out.line(value(config, "vec3", "n", cat("worldNormal * ", builtin(config, "inversesqrt"), "(max(dot(worldNormal, worldNormal), 1e-20))")));
    out.line(
        variable(config, "vec3", "p",
                 cat("(", transform(config, "penumbra_lightFromWorld", "vec4(worldPos, 1.0)"), ").xyz")));
    out.line(value(config, "vec3", "nLight",
                   transform(config, upper_3x3(config, "penumbra_lightFromWorld"), "n")));
    if (config.light == Light::rect) out.line("p.z = max(p.z, 1e-6); // points on or behind the light plane");
    if (offset) write_normal_offset(out, config);
    if (tilt) write_receiver_plane_slope(out, config);
    const Text moved = choose(offset, cat("worldPos + n * (", format_float(config.shadow_map.normal_offset),
                                          " * texel * sine)"),
                              Text("worldPos"));
    if (tilt)
        out.line("return penumbra_filteredVisibility(", moved, ", depthSlope);");
    else
        out.line("return penumbraVisibility(", moved, ");");
    out.line("}");
}

// Declarations and functions of penumbraVisibility for a shadow map technique.
constexpr void write_shadow_visibility(LineWriter& out, const Config& config, int& next_binding) {
    write_params(out, config, shadow_visibility_params(config), "PenumbraVisibility", next_binding);
    write_shadow_coord_function(out, config);
    write_rotation_function(out, config);
    out.chunk("visibility");
    out.comment(cat("Fraction of the light visible from worldPos: 1 lit, 0 in shadow (", to_string(config.technique),
                    ": ", shadow_taps_label(config), ")."));
    const bool tilt = tilts_taps_to_receiver_plane(config);
    if (tilt) {
        out.comment("depthSlope: the receiver's tangent plane, stored depth per unit of shadow-map uv (the");
        out.comment("receiver-plane depth bias); each tap compares against the plane's depth under it");
        out.line(signature(config, "float", "penumbra_filteredVisibility", {{"vec3", "worldPos"}, {"vec2", "depthSlope"}}));
    } else {
        out.line(signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    }
    out.line("{");
    out.line(value(config, "vec4", "coord", "penumbra_shadowCoord(worldPos)"));
    if (rotates(config)) out.line(value(config, "mat2", "penumbra_rot", "penumbra_rotation(worldPos)"));
    if (config.technique == Technique::shadowmap || config.technique == Technique::erosion) {
        if (config.technique == Technique::erosion)
            out.comment("erosion is a screen-space filter: per point, only its hard shadow (the soft one: the screen passes)");
        out.comment("one comparison tap; the hardware filters the 2x2 comparisons around it bilinearly");
        out.line("return ", sample_compare(config, shadow_map_texture, "coord.xy", "coord.z"), ";");
    } else if (config.technique == Technique::pcf) {
        const PcfParams& pcf = config.pcf;
        out.comment(cat("kernel radius: ", format_float(pcf.radius),
                        " scene units on the receiver, in shadow-map uv, at most half the map"));
        out.line(value(config, "float", "radius", cat("min(", format_float(pcf.radius), " * penumbra_uvPerUnit(coord.w), 0.5)")));
        if (pcf.pattern == TapPattern::grid)
            write_comparison_taps(out, config, grid_taps(pcf.grid_size), pcf.grid_size, "grid row, taps", "radius");
        else
            write_comparison_taps(out, config, poisson_disk(pcf.poisson_taps), 4, "taps", "radius");
    } else {
        write_pcss_body(out, config);
    }
    out.line("}");
    out.blank();
    if (tilt) {
        out.comment("Without a normal there is no tangent plane: every tap compares against the receiver's depth.");
        out.line(signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
        out.line("{");
        out.line("return penumbra_filteredVisibility(worldPos, vec2(0.0));");
        out.line("}");
        out.blank();
    }
    write_normal_visibility(out, config);
}

} // namespace penumbra::detail
