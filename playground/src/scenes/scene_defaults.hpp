// playground/src/scenes/scene_defaults.hpp — lights and camera derived from a scene's bounds.
//
// Procedural scenes and loaded OBJ files get their lights and camera from the same rules, so
// an OBJ file of the same size as the procedural scenes is lit the same way.
#pragma once

#include "scenes/scene.hpp"

namespace penumbra::playground {

// A horizontal square light facing down (u = +x, v = +z, so normal() = −y), centred above the
// bounds. For the procedural scenes (10×10 ground, objects ≤ 3 tall) this is a 2×2 light at
// y = 7: 4 units above the tallest occluder, big enough for wide penumbrae.
penumbra::RectLight default_rect_light(glm::vec3 bounds_min, glm::vec3 bounds_max);

// The sun slightly off vertical, with 5× the real sun's angular diameter.
penumbra::SunLight default_sun_light();

// An oblique view of the whole bounding box.
OrbitCamera default_camera(glm::vec3 bounds_min, glm::vec3 bounds_max);

// Sets bounds_min/max from the mesh, then the default light, sun and camera; a light the loaded file
// brought (scene.file_light, scene.file_sun_direction) replaces the default one.
void finish_scene(Scene& scene);

} // namespace penumbra::playground
