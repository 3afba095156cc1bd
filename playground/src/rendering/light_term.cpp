#include "light_term.hpp"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::playground {

namespace {

// A convex polygon of directions from the receiver: the light's four corners, at most five once clipped.
struct Polygon {
    std::array<glm::dvec3, 5> corners{};
    int count = 0;
};

// The part of `polygon` strictly above the plane through the receiver with unit normal n (one pass of
// Sutherland–Hodgman).
Polygon above(const Polygon& polygon, glm::dvec3 n) {
    Polygon out;
    for (int i = 0; i < polygon.count; ++i) {
        const glm::dvec3 a = polygon.corners[i], b = polygon.corners[(i + 1) % polygon.count];
        const double da = glm::dot(n, a), db = glm::dot(n, b);
        if (da > 0.0 && out.count < 5) out.corners[out.count++] = a;
        if ((da > 0.0) != (db > 0.0) && out.count < 5) out.corners[out.count++] = a + (b - a) * (da / (da - db));
    }
    return out;
}

// The irradiance, over the light's radiance times pi, of a receiver with unit normal n from a uniformly
// emitting polygon above its tangent plane: the polygon's form factor, a sum over its edges.
double form_factor(const Polygon& polygon, glm::dvec3 n) {
    if (polygon.count < 3) return 0.0;
    double sum = 0.0;
    for (int i = 0; i < polygon.count; ++i) {
        const glm::dvec3 a = glm::normalize(polygon.corners[i]), b = glm::normalize(polygon.corners[(i + 1) % polygon.count]);
        const glm::dvec3 c = glm::cross(a, b);
        const double length = glm::length(c);
        if (length < 1e-15) continue;
        sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, c / length);
    }
    return std::abs(sum) / (2.0 * glm::pi<double>());
}

// The normal of the side the viewer sees, unit length; zero when unusable.
glm::dvec3 viewer_side(glm::vec3 position, glm::vec3 normal, glm::vec3 eye) {
    const glm::dvec3 n(normal);
    const double length = glm::length(n);
    if (!(length > 1e-12) || !std::isfinite(length)) return glm::dvec3(0.0);
    return (glm::dot(n, glm::dvec3(eye - position)) < 0.0 ? -n : n) / length;
}

} // namespace

float rect_light_term(glm::vec3 position, glm::vec3 normal, glm::vec3 eye, const RectLight& light) {
    const glm::dvec3 n = viewer_side(position, normal, eye);
    const glm::dvec3 to_centre = light.center - glm::dvec3(position);
    // the light emits from its front side only (as the ground truth assumes)
    if (n == glm::dvec3(0.0) || glm::dot(to_centre, light.normal()) >= 0.0) return 0.0f;
    const glm::dvec3 half_u = 0.5 * light.width * glm::normalize(light.u_axis);
    const glm::dvec3 half_v = 0.5 * light.height * glm::normalize(light.v_axis);
    Polygon quad;
    quad.corners = {to_centre - half_u - half_v, to_centre + half_u - half_v, to_centre + half_u + half_v,
                    to_centre - half_u + half_v, glm::dvec3(0.0)};
    quad.count = 4;
    const glm::dvec3 towards_centre = glm::normalize(to_centre);
    const double facing = form_factor(above(quad, towards_centre), towards_centre);
    if (!(facing > 0.0)) return 0.0f;
    return static_cast<float>(std::clamp(form_factor(above(quad, n), n) / facing, 0.0, 1.0));
}

float sun_light_term(glm::vec3 position, glm::vec3 normal, glm::vec3 eye, const SunLight& sun) {
    const glm::dvec3 n = viewer_side(position, normal, eye);
    return static_cast<float>(std::max(glm::dot(n, -glm::normalize(sun.direction)), 0.0));
}

const char* const light_term_glsl = R"(
// The playground's light term (playground/src/rendering/light_term.cpp, whose twin this is).
vec3 penumbra_viewerSide(vec3 position, vec3 normal, vec3 eye)
{
    float len = length(normal);
    if (len < 1e-12) return vec3(0.0);
    return (dot(normal, eye - position) < 0.0 ? -normal : normal) / len;
}

float penumbra_formFactor(vec3 corners[5], int count, vec3 n)
{
    if (count < 3) return 0.0;
    float sum = 0.0;
    for (int i = 0; i < count; ++i) {
        vec3 a = normalize(corners[i]);
        vec3 b = normalize(corners[(i + 1) % count]);
        vec3 c = cross(a, b);
        float len = length(c);
        if (len < 1e-12) continue;
        sum += acos(clamp(dot(a, b), -1.0, 1.0)) * dot(n, c / len);
    }
    return abs(sum) / (2.0 * 3.14159265358979);
}

// the light's quad (corners from the receiver) above the plane through the receiver with normal n
float penumbra_clippedFormFactor(vec3 quad[4], vec3 n)
{
    vec3 corners[5];
    int count = 0;
    for (int i = 0; i < 4; ++i) {
        vec3 a = quad[i];
        vec3 b = quad[(i + 1) % 4];
        float da = dot(n, a);
        float db = dot(n, b);
        if (da > 0.0 && count < 5) corners[count++] = a;
        if ((da > 0.0) != (db > 0.0) && count < 5) corners[count++] = a + (b - a) * (da / (da - db));
    }
    return penumbra_formFactor(corners, count, n);
}

float penumbra_rectLightTerm(vec3 position, vec3 normal, vec3 eye, vec3 centre, vec3 halfU, vec3 halfV)
{
    vec3 n = penumbra_viewerSide(position, normal, eye);
    vec3 toCentre = centre - position;
    if (dot(n, n) == 0.0 || dot(toCentre, cross(halfU, halfV)) >= 0.0) return 0.0;
    vec3 quad[4] = vec3[4](toCentre - halfU - halfV, toCentre + halfU - halfV, toCentre + halfU + halfV,
                           toCentre - halfU + halfV);
    float facing = penumbra_clippedFormFactor(quad, normalize(toCentre));
    if (facing <= 0.0) return 0.0;
    return clamp(penumbra_clippedFormFactor(quad, n) / facing, 0.0, 1.0);
}

float penumbra_sunLightTerm(vec3 position, vec3 normal, vec3 eye, vec3 sunDirection)
{
    return max(dot(penumbra_viewerSide(position, normal, eye), -normalize(sunDirection)), 0.0);
}
)";

} // namespace penumbra::playground
