// The playground's example shading (rendering/light_term.hpp): the rectangle's unoccluded irradiance in
// closed form against a numerical integral, 0 on a face turned from the whole light, the viewer's side.
#include "rendering/light_term.hpp"

#include <doctest/doctest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>

namespace {

using penumbra::RectLight;
using penumbra::playground::rect_light_term;
using penumbra::playground::sun_light_term;

// The irradiance at p (unit normal n) from `light`, by a midpoint sum over a fine grid of the rectangle:
// cos θ_receiver · cos θ_light / r² for the points above the tangent plane.
double integrated_irradiance(glm::dvec3 p, glm::dvec3 n, const RectLight& light, int steps = 400) {
    const glm::dvec3 u = glm::normalize(light.u_axis), v = glm::normalize(light.v_axis), light_normal = light.normal();
    double sum = 0.0;
    for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j) {
            const glm::dvec3 q = light.center + u * ((i + 0.5) / steps - 0.5) * light.width +
                                 v * ((j + 0.5) / steps - 0.5) * light.height;
            const glm::dvec3 d = q - p;
            const double r2 = glm::dot(d, d);
            const double cos_receiver = glm::dot(n, d) / std::sqrt(r2);
            const double cos_light = -glm::dot(light_normal, d) / std::sqrt(r2);
            if (cos_receiver > 0.0 && cos_light > 0.0) sum += cos_receiver * cos_light / r2;
        }
    return sum * light.width * light.height / (double(steps) * steps);
}

// A 4×2 light at height 2 over the origin: large next to its distance, so clipping matters.
RectLight large_light() {
    RectLight light;
    light.center = {0.0, 2.0, 0.0};
    light.width = 4.0;
    light.height = 2.0;
    return light;
}

} // namespace

TEST_CASE("light term: the rectangle's irradiance over that of a receiver facing its centre") {
    const RectLight light = large_light();
    const glm::vec3 eye(0.0f, 1.0f, 5.0f); // in front of every receiver below
    const glm::dvec3 p(0.5, 0.0, 0.3);
    const glm::dvec3 facing = glm::normalize(light.center - p);
    const double reference = integrated_irradiance(p, facing, light);
    // upright, tilted, a wall that sees part of the light, and one that sees a corner of it
    const glm::dvec3 normals[] = {{0.0, 1.0, 0.0}, glm::normalize(glm::dvec3(1.0, 1.0, 0.0)), {1.0, 0.0, 0.0},
                                  glm::normalize(glm::dvec3(1.0, -0.6, 1.0))};
    for (const glm::dvec3& n : normals) {
        CAPTURE(n.x);
        CAPTURE(n.y);
        CAPTURE(n.z);
        const double expected = std::min(integrated_irradiance(p, n, light) / reference, 1.0);
        const float term = rect_light_term(glm::vec3(p), glm::vec3(n), glm::vec3(p) + 5.0f * glm::vec3(n), light);
        CHECK(term > 0.0f);
        CHECK(term == doctest::Approx(expected).epsilon(0.01));
    }
    // a small light far above: the cosine of its direction
    RectLight small;
    small.center = {0.0, 100.0, 0.0};
    small.width = small.height = 0.01;
    const glm::vec3 tilted = glm::normalize(glm::vec3(1.0f, 1.0f, 0.0f));
    CHECK(rect_light_term({0.0f, 0.0f, 0.0f}, tilted, eye, small) == doctest::Approx(std::sqrt(0.5)).epsilon(1e-3));
}

TEST_CASE("light term: no light on a face turned from all of the light, nor behind it") {
    const RectLight light = large_light();
    const glm::vec3 p(0.0f, 0.0f, 0.0f);
    // facing down, seen from below (a floor's underside): the whole light is behind it
    CHECK(rect_light_term(p, {0.0f, -1.0f, 0.0f}, {0.0f, -3.0f, 1.0f}, light) == 0.0f);
    // a wall of the light's far side seen from outside it: the light is wholly behind its plane
    CHECK(rect_light_term({3.0f, 1.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {6.0f, 1.0f, 0.0f}, light) == 0.0f);
    // above the light's plane (the light emits downwards only)
    CHECK(rect_light_term({0.0f, 3.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 5.0f, 1.0f}, light) == 0.0f);
    // sun: under the horizon of the seen side
    penumbra::SunLight sun;
    sun.direction = {0.0, -1.0, 0.0};
    CHECK(sun_light_term(p, {0.0f, -1.0f, 0.0f}, {0.0f, -3.0f, 0.0f}, sun) == 0.0f);
    CHECK(sun_light_term(p, {0.0f, 1.0f, 0.0f}, {0.0f, 3.0f, 0.0f}, sun) == doctest::Approx(1.0f));
}

TEST_CASE("light term: the side the viewer sees, whichever way the normal points") {
    const RectLight light = large_light();
    const glm::vec3 p(0.0f, 0.0f, 0.0f), eye(0.0f, 4.0f, 4.0f);
    // a floor whose normal points down but is seen from above: lit as the upper side
    CHECK(rect_light_term(p, {0.0f, -1.0f, 0.0f}, eye, light) == doctest::Approx(rect_light_term(p, {0.0f, 1.0f, 0.0f}, eye, light)));
    CHECK(rect_light_term(p, {0.0f, 1.0f, 0.0f}, eye, light) > 0.9f);
    // a zero normal: no side, no light
    CHECK(rect_light_term(p, {0.0f, 0.0f, 0.0f}, eye, light) == 0.0f);
}
