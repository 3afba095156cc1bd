// penumbra/sun_path.hpp — the sun on a fixed path over a day, for occlusion interval maps
// (Donnelly & Demers, GPU Gems ch. 13): directions over a parameter t in [0, 1] and the time
// window of width dt that stands for the sun's disk.
//
//   penumbra::SunPath path;                                   // a default day, east to south to west
//   if (auto errors = penumbra::validate(path); !errors.empty()) { /* errors[0].message */ }
//   glm::dvec3 towards_sun = penumbra::sun_direction(path, 0.5);          // noon, unit length
//   penumbra::SunWindow w = penumbra::sun_window(path, 0.5, 0.0465);      // penumbra_timeWindow
//
// Frame: +y up, azimuth clockwise from north seen from above, north = −z, east = +x.
// GLM only, no GL.
#pragma once

#include "validate.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace penumbra {

// One point of the path, in degrees. Points are evenly spaced in t; between two neighbours the sun
// moves along the great circle at constant speed.
struct SunPathPoint {
    double azimuth_degrees = 180.0;  // clockwise from north (−z) seen from above: 90 east (+x), 180 south (+z)
    double elevation_degrees = 45.0; // above the horizon (the plane y = 0); −90 to 90

    friend constexpr bool operator==(const SunPathPoint&, const SunPathPoint&) = default;
};

struct SunPath {
    // Default: morning (east-south-east, 10°) to noon (south, 50°) to evening (west-south-west, 10°).
    std::vector<SunPathPoint> points{{100.0, 10.0}, {180.0, 50.0}, {260.0, 10.0}};

    friend bool operator==(const SunPath&, const SunPath&) = default;
};

// The time window of a linear light along the path: visibility is averaged over t in
// [start, end]; inverse_width = 1 / (end − start) (the chapter's intervalStart, intervalEnd,
// intervalInverseWidth). A zero angular diameter gives the narrowest window, min_window_width:
// the hard shadow of the sun's centre.
struct SunWindow {
    double start = 0.0, end = 0.0, inverse_width = 0.0;
};

inline constexpr double min_window_width = 1e-6; // in t; narrower windows are widened to this

namespace detail {

inline glm::dvec3 direction_from_degrees(const SunPathPoint& p) {
    const double az = glm::radians(p.azimuth_degrees), el = glm::radians(p.elevation_degrees);
    return {std::sin(az) * std::cos(el), std::sin(el), -std::cos(az) * std::cos(el)};
}

inline double angle_between(glm::dvec3 a, glm::dvec3 b) {
    return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

inline std::string format_double(double value) {
    std::string text = std::to_string(value);
    while (text.size() > 1 && text.back() == '0') text.pop_back();
    if (!text.empty() && text.back() == '.') text.pop_back();
    return text;
}

} // namespace detail

// Every problem with `path`; empty when it is valid. A path needs two or more points, finite
// angles (azimuth −360 to 360, elevation −90 to 90), neighbours neither equal nor opposite, and
// at least one point above the horizon.
inline std::vector<ConfigError> validate(const SunPath& path) {
    std::vector<ConfigError> errors;
    auto add = [&](std::string field, std::string value, std::string what) {
        errors.push_back({field, value, field + ": " + value + " " + what});
    };
    const std::size_t n = path.points.size();
    if (n < 2) {
        add("sun_path", std::to_string(n) + " point(s)",
            "is too short; allowed: two or more azimuth/elevation points (degrees), evenly spaced in t");
        return errors;
    }
    for (std::size_t i = 0; i < n; ++i) {
        const SunPathPoint& p = path.points[i];
        const std::string where = "sun_path[" + std::to_string(i) + "]";
        if (!std::isfinite(p.azimuth_degrees) || std::abs(p.azimuth_degrees) > 360.0)
            add(where + ".azimuth", detail::format_double(p.azimuth_degrees), "is out of range; allowed: -360 to 360 degrees");
        if (!std::isfinite(p.elevation_degrees) || std::abs(p.elevation_degrees) > 90.0)
            add(where + ".elevation", detail::format_double(p.elevation_degrees), "is out of range; allowed: -90 to 90 degrees");
    }
    if (!errors.empty()) return errors;
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const double angle = detail::angle_between(detail::direction_from_degrees(path.points[i]),
                                                   detail::direction_from_degrees(path.points[i + 1]));
        const std::string where = "sun_path[" + std::to_string(i) + "]";
        if (angle < 1e-6)
            add(where, "to point " + std::to_string(i + 1),
                "has zero length (the sun would stand still); allowed: neighbouring points in different directions");
        else if (angle > glm::pi<double>() - 1e-6)
            add(where, "to point " + std::to_string(i + 1),
                "joins opposite directions (no unique great circle); allowed: neighbours less than 180 degrees apart");
    }
    bool above = false;
    for (const SunPathPoint& p : path.points) above = above || p.elevation_degrees > 0.0;
    if (!above)
        add("sun_path", "elevations", "never rise above the horizon (no sunlight at any t); allowed: at least one point with elevation above 0");
    return errors;
}

// Unit vector from the scene towards the sun at t (clamped to [0, 1]). Precondition: validate(path) is empty.
inline glm::dvec3 sun_direction(const SunPath& path, double t) {
    const int segments = static_cast<int>(path.points.size()) - 1;
    const double s = std::clamp(t, 0.0, 1.0) * segments;
    const int k = std::min(static_cast<int>(s), segments - 1);
    const double f = s - k;
    const glm::dvec3 a = detail::direction_from_degrees(path.points[k]);
    const glm::dvec3 b = detail::direction_from_degrees(path.points[k + 1]);
    const double angle = detail::angle_between(a, b);
    // slerp: constant angular speed along the great circle
    const glm::dvec3 d = (std::sin((1.0 - f) * angle) * a + std::sin(f * angle) * b) / std::sin(angle);
    return glm::normalize(d);
}

// Angular speed of the sun at t, in radians per unit of t.
inline double sun_speed(const SunPath& path, double t) {
    const int segments = static_cast<int>(path.points.size()) - 1;
    const int k = std::min(static_cast<int>(std::clamp(t, 0.0, 1.0) * segments), segments - 1);
    return segments * detail::angle_between(detail::direction_from_degrees(path.points[k]),
                                            detail::direction_from_degrees(path.points[k + 1]));
}

// The window centred at t whose width dt is the time the sun takes to move by its angular
// diameter (radians): the sun's disk becomes a linear light along the path (GPU Gems ch. 13).
inline SunWindow sun_window(const SunPath& path, double t, double angular_diameter) {
    const double width = std::max(angular_diameter / sun_speed(path, t), min_window_width);
    return {t - 0.5 * width, t + 0.5 * width, 1.0 / width};
}

} // namespace penumbra
