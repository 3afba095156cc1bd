// penumbra/uniform_values.hpp — the value of every uniform whose layout.json "source" is "light"
// (and "camera" when the camera is given), by name: one table, no technique branches. A new
// technique adds names to the table; the runtime sets whatever the layout's programs declare.
//
//   penumbra::UniformInputs in{.frame = penumbra::slice_frame(light, lo, hi, config.slices), .light = config.light};
//   std::optional<penumbra::UniformValue> v = penumbra::uniform_value("penumbra_sliceDepths", in);
//
// GLM only, no GL.
#pragma once

#include "config.hpp"
#include "light_frame.hpp"

#include <glm/glm.hpp>

#include <optional>
#include <string_view>
#include <variant>
#include <vector>

namespace penumbra {

using UniformValue = std::variant<int, float, glm::vec2, glm::vec4, glm::mat4>;

// Everything a uniform value may be computed from.
struct UniformInputs {
    SliceFrame frame;                         // slice_frame(light, bounds_min, bounds_max, slices)
    Light light = Light::rect;                // which slice_frame made it
    std::optional<glm::mat4> clip_from_world; // the viewer's camera, when the caller has one
    ShadowFrame shadow;                       // shadow_frame(light, bounds_min, bounds_max): shadow map techniques
    // Occlusion interval maps: the sun's time window along its path (penumbra::sun_window: start,
    // end, 1 / width, centre t), when the light is a sun on a path.
    std::optional<glm::vec4> time_window;
};

struct UniformRule {
    std::string_view name;
    std::optional<UniformValue> (*value)(const UniformInputs&);
};

// The table: name → how to compute it.
inline const std::vector<UniformRule>& uniform_rules() {
    using V = std::optional<UniformValue>;
    static const std::vector<UniformRule> rules{
        {"penumbra_lightFromWorld", [](const UniformInputs& in) -> V { return in.frame.light_from_world; }},
        {"penumbra_sliceClipFromWorld", [](const UniformInputs& in) -> V { return in.frame.slice_clip_from_world; }},
        {"penumbra_sliceDepths", [](const UniformInputs& in) -> V { return in.frame.slice_depths; }},
        {"penumbra_lightSize", [](const UniformInputs& in) -> V { return in.frame.light_size; }},
        {"penumbra_copDistance", [](const UniformInputs& in) -> V { return in.frame.cop_distance; }},
        {"penumbra_windowHalfSize", [](const UniformInputs& in) -> V { return in.frame.window_half_size; }},
        {"penumbra_tanAngularRadius", [](const UniformInputs& in) -> V { return in.frame.tan_angular_radius; }},
        // shadow map techniques (shadow_frame); penumbra_lightFromWorld, penumbra_lightSize,
        // penumbra_windowHalfSize and penumbra_tanAngularRadius are the same in both frames
        {"penumbra_shadowClipFromWorld", [](const UniformInputs& in) -> V { return in.shadow.shadow_clip_from_world; }},
        {"penumbra_shadowDepthRange", [](const UniformInputs& in) -> V { return in.shadow.depth_range; }},
        {"penumbra_shadowTanHalfFov", [](const UniformInputs& in) -> V { return in.shadow.tan_half_fov; }},
        {"penumbra_lightSizeUV", [](const UniformInputs& in) -> V { return in.shadow.light_size_uv; }},
        // rect: the light's centre (the light frame's origin), w = 1; sun: the direction towards the
        // sun (minus the light frame's z axis), w = 0
        {"penumbra_toLight",
         [](const UniformInputs& in) -> V {
             const glm::mat4 world_from_light = glm::inverse(in.frame.light_from_world);
             if (in.light == Light::sun) return glm::vec4(-glm::vec3(world_from_light[2]), 0.0f);
             return glm::vec4(glm::vec3(world_from_light[3]), 1.0f);
         }},
        {"penumbra_timeWindow",
         [](const UniformInputs& in) -> V {
             if (!in.time_window) return std::nullopt;
             return *in.time_window;
         }},
        {"penumbra_clipFromWorld",
         [](const UniformInputs& in) -> V {
             if (!in.clip_from_world) return std::nullopt;
             return *in.clip_from_world;
         }},
    };
    return rules;
}

// The value of uniform `name`, or nothing when the table has no rule for it (or lacks its input).
inline std::optional<UniformValue> uniform_value(std::string_view name, const UniformInputs& in) {
    for (const UniformRule& rule : uniform_rules())
        if (rule.name == name) return rule.value(in);
    return std::nullopt;
}

inline bool has_uniform_rule(std::string_view name) {
    for (const UniformRule& rule : uniform_rules())
        if (rule.name == name) return true;
    return false;
}

} // namespace penumbra
