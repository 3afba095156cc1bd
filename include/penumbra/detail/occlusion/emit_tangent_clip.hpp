// penumbra/detail/occlusion/emit_tangent_clip.hpp — the receiver's side of the light in
// penumbraVisibility: the tangent clip (the part of the light above the receiver's plane), the irradiance
// window, the receiver in the light frame.
#pragma once

#include "emit_kernel.hpp"

namespace penumbra::detail {

// Config::tangent_clip_offset: slicing-grid texels by which the tangent clip moves a point sideways
// along its normal. A wall's own footprint in a slice is up to two texels wide (perspective spread over
// the slice and its leak-fix copy, and rasterisation), and a level-0 lookup blends the texels within one
// texel of the kernel's centre; but every texel of offset also moves the kernels off the occluders that
// lie within a slice or two of the receiver, which real meshes are full of (a lid's rim, legs under a
// body, creases). docs/model.md §1.9 gives the measurements behind the default.

// Orientation-aware lookup: a surface receives only the part of the light above its tangent
// plane (the cosine term removes the rest), so each kernel is restricted to that part.
constexpr void write_tangent_clip_function(LineWriter& out, const Config& config) {
    out.chunk("tangent_clip");
    out.comment("The part of the light above the tangent plane at p (unit normal n, light frame), in the light's");
    out.comment("unit square [-0.5, 0.5]^2: xy = centre of the clipped rectangle, z = its shorter side. The plane");
    out.comment("is cut along the axis it crosses most steeply, at the other axis' centre line (exact for planes");
    out.comment("parallel to a light axis, the same area otherwise), or where that leaves less, in the corner it spares.");
    out.line(signature(config, "vec3", "penumbra_tangentClip", {{"vec3", "p"}, {"vec3", "n"}}));
    out.line("{");
    if (config.light == Light::rect) {
        out.comment("light point (X w, Y h, 0) is above the plane where n.x X w + n.y Y h > dot(n, p)");
        out.line(value(config, "vec2", "slopes", "n.xy * penumbra_lightSize"));
        out.line(value(config, "float", "level", "dot(n, p)"));
    } else {
        out.comment("direction (X, Y) 2 tan(alpha) sideways, 1 up towards the sun is above where its dot with n > 0");
        out.line(value(config, "vec2", "slopes", "n.xy * (2.0 * penumbra_tanAngularRadius)"));
        out.line(value(config, "float", "level", "n.z"));
    }
    out.line(value(config, "bool", "alongX", "abs(slopes.x) >= abs(slopes.y)"));
    out.line(value(config, "float", "slope", conditional(config, "alongX", "slopes.x", "slopes.y")));
    out.line(value(config, "float", "safe", conditional(config, "slope >= 0.0", "max(slope, 1e-12)", "min(slope, -1e-12)")));
    out.line(value(config, "float", "cut", "clamp(level / safe, -0.5, 0.5)"));
    out.line(value(config, "float", "lo", conditional(config, "safe > 0.0", "cut", "-0.5")));
    out.line(value(config, "float", "hi", conditional(config, "safe > 0.0", "0.5", "cut")));
    out.line(value(config, "float", "mid", "0.5 * (lo + hi)"));
    out.line(variable(config, "vec3", "clip", cat("vec3(", conditional(config, "alongX", "vec2(mid, 0.0)", "vec2(0.0, mid)"), ", hi - lo)")));
    out.comment("a plane that leaves a corner of the light above it (the centre line may lie wholly below): the");
    out.comment("largest square in that corner, where it is larger; 0 where the whole light is below the plane");
    out.line(value(config, "float", "slopeSum", "abs(slopes.x) + abs(slopes.y)"));
    out.line(value(config, "float", "corner", "clamp((0.5 * slopeSum - level) / max(slopeSum, 1e-12), 0.0, 1.0)"));
    out.line("if (corner > clip.z) { clip = vec3(sign(slopes) * (0.5 - 0.5 * corner), corner); }");
    out.line("return clip;");
    out.line("}");
    out.blank();
}

// Config::irradiance_quadrants (docs/model.md §1.7.6): the quadrant `i` (0 lower left, 1 lower right, 2 upper
// left, 3 upper right) of the part `clip` of the light's unit square.
constexpr Text clip_quadrant(std::string_view clip, std::string_view corner) {
    return cat("vec3(", clip, ".xy + 0.25 * ", clip, ".z * ", corner, ", 0.5 * ", clip, ".z)");
}

// Config::irradiance_quadrants: each quadrant's share of the clip's irradiance outside the core, the weights
// of the quadrants' visibilities (the core's is what they leave).
constexpr void write_ring_shares_function(LineWriter& out, const Config& config) {
    out.chunk("tangent_clip");
    out.comment("The rectangle the squares `part` and `core` of the light's unit square share: xy its lower "
                "corner, zw");
    out.comment("its upper one (empty where an upper coordinate is not above the lower)");
    out.line(signature(config, "vec4", "penumbra_sharedRectangle", {{"vec3", "part"}, {"vec3", "core"}}));
    out.line("{");
    out.line("return vec4(max(part.xy - vec2(0.5 * part.z), core.xy - vec2(0.5 * core.z)),");
    out.line("    min(part.xy + vec2(0.5 * part.z), core.xy + vec2(0.5 * core.z)));");
    out.line("}");
    out.blank();
    out.chunk("tangent_clip");
    out.comment("The share of the irradiance at p (unit normal n) within the part `clip` of the light's unit "
                "square that");
    out.comment("each of its quadrants sends outside the core `core` (x lower left, y lower right, z upper "
                "left, w upper right)");
    out.line(signature(config, "vec4", "penumbra_ringShares",
                       {{"vec3", "p"}, {"vec3", "n"}, {"vec3", "clip"}, {"vec3", "core"}}));
    out.line("{");
    out.line(value(config, "float", "whole", "penumbra_irradianceOf(p, n, clip)"));
    out.line(variable(config, "vec4", "shares", "vec4(0.0)"));
    for (int i = 0; i < 4; ++i) {
        out.line("{");
        out.line(value(config, "vec3", "quadrant", clip_quadrant("clip", quadrant_corners[i])), " // ",
                 quadrant_names[i]);
        out.line(value(config, "vec4", "both", "penumbra_sharedRectangle(quadrant, core)"));
        out.line(value(config, "float", "inCore",
                       conditional(config, "both.z > both.x && both.w > both.y",
                                   "penumbra_irradianceBetween(p, n, both.xy, both.zw)", "0.0")));
        out.line("shares.", channel_name(i), " = max(penumbra_irradianceOf(p, n, quadrant) - inCore, 0.0);");
        out.line("}");
    }
    out.comment("an empty clip: the core alone");
    out.line("return ", conditional(config, "whole > 1e-12", "shares / max(whole, 1e-12)", "vec4(0.0)"), ";");
    out.line("}");
    out.blank();
}

// Config::irradiance_window (docs/model.md §1.7.5): the visibility weighs the light by the irradiance each of
// its points sends the receiver, as the shading's unoccluded irradiance does, not by its area. A light point at
// offset d = l - p from a receiver of unit normal n at depth z sends it cos θ_receiver cos θ_light / r², that is
// dot(n, d) z / r⁴, which integrates over a rectangle of the light in closed form (its form factor). The
// weight is approximated by two nested windows: the tangent clip's part, and its core, a square half as wide
// around the weight's peak (the light point straight above a receiver facing the light, moved towards the side
// its normal leans to, by z / sqrt(3) on a wall). Their visibilities, mixed with the weights that
// give the core and the ring around it their true share of the irradiance, are exact for occluders spread
// evenly over each; the slice loop runs once for each window.
constexpr void write_irradiance_window_function(LineWriter& out, const Config& config) {
    out.chunk("tangent_clip");
    out.comment("The irradiance, over pi, that a receiver of unit normal n (light frame) gets from the light's part");
    out.comment("between its foot and the corner a (offsets over its depth): the rectangle's form factor, a corner's term");
    out.line(signature(config, "float", "penumbra_formFactorCorner", {{"vec2", "a"}, {"vec3", "n"}}));
    out.line("{");
    out.line(value(config, "vec2", "s", cat(builtin(config, "inversesqrt"), "(1.0 + a * a)")));
    out.line("return -0.5 * (s.x * atan(a.y * s.x) * (n.x + n.z * a.x) + s.y * atan(a.x * s.y) * (n.y + n.z * a.y));");
    out.line("}");
    out.blank();
    out.chunk("tangent_clip");
    out.comment("The irradiance, over pi, at p (unit normal n) from the rectangle between the corners "
                "`lower` and `upper`");
    out.comment("of the light's unit square; the part of the light below the tangent plane, which the clip "
                "leaves where it");
    out.comment("cuts aslant, counts 0");
    out.line(signature(config, "float", "penumbra_irradianceBetween",
                       {{"vec3", "p"}, {"vec3", "n"}, {"vec2", "lower"}, {"vec2", "upper"}}));
    out.line("{");
    out.line(value(config, "vec2", "lo", "(lower * penumbra_lightSize - p.xy) / p.z"));
    out.line(value(config, "vec2", "hi", "(upper * penumbra_lightSize - p.xy) / p.z"));
    out.line("return max(penumbra_formFactorCorner(hi, n) - penumbra_formFactorCorner(vec2(lo.x, hi.y), n)");
    out.line("    - penumbra_formFactorCorner(vec2(hi.x, lo.y), n) + penumbra_formFactorCorner(lo, n), 0.0);");
    out.line("}");
    out.blank();
    out.chunk("tangent_clip");
    out.comment("The same from the square `part` of the light's unit square (xy centre, z side)");
    out.line(signature(config, "float", "penumbra_irradianceOf",
                       {{"vec3", "p"}, {"vec3", "n"}, {"vec3", "part"}}));
    out.line("{");
    out.line("return penumbra_irradianceBetween(p, n, part.xy - vec2(0.5 * part.z), part.xy + vec2(0.5 * "
             "part.z));");
    out.line("}");
    out.blank();
    out.chunk("tangent_clip");
    out.comment("The irradiance window at p (unit normal n) within the part `clip` of the light's unit square (xy centre,");
    out.comment("z side): xyz the core, a square half the clip's side around the weight's peak, kept inside the clip;");
    out.comment("w the weight of the whole clip's visibility, the core's being 1 - w (docs/model.md §1.7.5)");
    out.line(signature(config, "vec4", "penumbra_irradianceWindow", {{"vec3", "p"}, {"vec3", "n"}, {"vec3", "clip"}}));
    out.line("{");
    out.line(value(config, "float", "side", "0.5 * clip.z"));
    out.comment("the weight's peak: the foot, moved towards the normal's side by up to z / sqrt(3) on a wall");
    out.line(value(config, "float", "facing", "max(-n.z, 0.0)"));
    out.line(value(config, "vec2", "peak", "p.xy + p.z * n.xy / max(2.0 * facing + sqrt(4.0 * facing * facing + 3.0 * dot(n.xy, n.xy)), 1e-6)"));
    out.line(value(config, "vec2", "centre", clamp_vector(config, "vec2", "peak / penumbra_lightSize",
                                                        "clip.xy - vec2(0.5 * side)", "clip.xy + vec2(0.5 * side)")));
    out.line(value(config, "float", "whole", "penumbra_irradianceOf(p, n, clip)"));
    out.line(value(config, "float", "core", "penumbra_irradianceOf(p, n, vec3(centre, side))"));
    out.comment("the ring holds 3/4 of the clip's area and 1 - core / whole of its irradiance; an empty clip is one pass");
    out.line(value(config, "float", "ring", conditional(config, "whole > 1e-12", "(1.0 - core / max(whole, 1e-12)) / 0.75", "1.0")));
    out.line("return vec4(centre, side, clamp(ring, 0.0, 1.0));");
    out.line("}");
    out.blank();
    if (weighs_quadrants(config)) write_ring_shares_function(out, config);
}

// Config::irradiance_window: the visibility of the clip and of the irradiance window's core, mixed. A loop
// whose bound the compiler cannot fold keeps one copy of the unrolled slice loop in the program.
constexpr void write_quadrant_visibility_function(LineWriter& out, const Config& config);

constexpr void write_windowed_visibility_function(LineWriter& out, const Config& config) {
    if (weighs_quadrants(config)) {
        write_quadrant_visibility_function(out, config);
        return;
    }
    out.chunk("visibility");
    out.comment("The visibility at light-frame point p weighed by the irradiance: the clip's with weight window.w, the");
    out.comment("core's (window.xyz) with 1 - window.w; a window whose core carries no weight needs the first only");
    out.line(signature(config, "float", "penumbra_windowedVisibility", {{"vec3", "p"}, {"vec3", "clip"}, {"vec4", "window"}}));
    out.line("{");
    out.line(variable(config, "float", "visibility", "0.0"));
    out.line(value(config, "int", "passes", conditional(config, "window.w < 1.0", "2", "1")));
    out.line(counted_loop(config, "penumbra_pass", "passes"), " {");
    out.line(value(config, "bool", "core", "penumbra_pass == 1"));
    out.line("visibility += (", conditional(config, "core", "1.0 - window.w", "window.w"),
             ") * penumbra_clippedVisibility(p, ", conditional(config, "core", "window.xyz", "clip"), ");");
    out.line("}");
    out.line("return visibility;");
    out.line("}");
    out.blank();
}

// Config::irradiance_quadrants: the core's visibility first, then each quadrant's, whose part outside the
// core (its visibility less the core's share of it) carries that part's share of the irradiance. One loop
// whose bound the compiler cannot fold, as the two windows' (one copy of the unrolled slice loop).
constexpr void write_quadrant_visibility_function(LineWriter& out, const Config& config) {
    out.chunk("visibility");
    out.comment("The visibility at light-frame point p weighed by the irradiance: the core's (window.xyz) "
                "and the four");
    out.comment("quadrants' of the clip, each quadrant's part outside the core with its share of the "
                "irradiance (rings),");
    out.comment("the core with what they leave (docs/model.md §1.7.6)");
    out.line(signature(config, "float", "penumbra_windowedVisibility",
                       {{"vec3", "p"}, {"vec3", "clip"}, {"vec4", "window"}, {"vec4", "rings"}}));
    out.line("{");
    out.line(variable(config, "float", "visibility", "0.0"));
    out.line(variable(config, "float", "core", "1.0"), " // the core's visibility, from the first pass");
    out.line(value(config, "int", "passes", conditional(config, "window.w < 2.0", "5", "1")), " // always 5");
    out.line(counted_loop(config, "penumbra_pass", "passes"), " {");
    out.line(value(config, "int", "quadrant", "penumbra_pass - 1"));
    out.line(value(config, "vec2", "corner",
                   cat("vec2(", conditional(config, "quadrant == 1 || quadrant == 3", "1.0", "-1.0"), ", ",
                       conditional(config, "quadrant >= 2", "1.0", "-1.0"), ")")));
    out.line(value(config, "vec3", "part",
                   conditional(config, "penumbra_pass == 0", "window.xyz", clip_quadrant("clip", "corner"))));
    out.line(value(config, "float", "seen", "penumbra_clippedVisibility(p, part)"));
    out.line("if (penumbra_pass == 0) {");
    out.line("core = seen;");
    out.line("visibility += (1.0 - dot(rings, vec4(1.0))) * seen;");
    out.line("} else {");
    out.comment("the part of the quadrant inside the core, which the core's pass counts");
    out.line(value(config, "vec4", "both", "penumbra_sharedRectangle(part, window.xyz)"));
    out.line(value(config, "vec2", "overlap", "max(both.zw - both.xy, vec2(0.0))"));
    out.line(value(config, "float", "inCore", "overlap.x * overlap.y / max(part.z * part.z, 1e-12)"));
    out.line(value(config, "float", "share",
                   cat("dot(rings, vec4(", conditional(config, "quadrant == 0", "1.0", "0.0"), ", ",
                       conditional(config, "quadrant == 1", "1.0", "0.0"), ", ",
                       conditional(config, "quadrant == 2", "1.0", "0.0"), ", ",
                       conditional(config, "quadrant == 3", "1.0", "0.0"), "))")));
    out.line("visibility += share * ", saturate(config, "(seen - inCore * core) / max(1.0 - inCore, 1e-6)"),
             ";");
    out.line("}");
    out.line("}");
    out.line("return ", saturate(config, "visibility"), ";");
    out.line("}");
    out.blank();
}

// The tangent clip's return in penumbraVisibility: the windowed visibility, or the clip's alone.
constexpr Text clipped_visibility_return(const Config& config) {
    if (weighs_quadrants(config))
        return "return penumbra_windowedVisibility(p, penumbra_clip, penumbra_window, penumbra_rings);";
    if (weighs_irradiance(config))
        return "return penumbra_windowedVisibility(p, penumbra_clip, penumbra_window);";
    return "return penumbra_clippedVisibility(p, penumbra_clip);";
}

// How far outside the slicing pyramid, relative to its half width, a receiver still reads the textures:
// the bounds' own corners lie on the pyramid, within rounding.
inline constexpr double pyramid_margin = 1.001;

// The receiver in the light frame, p, at the start of every penumbraVisibility (and its generic twin).
constexpr void write_light_frame_point(LineWriter& out, const Config& config) {
    out.line(
        variable(config, "vec3", "p",
                 cat("(", transform(config, "penumbra_lightFromWorld", "vec4(worldPos, 1.0)"), ").xyz")));
    out.line("p.z = max(p.z, 1e-6); // points on or behind the light plane");
    if (config.light != Light::rect) return;
    out.comment(
        "a receiver beside the light, outside the slicing pyramid (a room's wall just under the ceiling,");
    out.comment(
        "docs/model.md §1.2b): its kernels would read beyond the textures (the atlas's next tile); what");
    out.comment("could shadow it lies mostly outside the pyramid too, where nothing is sliced: it is left "
                "unshadowed");
    out.line(if_then(
        config,
        cat("max(abs(p.x) / penumbra_lightSize.x, abs(p.y) / penumbra_lightSize.y) * penumbra_copDistance > ",
            format_float(0.5 * pyramid_margin), " * (penumbra_copDistance + p.z)"),
        "return 1.0;"));
}
// The generic reference program's (GLSL only).
constexpr void write_light_frame_point(LineWriter& out, Light light) {
    Config glsl;
    glsl.light = light;
    write_light_frame_point(out, glsl);
}

// GLSL float expressions of the tangent clip's offsets: baked literals in the specialized code,
// uniform expressions in the generic reference (emit_generic.hpp).
struct TangentClipOffsets {
    Text offset_uv;       // Config::tangent_clip_offset in uv of the slicing grid
    Text offset_words;    // the same in texels, for the comment
    Text footprint_reach; // slice thicknesses a slice's content spans (own slice and leak-fix copies); empty: off
    Text footprint_cap_uv; // the footprint's cap in uv of the slicing grid
};

// Slicing texels the footprint move is capped at: surfaces turned nearly edge-on away from the light
// would otherwise move without bound.
inline constexpr double clip_footprint_cap_texels = 4.0;

constexpr TangentClipOffsets tangent_clip_offsets(const Config& config) {
    return {format_float(config.tangent_clip_offset / config.resolution), format_float(config.tangent_clip_offset),
            choose(config.clip_footprint, format_float(1 + leak_fix_reach(config)), Text()),
            format_float(clip_footprint_cap_texels / config.resolution)};
}

// The tangent clip's set-up in penumbraVisibility: the normal in the light frame, the clip, and
// the sideways moves. Every surface is rasterised into the slices it crosses, so without them a
// wall's kernels would sit on the wall's own texels: a fixed one of tangent_clip_offset texels
// (rasterisation and the level-0 blend), and with clip_footprint the footprint of the receiver's own
// tangent plane in the slice above it, whose content spans `reach` slice thicknesses flattened onto
// one plane (docs/model.md §1.9): per unit of depth the plane moves n.z / |n.xy| sideways, and the
// perspective of the slicing projection adds dot(p.xy, n.xy) / (|n.xy| (d + z)). Surfaces facing the
// light have no footprint there (the fade takes their own slice); it is capped for the others.
constexpr void write_tangent_clip_setup(LineWriter& out, const Config& config, const TangentClipOffsets& k) {
    out.line(variable(config, "vec3", "n",
                      transform(config, upper_3x3(config, "penumbra_lightFromWorld"), "worldNormal")));
    out.line("n *= ", builtin(config, "inversesqrt"), "(max(dot(n, n), 1e-20));");
    out.line(value(config, "vec3", "penumbra_clip", "penumbra_tangentClip(p, n)"));
    out.comment("a receiver turned away from all of the light receives none of it: its lookups would read the");
    out.comment("occluders beside it, or none, and light it");
    out.line("if (penumbra_clip.z <= 0.0) { return 0.0; }");
    if (weighs_irradiance(config)) {
        out.comment("weighed by the irradiance at the receiver, before it moves (docs/model.md §1.7.5)");
        out.line(value(config, "vec4", "penumbra_window", "penumbra_irradianceWindow(p, n, penumbra_clip)"));
        if (weighs_quadrants(config))
            out.line(value(config, "vec4", "penumbra_rings",
                           "penumbra_ringShares(p, n, penumbra_clip, penumbra_window.xyz)"));
    }
    const bool rect = config.light == Light::rect;
    if (!k.footprint_reach.empty()) {
        out.comment("footprint of the receiver's own tangent plane in the slice above it, along its normal (scene units)");
        out.line(value(config, "float", "penumbra_across", "max(length(n.xy), 1e-6)"));
        if (rect)
            out.line(value(config, "float", "penumbra_spread",
                           "max(n.z / penumbra_across + dot(p.xy, n.xy) / (penumbra_across * (penumbra_copDistance + p.z)), 0.0)"));
        else
            out.line(value(config, "float", "penumbra_spread", "max(n.z / penumbra_across, 0.0)"));
        out.line(value(config, "float", "penumbra_footprint", cat("penumbra_spread * ", k.footprint_reach, " * penumbra_sliceDepths.y")));
        if (rect)
            out.line(value(config, "float", "penumbra_cap",
                           cat("max(penumbra_lightSize.x, penumbra_lightSize.y) * (penumbra_copDistance + p.z) / penumbra_copDistance * ",
                               k.footprint_cap_uv)));
        else
            out.line(value(config, "float", "penumbra_cap", cat("2.0 * penumbra_windowHalfSize * ", k.footprint_cap_uv)));
    }
    out.comment(cat("move the point ", k.offset_words, " slicing texels sideways along its normal, off its own texels"));
    if (rect)
        out.line("p.xy += n.xy * penumbra_lightSize * ((penumbra_copDistance + p.z) / penumbra_copDistance * ",
                 k.offset_uv, ");");
    else
        out.line("p.xy += n.xy * (2.0 * penumbra_windowHalfSize * ", k.offset_uv, ");");
    if (!k.footprint_reach.empty()) {
        out.comment("and off its own footprint");
        out.line("p.xy += n.xy / penumbra_across * min(penumbra_footprint, penumbra_cap);");
    }
}

constexpr void write_tangent_clip_setup(LineWriter& out, const Config& config) {
    write_tangent_clip_setup(out, config, tangent_clip_offsets(config));
}

} // namespace penumbra::detail
