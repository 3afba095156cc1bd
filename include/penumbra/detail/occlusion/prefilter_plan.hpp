// penumbra/detail/occlusion/prefilter_plan.hpp — which prefilter pass builds which filter level: the
// levels the atlas packing pass writes, and, with the compute prefilter (Config::prefilter_stage),
// how the levels above it are grouped into dispatches. Shared by the emitters, the layout and
// validation, so the three cannot disagree.
#pragma once

#include "parameters.hpp"

#include <vector>

namespace penumbra::detail {

// The highest filter level the atlas packing pass writes: level 0 (the slicing output as tiles),
// and for N-buffer and Gaussian levels also level 1, whose taps it reads from the slices anyway
// (one pass, two outputs of one size, instead of a copy and a level pass), where level 1 has level
// 0's size (a pass's outputs share one size: not with level_reduction 0). Mip chains: 0.
constexpr int packed_level(const Config& config) {
    return config.packing == Packing::atlas && has_level_images(config) && max_level(config) >= 1 &&
                   level_spacing(config, 1) == 1
               ? 1
               : 0;
}

// The compute prefilter (emit_prefilter_compute.hpp). A workgroup of compute_group_side²
// invocations loads one block of the level a dispatch starts from, plus the apron the wider windows
// reach, into shared memory once, and builds the dispatch's levels there.
inline constexpr int compute_group_side = 16;
// Bytes of shared memory every OpenGL 4.3+ implementation has (GL_MAX_COMPUTE_SHARED_MEMORY_SIZE):
// the tile of vec4 must fit, 45 x 45 texels at most.
inline constexpr int compute_shared_bytes = 32768;
// Levels (image outputs) one dispatch builds at most.
inline constexpr int compute_max_levels = 4;
// The widest tap offset of a dispatch's first level, in texels of its source level, that still fits
// one level's apron next to the block (16 + 16 texels per side), and the level_reduction that keeps
// every level's offset within it (2^level_reduction texels).
inline constexpr int compute_max_step = 16;
inline constexpr int compute_max_level_reduction = 4;

// One dispatch: levels source_level + 1 … source_level + levels from level source_level.
struct ComputeDispatch {
    int source_level = 0;
    int levels = 0;
};

// Offset between the taps of level source_level + 1, in texels of level source_level: 2^source_level
// texels of level 0, and a texel of a reduced level spans level_spacing of them.
constexpr int compute_step(const Config& config, int source_level) {
    return (1 << source_level) / level_spacing(config, source_level);
}

// Texels per side of the shared tile a dispatch needs: the block, and the apron the last level's
// windows reach (offsets step, 2·step, … 2^(levels-1)·step add up to (2^levels - 1)·step).
constexpr int compute_tile_side(const Config& config, const ComputeDispatch& d) {
    return compute_group_side + ((1 << d.levels) - 1) * compute_step(config, d.source_level);
}

constexpr bool compute_tile_fits(int side) { return side * side * 16 <= compute_shared_bytes; }

// The largest first-level offset among the levels above packed_level (0 when there are none):
// validation refuses the compute prefilter when one level alone would not fit the tile.
constexpr int compute_source_step(const Config& config) {
    int step = 0;
    for (int b = packed_level(config); b < max_level(config); ++b)
        step = step > compute_step(config, b) ? step : compute_step(config, b);
    return step;
}

// Levels packed_level + 1 … max_level grouped into dispatches, greedily: as many levels per dispatch
// as the shared tile holds (at most compute_max_levels). Default (512², level_reduction 2, every
// level): levels 2–4 from level 1, 5–7 from level 4, 8–9 from level 7.
constexpr std::vector<ComputeDispatch> compute_dispatches(const Config& config) {
    std::vector<ComputeDispatch> plan;
    const int L = max_level(config);
    for (int b = packed_level(config); b < L;) {
        ComputeDispatch d{b, 1};
        while (b + d.levels < L && d.levels < compute_max_levels &&
               compute_tile_fits(compute_tile_side(config, {b, d.levels + 1})))
            ++d.levels;
        plan.push_back(d);
        b += d.levels;
    }
    return plan;
}

// Texels per side of the shared tile the emitted program declares: the largest any dispatch needs.
constexpr int compute_shared_side(const Config& config) {
    int side = compute_group_side;
    for (const ComputeDispatch& d : compute_dispatches(config))
        side = side > compute_tile_side(config, d) ? side : compute_tile_side(config, d);
    return side;
}

} // namespace penumbra::detail
