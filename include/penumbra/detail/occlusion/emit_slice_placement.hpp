// penumbra/detail/occlusion/emit_slice_placement.hpp — adaptive slice placement (paper §5, future work:
// "slice placement"): where the slice boundaries lie along the light normal, computed on the GPU
// from the scene itself, with no read-back to the CPU.
//
// Uniform slices spend as many slices on empty depth ranges as on occupied ones, and every
// occluder is flattened onto its slice's bottom plane, up to a slice thickness below where it is.
// Two passes move the boundaries to where the geometry is:
//   1. depth_bins (draw_scene, four draws of 16 bins): the scene from the slicing camera at 64²,
//      each fragment marking its bin of the uniform slices' depth range split in 64 (RGBA8, blend
//      MAX, like the slicing pass), then a mip chain of the bins;
//   2. slice_boundaries (one row of S + 1 fragments): a bin is occupied when any cell of the
//      chain's 8×8 level holds geometry in it; half of the depth weight is spread evenly over the
//      bins, half over the occupied ones, and boundary k sits at the quantile k / S of that weight
//      (linear within a bin). The even half keeps every slice at most twice the uniform thickness
//      and none empty of weight; the ends stay the bounds' range.
// The slicing pass and penumbraVisibility read the boundaries with texelFetch (parameters.hpp).
#pragma once

#include "emit_slicing.hpp"

namespace penumbra::detail {

// Share of the depth weight spread evenly over the bins (the rest goes to the occupied bins).
inline constexpr double adaptive_even_share = 0.5;

constexpr Text depth_bins_vertex(const Config& config) {
    return slicing_camera_vertex(config, "adaptive slice placement, depth-bin pre-pass, vertex stage",
                                 depth_bins_params(), "PenumbraPass");
}

constexpr Text depth_bins_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "adaptive slice placement, depth-bin pre-pass, fragment stage (blend MAX, clear to 0)");
    out.chunk("depth_bins_outputs");
    out.line(stage_variable(out, config, "in", 0, "float", "penumbra_depth", has_varying_locations(config)));
    write_alpha_test_fragment_inputs(out, config);
    for (int t = 0; t < depth_bins_per_draw / 4; ++t)
        out.line(stage_variable(out, config, "out", t, "vec4", cat("penumbra_bins", format_int(t)), true),
                 " // bins penumbra_firstBin + ", format_int(4 * t), " to + ", format_int(4 * t + 3));
    out.blank();
    int binding = 0;
    write_params(out, config, depth_bins_params(), "PenumbraPass", binding);
    write_alpha_test_params(out, config, binding);
    out.chunk("depth_bins_main");
    out.line(main_signature(config));
    out.line("{");
    write_alpha_test_discard(out, config);
    write_light_plane_clip(out, config);
    out.comment(cat("paper §5, slice placement: the uniform slices' depth range in ", format_int(depth_bins),
                    " bins; bin b holds (z0 + b * w, z0 + (b + 1) * w]"));
    out.line(value(config, "float", "width", cat("penumbra_sliceDepths.y * ", format_float(double(config.slices) / depth_bins))));
    out.line(value(config, "float", "bin",
                   cat("clamp(ceil((penumbra_depth - penumbra_sliceDepths.x) / width) - 1.0, 0.0, ", format_float(depth_bins - 1),
                       ") - ", construct(config, "float", "penumbra_firstBin"))));
    for (int t = 0; t < depth_bins_per_draw / 4; ++t)
        out.line("penumbra_bins", format_int(t), " = ",
                 construct(config, "vec4",
                           compare(config, "equal", "vec4(bin)",
                                   cat("vec4(", format_float(4 * t), ", ", format_float(4 * t + 1), ", ", format_float(4 * t + 2),
                                       ", ", format_float(4 * t + 3), ")"))),
                 ";");
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

