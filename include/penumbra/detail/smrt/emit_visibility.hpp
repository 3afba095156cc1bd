// penumbra/detail/smrt/emit_visibility.hpp — float penumbraVisibility(vec3 worldPos) for shadow-map
// ray tracing (SMRT), the soft shadows of Unreal Engine 5's virtual shadow maps:
//   rays     smrt.rays per pixel, from the receiver to points spread over the light (the rectangle,
//            or the sun's disc) by a low-discrepancy set (Hammersley) shifted per pixel at random
//            (a Cranley-Patterson rotation: every pixel gets the set's spread, a different one), the
//            shift also turned by smrt.frame for a temporal accumulation;
//   march    smrt.samples per ray through the light's depth map, from the light end toward the
//            receiver, at ((k + jitter) / N)² of the ray: the step grows with the distance from the
//            receiver, dense where contact hardening needs it; the ray is blocked where it crosses a
//            surface of the map (in front of it, then behind it, the surface within the depth the ray
//            went through between the two samples), not where it only passes under an occluder's
//            silhouette (penumbra_smrtRay says why);
//   extrapolation  behind a silhouette the map shows what lies past the occluder's edge: the occluder's
//            last surface (depth slope at most smrt.extrapolate_max_slope) is carried over the gap at
//            its slope, and a ray that went behind it is blocked (0: no extrapolation);
//   bias     the receiver's depth change across one shadow-map texel (its slope from the normal,
//            at most smrt.max_slope_bias), and the rays' origin moved off the receiver along its normal
//            by up to smrt.texel_dither texels at random.
// The method is written from its public description; the names and defaults of the parameters are
// Unreal's console variables' (docs/techniques.md). Counts, offsets, slopes and the pattern are literals;
// the rays are written out one line each, the samples of a ray are a counted loop that stops at a block.
#pragma once

#include "../shadow_map/poisson.hpp"
#include "parameters.hpp"

