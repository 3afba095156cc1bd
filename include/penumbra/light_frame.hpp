// penumbra/light_frame.hpp — the uniforms that place the slices (occlusion textures: light frame,
// slicing camera, slice depths; docs/model.md §1.1–1.3, §1.9) and the shadow-map camera
// (shadowmap, pcf, pcss), from a light and the scene's bounds. GLM only, no GL.
//
//   penumbra::SliceFrame f = penumbra::slice_frame(light, bounds_min, bounds_max, config.slices);
//   // penumbra_lightFromWorld = f.light_from_world, penumbra_sliceClipFromWorld = f.slice_clip_from_world, ...
//   penumbra::ShadowFrame s = penumbra::shadow_frame(light, bounds_min, bounds_max);
//   // penumbra_shadowClipFromWorld = s.shadow_clip_from_world, penumbra_shadowDepthRange = s.depth_range, ...
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
    // true: every corner of the bounds lies in front of the light and inside the slicing pyramid. false
    // in a room (a corner on or behind the light's plane, or beside the light where the pyramid's angle is
    // capped): nothing is wrong then; what is behind the plane casts nothing, and a receiver outside the
    // pyramid is shadowed only by what lies inside it (docs/model.md §1.2b).
    bool contained = true;
};

// The shadow-map camera. Conventions: the light frame is right-handed, x along the light's u axis,
// y along v, z = depth along the light's direction (growing into the scene), in scene units. The
// shadow map's uv is (0, 0) at the -x, -y corner: uv = 0.5 + xy / (2 tan_half_fov z) (rect,
// perspective from the light centre) or 0.5 + xy / (2 window_half_size) (sun, orthographic). Clip z
// is 0 (no clipping in depth); the depth pass writes gl_FragDepth = (z - near) / (far - near), so
// stored depth runs linearly from 0 at the near plane to 1 at the far plane, and LESS keeps the
// nearest occluder.
struct ShadowFrame {
    glm::mat4 light_from_world{1.0f};       // penumbra_lightFromWorld
    glm::mat4 shadow_clip_from_world{1.0f}; // penumbra_shadowClipFromWorld (GL clip space, z = 0)
    glm::vec2 depth_range{0.0f, 1.0f};      // penumbra_shadowDepthRange: near, far along the light axis (scene units)
    float tan_half_fov = 0.0f;              // penumbra_shadowTanHalfFov (rect): square frustum holding the bounds
    float window_half_size = 0.0f;          // penumbra_windowHalfSize (sun): half side of the orthographic window
    glm::vec2 light_size{0.0f};             // penumbra_lightSize (rect): width, height (scene units)
    float tan_angular_radius = 0.0f;        // penumbra_tanAngularRadius (sun)
    // penumbra_lightSizeUV (PCSS): rect: the light's width, height on the near plane in shadow-map uv,
    // w / (2 tan_half_fov near) (Fernando 2005's LIGHT_SIZE_UV); sun: the cone's footprint growth per
    // unit of depth in uv, 2 tan(angular radius) / (2 window_half_size).
    glm::vec2 light_size_uv{0.0f};
    bool contained = true; // false (rect): a bounds corner lies on or behind the light plane, or outside the
                           // frustum, whose half angle is capped at max_frustum_half_angle (docs/model.md §1.2b)
};

// The widest half angle of the slicing pyramid and of the shadow-map frustum of a rectangular light
// (docs/model.md §1.2b). In a room the bounds reach the light's plane beside the light, and a pyramid
// holding every corner would open to 180°, its texels spread over an unbounded plane. Capped, the
// pyramid holds what the light faces; a receiver beside it, outside, is shadowed by what lies inside it
// only. Light above a scene (every built-in and corpus scene at ×1 to ×32) stays well inside the cap.
inline constexpr double max_frustum_half_angle = 1.2217304763960306; // 70°

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