constexpr Text slice_boundaries_fragment(const Config& config) {
    const int cells = depth_bins_resolution >> depth_bins_read_level;
    const Text S = format_float(config.slices), B = format_float(depth_bins);
    LineWriter out;
    write_preamble(out, config, "adaptive slice placement, boundaries from the depth bins, fragment stage");
    out.chunk("slice_boundaries_outputs");
    out.line(stage_variable(out, config, "out", 0, "uint", "penumbra_boundary", true),
             " // bits of the boundary's depth (scene units)");
    declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
    out.blank();
    int binding = 0;
    write_params(out, config, slice_boundaries_params(), "PenumbraPass", binding);
    out.chunk("slice_boundaries_main");
    out.line(main_signature(config));
    out.line("{");
    out.comment("paper §5, slice placement: boundaries where the geometry is, so fewer slices go to empty depths and");
    out.comment("occluders lie closer to their slice's plane; half the weight stays uniform, so no slice is more");
    out.comment("than twice the uniform thickness");
    out.line(value(config, "int", "k", construct(config, "int", cat(frag_coord(config), ".x"))),
             " // boundary k: the top of slice k; k = ", format_int(config.slices), ": the last slice's bottom");
    out.comment(cat("a bin is occupied when any ", format_int(cells), "x", format_int(cells), " cell of level ",
                    format_int(depth_bins_read_level), " holds geometry in it (one texel of level 0 stays non-zero there)"));
    out.line(array_variable(config, "float", "occupied", format_int(depth_bins)));
    out.line(variable(config, "float", "count", "0.0"));
    out.line(counted_loop(config, "layer", format_int(depth_bins / 4)));
    out.line("{");
    out.line(variable(config, "vec4", "texel", "vec4(0.0)"));
    out.line(counted_loop(config, "y", format_int(cells)), " {");
    out.line(counted_loop(config, "x", format_int(cells)), " {");
    out.line("texel = max(texel, ",
             fetch_layer(config, "penumbra_depthBins", choose(is_wgsl(config), Text("vec2i(x, y)"), Text("x, y")), "layer",
                         format_int(depth_bins_read_level)),
             ");");
    out.line("}");
    out.line("}");
    out.line(value(config, "vec4", "bins", construct(config, "vec4", compare(config, "greaterThan", "texel", "vec4(0.0)"))));
    out.line("occupied[4 * layer] = bins.r;");
    out.line("occupied[4 * layer + 1] = bins.g;");
    out.line("occupied[4 * layer + 2] = bins.b;");
    out.line("occupied[4 * layer + 3] = bins.a;");
    out.line("count += dot(bins, vec4(1.0));");
    out.line("}");
    out.comment(cat("weight of a bin: ", format_float(adaptive_even_share),
                    " spread evenly, the rest over the occupied bins (all of it evenly in an empty scene)"));
    out.line(value(config, "float", "even",
                   conditional(config, "count > 0.0", format_float(adaptive_even_share / depth_bins), format_float(1.0 / depth_bins))));
    out.line(value(config, "float", "share",
                   conditional(config, "count > 0.0", cat(format_float(1.0 - adaptive_even_share), " / count"), "0.0")));
    out.comment("boundary k at the quantile k / S of the weight, linear within its bin");
    out.line(value(config, "float", "quantile", cat(construct(config, "float", "k"), " / ", S)));
    out.line(variable(config, "float", "below", "0.0"));
    out.line(variable(config, "float", "position", B));
    out.line(counted_loop(config, "b", format_int(depth_bins)));
    out.line("{");
    out.line(value(config, "float", "weight", "even + share * occupied[b]"));
    out.line("if (below + weight >= quantile)");
    out.line("{");
    out.line("position = ", construct(config, "float", "b"), " + (quantile - below) / weight;");
    out.line("break;");
    out.line("}");
    out.line("below += weight;");
    out.line("}");
    out.line(variable(config, "float", "z",
                      cat("penumbra_sliceDepths.x + min(position, ", B, ") * (penumbra_sliceDepths.y * ",
                          format_float(double(config.slices) / depth_bins), ")")));
    out.comment("the ends are the bounds' range, exactly");
    out.line(if_then(config, "k == 0", "z = penumbra_sliceDepths.x;"));
    out.line(if_then(config, cat("k == ", format_int(config.slices)), cat("z = penumbra_sliceDepths.x + ", S, " * penumbra_sliceDepths.y;")));
    out.line("penumbra_boundary = ", float_bits(config, "uint", "z"), ";");
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

} // namespace penumbra::detail
