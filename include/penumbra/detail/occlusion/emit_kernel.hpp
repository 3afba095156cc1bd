// penumbra/detail/occlusion/emit_kernel.hpp — the kernel of penumbraVisibility: the square of the light
// seen from a receiver, projected into a slice, and the filter level that covers it (docs/model.md §3).
#pragma once

#include "parameters.hpp"

namespace penumbra::detail {

// The four quadrants of a square of the light's unit square (a kernel, the tangent clip's part), in the order
// the vec4s of clustered fusion (penumbra_clusterCount) and of the irradiance window's quadrants
// (penumbra_ringShares) hold them: each one's corner (-1 or 1 per axis) and name.
inline constexpr std::array<std::string_view, 4> quadrant_corners{"vec2(-1.0, -1.0)", "vec2(1.0, -1.0)",
                                                                  "vec2(-1.0, 1.0)", "vec2(1.0, 1.0)"};
inline constexpr std::array<std::string_view, 4> quadrant_names{"lower left", "lower right", "upper left",
                                                                "upper right"};

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

} // namespace penumbra::detail
