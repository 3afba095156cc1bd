// playground/src/rendering/light_term.hpp — the playground's example shading: the light's term at a
// surface point before any shadow, which the visibility multiplies, as an engine's area-light shading does.
//
// For the rectangle it is the unoccluded irradiance of the side of the surface the viewer sees: the light
// clipped to the half-space above that side's tangent plane, integrated in closed form (the polygon's form
// factor, Lambert 1760; what LTC shading in three.js or Babylon.js approximates), over the irradiance of a
// surface at the same point facing the light's centre. So it is the cosine of a small light, it falls to 0
// as the light sinks below the surface, and it is 0 exactly where the light is wholly below it: a face
// turned from the light is never lit, whatever the visibility says there. The pixels it lights are those
// the `oriented` and `irradiance` references are defined on (reference/ground_truth.hpp).
// The sun's: the cosine of its direction on the viewer's side.
#pragma once

#include <penumbra/light.hpp>

#include <glm/glm.hpp>

namespace penumbra::playground {

// In [0, 1]. `normal`: the surface's normal, any length, either side; `eye`: the viewer's position
// (the normal is turned to its side).
float rect_light_term(glm::vec3 position, glm::vec3 normal, glm::vec3 eye, const RectLight& light);
float sun_light_term(glm::vec3 position, glm::vec3 normal, glm::vec3 eye, const SunLight& sun);

// The same two functions in GLSL 4.50, for the window's compose pass (window/frame_renderer.cpp):
// float penumbra_rectLightTerm(vec3 position, vec3 normal, vec3 eye, vec3 centre, vec3 halfU, vec3 halfV)
// float penumbra_sunLightTerm(vec3 position, vec3 normal, vec3 eye, vec3 sunDirection)
// (halfU, halfV: half the rectangle's sides, along its axes).
extern const char* const light_term_glsl;

} // namespace penumbra::playground
