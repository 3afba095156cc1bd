// penumbra/detail/occlusion/emit_visibility.hpp — float penumbraVisibility(vec3 worldPos), specialized.
//
// Everything the configuration fixes is baked in as literals: slice count, resolution, levels,
// slice plane indices, tile offsets. The static loop is written out iteration by iteration
// (docs/model.md §3): over filter levels for N-buffer/Gaussian atlases (paper Algorithm 2), over slices
// for everything else. A slice's channel is picked by dot(texel, i) with i a one-hot vec4 that
// rotates by i.yzwx from one slice to the next one up (towards the light), so no code branches
// on the slice index.
#pragma once

#include "parameters.hpp"

namespace penumbra::detail {

// Gaussian levels are à-trous blurs whose standard deviation at level l is about 2^l / sqrt(6)
// texels; a disk of diameter D has a standard deviation of D / 4 per axis, so a kernel of side
// D texels reads level log2(D) + log2(sqrt(6) / 4) (see emit_prefilter.hpp).
inline constexpr double gaussian_level_bias = -0.70751874963942190927; // log2(sqrt(6) / 4)

struct VisibilityConstants {
    Text R, L, T, inv_T, S_minus_1;
};

constexpr VisibilityConstants constants(const Config& config) {
    return {format_float(config.resolution), format_float(max_level(config)), format_float(texture_count(config)),
            format_float(1.0 / texture_count(config)), format_float(config.slices - 1)};
}

// `resolution` and `max_level` are GLSL float expressions: baked literals in the specialized code,
// uniforms in the generic reference (emit_generic.hpp).
// The kernel's centre and side: assigned again by the tangent clip (WGSL: var), set once without it (let).
constexpr Text kernel_local(const Config& config, std::string_view type, std::string_view name, std::string_view init) {
    if (config.tangent_clip) return variable(config, type, name, init);
    return value(config, type, name, init);
}

constexpr void write_kernel_function(LineWriter& out, const Config& config, std::string_view resolution,
                                     std::string_view max_level) {
    out.chunk("kernel");
    out.comment("Kernel on the slice plane at depth zeta, seen from light-frame point p (docs/model.md §1.4, §1.9):");
    out.comment("xy = centre (uv of the slice's texture), z = side (uv), w = filter level.");
    if (config.tangent_clip) {
        out.comment("clip: the part of the light above the receiver's tangent plane (penumbra_tangentClip)");
        out.line(signature(config, "vec4", "penumbra_kernel", {{"vec3", "p"}, {"float", "zeta"}, {"vec3", "clip"}}));
    } else {
        out.line(signature(config, "vec4", "penumbra_kernel", {{"vec3", "p"}, {"float", "zeta"}}));
    }
    out.line("{");
    if (config.light == Light::rect) {
        out.comment("rays from p to the light rectangle cut the plane in a square; w and h cancel out of its side");
        out.line(value(config, "float", "scale", "penumbra_copDistance / (p.z * (penumbra_copDistance + zeta))"));
        out.line(kernel_local(config, "vec2", "centre", "0.5 + p.xy * (zeta * scale) / penumbra_lightSize"));
        out.line(kernel_local(config, "float", "side", "max(p.z - zeta, 0.0) * scale"));
    } else {
        out.comment("journal §3.5: orthographic slicing, the cone towards the sun grows linearly with distance");
        out.line(kernel_local(config, "vec2", "centre", "0.5 + p.xy / (2.0 * penumbra_windowHalfSize)"));
        out.line(kernel_local(config, "float", "side", "max(p.z - zeta, 0.0) * penumbra_tanAngularRadius / penumbra_windowHalfSize"));
    }
    if (config.tangent_clip) {
        out.comment("the light's unit square maps affinely onto the kernel: the clipped part is the square of");
        out.comment("its shorter side at its centre, so the kernel never reaches behind the tangent plane");
        out.line("centre += clip.xy * side;");
        out.line("side *= clip.z;");
    }
    const Text bias = choose(config.filter == Filter::gaussian, cat(" + (", format_float(gaussian_level_bias), ")"), Text());
    out.comment("windows narrower than one texel read level 0");
    out.line(value(config, "float", "level", cat("clamp(log2(max(side * ", resolution, ", 1.0))", bias, ", 0.0, ", max_level, ")")));
    out.line("return vec4(centre, side, level);");
    out.line("}");
    out.blank();
}

constexpr void write_kernel_function(LineWriter& out, const Config& config) {
    const VisibilityConstants k = constants(config);
    write_kernel_function(out, config, k.R, k.L);
}

// How the loops call the kernel function.
constexpr Text kernel_call(const Config& config) {
    return choose(config.tangent_clip, "penumbra_kernel(p, zeta, penumbra_clip)", "penumbra_kernel(p, zeta)");
}

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
    out.comment("The irradiance, over pi, at p (unit normal n) from the part `part` of the light's unit square (xy centre,");
    out.comment("z side); the part of the light below the tangent plane, which the clip leaves where it cuts aslant, counts 0");
    out.line(signature(config, "float", "penumbra_irradianceOf", {{"vec3", "p"}, {"vec3", "n"}, {"vec3", "part"}}));
    out.line("{");
    out.line(value(config, "vec2", "lo", "((part.xy - vec2(0.5 * part.z)) * penumbra_lightSize - p.xy) / p.z"));
    out.line(value(config, "vec2", "hi", "((part.xy + vec2(0.5 * part.z)) * penumbra_lightSize - p.xy) / p.z"));
    out.line("return max(penumbra_formFactorCorner(hi, n) - penumbra_formFactorCorner(vec2(lo.x, hi.y), n)");
    out.line("    - penumbra_formFactorCorner(vec2(hi.x, lo.y), n) + penumbra_formFactorCorner(lo, n), 0.0);");
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
}

