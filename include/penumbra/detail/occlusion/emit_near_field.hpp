// penumbra/detail/occlusion/emit_near_field.hpp — the near field of penumbraVisibility (near_field,
// docs/model.md §1.7.7): rays from the receiver towards points of the light, marched through the two slice
// thicknesses above it over the slices' nearest depths (penumbra_nearDepth, written by the slicing pass).
// The slices hold an occluder in the receiver's own slice nowhere the fade lets it count, so a contact
// (a foot on the ground, a board over a shelf) is too light without this.
#pragma once

#include "emit_kernel.hpp"

namespace penumbra::detail {

// The rays: the centres of a 3 × 3 grid over the part of the light the kernel covers (offsets in its side).
inline constexpr int near_field_rays_per_axis = 3;
// The steps along each ray: at (j + 0.5) / steps of the reach above the receiver, in slice thicknesses.
inline constexpr int near_field_steps = 4;
inline constexpr double near_field_reach = 2.0; // slice thicknesses: up to two slices above the receiver's

// Ray a (of near_field_rays_per_axis) along one axis: its offset from the kernel's centre, in the kernel's
// side.
constexpr double near_field_offset(int a) { return (a + 0.5) / near_field_rays_per_axis - 0.5; }
// Step j: its height above the receiver, in slice thicknesses.
constexpr double near_field_height(int j) { return (j + 0.5) / near_field_steps * near_field_reach; }
// A stored surface blocks a ray point only when it lies this many slice thicknesses nearer the light than the
// point: above the 1/254 the 8-bit depth is rounded to, below any step.
inline constexpr double near_field_bias = 1.0 / 64.0;

constexpr Text near_field_call(const Config& config) {
    if (!marches_near_field(config)) return {};
    return choose(config.tangent_clip, "penumbra_nearField(p, penumbra_clip)", "penumbra_nearField(p)");
}

constexpr void write_near_field_functions(LineWriter& out, const Config& config) {
    out.chunk("near_field");
    out.comment("Near field: 1 where the ray from light-frame point p towards the light point `offset` (in "
                "the kernel's");
    out.comment("side, from its centre) passes `height` slice thicknesses above p below the surface the "
                "slicing pass kept");
    out.comment("nearest the light in the slice it is in, 0 otherwise.");
    if (config.tangent_clip)
        out.line(
            signature(config, "float", "penumbra_nearBlocked",
                      {{"vec3", "p"}, {"vec3", "penumbra_clip"}, {"vec2", "offset"}, {"float", "height"}}));
    else
        out.line(signature(config, "float", "penumbra_nearBlocked",
                           {{"vec3", "p"}, {"vec2", "offset"}, {"float", "height"}}));
    out.line("{");
    out.line(value(config, "float", "zeta", "p.z - height * penumbra_sliceDepths.y"));
    out.comment(
        "past the last slice nothing was sliced: open (the slicing pass clamps such fragments to it)");
    out.line(if_then(
        config,
        cat("zeta > penumbra_sliceDepths.x + ", format_float(config.slices), " * penumbra_sliceDepths.y"),
        "return 0.0;"));
    out.comment("the ray meets the plane at depth zeta where the light point meets the kernel of that plane");
    out.line(value(config, "vec4", "kernel", kernel_call(config)));
    out.line(value(config, "vec2", "uv", "kernel.xy + offset * kernel.z"));
    out.line(value(config, "float", "slice", uniform_slice_of(config, "zeta")));
    out.line(value(config, "vec4", "texel",
                   sample_layer_level(config, "penumbra_nearDepth", "uv", "floor(slice / 4.0)", "0.0")));
    out.line(value(config, "float", "stored",
                   cat("dot(texel, ",
                       construct(config, "vec4",
                                 compare(config, "equal", cat("vec4(", modulo(config, "slice", "4.0"), ")"),
                                         "vec4(0.0, 1.0, 2.0, 3.0)")),
                       ")")));
    out.comment(
        "the stored surface's depth: 1 - f * 254/255 with f its place in the slice from the slice's top");
    out.line(value(config, "float", "surface",
                   cat("penumbra_sliceDepths.x + (slice + (1.0 - stored) * ", format_float(255.0 / 254.0),
                       ") * penumbra_sliceDepths.y")));
    out.line("return ",
             conditional(config,
                         cat("stored > ", format_float(0.5 / 255.0), " && surface < zeta - ",
                             format_float(near_field_bias), " * penumbra_sliceDepths.y"),
                         "1.0", "0.0"),
             ";");
    out.line("}");
    out.blank();

    out.comment(cat("Near field: the fraction of ",
                    format_int(near_field_rays_per_axis * near_field_rays_per_axis),
                    " rays from p towards the light that no surface within ", format_float(near_field_reach),
                    " slice thicknesses above p blocks"));
    out.comment(cat("(", format_int(near_field_steps), " steps each; a blocked step blocks the ray)."));
    if (config.tangent_clip)
        out.line(
            signature(config, "float", "penumbra_nearField", {{"vec3", "p"}, {"vec3", "penumbra_clip"}}));
    else
        out.line(signature(config, "float", "penumbra_nearField", {{"vec3", "p"}}));
    out.line("{");
    out.line(variable(config, "float", "penumbra_open", "0.0"));
    const int n = near_field_rays_per_axis;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const Text offset = cat("vec2(", format_float(near_field_offset(a)), ", ",
                                    format_float(near_field_offset(b)), ")");
            out.line("// ray ", format_int(a * n + b), ": towards the light point ", offset,
                     " of the kernel's side");
            out.line("{");
            out.line(variable(config, "float", "blocked", "0.0"));
            for (int j = 0; j < near_field_steps; ++j) {
                const Text height = format_float(near_field_height(j));
                out.line("blocked = max(blocked, penumbra_nearBlocked(p, ",
                         choose(config.tangent_clip, "penumbra_clip, ", ""), offset, ", ", height,
                         ")); // step ", format_int(j), ": ", height, " slices above p");
            }
            out.line("penumbra_open += 1.0 - blocked;");
            out.line("}");
        }
    out.line("return penumbra_open * ", format_float(1.0 / (n * n)), ";");
    out.line("}");
    out.blank();
}

} // namespace penumbra::detail
