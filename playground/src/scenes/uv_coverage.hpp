// playground/src/scenes/uv_coverage.hpp — a mesh's texture coordinates rasterized into an R×R
// texel grid: which surface point each texel stands for, and whether two triangles claim one texel.
//
// Texel (x, y) covers uv [x/R, (x+1)/R] × [y/R, (y+1)/R] and is element y·R + x (row 0 at v = 0,
// the first row glTexImage2D uploads). Needs mesh.uvs.
#pragma once

#include "scenes/scene.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::playground {

// The surface point a texel stands for: the point of the nearest triangle (in texel units) closest
// to the texel centre, among triangles that come within half a texel diagonal of it. Conservative:
// every texel a fragment of a triangle can read gets a point of that triangle or of a neighbour of
// the same chart.
struct TexelSample {
    std::int32_t triangle = -1; // -1: no triangle near this texel
    glm::vec3 position{0.0f};   // world
    glm::vec3 normal{0.0f};     // interpolated vertex normal, unit length
};

std::vector<TexelSample> texel_samples(const Mesh& mesh, int resolution);

// Two triangles whose interiors both hold the centre of texel (x, y) (top-left rule on shared edges,
// so neighbours never collide).
struct UvOverlap {
    std::size_t first = 0, second = 0; // triangle indices, first < second
    int x = 0, y = 0;
};

std::optional<UvOverlap> find_uv_overlap(const Mesh& mesh, int resolution);

// Empty when mesh.uvs are a unique parameterization at `resolution` (present, inside [0,1]², no
// triangle without area in uv, no overlap); otherwise one line saying what is wrong.
std::string check_unique_uvs(const Mesh& mesh, int resolution);

} // namespace penumbra::playground
