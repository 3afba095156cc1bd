// playground/src/scenes/ground_plane.hpp — the floor a loaded mesh stands on.
//
// A mesh file is a lone object; the shadow people look at first is the one it casts on the floor.
// So every tool that loads a file (unless --no-ground) puts a receiver under it.
#pragma once

#include "scenes/scene.hpp"

namespace penumbra::playground {

// How the floor is sized from the object's bounds: a square, facing +y, centred under the bounds,
// `ground_size_factor` times the larger horizontal extent (the shadow and its penumbra fall beyond
// the footprint), `ground_gap_factor` times the largest extent below the bounds' lowest point.
inline constexpr float ground_size_factor = 2.0f;
inline constexpr float ground_gap_factor = 0.01f;

// Adds the floor (two triangles) to scene.mesh, then sets the bounds, the default light, sun and
// camera from the new bounds (scene_defaults.hpp) and scene.ground. The file's own texture
// coordinates are dropped (the floor would overlap its charts): the scene gets generated, unique
// ones when a technique needs them (scene.generated_charts, scenes/charts.hpp), like the
// procedural scenes.
void add_ground_plane(Scene& scene);

} // namespace penumbra::playground
