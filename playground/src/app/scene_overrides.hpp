// playground/src/app/scene_overrides.hpp — the light and camera given on the command line
// (--light-center, --light-normal, --light-up, --light-size, --camera-position, --camera-target),
// parsed, checked and set on a scene after it is made (a built-in scene or a loaded file alike).
// Shared by penumbra-playground (headless and window) and the GL benchmarks, so that every tool
// accepts and rejects the same text with the same messages. Header-only: it needs the scene's
// types (scenes/scene.hpp) and the project's number parsing (penumbra_tools/cli.hpp).
#pragma once

#include "scenes/scene.hpp"

#include <penumbra/config.hpp>
#include <penumbra/light.hpp>
#include <penumbra_tools/cli.hpp>
#include <penumbra_tools/printable.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::playground {

// What the command line says of the scene's light and camera; each unset field keeps the scene's.
struct SceneOverrides {
    std::optional<glm::dvec3> light_center; // --light-center X,Y,Z
    std::optional<glm::dvec3>
        light_normal;                      // --light-normal X,Y,Z: unit length, where the light emits towards
    std::optional<glm::dvec3> light_up;    // --light-up X,Y,Z: unit length, the light's v (height) side
    std::optional<double> light_size;      // --light-size W: the longer side (aspect kept) / sun degrees
    std::optional<glm::dvec2> light_sides; // --light-size W,H: width along u, height along v
    std::optional<glm::dvec3> camera_position; // --camera-position X,Y,Z
    std::optional<glm::dvec3> camera_target;   // --camera-target X,Y,Z

    // True when the rectangle light's place, orientation or sides are given (not the one-number size).
    bool moves_rect() const { return light_center || light_normal || light_up || light_sides; }
    bool moves_camera() const { return camera_position || camera_target; }
};

// Coordinates of points are finite and within this (as a mesh file's, scenes/obj_loader.hpp).
inline constexpr double override_coordinate_limit = 1e9;
// --light-up closer than this (the sine of the angle) to the normal is parallel: about 0.06°.
inline constexpr double override_parallel_sine = 1e-3;
// A camera target closer than this to the position is the position.
inline constexpr double override_min_camera_distance = 1e-6;
// A camera straight above or below its target is tilted this far (radians, 0.1°) off the vertical:
// the orbit camera's view keeps +y up.
inline constexpr double override_vertical_margin = 0.0017453292519943296;

inline constexpr const char* scene_override_flag_list =
    "--light-center, --light-normal, --light-up, --light-size, --camera-position, --camera-target";

inline bool is_scene_override_flag(std::string_view flag) {
    for (std::string_view f : {"--light-center", "--light-normal", "--light-up", "--light-size",
                               "--camera-position", "--camera-target"})
        if (flag == f) return true;
    return false;
}

namespace overrides_detail {

inline std::string shown(double x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

inline std::string shown(glm::dvec3 v) { return shown(v.x) + "," + shown(v.y) + "," + shown(v.z); }

// "a,b,c" → its numbers; *error (without the flag) on text that is not `count` finite numbers.
inline std::optional<std::vector<double>> numbers(std::string_view text, std::size_t min_count,
                                                  std::size_t max_count, std::string* error) {
    std::vector<double> values;
    std::string_view rest = text;
    while (true) {
        const std::size_t comma = rest.find(',');
        const std::string_view part = rest.substr(0, comma);
        double value = 0.0;
        if (!cli::parse_number(part, value) || !std::isfinite(value)) {
            *error = "'" + penumbra_gen::printable(text) + "': '" + penumbra_gen::printable(part) +
                     "' is not a finite number";
            return std::nullopt;
        }
        values.push_back(value);
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
    }
    if (values.size() < min_count || values.size() > max_count) {
        *error = "'" + penumbra_gen::printable(text) + "' has " + std::to_string(values.size()) + " number" +
                 (values.size() == 1 ? "" : "s");
        return std::nullopt;
    }
    return values;
}

// `v` at unit length, scaled first so that no square overflows; nullopt for the zero vector.
inline std::optional<glm::dvec3> unit(glm::dvec3 v) {
    const double m = std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)});
    if (!(m > 0.0) || !std::isfinite(m)) return std::nullopt;
    v /= m;
    return v / glm::length(v);
}

// The sine of the angle between two unit vectors (0: parallel or opposite).
inline double sine_between(glm::dvec3 a, glm::dvec3 b) { return glm::length(glm::cross(a, b)); }

} // namespace overrides_detail