namespace penumbra::detail {

// Van der Corput's radical inverse in base 2 of i: the second coordinate of the Hammersley set.
constexpr double smrt_radical_inverse(int i) {
    double result = 0.0, digit = 0.5;
    for (int v = i; v > 0; v >>= 1, digit *= 0.5)
        if (v & 1) result += digit;
    return result;
}

// Point i of `rays` on the unit square: ((i + 0.5) / rays, radical inverse of i).
struct SmrtPoint {
    double u, v;
};
constexpr SmrtPoint smrt_pattern_point(int i, int rays) { return {(i + 0.5) / rays, smrt_radical_inverse(i)}; }

// The fractional part of x >= 0, rounded to six decimals: the per-frame turn of the pattern.
constexpr double smrt_fraction(double x) { return x - static_cast<double>(static_cast<long long>(x)); }

// Frame f turns the pattern's shift by f steps of the R2 sequence (Roberts 2018) and the march's
// jitter by f golden-ratio steps: over N frames the shifts are themselves spread evenly.
constexpr double smrt_frame_turn(int frame, int axis) {
    constexpr double steps[] = {0.7548776662466927, 0.5698402909980532, 0.6180339887498949};
    return six_decimals(smrt_fraction(frame * steps[axis]));
}

// penumbra_smrtHash: a PCG step (Jarzynski & Olano 2020); penumbra_smrtRandom: its top 24 bits in [0, 1).
constexpr void write_smrt_random(LineWriter& out, const Config& config) {
    out.chunk("smrt_random");
    out.comment("per-pixel random numbers: a PCG hash of the world position's bits, the same on every API and GPU");
    out.line(signature(config, "uint", "penumbra_smrtHash", {{"uint", "v"}}));
    out.line("{");
    out.line(value(config, "uint", "s", "v * 747796405u + 2891336453u"));
    out.line(value(config, "uint", "w", "((s >> ((s >> 28u) + 4u)) ^ s) * 277803737u"));
    out.line("return (w >> 22u) ^ w;");
    out.line("}");
    out.blank();
    out.line(signature(config, "float", "penumbra_smrtRandom", {{"uint", "h"}}));
    out.line("{");
    out.line("return ", construct(config, "float", "h >> 8u"), " * (1.0 / 16777216.0);");
    out.line("}");
    out.blank();
}

// penumbra_smrtToLight: from a ray's origin (light frame) to the point of the light that `u` (unit
// square) names, up to where the ray leaves the depth map (its near plane).
constexpr void write_smrt_to_light(LineWriter& out, const Config& config) {
    out.chunk("smrt_to_light");
    if (config.light == Light::rect) {
        out.comment("the ray from origin to the point u of the rectangle (light frame: its centre at 0, z = 0),");
        out.comment("cut where it leaves the depth map (the near plane, z = penumbra_shadowDepthRange.x)");
    } else {
        out.comment("the ray from origin towards the point u of the sun's disc (polar map of the unit square), cut");
        out.comment("where it leaves the depth map (the top of the scene, z = penumbra_shadowDepthRange.x)");
    }
    out.line(signature(config, "vec3", "penumbra_smrtToLight", {{"vec3", "origin"}, {"vec2", "u"}}));
    out.line("{");
    out.line(value(config, "float", "above", "max(origin.z - penumbra_shadowDepthRange.x, 0.0)"));
    if (config.light == Light::rect) {
        out.line(value(config, "vec3", "lightPoint", "vec3((u - 0.5) * penumbra_lightSize, 0.0)"));
        out.line("return (lightPoint - origin) * (above / max(origin.z, 1e-6));");
    } else {
        out.line(value(config, "float", "radius", "sqrt(u.y) * penumbra_tanAngularRadius"));
        out.line(value(config, "float", "angle", "6.283185307 * u.x"));
        out.line("return vec3(radius * cos(angle), radius * sin(angle), -1.0) * above;");
    }
    out.line("}");
    out.blank();
}

// penumbra_smrtUV: the depth map's uv of a light-frame point.
constexpr void write_smrt_uv(LineWriter& out, const Config& config) {
    out.chunk("smrt_uv");
    if (config.light == Light::rect) {
        out.comment("shadow-map uv of a light-frame point: perspective from the light centre, square frustum");
        out.line(signature(config, "vec2", "penumbra_smrtUV", {{"vec3", "x"}}));
        out.line("{");
        out.line("return 0.5 + x.xy / (2.0 * penumbra_shadowTanHalfFov * max(x.z, 1e-6));");
    } else {
        out.comment("shadow-map uv of a light-frame point: orthographic along the sun's direction");
        out.line(signature(config, "vec2", "penumbra_smrtUV", {{"vec3", "x"}}));
        out.line("{");
        out.line("return 0.5 + x.xy / (2.0 * penumbra_windowHalfSize);");
    }
    out.line("}");
    out.blank();
}

// penumbra_smrtRay: 1 when the ray reaches the light, 0 when the depth map blocks it. The map holds one
// depth per texel, seen from the light centre: a ray sample behind it is in that surface's shadow from
// the centre, not necessarily inside an occluder (under an occluder's edge it is free space). So a ray is
// blocked where it crosses a surface: in front of the map at one sample, behind it at the next, and the
// surface's depth there within the depth the ray went through between the two (not nearer the light
// than the ray was at the first). A surface nearer than that is a silhouette the ray went under from
// its side, which blocks nothing. And across a silhouette the other way (the map falls back behind the
// ray) the last surface, if its depth slope is at most extrapolate_max_slope, is carried over the gap at
// that slope: a ray behind that continuation passed behind the occluder's edge.
constexpr void write_smrt_ray(LineWriter& out, const Config& config) {
    const SmrtParams& s = config.smrt;
    const bool extrapolates = s.extrapolate_max_slope > 0.0;
    const Text max_slope = format_float(s.extrapolate_max_slope);
    out.chunk("smrt_ray");
    out.line("// one ray: ", format_int(s.samples), " depth-map samples from the light end toward the receiver, at");
    out.comment("((k + jitter) / N)² of the ray (the step grows away from the receiver); 1 lit, 0 blocked");
    out.line(signature(config, "float", "penumbra_smrtRay",
                       {{"vec3", "origin"}, {"vec3", "toLight"}, {"float", "jitter"}, {"float", "bias"}}));
    out.line("{");
    out.line(value(config, "vec2", "range", "penumbra_shadowDepthRange"));
    out.line(variable(config, "float", "lastZ", "0.0"), " // the ray's depth at the previous sample");
    out.line(variable(config, "bool", "front", "false"), " // the previous sample was in front of the map");
    if (extrapolates) {
        out.line(variable(config, "float", "lastDepth", "0.0"), " // the previous sample's map depth (scene units)");
        out.line(variable(config, "vec2", "lastXY", "vec2(0.0)"), " // and where it was, across the light");
        out.line(variable(config, "float", "slope", "0.0"), " // the surface's depth slope between the last two samples");
        out.line(variable(config, "bool", "surface", "false"), " // the last two samples lie on one surface");
    }
    out.line(counted_loop(config, "i", format_int(s.samples)));
    out.line("{");
    out.line(variable(config, "float", "t",
                      cat("(", construct(config, "float", cat(format_int(s.samples - 1), " - i")), " + jitter) * ",
                          format_float(1.0 / s.samples))));
    out.line("t = t * t;");
    out.line(value(config, "vec3", "x", "origin + toLight * t"));
    out.line(value(config, "float", "mapDepth",
                   cat("range.x + ", sample_depth(config, "penumbra_shadowDepth", "penumbra_smrtUV(x)"),
                       " * (range.y - range.x)")));
    out.line(value(config, "bool", "behind", "mapDepth < x.z - bias"));
    out.comment("a crossing: behind the map now, in front of it before, the surface no nearer the light than the ray");
    out.comment("was then (nearer: a silhouette the ray went under); or behind at the light end already");
    out.line(if_then(config, "behind && (i == 0 || (front && mapDepth >= lastZ - bias))", "return 0.0;"));
    if (extrapolates) {
        out.comment("behind a silhouette (the map falls back behind the ray): the last surface, carried over the gap");
        out.comment("at its slope, in front of the ray");
        out.line(value(config, "float", "gap", "max(distance(x.xy, lastXY), 1e-6)"));
        out.line(if_then(config, "!behind && surface && lastDepth + slope * gap < x.z - bias", "return 0.0;"));
        out.line("slope = (mapDepth - lastDepth) / gap;");
        out.line("surface = i > 0 && abs(slope) <= ", max_slope, ";");
        out.line("lastDepth = mapDepth;");
        out.line("lastXY = x.xy;");
    }
    out.line("front = !behind;");
    out.line("lastZ = x.z;");
    out.line("}");
    out.line("return 1.0;");
    out.line("}");
    out.blank();
}

// The light-point line of ray i: fract(point + shift), the per-pixel Cranley-Patterson rotation.
constexpr Text smrt_ray_line(const Config& config, int i) {
    const SmrtPoint q = smrt_pattern_point(i, config.smrt.rays);
    return cat("reached += penumbra_smrtRay(origin, penumbra_smrtToLight(origin, fract(vec2(", format_float(q.u), ", ",
               format_float(q.v), ") + shift)), jitter, bias); // ray ", format_int(i + 1), " of ",
               format_int(config.smrt.rays));
}

// Declarations and functions of penumbraVisibility for SMRT.
constexpr void write_smrt_visibility(LineWriter& out, const Config& config, int& next_binding) {
    const SmrtParams& s = config.smrt;
    const int R = config.shadow_map.resolution;
    write_params(out, config, smrt_visibility_params(config), "PenumbraVisibility", next_binding);
    write_smrt_random(out, config);
    write_smrt_uv(out, config);
    write_smrt_to_light(out, config);
    write_smrt_ray(out, config);
    out.chunk("visibility");
    out.comment(cat("Fraction of the light visible from worldPos: 1 lit, 0 in shadow (smrt: ", format_int(s.rays),
                    " rays of ", format_int(s.samples), " samples)."));
    out.comment("worldNormal: the receiver's side, for the bias and the dither (zero: neither)");
    out.line(signature(config, "float", "penumbra_smrtVisibility", {{"vec3", "worldPos"}, {"vec3", "worldNormal"}}));
    out.line("{");
    out.line(value(config, "vec3", "p", cat("(", transform(config, "penumbra_lightFromWorld", "vec4(worldPos, 1.0)"), ").xyz")));
    out.line(value(config, "vec3", "n",
                   cat("worldNormal * ", builtin(config, "inversesqrt"), "(max(dot(worldNormal, worldNormal), 1e-20))")));
    out.line(value(config, "vec3", "nLight", transform(config, upper_3x3(config, "penumbra_lightFromWorld"), "n")));
    out.comment(cat("per-pixel random numbers from the position's bits", s.frame > 0 ? ", turned for frame " : "",
                    s.frame > 0 ? format_int(s.frame) : Text()));
    out.line(value(config, "uvec3", "bits", float_bits(config, "uvec3", "worldPos")));
    out.line(value(config, "uint", "h1",
                   "penumbra_smrtHash(bits.x ^ penumbra_smrtHash(bits.y ^ penumbra_smrtHash(bits.z)))"));
    out.line(value(config, "uint", "h2", "penumbra_smrtHash(h1)"));
    out.line(value(config, "uint", "h3", "penumbra_smrtHash(h2)"));
    out.line(value(config, "uint", "h4", "penumbra_smrtHash(h3)"));
    if (s.frame > 0) {
        out.line(value(config, "vec2", "shift",
                       cat("fract(vec2(penumbra_smrtRandom(h1), penumbra_smrtRandom(h2)) + vec2(",
                           format_float(smrt_frame_turn(s.frame, 0)), ", ", format_float(smrt_frame_turn(s.frame, 1)),
                           "))")));
        out.line(value(config, "float", "jitter",
                       cat("fract(penumbra_smrtRandom(h3) + ", format_float(smrt_frame_turn(s.frame, 2)), ")")));
    } else {
        out.line(value(config, "vec2", "shift", "vec2(penumbra_smrtRandom(h1), penumbra_smrtRandom(h2))"));
        out.line(value(config, "float", "jitter", "penumbra_smrtRandom(h3)"));
    }
    if (config.light == Light::rect) {
        out.comment("a shadow-map texel at the receiver (scene units); the cosine to the direction towards the light");
        out.line(value(config, "float", "texel",
                       cat("2.0 * penumbra_shadowTanHalfFov * max(p.z, 1e-6) * ", format_float(1.0 / R))));
        out.line(value(config, "float", "cosine", "dot(nLight, -normalize(p))"));
    } else {
        out.comment("a shadow-map texel (scene units); the cosine to the direction towards the sun");
        out.line(value(config, "float", "texel", cat("2.0 * penumbra_windowHalfSize * ", format_float(1.0 / R))));
        out.line(value(config, "float", "cosine", "-nLight.z"));
    }
    out.line("// the receiver bias follows its slope: depth change across one texel, the slope at most ",
             format_float(s.max_slope_bias));
    out.line(value(config, "float", "sine", "sqrt(max(dot(nLight, nLight) - cosine * cosine, 0.0))"));
    out.line(value(config, "float", "bias",
                   cat("texel * min(sine / max(cosine, 1e-3), ", format_float(s.max_slope_bias), ")")));
    out.line("// the rays start off the receiver along its normal, up to ", format_float(s.texel_dither), " texels");
    out.line(value(config, "vec3", "origin",
                   cat("p + nLight * (texel * ", format_float(s.texel_dither), " * penumbra_smrtRandom(h4))")));
    out.line(variable(config, "float", "reached", "0.0"));
    for (int i = 0; i < s.rays; ++i) out.line(smrt_ray_line(config, i));
    out.line("return reached * ", format_float(1.0 / s.rays), ";");
    out.line("}");
    out.blank();
    out.comment("Without a normal: no slope to follow, no dither.");
    out.line(signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    out.line("{");
    out.line("return penumbra_smrtVisibility(worldPos, vec3(0.0));");
    out.line("}");
    out.blank();
    out.comment("With the receiver's normal (the side being lit): the slope-following bias and the dither.");
    out.line(signature(config, "float", visibility_with_normal(config), {{"vec3", "worldPos"}, {"vec3", "worldNormal"}}));
    out.line("{");
    out.line("return penumbra_smrtVisibility(worldPos, worldNormal);");
    out.line("}");
}

// The includable snippet penumbra_visibility.glsl: no #version, declarations from binding 0.
constexpr Text smrt_visibility_snippet(const Config& config) {
    LineWriter out;
    write_snippet_header(out, config, signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    out.blank();
    write_hlsl_names(out, config);
    int binding = 0;
    write_smrt_visibility(out, config, binding);
    return out.take();
}

} // namespace penumbra::detail