// Rectangular light: perspective slicing from E = C − d·N, near plane = the light rectangle; d the
// largest that holds every corner of the bounds in front of the light, at most 1000·max(w, h), and at
// least what keeps the pyramid's half angle within max_frustum_half_angle (docs/model.md §1.2, §1.2b).
inline SliceFrame slice_frame(const RectLight& light, glm::dvec3 bounds_min, glm::dvec3 bounds_max, int slices) {
    SliceFrame f;
    const glm::dvec3 u = glm::normalize(light.u_axis), v = glm::normalize(light.v_axis), n = light.normal();
    const glm::dmat4 lfw = detail::frame_matrix(u, v, n, light.center);
    const double w = light.width, h = light.height;
    const double cap = 1000.0 * std::max(w, h);
    // the pyramid's half angle is atan(max(w, h) / (2 d)): d below this would open it past the cap
    const double floor_d = 0.5 * std::max(w, h) / std::tan(max_frustum_half_angle);
    double d = cap;
    bool room = false; // the bounds reach the light's plane: receivers beside the light, up to its plane
    double zmin = std::numeric_limits<double>::max(), zmax = std::numeric_limits<double>::lowest();
    for (const glm::dvec3& corner : detail::box_corners(bounds_min, bounds_max)) {
        const glm::dvec3 p = glm::dvec3(lfw * glm::dvec4(corner, 1.0));
        zmin = std::min(zmin, p.z);
        zmax = std::max(zmax, p.z);
        if (p.z <= 0.0) { // on or behind the light's plane: clipped by the light passes, nothing to hold
            room = true;
            continue;
        }
        if (std::abs(p.x) > w / 2) d = std::min(d, (w / 2) * p.z / (std::abs(p.x) - w / 2));
        if (std::abs(p.y) > h / 2) d = std::min(d, (h / 2) * p.z / (std::abs(p.y) - h / 2));
    }
    // A room (the bounds reach the light's plane): its walls rise beside the light up to the plane, so the
    // pyramid opens as wide as the cap allows, to hold as much of them as it can (docs/model.md §1.2b
    // measures this against the pyramid that only holds the bounds' corners in front of the light). A
    // corner beside the light just in front of its plane is capped the same way.
    if (room || d < floor_d) {
        d = floor_d;
        f.contained = false;
    }
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

// Rectangular light: perspective from the light centre along its normal; the square frustum's
// half angle is the smallest that holds every corner of the bounds in front of the light, capped at
// max_frustum_half_angle; near and far are the bounds' nearest and farthest depths.
inline ShadowFrame shadow_frame(const RectLight& light, glm::dvec3 bounds_min, glm::dvec3 bounds_max) {
    ShadowFrame f;
    const glm::dvec3 u = glm::normalize(light.u_axis), v = glm::normalize(light.v_axis), n = light.normal();
    const glm::dmat4 lfw = detail::frame_matrix(u, v, n, light.center);
    const std::array<glm::dvec3, 8> corners = detail::box_corners(bounds_min, bounds_max);
    double zmin = std::numeric_limits<double>::max(), zmax = std::numeric_limits<double>::lowest();
    for (const glm::dvec3& corner : corners) {
        const double z = (lfw * glm::dvec4(corner, 1.0)).z;
        zmin = std::min(zmin, z);
        zmax = std::max(zmax, z);
    }
    f.contained = zmin > 0.0;
    const double extent = std::max(glm::length(bounds_max - bounds_min), 1e-6);
    // far: 1% beyond the farthest corner, so the depth bias of the farthest surfaces is not clamped away
    const double near = std::max(zmin, 1e-3 * extent), far = std::max(zmax, near + 1e-3 * extent) + 0.01 * (zmax - zmin);
    double tan_half = 1e-6; // x / z is quasi-linear: its largest |value| over the box is at a corner
    for (const glm::dvec3& corner : corners) {
        const glm::dvec3 p = glm::dvec3(lfw * glm::dvec4(corner, 1.0));
        if (p.z <= 0.0) continue; // behind the light's plane: the depth pass clips it
        tan_half =
            std::max({tan_half, std::abs(p.x) / std::max(p.z, near), std::abs(p.y) / std::max(p.z, near)});
    }
    tan_half *= 1.001;
    // a room (the bounds reach the light's plane) opens the frustum to the cap, as the slicing pyramid
    if (zmin <= 0.0 || tan_half > std::tan(max_frustum_half_angle)) {
        tan_half = std::tan(max_frustum_half_angle);
        f.contained = false;
    }
    // clip = (x / t, y / t, 0, z) in light-frame coordinates
    glm::dmat4 clip_from_light(0.0);
    clip_from_light[0][0] = 1.0 / tan_half;
    clip_from_light[1][1] = 1.0 / tan_half;
    clip_from_light[2][3] = 1.0;
    f.light_from_world = glm::mat4(lfw);
    f.shadow_clip_from_world = glm::mat4(clip_from_light * lfw);
    f.depth_range = {static_cast<float>(near), static_cast<float>(far)};
    f.tan_half_fov = static_cast<float>(tan_half);
    f.light_size = {static_cast<float>(light.width), static_cast<float>(light.height)};
    f.light_size_uv = glm::vec2(glm::dvec2(light.width, light.height) / (2.0 * tan_half * near));
    return f;
}

// Sun: orthographic along the light direction over a square window holding the bounds (the same
// frame as the sun's slicing, slice_frame(SunLight, ...)).
inline ShadowFrame shadow_frame(const SunLight& sun, glm::dvec3 bounds_min, glm::dvec3 bounds_max) {
    const SliceFrame slices = slice_frame(sun, bounds_min, bounds_max, 1);
    ShadowFrame f;
    f.light_from_world = slices.light_from_world;
    f.shadow_clip_from_world = slices.slice_clip_from_world;
    double zmin = std::numeric_limits<double>::max(), zmax = std::numeric_limits<double>::lowest();
    for (const glm::dvec3& corner : detail::box_corners(bounds_min, bounds_max)) {
        const double z = (glm::dmat4(slices.light_from_world) * glm::dvec4(corner, 1.0)).z;
        zmin = std::min(zmin, z);
        zmax = std::max(zmax, z);
    }
    const double pad = 1e-4 * std::max(zmax - zmin, 1e-6);
    f.depth_range = {static_cast<float>(zmin - pad), static_cast<float>(zmax + 0.01 * (zmax - zmin) + pad)};
    f.window_half_size = slices.window_half_size;
    f.tan_angular_radius = slices.tan_angular_radius;
    const float growth = 2.0f * f.tan_angular_radius / (2.0f * f.window_half_size);
    f.light_size_uv = {growth, growth};
    return f;
}

} // namespace penumbra
