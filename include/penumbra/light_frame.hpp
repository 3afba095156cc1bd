// penumbra/light_frame.hpp — the uniforms that place the slices: light frame, slicing camera,
// slice depths, from a light and the scene's bounds (docs/model.md §1.1–1.3, §1.9). GLM only, no GL.
//
//   penumbra::SliceFrame f = penumbra::slice_frame(light, bounds_min, bounds_max, config.slices);
//   // penumbra_lightFromWorld = f.light_from_world, penumbra_sliceClipFromWorld = f.slice_clip_from_world, ...
#pragma once

#include "light.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace penumbra {

struct SliceFrame {
    glm::mat4 light_from_world{1.0f};      // penumbra_lightFromWorld: x along u, y along v, z along the normal
    glm::mat4 slice_clip_from_world{1.0f}; // penumbra_sliceClipFromWorld (clip z is 0: no depth test is used)
    glm::vec2 light_size{0.0f};            // penumbra_lightSize (rect)
    float cop_distance = 0.0f;             // penumbra_copDistance (rect): d, E = C − d·N
    glm::vec2 slice_depths{0.0f};          // penumbra_sliceDepths: z0, thickness Δ
    float window_half_size = 0.0f;         // penumbra_windowHalfSize (sun)
    float tan_angular_radius = 0.0f;       // penumbra_tanAngularRadius (sun)
    bool contained = true;                 // false: a bounds corner lies on or above the light plane,
                                           // or d hit its cap (the scene cannot be seen at a sane field of view)
};

namespace detail {

// World → frame with rows u, v, n and origin o.
inline glm::dmat4 frame_matrix(glm::dvec3 u, glm::dvec3 v, glm::dvec3 n, glm::dvec3 o) {
    glm::dmat4 m(1.0);
    const glm::dvec3 rows[3] = {u, v, n};
    for (int r = 0; r < 3; ++r) {
        m[0][r] = rows[r].x;
        m[1][r] = rows[r].y;
        m[2][r] = rows[r].z;
        m[3][r] = -glm::dot(rows[r], o);
    }
    return m;
}

inline std::array<glm::dvec3, 8> box_corners(glm::dvec3 lo, glm::dvec3 hi) {
    std::array<glm::dvec3, 8> c;
    for (int i = 0; i < 8; ++i) c[i] = {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    return c;
}

inline glm::vec2 depth_range_slices(double zmin, double zmax, int slices) {
    const double pad = 1e-4 * std::max(zmax - zmin, 1e-6);
    const double z0 = zmin - pad, zs = zmax + pad;
    return {static_cast<float>(z0), static_cast<float>((zs - z0) / std::max(slices, 1))};
}

} // namespace detail

// Rectangular light: perspective slicing from E = C − d·N, near plane = the light rectangle.
inline SliceFrame slice_frame(const RectLight& light, glm::dvec3 bounds_min, glm::dvec3 bounds_max, int slices) {
    SliceFrame f;
    const glm::dvec3 u = glm::normalize(light.u_axis), v = glm::normalize(light.v_axis), n = light.normal();
    const glm::dmat4 lfw = detail::frame_matrix(u, v, n, light.center);
    const double w = light.width, h = light.height;
    const double cap = 1000.0 * std::max(w, h);
    double d = cap;
    double zmin = std::numeric_limits<double>::max(), zmax = std::numeric_limits<double>::lowest();
    for (const glm::dvec3& corner : detail::box_corners(bounds_min, bounds_max)) {
        const glm::dvec3 p = glm::dvec3(lfw * glm::dvec4(corner, 1.0));
        zmin = std::min(zmin, p.z);
        zmax = std::max(zmax, p.z);
        if (p.z <= 0.0) {
            f.contained = false;
            continue;
        }
        if (std::abs(p.x) > w / 2) d = std::min(d, (w / 2) * p.z / (std::abs(p.x) - w / 2));
        if (std::abs(p.y) > h / 2) d = std::min(d, (h / 2) * p.z / (std::abs(p.y) - h / 2));
    }
    if (d >= cap) f.contained = d > 0.0 && f.contained; // cap reached: fine, the scene is inside anyway
    // clip = (2·a·d/w, 2·b·d/h, 0, d + z) in light-frame coordinates (a, b, z)
    glm::dmat4 clip_from_light(0.0);
    clip_from_light[0][0] = 2.0 * d / w;
    clip_from_light[1][1] = 2.0 * d / h;
    clip_from_light[2][3] = 1.0;
    clip_from_light[3][3] = d;
    f.light_from_world = glm::mat4(lfw);
    f.slice_clip_from_world = glm::mat4(clip_from_light * lfw);
    f.light_size = {static_cast<float>(w), static_cast<float>(h)};
    f.cop_distance = static_cast<float>(d);
    f.slice_depths = detail::depth_range_slices(std::max(zmin, 0.0), zmax, slices);
    return f;
}

// Sun: orthographic slicing along the light direction over a square window covering the bounds;
// the light frame's origin is on the axis through the bounds' centre, above the scene.
inline SliceFrame slice_frame(const SunLight& sun, glm::dvec3 bounds_min, glm::dvec3 bounds_max, int slices) {
    SliceFrame f;
    const glm::dvec3 n = glm::normalize(sun.direction);
    const glm::dvec3 helper = std::abs(n.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(helper, n));
    const glm::dvec3 v = glm::cross(n, u); // cross(u, v) = n
    const glm::dvec3 centre = 0.5 * (bounds_min + bounds_max);
    const double radius = std::max(0.5 * glm::length(bounds_max - bounds_min), 1e-3);
    const glm::dvec3 origin = centre - n * (radius * 1.1);
    const glm::dmat4 lfw = detail::frame_matrix(u, v, n, origin);
    double half = 0.0, zmin = std::numeric_limits<double>::max(), zmax = std::numeric_limits<double>::lowest();
    for (const glm::dvec3& corner : detail::box_corners(bounds_min, bounds_max)) {
        const glm::dvec3 p = glm::dvec3(lfw * glm::dvec4(corner, 1.0));
        half = std::max({half, std::abs(p.x), std::abs(p.y)});
        zmin = std::min(zmin, p.z);
        zmax = std::max(zmax, p.z);
    }
    half = std::max(half * 1.001, 1e-6);
    glm::dmat4 clip_from_light(0.0);
    clip_from_light[0][0] = 1.0 / half;
    clip_from_light[1][1] = 1.0 / half;
    clip_from_light[3][3] = 1.0;
    f.light_from_world = glm::mat4(lfw);
    f.slice_clip_from_world = glm::mat4(clip_from_light * lfw);
    f.window_half_size = static_cast<float>(half);
    f.tan_angular_radius = static_cast<float>(std::tan(0.5 * sun.angular_diameter));
    f.slice_depths = detail::depth_range_slices(zmin, zmax, slices);
    return f;
}

} // namespace penumbra
