// playground/src/scenes/scene_defaults.cpp
#include "scenes/scene_defaults.hpp"

#include "scenes/closed_parts.hpp"
#include "scenes/mesh_builder.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace penumbra::playground {

penumbra::RectLight default_rect_light(glm::vec3 bounds_min, glm::vec3 bounds_max) {
    const glm::vec3 extent = bounds_max - bounds_min;
    const float span = std::max({extent.x, extent.z, 1e-3f});
    const glm::vec3 centre = 0.5f * (bounds_min + bounds_max);
    penumbra::RectLight light;
    light.center = glm::dvec3(centre.x, bounds_max.y + 0.4 * span, centre.z);
    light.u_axis = glm::dvec3(1.0, 0.0, 0.0);
    light.v_axis = glm::dvec3(0.0, 0.0, 1.0); // cross(+x, +z) = −y: the light faces down
    light.width = 0.2 * span;
    light.height = 0.2 * span;
    return light;
}

penumbra::SunLight default_sun_light() {
    penumbra::SunLight sun;
    sun.direction = glm::normalize(glm::dvec3(0.25, -1.0, 0.15));
    // The real sun subtends 0.0093 rad: a 3-unit-tall occluder then casts a penumbra about
    // 0.03 units wide, less than a pixel in our 256² test views of a 10-unit scene. Five times
    // the real diameter makes the sun's soft shadows visible and measurable.
    sun.angular_diameter = 0.0093 * 5.0;
    return sun;
}

OrbitCamera default_camera(glm::vec3 bounds_min, glm::vec3 bounds_max) {
    OrbitCamera camera;
    camera.target = 0.5f * (bounds_min + bounds_max);
    camera.fov_y_radians = glm::radians(45.0f);
    camera.yaw_radians = glm::radians(35.0f);
    camera.pitch_radians = glm::radians(35.0f);
    const float radius = std::max(0.5f * glm::length(bounds_max - bounds_min), 1e-3f);
    // Distance at which the bounding sphere fits the vertical field of view, plus a margin.
    camera.distance = 1.05f * radius / std::sin(0.5f * camera.fov_y_radians);
    camera.z_near = std::max(1e-3f, 0.01f * camera.distance);
    camera.z_far = camera.distance + 3.0f * radius;
    return camera;
}

void finish_scene(Scene& scene) {
    complete_cut_materials(scene.mesh); // a floor added under cut-out casters is solid
    scene.mesh.triangle_closed = closed_triangles(scene.mesh);
    std::tie(scene.bounds_min, scene.bounds_max) = compute_bounds(scene.mesh);
    scene.light = default_rect_light(scene.bounds_min, scene.bounds_max);
    scene.sun = default_sun_light();
    if (scene.file_light) scene.light = *scene.file_light; // a loaded file's own light wins over the defaults
    if (scene.file_sun_direction) scene.sun.direction = *scene.file_sun_direction;
    scene.camera = default_camera(scene.bounds_min, scene.bounds_max);
}

} // namespace penumbra::playground
