// bench/compare/lights.hpp — the light of each measurement: the scene's rectangle or sun at a multiple
// of its size, moved frame by frame for the flicker measurement, set on a runtime.
#pragma once

#include "bake/oim_scene.hpp"
#include "scenes/scene.hpp"

#include <penumbra/gl/runtime.hpp>
#include <penumbra/sun_path.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::bench {

using namespace penumbra::playground;
using json = nlohmann::ordered_json;

inline RectLight scaled_light(const RectLight& light, double scale) {
    RectLight out = light;
    out.width *= scale;
    out.height *= scale;
    return out;
}

// Frame f of the flicker sequence: the light's centre moved along its u axis.
inline RectLight moved_light(const RectLight& light, double step, int frame) {
    RectLight out = light;
    out.center += light.u_axis * (step * frame);
    return out;
}

inline double ground_span(const Scene& scene) {
    return std::max(scene.bounds_max.x - scene.bounds_min.x, scene.bounds_max.z - scene.bounds_min.z);
}

// The sun moves this far along its path (in t, 0 to 1) per flicker frame: about 0.3 degrees.
constexpr double sun_flicker_step = 0.002;

// The sun's path for a scene's sun, through it at t = 0.5, from 80 degrees of azimuth before it to
// 80 after it, 10 degrees above the horizon at both ends: what occlusion interval maps bake. Every
// setting under the sun sees the same sun, at the same t.
inline SunPath path_through(const SunLight& sun) {
    const glm::dvec3 to_sun = -glm::normalize(sun.direction);
    const double elevation = glm::degrees(std::asin(std::clamp(to_sun.y, -1.0, 1.0)));
    const double azimuth = glm::degrees(std::atan2(to_sun.x, -to_sun.z)); // clockwise from north (-z)
    return {{{azimuth - 80.0, 10.0}, {azimuth, elevation}, {azimuth + 80.0, 10.0}}};
}

// One light of a measurement: the scene's rectangle or its sun at a multiple of its size (the
// rectangle's sides, the sun's angular diameter), at frame `frame` of the flicker motion (the
// rectangle moves along its u axis by rect_step per frame, the sun along its path).
struct LightAt {
    RectLight rect;
    SunLight sun;
    double t = 0.5; // the sun's time on its path
};

inline LightAt light_at(const Scene& scene, const SunPath& path, double scale, double rect_step, int frame) {
    LightAt l{moved_light(scaled_light(scene.light, scale), rect_step, frame), scene.sun, 0.5 + sun_flicker_step * frame};
    l.sun.direction = -sun_direction(path, l.t);
    l.sun.angular_diameter *= scale;
    return l;
}

inline void set_light(gl::Runtime& runtime, const Scene& scene, Light kind, const SunPath& path, const LightAt& l, bool oim) {
    if (kind == Light::sun) runtime.set_light(l.sun, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
    else runtime.set_light(l.rect, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
    if (oim) runtime.set_time_window(oim_time_window(path, l.t, l.sun.angular_diameter));
}

} // namespace penumbra::bench