// One of the flags above with its value: "" when it parsed, else the one-line message, without the
// "error: " prefix ("--light-normal: '0,0,0' has zero length; allowed: ...").
inline std::string parse_scene_override(std::string_view flag, std::string_view value, SceneOverrides& o) {
    using namespace overrides_detail;
    std::string error;
    const std::string name(flag);
    if (flag == "--light-size") {
        const std::string allowed =
            "; allowed: W, the rectangle's longer side in scene units with its aspect kept (rect) or the "
            "sun's "
            "angular diameter in degrees, below 90 (sun); or W,H, the rectangle's width (along u) and height "
            "(along v) in scene units; each a positive finite number";
        const std::optional<std::vector<double>> v = numbers(value, 1, 2, &error);
        if (!v) {
            // One number that is not a positive number keeps its message of before W,H existed.
            if (value.find(',') == std::string_view::npos)
                return name + ": '" + penumbra_gen::printable(value) + "' is not a positive number" + allowed;
            return name + ": " + error + allowed;
        }
        for (double x : *v)
            if (!(x > 0.0))
                return name + ": '" + penumbra_gen::printable(value) + "' is not a positive number" +
                       (v->size() == 2 ? " pair" : "") + allowed;
        if (v->size() == 1) {
            o.light_size = (*v)[0];
            o.light_sides.reset();
        } else {
            o.light_sides = glm::dvec2((*v)[0], (*v)[1]);
            o.light_size.reset();
        }
        return {};
    }
    const bool direction = flag == "--light-normal" || flag == "--light-up";
    const std::string allowed =
        direction ? std::string("; allowed: a direction X,Y,Z, three finite numbers not all 0, e.g. ") +
                        (flag == "--light-normal" ? "0,-1,0 (emitting straight down)" : "0,0,1")
                  : "; allowed: a point X,Y,Z, three finite numbers within ±1e9, e.g. 0,10,0";
    const std::optional<std::vector<double>> v = numbers(value, 3, 3, &error);
    if (!v) return name + ": " + error + allowed;
    const glm::dvec3 p((*v)[0], (*v)[1], (*v)[2]);
    if (direction) {
        const std::optional<glm::dvec3> u = unit(p);
        if (!u) return name + ": '" + penumbra_gen::printable(value) + "' has zero length" + allowed;
        (flag == "--light-normal" ? o.light_normal : o.light_up) = *u;
        return {};
    }
    for (int i = 0; i < 3; ++i)
        if (std::abs(p[i]) > override_coordinate_limit)
            return name + ": '" + penumbra_gen::printable(value) + "' is out of range" + allowed;
    if (flag == "--light-center")
        o.light_center = p;
    else if (flag == "--camera-position")
        o.camera_position = p;
    else
        o.camera_target = p; // --camera-target
    return {};
}

// Checks between the flags, once all are parsed: the up side parallel to the normal, the camera's
// target at its position. "" or the message.
inline std::string check_scene_overrides(const SceneOverrides& o) {
    using namespace overrides_detail;
    if (o.light_normal && o.light_up && sine_between(*o.light_normal, *o.light_up) < override_parallel_sine)
        return "--light-up: " + shown(*o.light_up) + " is parallel to --light-normal " +
               shown(*o.light_normal) +
               "; allowed: a direction at least 0.06 degrees off the normal (the light's height side, v)";
    if (o.camera_position && o.camera_target &&
        glm::length(*o.camera_target - *o.camera_position) < override_min_camera_distance)
        return "--camera-target: " + shown(*o.camera_target) +
               " is the camera's position (--camera-position); allowed: a point other than the position";
    return {};
}

// The rectangle's frame with this normal: v along `up` projected onto the light's plane, u = cross(v,
// normal), so that cross(u, v) == normal. `up` must not be parallel to the normal.
inline void orient_rect(RectLight& light, glm::dvec3 normal, glm::dvec3 up) {
    const glm::dvec3 u = glm::normalize(glm::cross(up, normal));
    light.u_axis = u;
    light.v_axis = glm::cross(normal, u); // = up − normal·(normal·up), normalised: unit since u ⟂ normal
}

// The up side when --light-up is absent: the light's own v axis projected onto the plane when it is
// not parallel to the normal, else world +y, else +z.
inline glm::dvec3 default_light_up(const RectLight& light, glm::dvec3 normal) {
    for (const glm::dvec3 up : {light.v_axis, glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 0.0, 1.0)})
        if (overrides_detail::sine_between(normal, glm::normalize(up)) >= override_parallel_sine) return up;
    return {1.0, 0.0, 0.0}; // unreachable: +y and +z are not both parallel to one direction
}

// --light-size W for the rectangle: its longer side becomes W, the aspect kept; for the sun, the
// angular diameter in degrees.
inline void scale_light_to(Scene& scene, Light light, double size) {
    if (light == Light::sun) {
        scene.sun.angular_diameter = size * 3.14159265358979323846 / 180.0;
        return;
    }
    const double scale = size / std::max(scene.light.width, scene.light.height);
    scene.light.width *= scale;
    scene.light.height *= scale;
}

