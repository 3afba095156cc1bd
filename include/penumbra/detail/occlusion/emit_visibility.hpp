// penumbra/detail/occlusion/emit_visibility.hpp — float penumbraVisibility(vec3 worldPos), specialized.
//
// Everything the configuration fixes is baked in as literals: slice count, resolution, levels,
// slice plane indices, tile offsets. The static loop is written out iteration by iteration
// (docs/model.md §3): over filter levels for N-buffer/Gaussian atlases (paper Algorithm 2), over slices
// for everything else. A slice's channel is picked by dot(texel, i) with i a one-hot vec4 that
// rotates by i.yzwx from one slice to the next one up (towards the light), so no code branches
// on the slice index.
// The parts: emit_kernel.hpp (the kernel), emit_tangent_clip.hpp (the receiver's side of the light),
// emit_lookup.hpp (fade and reads), emit_fusion.hpp (fusion rules); this file writes the loops and the
// function itself.
#pragma once

#include "emit_fusion.hpp"
#include "emit_lookup.hpp"
#include "emit_near_field.hpp"
#include "emit_tangent_clip.hpp"

namespace penumbra::detail {

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
    if (weighs_irradiance(config)) write_irradiance_window_function(out, config);
    if (config.fusion == Fusion::correlated) write_correlated_step_function(out, config);
    if (reads_doubled_window(config.fusion)) {
        const VisibilityConstants k = constants(config);
        write_extent_step_function(out, config);
        write_wide_level_function(out, config, k.R, k.L);
        if (config.fusion == Fusion::clustered) write_cluster_functions(out, config, k.R, k.L);
    }
    if (marches_near_field(config)) write_near_field_functions(out, config);
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
    write_fusion_result(out, config, near_field_call(config));
    out.line("}");
    if (!config.tangent_clip) return;
    out.blank();
    if (weighs_irradiance(config)) write_windowed_visibility_function(out, config);
    out.chunk("visibility");
    out.comment("Fraction of the part of the light above the tangent plane at worldPos (worldNormal: the normal of");
    out.comment("the side being lit, any length but not zero) that is visible: 1 lit, 0 in umbra.");
    out.line(signature(config, "float", visibility_with_normal(config), {{"vec3", "worldPos"}, {"vec3", "worldNormal"}}));
    out.line("{");
    write_light_frame_point(out, config);
    write_tangent_clip_setup(out, config);
    out.line(clipped_visibility_return(config));
    out.line("}");
    out.blank();
    out.comment(choose(
        weighs_irradiance(config),
        "Without a normal: the visible fraction of the whole light's irradiance (no clip),",
        "Without a normal: the fraction of the whole light that is visible (the paper's kernels, no clip),"));
    out.comment("for shaders written against penumbraVisibility(vec3 worldPos) of every technique.");
    out.line(signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    out.line("{");
    write_light_frame_point(out, config);
    if (weighs_quadrants(config)) {
        out.line(value(config, "vec4", "penumbra_window",
                       "penumbra_irradianceWindow(p, vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0))"));
        out.line("return penumbra_windowedVisibility(p, vec3(0.0, 0.0, 1.0), penumbra_window, "
                 "penumbra_ringShares(p, vec3(0.0, 0.0, -1.0), "
                 "vec3(0.0, 0.0, 1.0), penumbra_window.xyz));");
    } else if (weighs_irradiance(config))
        out.line("return penumbra_windowedVisibility(p, vec3(0.0, 0.0, 1.0), penumbra_irradianceWindow(p, vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0)));");
    else
        out.line("return penumbra_clippedVisibility(p, vec3(0.0, 0.0, 1.0));");
    out.line("}");
}

// The includable snippet penumbra_visibility.glsl: no #version, declarations from binding 0.
constexpr Text visibility_snippet(const Config& config) {
    LineWriter out;
    // With the tangent clip the snippet also defines the visibility clipped to the receiver's plane.
    Text signatures;
    if (is_wgsl(config)) {
        signatures = cat(choose(config.tangent_clip,
                                cat(signature(config, "float", "penumbraVisibilityWithNormal",
                                              {{"vec3", "worldPos"}, {"vec3", "worldNormal"}}),
                                    " (clipped to the tangent plane) and "),
                                Text()),
                         signature(config, "float", "penumbraVisibility", {{"vec3", "worldPos"}}));
    } else {
        const std::string_view vec3 = is_hlsl(config) ? "float3" : "vec3";
        signatures = cat("float penumbraVisibility(", vec3, " worldPos",
                         choose(config.tangent_clip,
                                cat(", ", vec3, " worldNormal) (clipped to the tangent plane) and (", vec3, " worldPos"),
                                Text()),
                         ")");
    }
    write_snippet_header(out, config, signatures);
    out.blank();
    write_precision(out, config); // ES 3.00: highp defaults, so `#version 300 es` + this text compiles
    int binding = 0;
    write_visibility(out, config, binding);
    return out.take();
}

} // namespace penumbra::detail
