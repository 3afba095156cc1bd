// penumbra/light.hpp — lights in physical terms (scene units, radians), no per-technique factors.
#pragma once

#include <glm/glm.hpp>

namespace penumbra {

// A rectangular area light. `u_axis` and `v_axis` are orthonormal; the light emits towards
// normal() = cross(u_axis, v_axis), i.e. into the scene. Lengths in scene units.
struct RectLight {
    glm::dvec3 center{0.0, 10.0, 0.0};
    glm::dvec3 u_axis{1.0, 0.0, 0.0};
    glm::dvec3 v_axis{0.0, 0.0, 1.0}; // with u = +x this makes the normal −y: straight down
    double width = 2.0;               // extent along u_axis
    double height = 2.0;              // extent along v_axis

    glm::dvec3 normal() const { return glm::normalize(glm::cross(u_axis, v_axis)); }
};

// A light at infinity, seen as a disk of the given angular diameter (the sun: about 0.0093 rad).
struct SunLight {
    glm::dvec3 direction{0.0, -1.0, 0.0}; // direction the light travels (from the sun into the scene)
    double angular_diameter = 0.0093;     // radians
};

} // namespace penumbra
