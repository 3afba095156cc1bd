// playground/src/scenes/ground_plane.cpp
#include "scenes/ground_plane.hpp"

#include "scenes/mesh_builder.hpp"
#include "scenes/scene_defaults.hpp"

#include <algorithm>

namespace penumbra::playground {

void add_ground_plane(Scene& scene) {
    const auto [lo, hi] = compute_bounds(scene.mesh);
    const glm::vec3 extent = hi - lo;
    const float footprint = std::max({extent.x, extent.z, 1e-3f});
    const float gap = ground_gap_factor * std::max({extent.x, extent.y, extent.z, 1e-3f});
    const float side = ground_size_factor * footprint;
    scene.mesh.uvs.clear(); // the floor would overlap the file's charts
    scene.generated_charts = true;
    add_horizontal_rect(scene.mesh, 0.5f * (lo.x + hi.x), lo.y - gap, 0.5f * (lo.z + hi.z), side, side);
    scene.ground = true;
    finish_scene(scene);
}

} // namespace penumbra::playground
