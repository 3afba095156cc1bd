// penumbra/detail/occlusion/emit_fusion.hpp — how penumbraVisibility fuses the slices' occlusion into one
// visibility (Config::fusion, docs/model.md §1.7): each rule's step, the start, the accumulation, the result.
#pragma once

#include "emit_kernel.hpp"

namespace penumbra::detail {

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

// The fused visibility; with near_field, capped by the near field's rays (`near`: the call that marches
// them).
constexpr void write_fusion_result(LineWriter& out, const Config& config, std::string_view near = {}) {
    out.chunk("fusion_result");
    Text fused;
    switch (config.fusion) {
    case Fusion::probabilistic: fused = "penumbra_lit"; break;
    case Fusion::additive: fused = "max(0.0, 1.0 - penumbra_sum)"; break;
    case Fusion::maximum: fused = "1.0 - penumbra_max"; break;
    case Fusion::average:
        out.comment("Soler & Sillion: halfway between the additive and the maximum estimate");
        fused = "1.0 - 0.5 * (min(1.0, penumbra_sum) + penumbra_max)";
        break;
    case Fusion::chained:
    case Fusion::correlated:
    case Fusion::extent:
    case Fusion::clustered: fused = "clamp(penumbra_lit, 0.0, 1.0)"; break;
    }
    if (near.empty()) {
        out.line("return ", fused, ";");
        return;
    }
    out.comment("near field: the slices cannot see an occluder in the receiver's own slice; the rays can");
    out.line("return min(", fused, ", ", near, ");");
}

// Clustered fusion: the slice's coverage in the kernel's four quadrants, into penumbra_quadrants.
// `lookup(quadrant)` reads the four channels over the quadrant kernel named `quadrant`.
template <class Lookup> constexpr void write_quadrants(LineWriter& out, const Config& config, Lookup lookup) {
    out.line(variable(config, "vec4", "penumbra_quadrants", "vec4(0.0)"));
    for (int i = 0; i < 4; ++i) {
        out.line("{");
        out.line(
            value(config, "vec4", "quadrant", cat("penumbra_quadrant(kernel, ", quadrant_corners[i], ")")),
            " // ", quadrant_names[i]);
        out.line("penumbra_quadrants.", channel_name(i), " = dot(", lookup("quadrant"), ", penumbra_i);");
        out.line("}");
    }
}

// Unrolled over slices, from the bottom one up to the light: array, volume, and every mipmap or

} // namespace penumbra::detail
