// penumbra/level_bound.hpp — the highest filter level any receiver inside the scene bounds can ask
// for (docs/model.md §2, "Only the levels the kernels reach"), from the slicing frame alone.
//
//   penumbra::SliceFrame frame = penumbra::slice_frame(light, bounds_min, bounds_max, config.slices);
//   config.level_bound = penumbra::kernel_level_bound(frame, config); // then emit: fewer levels
//
// A receiver P at depth z_P sees the plane at depth ζ through a kernel of side
// σ = d·(z_P − ζ)/(z_P·(d + ζ)) (rect, §1.4) or (z_P − ζ)·tan α / s (sun, §1.9). σ grows with z_P
// and shrinks with ζ, so the widest kernel is the one of a receiver on the bottom of the slice range
// (z_S) through the topmost plane (ζ_0, the bottom of slice 0). The tangent clip only shrinks
// kernels (side × clip.z ≤ side) and moves the point sideways, not in depth, so the whole-light
// kernel bounds it. The lookup reads level λ = log2(σ·R) (+ the Gaussian bias) and blends with the
// level above it, so the bound is ⌈λ⌉, clamped to [0, log2 R]. Extent fusion also reads a window twice
// the kernel's side (docs/model.md §1.7.2), one level higher.
#pragma once

#include "config.hpp"
#include "light_frame.hpp"

#include <algorithm>
#include <cmath>

namespace penumbra {

// The depth of the topmost slice plane ζ_0 can take: z_0 + Δ for uniform slices; adaptive slices
// (depth_bins bins of weight 0.5/B + 0.5·[occupied]/occupied) are at least Δ / (0.5 + 0.5·B) thick
// (every bin occupied but one, that one holding all of the first quantile), less 1 % for fp32.
inline double topmost_plane_depth(const SliceFrame& frame, const Config& config) {
    const double z0 = frame.slice_depths.x, thickness = frame.slice_depths.y;
    if (!places_slices_adaptively(config)) return z0 + thickness;
    return z0 + 0.99 * thickness / (0.5 + 0.5 * depth_bins);
}

// The widest kernel (texture units, [0, 1] across an occlusion texture) of any receiver inside the
// bounds the frame was made for.
inline double widest_kernel(const SliceFrame& frame, const Config& config) {
    const double bottom = frame.slice_depths.x + config.slices * double(frame.slice_depths.y);
    const double zeta = topmost_plane_depth(frame, config);
    if (!(bottom > zeta)) return 0.0;
    if (config.light == Light::sun)
        return (bottom - zeta) * double(frame.tan_angular_radius) / std::max(double(frame.window_half_size), 1e-30);
    const double d = frame.cop_distance;
    return d * (bottom - zeta) / (bottom * (d + zeta));
}

// The level_bound the frame needs: ⌈log2(widest kernel · R) + bias⌉ in [0, log2 R]. Filters without
// levels (summed-area tables) and techniques other than occlusion textures: -1 (not used).
inline int kernel_level_bound(const SliceFrame& frame, const Config& config) {
    if (config.technique != Technique::occlusion || config.filter == Filter::sat) return -1;
    const double window = reads_doubled_window(config.fusion) ? 2.0 : 1.0; // extent, clustered: the doubled window
    const double texels = window * widest_kernel(frame, config) * config.resolution;
    // log2(√6/4): the Gaussian levels' bias (detail/occlusion/emit_visibility.hpp)
    const double bias = config.filter == Filter::gaussian ? -0.70751874963942190927 : 0.0;
    const double level = std::log2(std::max(texels, 1.0)) + bias;
    const int all = resolution_levels(config);
    if (!std::isfinite(level)) return all;
    // 1e-6: an exact power of two still reads only its own level; fp32 on the GPU is well inside
    return std::clamp(static_cast<int>(std::ceil(level - 1e-6)), 0, all);
}

} // namespace penumbra