// Config::irradiance_window: the visibility of the clip and of the irradiance window's core, mixed. A loop
// whose bound the compiler cannot fold keeps one copy of the unrolled slice loop in the program.
constexpr void write_windowed_visibility_function(LineWriter& out, const Config& config) {
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

// The receiver in the light frame, p, at the start of every penumbraVisibility (and its generic twin).
constexpr void write_light_frame_point(LineWriter& out, const Config& config) {
    out.line(
        variable(config, "vec3", "p",
                 cat("(", transform(config, "penumbra_lightFromWorld", "vec4(worldPos, 1.0)"), ").xyz")));
    out.line("p.z = max(p.z, 1e-6); // points on or behind the light plane");
}
// The generic reference program's (GLSL only).
constexpr void write_light_frame_point(LineWriter& out) { write_light_frame_point(out, Config{}); }

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
    if (config.irradiance_window) {
        out.comment("weighed by the irradiance at the receiver, before it moves (docs/model.md §1.7.5)");
        out.line(value(config, "vec4", "penumbra_window", "penumbra_irradianceWindow(p, n, penumbra_clip)"));
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

// Adaptive placement with the fade: each plane's ramp runs over the slice below it (the one a point
// crosses while the ramp is active), so the fade takes that thickness. Both loops visit the planes
// from the bottom up and keep the plane below in penumbra_below (one fetch per slice); below the
// last plane lies a virtual one, a last slice's thickness further.
constexpr bool fades_over_own_thickness(const Config& config) {
    return config.self_shadow_fade && places_slices_adaptively(config);
}

// The depth the fade ramps over, Config::fade_ramp of `thickness` (a GLSL expression): `thickness`
// itself for the paper's ramp over the whole slice.
constexpr Text fade_ramp_depth(const Config& config, std::string_view thickness) {
    return choose(config.fade_ramp == 1.0, Text(thickness), cat("(", thickness, " * ", format_float(config.fade_ramp), ")"));
}

constexpr Text fade_ramp_words(const Config& config) {
    return choose(config.fade_ramp == 1.0, Text("the slice"), cat(format_float(config.fade_ramp), " of the slice"));
}

constexpr void write_weight_function(LineWriter& out, const Config& config) {
    out.chunk("fade");
    if (fades_over_own_thickness(config)) {
        out.comment(cat("paper §3.4.2: 0 for planes at or below the point, a ramp over ", fade_ramp_words(config),
                        " below the plane, then 1"));
        out.line(signature(config, "float", "penumbra_weight", {{"float", "zPoint"}, {"float", "zeta"}, {"float", "thickness"}}));
        out.line("{");
        out.line("return clamp((zPoint - zeta) / ", fade_ramp_depth(config, "thickness"), ", 0.0, 1.0);");
    } else if (config.self_shadow_fade) {
        out.comment(cat("paper §3.4.2: 0 for planes at or below the point, a ramp over ", fade_ramp_words(config),
                        " above the point, then 1"));
        out.line(signature(config, "float", "penumbra_weight", {{"float", "zPoint"}, {"float", "zeta"}}));
        out.line("{");
        out.line("return clamp((zPoint - zeta) / ", fade_ramp_depth(config, "penumbra_sliceDepths.y"), ", 0.0, 1.0);");
    } else {
        out.comment("fade off: planes strictly above the point count fully, the others not at all");
        out.line(signature(config, "float", "penumbra_weight", {{"float", "zPoint"}, {"float", "zeta"}}));
        out.line("{");
        out.line("return 1.0 - step(zPoint, zeta);");
    }
    out.line("}");
    out.blank();
}

// penumbra_below before the bottom plane: the virtual plane a last slice's thickness below it, so
// the last plane's ramp runs over the last slice's own thickness.
constexpr void write_virtual_plane(LineWriter& out, const Config& config) {
    const Text S = format_int(config.slices), S1 = format_int(config.slices - 1);
    out.line(variable(config, "float", "penumbra_below",
                      cat("2.0 * penumbra_boundary(", S, ") - penumbra_boundary(", S1, ")")),
             " // below the bottom plane");
}

// How the loops call the fade function.
constexpr Text weight_call(const Config& config) {
    return choose(fades_over_own_thickness(config), "penumbra_weight(p.z, zeta, thickness)", "penumbra_weight(p.z, zeta)");
}

// N-buffer level l stores at a texel the mean of the 2^l-texel window anchored there, so a window
// centred at c is read at c - 2^(l-1) texels, plus half a texel to land on the texel centre. A
// reduced level (level_spacing s > 1) has texel j anchored at level-0 texel s·j, its centre s/2
// texels further: the read moves by 2^(l-1) - s/2.
constexpr Text nbuffer_shift(const Config& config, int level) {
    return format_float((0.5 * (1 << level) - 0.5 * level_spacing(config, level)) / config.resolution);
}

// Where the atlas's level loop reads level `level` for the kernel's centre coordinate `axis`
// ("kernel.x"): N-buffer levels at their window anchor; Gaussian levels at the centre, where a
// reduced level's texel j (the blur at level-0 texel s·j) is read (s - 1)/2 texels further.
constexpr Text level_read_coordinate(const Config& config, int level, std::string_view axis) {
    if (config.filter == Filter::nbuffer) return cat(axis, " - ", nbuffer_shift(config, level));
    const int spacing = level_spacing(config, level);
    if (spacing == 1) return cat(axis, " - 0.0");
    return cat(axis, " + ", format_float(0.5 * (spacing - 1) / config.resolution));
}

// Reads the filtered occlusion of all four channels for a kernel; one function per storage so the
// unrolled part stays one line per slice. Explicit LOD everywhere: the walk of the level loop is
// non-uniform control flow, where implicit derivatives are undefined.
constexpr void write_lookup_function(LineWriter& out, const Config& config) {
    const VisibilityConstants k = constants(config);
    out.chunk("lookup");
    if (config.filter == Filter::mipmap) {
        out.comment("paper §3.2: hardware trilinear filtering, level chosen explicitly");
        out.line(signature(config, "vec4", "penumbra_filtered", {{"vec4", "kernel"}, {"float", "tile"}}));
        out.line("{");
        if (config.packing == Packing::atlas)
            out.line("return ",
                     sample_level(config, "penumbra_occlusionAtlas", cat("vec2((tile + kernel.x) * ", k.inv_T, ", kernel.y)"),
                                  "kernel.w"),
                     ";");
        else
            out.line("return ", sample_layer_level(config, "penumbra_occlusion", "kernel.xy", "tile", "kernel.w"), ";");
        out.line("}");
    } else if (config.filter == Filter::sat) {
        const Text R1 = format_float(config.resolution + 1);
        out.comment("Crow 1984: prefix sum at texel corner X (in texels) lives at the centre of texel X of an");
        out.comment("(R+1)-texel tile; bilinear filtering between corners is exact for box-shaped coverage");
        out.line(signature(config, "vec4", "penumbra_prefix", {{"vec2", "corner"}, {"float", "tile"}}));
        out.line("{");
        if (!binds_samplers_apart(config)) {
            out.line("vec2 uv = (corner + 0.5) / ", R1, ";");
            if (config.packing == Packing::atlas)
                out.line("return textureLod(penumbra_satAtlas, vec2((tile + uv.x) * ", k.inv_T, ", uv.y), 0.0);");
            else
                out.line("return textureLod(penumbra_sat, vec3(uv, tile), 0.0);");
        } else {
            // WebGPU filters no 32-bit float texture without an optional feature: the bilinear read by hand
            const bool atlas = config.packing == Packing::atlas;
            const Text last = format_int(config.resolution); // the tile's last texel
            out.comment("WebGPU filters no 32-bit float texture (without an optional feature): the bilinear read by hand,");
            out.comment("the four texels around the corner (clamped to the tile) weighted by its fraction");
            out.line(value(config, "vec2", "base", "floor(corner)"));
            out.line(value(config, "vec2", "f", "corner - base"));
            const Text tile_index = construct(config, "int", "tile");
            out.line(value(config, "ivec2", "a",
                           cat("min(", construct(config, "ivec2", "base"), ", ",
                               construct(config, "ivec2", last), ")")));
            out.line(value(config, "ivec2", "b",
                           cat("min(a + ", construct(config, "ivec2", "1"), ", ",
                               construct(config, "ivec2", last), ")")));
            const Text offset = choose(
                atlas,
                cat(" + ", construct(config, "ivec2",
                                     cat(tile_index, " * ", format_int(config.resolution + 1), ", 0"))),
                Text());
            auto load = [&](std::string_view x, std::string_view y) {
                const Text texel = cat(construct(config, "ivec2", cat(x, ".x, ", y, ".y")), offset);
                return atlas ? fetch(config, "penumbra_satAtlas", texel, "0")
                             : fetch_layer(config, "penumbra_sat", texel, tile_index, "0");
            };
            out.line(value(config, "vec4", "bottom", cat("mix(", load("a", "a"), ", ", load("b", "a"), ", f.x)")));
            out.line(value(config, "vec4", "top", cat("mix(", load("a", "b"), ", ", load("b", "b"), ", f.x)")));
            out.line("return mix(bottom, top, f.y);");
        }
        out.line("}");
        out.blank();
        out.comment("exact box mean: the window is clipped to the texture, outside counts as unoccluded");
        out.line(signature(config, "vec4", "penumbra_filtered", {{"vec4", "kernel"}, {"float", "tile"}}));
        out.line("{");
        out.line(value(config, "float", "side", cat("max(kernel.z * ", k.R, ", 1.0)")));
        out.line(value(config, "vec2", "lo", clamp_vector(config, "vec2", cat("kernel.xy * ", k.R, " - 0.5 * side"), "0.0", k.R)));
        out.line(value(config, "vec2", "hi", clamp_vector(config, "vec2", cat("kernel.xy * ", k.R, " + 0.5 * side"), "0.0", k.R)));
        out.line(declaration(config, "vec4", "sum"), "penumbra_prefix(hi, tile) - penumbra_prefix(vec2(lo.x, hi.y), tile)");
        out.line("    - penumbra_prefix(vec2(hi.x, lo.y), tile) + penumbra_prefix(lo, tile);");
        out.line("return ", saturate(config, "sum / (side * side)"), ";");
        out.line("}");
    } else if (config.packing == Packing::array) {
        const bool nbuffer = config.filter == Filter::nbuffer;
        out.comment(nbuffer ? "N-buffers: two levels around the kernel's, each read at its window anchor, then a lerp"
                            : "Gaussian levels: two levels around the kernel's, then a lerp");
        out.line(signature(config, "vec4", "penumbra_filtered", {{"vec4", "kernel"}, {"float", "tile"}}));
        out.line("{");
        out.line(value(config, "float", "lo", "floor(kernel.w)"));
        out.line(value(config, "float", "hi", cat("min(lo + 1.0, ", k.L, ")")));
        if (nbuffer) {
            out.line(value(config, "vec2", "shiftLo", cat("vec2((exp2(lo - 1.0) - 0.5) / ", k.R, ")")));
            out.line(value(config, "vec2", "shiftHi", cat("vec2((exp2(hi - 1.0) - 0.5) / ", k.R, ")")));
        } else {
            out.line(value(config, "vec2", "shiftLo", "vec2(0.0)"));
            out.line(value(config, "vec2", "shiftHi", "vec2(0.0)"));
        }
        out.line(value(config, "vec4", "texelLo",
                       sample_layer_level(config, "penumbra_levels", "kernel.xy - shiftLo", cat("lo * ", k.T, " + tile"), "0.0")));
        out.line(value(config, "vec4", "texelHi",
                       sample_layer_level(config, "penumbra_levels", "kernel.xy - shiftHi", cat("hi * ", k.T, " + tile"), "0.0")));
        out.line("return mix(texelLo, texelHi, kernel.w - lo);");
        out.line("}");
    } else if (config.packing == Packing::volume) {
        out.comment("paper §3.7: levels along the depth of a 3D texture, the hardware interpolates between them;");
        out.comment("both levels are read at one position, so the N-buffer anchor follows the fractional level");
        for (int t = 0; t < texture_count(config); ++t) {
            const Text name = cat("penumbra_filtered", format_int(t));
            out.line(signature(config, "vec4", name, {{"vec4", "kernel"}}));
            out.line("{");
            if (config.filter == Filter::nbuffer)
                out.line(value(config, "vec2", "shift", cat("vec2((exp2(kernel.w - 1.0) - 0.5) / ", k.R, ")")));
            else
                out.line(value(config, "vec2", "shift", "vec2(0.0)"));
            out.line("return ",
                     sample_level(config, volume_name(t),
                                  cat("vec3(kernel.xy - shift, (kernel.w + 0.5) / ", format_float(max_level(config) + 1), ")"), "0.0"),
                     ";");
            out.line("}");
        }
    }
    out.blank();
}

// Correlated fusion (docs/model.md §1.7): the step of the chain from the slice visited before (q, kernel
// `prev`, `prevKernel`) to this one. The two slices block the light point t of the kernel's unit square
// where their masks cover c + side·t; for one occluder seen in both, the same point of it is hit by light
// points displaced by the parallax between the kernels, whose RMS over the light is
// sqrt(dc² + dside²/12) per axis. The occluder's size is taken as sqrt(q side²) of whichever slice sees the
// larger covered area, so the fraction of it both slices still share is (1 - shift/size) per axis: the
// weight between nested slices (the union is the larger one, chained fusion) and independent ones (the
// product). Generic program and oracle share it.
// The body both the correlated and the extent step share: the parallax between the kernels, then the
// weight between nested and independent slices for an occluder of size `feature` (a GLSL expression, and
// the comment saying where that size comes from).
constexpr void write_parallax_step_body(LineWriter& out, const Config& config, std::string_view feature_comment,
                                        std::string_view feature) {
    out.comment("parallax between the two kernels, RMS over the light's points, per axis (uv)");
    out.line(value(config, "vec2", "parallax", "kernel.xy - prevKernel.xy"));
    out.line(value(config, "float", "grow", "kernel.z - prevKernel.z"));
    out.line(value(config, "vec2", "shift", "sqrt(parallax * parallax + vec2(grow * grow / 12.0))"));
    out.comment(feature_comment);
    out.line(value(config, "float", "feature", feature));
    out.line(value(config, "vec2", "overlap", saturate(config, "1.0 - shift / max(feature, 1e-12)")));
    out.comment("blocked by both: nested (the smaller) when the occluder overlaps itself, independent (product) when not");
    out.line(value(config, "float", "both", "mix(q * prev, min(q, prev), overlap.x * overlap.y)"));
    out.line("return (1.0 - q - prev + both) / max(1.0 - prev, 1e-6);");
    out.line("}");
    out.blank();
}

constexpr void write_correlated_step_function(LineWriter& out, const Config& config) {
    out.chunk("fusion");
    out.comment("correlated fusion: light let through by this slice given the one visited before, docs/model.md §1.7");
    out.line(signature(config, "float", "penumbra_correlatedStep",
                       {{"float", "q"}, {"vec4", "kernel"}, {"float", "prev"}, {"vec4", "prevKernel"}}));
    out.line("{");
    write_parallax_step_body(out, config,
                             "the size of the occluder both kernels see (uv): at least the larger area either kernel sees covered",
                             "sqrt(max(q * kernel.z * kernel.z, prev * prevKernel.z * prevKernel.z))");
}

// The generic reference program's (GLSL only).
constexpr void write_correlated_step_function(LineWriter& out) { write_correlated_step_function(out, Config{}); }

// Extent fusion (docs/model.md §1.7.2): correlated fusion whose occluder size is read from the data. The
// covered area within the kernel is only a lower bound of the occluder's: a solid's edge that crosses the
// kernel covers part of it, and the parallax then decorrelates what is one occluder. The same slice read
// over a window twice the kernel's side (`area`: uv², the larger of the two covered areas) tells an
// occluder inside the kernel (the same area) from one that extends past it (up to four times the area).
// Generic program and oracle share it.
constexpr void write_extent_step_function(LineWriter& out, const Config& config) {
    out.chunk("fusion");
    out.comment("extent fusion: correlated fusion, the occluder's size from a window twice the kernel's side, docs/model.md §1.7.2");
    out.line(signature(config, "float", "penumbra_extentStep",
                       {{"float", "q"}, {"vec4", "kernel"}, {"float", "area"}, {"float", "prev"}, {"vec4", "prevKernel"},
                        {"float", "prevArea"}}));
    out.line("{");
    write_parallax_step_body(out, config, "the occluder's size (uv): the larger covered area either slice sees around its kernel",
                             "sqrt(max(area, prevArea))");
}

// The filter level of a window `factor` times the kernel's side, as penumbra_kernel picks levels.
// `resolution` and `max_level` as for write_kernel_function.
constexpr void write_window_level_function(LineWriter& out, const Config& config, std::string_view name, std::string_view factor,
                                           std::string_view comment, std::string_view resolution, std::string_view max_level) {
    out.chunk("fusion");
    out.comment(comment);
    out.line(signature(config, "float", name, {{"vec4", "kernel"}}));
    out.line("{");
    const Text bias = choose(config.filter == Filter::gaussian, cat(" + (", format_float(gaussian_level_bias), ")"), Text());
    out.line("return clamp(log2(max(", factor, " * kernel.z * ", resolution, ", 1.0))", bias, ", 0.0, ", max_level, ");");
    out.line("}");
    out.blank();
}

// The filter level of a window twice the kernel's side (extent and clustered fusion).
constexpr void write_wide_level_function(LineWriter& out, const Config& config, std::string_view resolution,
                                         std::string_view max_level) {
    write_window_level_function(out, config, "penumbra_wideLevel", "2.0",
                                "filter level of a window twice the kernel's side (extent fusion)", resolution, max_level);
}

// Clustered fusion (docs/model.md §1.7.3): the covered area extent fusion reads is shared by however many
// occluders lie in the kernel, counted from the coverage of the kernel's four quadrants. Their deviations from
// the mean split into three orthogonal patterns: two gradients and a saddle. An edge, or any smooth occluder
// larger than the kernel, is linear across it (no saddle): along an axis its coverage spreads by
// var = mean² and it counts as one (a diagonal one through the centre, var = mean² / 2, as two).
// N small occluders thrown at random fall into the quadrants as a binomial, spreading by var = 3 mean² / N
// and evenly over the three patterns. So N = c mean² / var, c from 1 (no saddle) to 3 (the saddle's share
// of the spread a third or more). The occluder's size for the parallax is then one occluder's,
// sqrt(area / N). Generic program and oracle share it.
constexpr void write_cluster_functions(LineWriter& out, const Config& config, std::string_view resolution,
                                       std::string_view max_level) {
    write_window_level_function(out, config, "penumbra_quarterLevel", "0.5",
                                "filter level of a window half the kernel's side: one quadrant (clustered fusion)", resolution,
                                max_level);
    out.comment("the kernel of one quadrant: corner (-1 or 1 per axis) picks which");
    out.line(signature(config, "vec4", "penumbra_quadrant", {{"vec4", "kernel"}, {"vec2", "corner"}}));
    out.line("{");
    out.line("return vec4(kernel.xy + 0.25 * kernel.z * corner, 0.5 * kernel.z, penumbra_quarterLevel(kernel));");
    out.line("}");
    out.blank();
    out.comment("clustered fusion: how many occluders share the covered area, from the spread of the four quadrants'");
    out.comment("coverage (lower left, lower right, upper left, upper right); at least one");
    out.line(signature(config, "float", "penumbra_clusterCount", {{"vec4", "quadrants"}}));
    out.line("{");
    out.line(value(config, "float", "m", "0.25 * (quadrants.x + quadrants.y + quadrants.z + quadrants.w)"));
    out.line(value(config, "vec4", "deviation", "quadrants - vec4(m)"));
    out.line(value(config, "float", "spread", "0.25 * dot(deviation, deviation)"));
    out.comment("the saddle pattern's share of the spread: 0 for an edge, a third on average for scattered occluders");
    out.line(value(config, "float", "saddle", "0.5 * (deviation.x - deviation.y - deviation.z + deviation.w)"));
    out.line(value(config, "float", "scattered", "min(0.75 * saddle * saddle / max(spread, 1e-10), 1.0)"));
    out.line("return max((1.0 + 2.0 * scattered) * m * m / max(spread, 1e-10), 1.0);");
    out.line("}");
    out.blank();
}

// What clustered fusion divides extent's covered area by: the occluders sharing it.
inline constexpr std::string_view clustered_area_divisor = " / penumbra_clusterCount(penumbra_quadrants)";

// The four quadrant corners, in the order penumbra_clusterCount's vector holds them.
inline constexpr std::array<std::string_view, 4> quadrant_corners{"vec2(-1.0, -1.0)", "vec2(1.0, -1.0)", "vec2(-1.0, 1.0)",
                                                                  "vec2(1.0, 1.0)"};

// The covered area (uv²) extent fusion takes for a slice: `fade` times the larger of the kernel's coverage
// and four times the doubled window's (`wide`, a channel of a vec4 expression), times the kernel's area.
constexpr Text extent_area(std::string_view fade, std::string_view texel_channel, std::string_view wide_channel) {
    return cat(fade, " * max(", texel_channel, ", 4.0 * ", wide_channel, ") * kernel.z * kernel.z");
}

// The generic reference program's (GLSL only).
constexpr void write_extent_step_function(LineWriter& out) { write_extent_step_function(out, Config{}); }

constexpr void write_fusion_start(LineWriter& out, const Config& config) {
    out.chunk("fusion");
    switch (config.fusion) {
    case Fusion::probabilistic: out.line(variable(config, "float", "penumbra_lit", "1.0"), " // paper eq. (5): product of (1 - q)"); break;
    case Fusion::additive: out.line(variable(config, "float", "penumbra_sum", "0.0")); break;
    case Fusion::maximum: out.line(variable(config, "float", "penumbra_max", "0.0")); break;
    case Fusion::average:
        out.line(variable(config, "float", "penumbra_sum", "0.0"));
        out.line(variable(config, "float", "penumbra_max", "0.0"));
        break;
    case Fusion::chained:
        out.comment("chained fusion: eq. (5) assumes independent slices, but the leak fix (paper §3.4.1) copies every");
        out.comment("surface into the next slice and a solid covers consecutive slices alike. Neighbours are taken");
        out.comment("as nested (fused by maximum), slices further apart as independent (product): a chain whose");
        out.comment("step from the previous slice's q to this one's lets through (1 - max(q, prev)) / (1 - prev).");
        out.line(variable(config, "float", "penumbra_lit", "1.0"));
        out.line(variable(config, "float", "penumbra_prev", "0.0"), " // q of the slice visited before (its neighbour)");
        break;
    case Fusion::correlated:
        out.comment("correlated fusion: neighbours between nested (chained) and independent (product), weighted by");
        out.comment("how much of the occluder the two kernels see survives the parallax between them");
        out.line(variable(config, "float", "penumbra_lit", "1.0"));
        out.line(variable(config, "float", "penumbra_prev", "0.0"), " // q of the slice visited before (its neighbour)");
        out.line(variable(config, "vec4", "penumbra_prevKernel", "vec4(0.0)"), " // and its kernel");
        break;
    case Fusion::extent:
    case Fusion::clustered: {
        const bool clustered = config.fusion == Fusion::clustered;
        if (clustered) {
            out.comment("clustered fusion: extent fusion, the covered area shared by the occluders counted from the");
            out.comment("spread of the kernel's four quadrants, so a crowd's or a canopy's neighbours stay independent");
        } else {
            out.comment("extent fusion: correlated fusion, the occluder's size from the covered area in a window twice");
            out.comment("the kernel's side, so an edge of a solid that crosses the kernel stays nested");
        }
        out.line(variable(config, "float", "penumbra_lit", "1.0"));
        out.line(variable(config, "float", "penumbra_prev", "0.0"), " // q of the slice visited before (its neighbour)");
        out.line(variable(config, "vec4", "penumbra_prevKernel", "vec4(0.0)"), " // its kernel");
        out.line(variable(config, "float", "penumbra_prevArea", "0.0"),
                 choose(clustered, " // and one occluder's area", " // and its covered area"));
        break;
    }
    }
}

constexpr void write_accumulate(LineWriter& out, const Config& config) {
    switch (config.fusion) {
    case Fusion::probabilistic: out.line("penumbra_lit *= 1.0 - q;"); break;
    case Fusion::additive: out.line("penumbra_sum += q;"); break;
    case Fusion::maximum: out.line("penumbra_max = max(penumbra_max, q);"); break;
    case Fusion::average:
        out.line("penumbra_sum += q;");
        out.line("penumbra_max = max(penumbra_max, q);");
        break;
    case Fusion::chained:
        out.line("penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);");
        out.line("penumbra_prev = q;");
        break;
    case Fusion::correlated:
        out.line("penumbra_lit *= penumbra_correlatedStep(q, kernel, penumbra_prev, penumbra_prevKernel);");
        out.line("penumbra_prev = q;");
        out.line("penumbra_prevKernel = kernel;");
        break;
    case Fusion::extent:
    case Fusion::clustered:
        out.line("penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);");
        out.line("penumbra_prev = q;");
        out.line("penumbra_prevKernel = kernel;");
        out.line("penumbra_prevArea = area;");
        break;
    }
}

constexpr void write_fusion_result(LineWriter& out, const Config& config) {
    out.chunk("fusion_result");
    switch (config.fusion) {
    case Fusion::probabilistic: out.line("return penumbra_lit;"); break;
    case Fusion::additive: out.line("return max(0.0, 1.0 - penumbra_sum);"); break;
    case Fusion::maximum: out.line("return 1.0 - penumbra_max;"); break;
    case Fusion::average:
        out.comment("Soler & Sillion: halfway between the additive and the maximum estimate");
        out.line("return 1.0 - 0.5 * (min(1.0, penumbra_sum) + penumbra_max);");
        break;
    case Fusion::chained:
    case Fusion::correlated:
    case Fusion::extent:
    case Fusion::clustered: out.line("return clamp(penumbra_lit, 0.0, 1.0);"); break;
    }
}

// Clustered fusion: the slice's coverage in the kernel's four quadrants, into penumbra_quadrants.
// `lookup(quadrant)` reads the four channels over the quadrant kernel named `quadrant`.
template <class Lookup> constexpr void write_quadrants(LineWriter& out, const Config& config, Lookup lookup) {
    constexpr std::array<std::string_view, 4> names{"lower left", "lower right", "upper left", "upper right"};
    out.line(variable(config, "vec4", "penumbra_quadrants", "vec4(0.0)"));
    for (int i = 0; i < 4; ++i) {
        out.line("{");
        out.line(value(config, "vec4", "quadrant", cat("penumbra_quadrant(kernel, ", quadrant_corners[i], ")")), " // ",
                 names[i]);
        out.line("penumbra_quadrants.", channel_name(i), " = dot(", lookup("quadrant"), ", penumbra_i);");
        out.line("}");
    }
}

// Unrolled over slices, from the bottom one up to the light: array, volume, and every mipmap or
// summed-area-table layout (their level is chosen by the lookup, not by the texture).
constexpr void write_slice_loop(LineWriter& out, const Config& config) {
    out.chunk("slice_loop");
    out.comment("static loop over the slices, unrolled; i selects the slice's channel");
    out.line(variable(config, "vec4", "penumbra_i", one_hot((config.slices - 1) % 4)));
    if (fades_over_own_thickness(config))
        write_virtual_plane(out, config);
    for (int s = config.slices - 1; s >= 0; --s) {
        const int tile = s / 4;
        if (places_slices_adaptively(config)) {
            out.line("// slice ", format_int(s), ": texture ", format_int(tile), ", channel ", channel_name(s % 4),
                     ", bottom plane at boundary ", format_int(s + 1));
            out.line("{");
            out.line(value(config, "float", "zeta", cat("penumbra_boundary(", format_int(s + 1), ")")));
            if (fades_over_own_thickness(config)) {
                out.line(value(config, "float", "thickness", "penumbra_below - zeta"), " // the slice below the plane");
                out.line("penumbra_below = zeta;");
            }
        } else {
            out.line("// slice ", format_int(s), ": texture ", format_int(tile), ", channel ", channel_name(s % 4),
                     ", bottom plane at z0 + ", format_int(s + 1), " * thickness");
            out.line("{");
            out.line(value(config, "float", "zeta", cat("penumbra_sliceDepths.x + ", format_float(s + 1), " * penumbra_sliceDepths.y")));
        }
        out.line(value(config, "vec4", "kernel", kernel_call(config)));
        const Text lookup = choose(config.packing == Packing::volume, cat("penumbra_filtered", format_int(tile), "(kernel)"),
                                   cat("penumbra_filtered(kernel, ", format_float(tile), ")"));
        if (reads_doubled_window(config.fusion)) {
            const Text wide = choose(config.packing == Packing::volume,
                                     cat("penumbra_filtered", format_int(tile), "(penumbra_wide)"),
                                     cat("penumbra_filtered(penumbra_wide, ", format_float(tile), ")"));
            out.line(value(config, "float", "fade", weight_call(config)));
            out.line(value(config, "float", "coverage", cat("dot(", lookup, ", penumbra_i)")));
            out.line(value(config, "float", "q", "fade * coverage"));
            out.comment("the same slice over a window twice the kernel's side: how far the occluder extends");
            out.line(value(config, "vec4", "penumbra_wide", "vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel))"));
            Text area = extent_area("fade", "coverage", cat("dot(", wide, ", penumbra_i)"));
            if (config.fusion == Fusion::clustered) {
                out.comment("the kernel's four quadrants: how many occluders share the covered area");
                write_quadrants(out, config, [&](std::string_view quadrant) {
                    return choose(config.packing == Packing::volume, cat("penumbra_filtered", format_int(tile), "(", quadrant, ")"),
                                  cat("penumbra_filtered(", quadrant, ", ", format_float(tile), ")"));
                });
                area = cat(area, clustered_area_divisor);
            }
            out.line(value(config, "float", "area", area));
        } else {
            out.line(value(config, "float", "q", cat(weight_call(config), " * dot(", lookup, ", penumbra_i)")));
        }
        write_accumulate(out, config);
        out.line("}");
        if (s > 0) out.line("penumbra_i = penumbra_i.yzwx;");
    }
}

// paper Algorithm 2, atlas of N-buffer or Gaussian levels: a static loop over levels, unrolled,
// textures indexed statically. Within a level a short dynamic walk visits the slices whose
// kernel falls in that level, so every slice above the point gets exactly one lookup at its own
// kernel size (Algorithm 2 as printed reads one slice per level and drops the others).
constexpr void write_level_loop(LineWriter& out, const Config& config) {
    const VisibilityConstants k = constants(config);
    const int levels = max_level(config);
    out.chunk("level_loop");
    out.comment("start at the nearest slice above the point; slices below it have weight 0");
    if (places_slices_adaptively(config)) {
        out.comment("(adaptive placement: one less than the number of boundaries above the point)");
        write_boundary_search(out, config, "penumbra_above", "p.z", config.slices);
        out.line(variable(config, "float", "penumbra_k", construct(config, "float", "penumbra_above - 1")));
        if (fades_over_own_thickness(config)) {
            write_virtual_plane(out, config);
            out.comment("the plane below the first slice visited, when it is not the last");
            out.line(if_then(config, cat("penumbra_above < ", format_int(config.slices)),
                             "penumbra_below = penumbra_boundary(penumbra_above + 1);"));
        }
    } else {
        out.line(variable(config, "float", "penumbra_k",
                          cat("clamp(ceil((p.z - penumbra_sliceDepths.x) / penumbra_sliceDepths.y) - 2.0, -1.0, ", k.S_minus_1, ")")));
    }
    out.line(variable(config, "vec4", "penumbra_i",
                      construct(config, "vec4",
                                compare(config, "equal", cat("vec4(", modulo(config, "max(penumbra_k, 0.0)", "4.0"), ")"),
                                        "vec4(0.0, 1.0, 2.0, 3.0)"))));
    out.line(variable(config, "float", "penumbra_delta", cat("floor(max(penumbra_k, 0.0) / 4.0) * ", k.inv_T)),
             " // horizontal offset of the slice's tile");
    for (int level = 0; level <= levels; ++level) {
        const bool last = level == levels;
        const Text lo = atlas_level_name(level);
        if (last)
            out.line("// level ", format_int(level), ": the remaining slices, windows of ", format_int(1 << level),
                     " texels and more");
        else
            out.line("// level ", format_int(level), ": windows of ", format_int(1 << level), " to ",
                     format_int(2 << level), " texels");
        out.line("while (penumbra_k >= 0.0) {");
        if (places_slices_adaptively(config)) {
            out.line(value(config, "float", "zeta", cat("penumbra_boundary(", construct(config, "int", "penumbra_k"), " + 1)")));
            if (fades_over_own_thickness(config)) {
                out.line(value(config, "float", "thickness", "penumbra_below - zeta"), " // the slice below the plane");
                out.line("penumbra_below = zeta;");
            }
        } else {
            out.line(value(config, "float", "zeta", "penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y"));
        }
        out.line(value(config, "vec4", "kernel", kernel_call(config)));
        auto read = [&](int l) {
            return sample_level(config, atlas_level_name(l),
                                cat("vec2(penumbra_delta + (", level_read_coordinate(config, l, "kernel.x"), ") * ", k.inv_T, ", ",
                                    level_read_coordinate(config, l, "kernel.y"), ")"),
                                "0.0");
        };
        if (reads_doubled_window(config.fusion)) {
            // the doubled window's level lies between this level and two above it (clamped to the last)
            const Text L1 = format_float(level + 1);
            if (!last) out.line(if_then(config, cat("kernel.w >= ", L1), "break;"));
            out.line(value(config, "vec4", "penumbra_lo", read(level)));
            if (last) {
                out.line(value(config, "vec4", "texel", "penumbra_lo"));
                out.line(value(config, "vec4", "penumbra_wide", "penumbra_lo"), " // no wider window than the last level's");
            } else {
                out.line(value(config, "vec4", "penumbra_hi", read(level + 1)));
                out.line(value(config, "vec4", "texel", cat("mix(penumbra_lo, penumbra_hi, kernel.w - ", format_float(level), ")")));
                out.comment("the same slice over a window twice the kernel's side: how far the occluder extends");
                out.line(value(config, "float", "penumbra_wideAt", "penumbra_wideLevel(kernel)"));
                if (level + 1 == levels) {
                    out.line(value(config, "vec4", "penumbra_wide",
                                   cat("mix(penumbra_lo, penumbra_hi, penumbra_wideAt - ", format_float(level), ")")));
                } else if (binds_samplers_apart(config)) { // select() evaluates both: the same reads
                    out.line(value(config, "vec4", "penumbra_wide",
                                   conditional(config, cat("penumbra_wideAt < ", L1),
                                               cat("mix(penumbra_lo, penumbra_hi, penumbra_wideAt - ", format_float(level), ")"),
                                               cat("mix(penumbra_hi, ", read(level + 2), ", penumbra_wideAt - ", L1, ")"))));
                } else {
                    out.line("vec4 penumbra_wide = penumbra_wideAt < ", L1, " ? mix(penumbra_lo, penumbra_hi, penumbra_wideAt - ",
                             format_float(level), ")");
                    out.line("    : mix(penumbra_hi, ", read(level + 2), ", penumbra_wideAt - ", L1, ");");
                }
            }
            out.line(value(config, "float", "fade", weight_call(config)));
            out.line(value(config, "float", "coverage", "dot(texel, penumbra_i)"));
            out.line(value(config, "float", "q", "fade * coverage"));
            Text area = extent_area("fade", "coverage", "dot(penumbra_wide, penumbra_i)");
            if (config.fusion == Fusion::clustered) {
                auto read_quadrant = [&](int l) {
                    return sample_level(config, atlas_level_name(l),
                                        cat("vec2(penumbra_delta + (", level_read_coordinate(config, l, "quadrant.x"), ") * ", k.inv_T,
                                            ", ", level_read_coordinate(config, l, "quadrant.y"), ")"),
                                        "0.0");
                };
                out.comment("the kernel's four quadrants, read a level below: how many occluders share the covered area");
                write_quadrants(out, config, [&](std::string_view quadrant) {
                    // a quadrant's level lies between the level below this one and this one (level 0: level 0)
                    if (level == 0) return read_quadrant(0);
                    return cat("mix(", read_quadrant(level - 1), ", ", read_quadrant(level), ", ", quadrant, ".w - ",
                               format_float(level - 1), ")");
                });
                area = cat(area, clustered_area_divisor);
            }
            out.line(value(config, "float", "area", area));
        } else {
            if (last) {
                out.line(value(config, "vec4", "texel", read(level)));
            } else {
                out.line(if_then(config, cat("kernel.w >= ", format_float(level + 1)), "break;"));
                out.line(declaration(config, "vec4", "texel"), "mix(", read(level), ",");
                out.line("    ", read(level + 1), ", kernel.w - ", format_float(level), ");");
            }
            out.line(value(config, "float", "q", cat(weight_call(config), " * dot(texel, penumbra_i)")));
        }
        write_accumulate(out, config);
        out.comment("next slice up: the channel rotates; wrapping from r to a moves one tile left");
        out.line("penumbra_k -= 1.0;");
        out.line("penumbra_i = penumbra_i.yzwx;");
        out.line("penumbra_delta -= penumbra_i.w * ", k.inv_T, ";");
        out.line("}");
    }
}

constexpr bool uses_level_loop(const Config& config) {
    return config.packing == Packing::atlas && has_level_images(config);
}

// Declarations and functions of penumbraVisibility, ready to paste into any stage of the target.
constexpr void write_visibility(LineWriter& out, const Config& config, int& next_binding) {
    write_params(out, config, visibility_params(config), "PenumbraVisibility", next_binding);
    if (places_slices_adaptively(config)) write_boundary_function(out, config);
    write_kernel_function(out, config);
    write_weight_function(out, config);
    if (!uses_level_loop(config)) write_lookup_function(out, config);
    if (config.tangent_clip) write_tangent_clip_function(out, config);
    if (config.irradiance_window) write_irradiance_window_function(out, config);
    if (config.fusion == Fusion::correlated) write_correlated_step_function(out, config);
    if (reads_doubled_window(config.fusion)) {
        const VisibilityConstants k = constants(config);
        write_extent_step_function(out, config);
        write_wide_level_function(out, config, k.R, k.L);
        if (config.fusion == Fusion::clustered) write_cluster_functions(out, config, k.R, k.L);
    }
    out.chunk("visibility");
    if (config.tangent_clip) {
        out.comment("The fused visibility at light-frame point p of the part of the light that penumbra_clip keeps.");
        out.line(signature(config, "float", "penumbra_clippedVisibility", {{"vec3", "p"}, {"vec3", "penumbra_clip"}}));
    } else {
        out.comment("Fraction of the light visible from worldPos: 1 lit, 0 in umbra.");
        out.line(signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    }
    out.line("{");
    if (!config.tangent_clip) write_light_frame_point(out, config);
    write_fusion_start(out, config);
    if (uses_level_loop(config))
        write_level_loop(out, config);
    else
        write_slice_loop(out, config);
    write_fusion_result(out, config);
    out.line("}");
    if (!config.tangent_clip) return;
    out.blank();
    if (config.irradiance_window) write_windowed_visibility_function(out, config);
    out.chunk("visibility");
    out.comment("Fraction of the part of the light above the tangent plane at worldPos (worldNormal: the normal of");
    out.comment("the side being lit, any length but not zero) that is visible: 1 lit, 0 in umbra.");
    out.line(signature(config, "float", visibility_with_normal(config), {{"vec3", "worldPos"}, {"vec3", "worldNormal"}}));
    out.line("{");
    write_light_frame_point(out, config);
    write_tangent_clip_setup(out, config);
    out.line(choose(config.irradiance_window, "return penumbra_windowedVisibility(p, penumbra_clip, penumbra_window);",
                    "return penumbra_clippedVisibility(p, penumbra_clip);"));
    out.line("}");
    out.blank();
    out.comment(choose(config.irradiance_window,
                       "Without a normal: the visible fraction of the whole light's irradiance (no clip),",
                       "Without a normal: the fraction of the whole light that is visible (the paper's kernels, no clip),"));
    out.comment("for shaders written against penumbraVisibility(vec3 worldPos) of every technique.");
    out.line(signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    out.line("{");
    write_light_frame_point(out, config);
    if (config.irradiance_window)
        out.line("return penumbra_windowedVisibility(p, vec3(0.0, 0.0, 1.0), penumbra_irradianceWindow(p, vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0)));");
    else
        out.line("return penumbra_clippedVisibility(p, vec3(0.0, 0.0, 1.0));");
    out.line("}");
}

// The includable snippet penumbra_visibility.glsl: no #version, declarations from binding 0.
constexpr Text visibility_snippet(const Config& config) {
    LineWriter out;
    if (is_wgsl(config)) {
        out.line("// Penumbra ", version_string, " - penumbra_visibility.wgsl: ",
                 choose(config.tangent_clip,
                        cat(signature(config, "float", "penumbraVisibilityWithNormal", {{"vec3", "worldPos"}, {"vec3", "worldNormal"}}),
                            " (clipped to the tangent plane) and "),
                        Text()),
                 signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
        out.line("// ", describe(config));
        out.comment("Add to a module of the shading stage. Bindings start at 0 in group 0; call penumbra_loadVisibility()"
                    " first in the entry point.");
    } else if (is_hlsl(config)) {
        out.line("// Penumbra ", version_string,
                 " - penumbra_visibility.hlsl: float penumbraVisibility(float3 worldPos",
                 choose(config.tangent_clip,
                        ", float3 worldNormal) (clipped to the tangent plane) and (float3 worldPos", ""),
                 ")");
        out.line("// ", describe(config));
        out.comment(
            "#include in a pixel shader. Registers start at 0 in space 0 (b#, t#, s# numbered together).");
    } else {
        out.line("// Penumbra ", version_string, " - penumbra_visibility.glsl: float penumbraVisibility(vec3 worldPos",
                 choose(config.tangent_clip, ", vec3 worldNormal) (clipped to the tangent plane) and (vec3 worldPos", ""),
                 ")");
        out.line("// ", describe(config));
        out.comment("Include after the #version line of a stage for this target. Bindings start at 0.");
    }
    out.blank();
    write_precision(out, config); // ES 3.00: highp defaults, so `#version 300 es` + this text compiles
    int binding = 0;
    write_visibility(out, config, binding);
    return out.take();
}

} // namespace penumbra::detail
