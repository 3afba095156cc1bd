// playground/src/reference/slice_coverage.hpp — the slicing pass computed on the CPU (docs/model.md §1,
// paper §3.4): which texel of which slice the scene covers, seen from the slicing camera, with the
// cut of cut-out casters (Config::alpha_test) or without it. The GL tests hold the GPU's slicing
// output to it; the oracle then filters and fuses that output (oracle.hpp).
#pragma once

#include "scenes/scene.hpp"

#include <penumbra/config.hpp>
#include <penumbra/light_frame.hpp>

#include <vector>

namespace penumbra::playground {

// What a texel of one slice holds. Texels whose centre lies within a texel of a triangle's edge,
// within rounding of a slice boundary, or within rounding of an alpha-texture texel where the cut
// changes may go either way.
enum class Coverage : unsigned char { empty, either, covered };

struct SliceCoverage {
    int resolution = 0, slices = 0;
    std::vector<Coverage> texels; // slice-major, rows from v = 0 up (as SliceTextures)

    Coverage& at(int slice, int x, int y) {
        return texels[(static_cast<std::size_t>(slice) * resolution + y) * resolution + x];
    }
    Coverage at(int slice, int x, int y) const {
        return texels[(static_cast<std::size_t>(slice) * resolution + y) * resolution + x];
    }
};

// The coverage of uniform slices of `frame` (slice_depths): each triangle covers the texel centres
// inside its projection, in the slice of its depth there, and the next `reach` slices (the leak fix,
// penumbra::leak_fix_reach). Depth and texture coordinates are interpolated perspective-correctly,
// as the rasteriser does. With `cut`, a triangle of a cut material covers a texel centre only where
// its texture's alpha there is at least the cutoff (nearest texel, repeat). With config.solid_casters
// the triangles of closed parts (Mesh::triangle_closed) toggle every slice from theirs (a face towards
// the light) or the next one (a face away from it) down instead, as the GPU's logic op XOR does.
SliceCoverage cpu_slice_coverage(const Mesh& mesh, const Config& config, const SliceFrame& frame, int reach,
                                 bool cut);

} // namespace penumbra::playground