// The orbit camera that looks from `position` at `target` (distinct points). Straight above or below
// it is tilted override_vertical_margin off the vertical (the view keeps +y up). The far plane reaches
// past the scene's bounds, the near plane is no farther than 1% of the distance.
inline void place_camera(OrbitCamera& camera, glm::dvec3 position, glm::dvec3 target, glm::vec3 bounds_min,
                         glm::vec3 bounds_max) {
    const glm::dvec3 d = position - target;
    const double distance = glm::length(d);
    const double limit = 0.5 * 3.14159265358979323846 - override_vertical_margin;
    const double pitch = std::clamp(std::asin(std::clamp(d.y / distance, -1.0, 1.0)), -limit, limit);
    const double yaw = std::hypot(d.x, d.z) > 0.0 ? std::atan2(d.x, d.z) : 0.0;
    camera.target = glm::vec3(target);
    camera.distance = static_cast<float>(distance);
    camera.yaw_radians = static_cast<float>(yaw);
    camera.pitch_radians = static_cast<float>(pitch);
    const glm::dvec3 centre = 0.5 * (glm::dvec3(bounds_min) + glm::dvec3(bounds_max));
    const double radius = 0.5 * glm::length(glm::dvec3(bounds_max) - glm::dvec3(bounds_min));
    camera.z_far =
        std::max(camera.z_far, static_cast<float>(glm::length(position - centre) + 2.0 * radius + 1.0));
    camera.z_near = std::min(camera.z_near, std::max(1e-3f, 0.01f * camera.distance));
}

// Sets the overrides on a made scene: the rectangle's centre, frame and sides (then --light-size W:
// its longer side, or the sun's diameter when `light` is the sun), the camera. "" or the message of
// what only the scene could tell (its light's normal parallel to --light-up, the scene's camera target
// at --camera-position); the scene is then left as it was.
inline std::string apply_scene_overrides(const SceneOverrides& o, Scene& scene, Light light) {
    using namespace overrides_detail;
    RectLight rect = scene.light;
    if (o.light_center) rect.center = *o.light_center;
    if (o.light_normal || o.light_up) {
        const glm::dvec3 normal = o.light_normal ? *o.light_normal : rect.normal();
        if (o.light_up && sine_between(normal, *o.light_up) < override_parallel_sine)
            return "--light-up: " + shown(*o.light_up) + " is parallel to the scene light's normal " +
                   shown(normal) +
                   "; allowed: a direction at least 0.06 degrees off the normal (or give --light-normal)";
        orient_rect(rect, normal, o.light_up ? *o.light_up : default_light_up(rect, normal));
    }
    if (o.light_sides) {
        rect.width = o.light_sides->x;
        rect.height = o.light_sides->y;
    }
    OrbitCamera camera = scene.camera;
    if (o.moves_camera()) {
        const glm::dvec3 position =
            o.camera_position ? *o.camera_position : glm::dvec3(scene.camera.eye_position());
        const glm::dvec3 target = o.camera_target ? *o.camera_target : glm::dvec3(scene.camera.target);
        if (glm::length(target - position) < override_min_camera_distance)
            return o.camera_position
                       ? "--camera-position: " + shown(position) +
                             " is the scene camera's target; allowed: a point other than it (or give "
                             "--camera-target)"
                       : "--camera-target: " + shown(target) +
                             " is the scene camera's position; allowed: a point other than it (or give "
                             "--camera-position)";
        place_camera(camera, position, target, scene.bounds_min, scene.bounds_max);
    }
    scene.light = rect;
    scene.camera = camera;
    if (o.light_size) scale_light_to(scene, light, *o.light_size);
    return {};
}

// The --help lines of the flags, `column` the indent of the descriptions.
inline std::string scene_override_usage(std::size_t column = 24) {
    auto line = [column](std::string_view flag, std::string_view text) {
        std::string out = "  " + std::string(flag);
        out.resize(std::max<std::size_t>(out.size() + 1, column), ' ');
        std::string indented;
        for (char c : text) {
            indented += c;
            if (c == '\n') indented += std::string(column, ' ');
        }
        return out + indented + "\n";
    };
    std::string out;
    out += line("--light-size W[,H]",
                "W: the rectangle's longer side in scene units, aspect kept (default: the\n"
                "scene's, 2 for the procedural scenes), or with the sun its angular\n"
                "diameter in degrees, below 90 (default 2.66, five times the real sun);\n"
                "W,H: the rectangle's width (along u) and height (along v). Positive");
    out += line("--light-center X,Y,Z", "the rectangle light's centre (default: the scene's)");
    out += line("--light-normal X,Y,Z",
                "the direction the rectangle faces and emits towards, not 0 (default: the\n"
                "scene's, 0,-1,0 for the procedural scenes: straight down)");
    out += line("--light-up X,Y,Z",
                "the direction of the rectangle's height side (v), projected onto its plane;\n"
                "not parallel to the normal (default: the scene light's v when not\n"
                "parallel to the normal, else +y, else +z). u = v x normal, so that\n"
                "normal = u x v");
    out += line("--camera-position X,Y,Z", "where the camera is (default: the scene's camera)");
    out += line("--camera-target X,Y,Z",
                "the point it looks at, not its position (default: the scene's); either flag\n"
                "alone keeps the other from the scene. Straight above or below the\n"
                "target it is tilted 0.1 degrees (the view keeps +y up)");
    out +=
        "  (light and camera flags are set after the scene is made, a built-in one or a file, and hold for\n"
        "  the ground truth too; points: finite numbers within ±1e9)\n";
    return out;
}

} // namespace penumbra::playground
