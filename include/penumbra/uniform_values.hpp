// penumbra/uniform_values.hpp — the value of every uniform whose layout.json "source" is "light"
// (and "camera" when the camera is given), by name: one table, no technique branches. A new
// technique adds names to the table; the runtime sets whatever the layout's programs declare.
//
//   penumbra::UniformInputs in{.frame = penumbra::slice_frame(light, lo, hi, config.slices), .light = config.light};
//   penumbra::UniformResult v = penumbra::uniform_value("penumbra_sliceDepths", in);
//   if (!v) log(v.error); // e.g. "penumbra_shadowDepthRange: UniformInputs::shadow is not set; set it to …"
//
// GLM only, no GL.
#pragma once

#include "config.hpp"
#include "light_frame.hpp"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace penumbra {

using UniformValue = std::variant<int, float, glm::vec2, glm::vec4, glm::mat4>;

// Everything a uniform value may be computed from. Each input is optional: a uniform whose input
// is unset has no value, and uniform_value says which input to set (never a default of zeros).
struct UniformInputs {
    std::optional<SliceFrame> frame;          // slice_frame(light, bounds_min, bounds_max, slices)
    Light light = Light::rect;                // which light the frames were made for
    std::optional<glm::mat4> clip_from_world; // the viewer's camera, when the caller has one
    std::optional<ShadowFrame> shadow;        // shadow_frame(light, bounds_min, bounds_max): shadow map techniques
    // Occlusion interval maps: the sun's time window along its path (penumbra::sun_window: start,
    // end, 1 / width, centre t), when the light is a sun on a path.
    std::optional<glm::vec4> time_window;
};

// A uniform's value, or one line saying why there is none: the input to set, or that no rule has
// the name. Tests true when there is a value; *result is the value.
struct UniformResult {
    std::optional<UniformValue> value;
    std::string error; // e.g. "penumbra_shadowDepthRange: UniformInputs::shadow is not set; set it to penumbra::shadow_frame(light, bounds_min, bounds_max)"

    explicit operator bool() const { return value.has_value(); }
    const UniformValue& operator*() const { return *value; }
};

struct UniformRule {
    std::string_view name;
    // Computes the value; gets the rule's name for its error message.
    UniformResult (*compute)(std::string_view name, const UniformInputs&);

    UniformResult value(const UniformInputs& in) const { return compute(name, in); }
};

namespace detail {

// The error of a uniform whose input is unset, naming the field and what fills it.
inline UniformResult missing_input(std::string_view uniform, std::string_view field, std::string_view how) {
    return {std::nullopt, std::string(uniform) + ": UniformInputs::" + std::string(field) + " is not set; set it to " +
                              std::string(how)};
}

// penumbra_toLight: rect: the light's centre (the light frame's origin), w = 1; sun: the direction
// towards the sun (minus the light frame's z axis), w = 0.
inline glm::vec4 to_light(const glm::mat4& light_from_world, bool sun) {
    const glm::mat4 world_from_light = glm::inverse(light_from_world);
    if (sun) return glm::vec4(-glm::vec3(world_from_light[2]), 0.0f);
    return glm::vec4(glm::vec3(world_from_light[3]), 1.0f);
}

constexpr std::string_view slice_frame_how = "penumbra::slice_frame(light, bounds_min, bounds_max, slices)";
constexpr std::string_view shadow_frame_how = "penumbra::shadow_frame(light, bounds_min, bounds_max)";

// A value read from the slice frame (occlusion textures), or the error naming it.
template <class F> UniformResult from_frame(std::string_view name, const UniformInputs& in, F read) {
    if (!in.frame) return missing_input(name, "frame", slice_frame_how);
    return {UniformValue(read(*in.frame)), {}};
}

// A value read from the shadow-map camera (shadow map techniques), or the error naming it.
template <class F> UniformResult from_shadow(std::string_view name, const UniformInputs& in, F read) {
    if (!in.shadow) return missing_input(name, "shadow", shadow_frame_how);
    return {UniformValue(read(*in.shadow)), {}};
}

// A value both frames carry the same (the light frame, the light's size): from whichever is set.
template <class F, class G>
UniformResult from_either(std::string_view name, const UniformInputs& in, F read_frame, G read_shadow) {
    if (in.frame) return {UniformValue(read_frame(*in.frame)), {}};
    if (in.shadow) return {UniformValue(read_shadow(*in.shadow)), {}};
    return {std::nullopt, std::string(name) + ": neither UniformInputs::frame nor UniformInputs::shadow is set; set " +
                              "frame to " + std::string(slice_frame_how) + " or shadow to " + std::string(shadow_frame_how)};
}

} // namespace detail

// The table: name → how to compute it.
inline const std::vector<UniformRule>& uniform_rules() {
    using R = UniformResult;
    using detail::from_either;
    using detail::from_frame;
    using detail::from_shadow;
    static const std::vector<UniformRule> rules{
        // the same in both frames: penumbra_lightFromWorld, penumbra_lightSize, penumbra_windowHalfSize,
        // penumbra_tanAngularRadius
        {"penumbra_lightFromWorld",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_either(name, in, [](const SliceFrame& f) { return f.light_from_world; },
                                [](const ShadowFrame& s) { return s.light_from_world; });
         }},
        {"penumbra_sliceClipFromWorld",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_frame(name, in, [](const SliceFrame& f) { return f.slice_clip_from_world; });
         }},
        {"penumbra_sliceDepths",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_frame(name, in, [](const SliceFrame& f) { return f.slice_depths; });
         }},
        {"penumbra_lightSize",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_either(name, in, [](const SliceFrame& f) { return f.light_size; },
                                [](const ShadowFrame& s) { return s.light_size; });
         }},
        {"penumbra_copDistance",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_frame(name, in, [](const SliceFrame& f) { return f.cop_distance; });
         }},
        {"penumbra_windowHalfSize",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_either(name, in, [](const SliceFrame& f) { return f.window_half_size; },
                                [](const ShadowFrame& s) { return s.window_half_size; });
         }},
        {"penumbra_tanAngularRadius",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_either(name, in, [](const SliceFrame& f) { return f.tan_angular_radius; },
                                [](const ShadowFrame& s) { return s.tan_angular_radius; });
         }},
        // shadow map techniques (shadow_frame)
        {"penumbra_shadowClipFromWorld",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_shadow(name, in, [](const ShadowFrame& s) { return s.shadow_clip_from_world; });
         }},
        {"penumbra_shadowDepthRange",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_shadow(name, in, [](const ShadowFrame& s) { return s.depth_range; });
         }},
        {"penumbra_shadowTanHalfFov",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_shadow(name, in, [](const ShadowFrame& s) { return s.tan_half_fov; });
         }},
        {"penumbra_lightSizeUV",
         [](std::string_view name, const UniformInputs& in) -> R {
             return from_shadow(name, in, [](const ShadowFrame& s) { return s.light_size_uv; });
         }},
        {"penumbra_toLight", // detail::to_light
         [](std::string_view name, const UniformInputs& in) -> R {
             const bool sun = in.light == Light::sun;
             return from_either(name, in,
                 [sun](const SliceFrame& f) { return detail::to_light(f.light_from_world, sun); },
                 [sun](const ShadowFrame& s) { return detail::to_light(s.light_from_world, sun); });
         }},
        {"penumbra_timeWindow",
         [](std::string_view name, const UniformInputs& in) -> R {
             if (!in.time_window)
                 return detail::missing_input(name, "time_window",
                                              "penumbra::sun_window(...) of the sun's path (penumbra/sun_path.hpp)");
             return {*in.time_window, {}};
         }},
        {"penumbra_clipFromWorld",
         [](std::string_view name, const UniformInputs& in) -> R {
             if (!in.clip_from_world)
                 return detail::missing_input(name, "clip_from_world",
                                              "the viewer's clip-from-world matrix (projection * view)");
             return {*in.clip_from_world, {}};
         }},
    };
    return rules;
}

// The value of uniform `name`, or an error naming the input to set (or saying that no rule has
// the name): never a default value standing in for a missing input.
inline UniformResult uniform_value(std::string_view name, const UniformInputs& in) {
    for (const UniformRule& rule : uniform_rules())
        if (rule.name == name) return rule.value(in);
    return {std::nullopt, std::string(name) + ": no rule computes this uniform (penumbra/uniform_values.hpp, uniform_rules())"};
}

inline bool has_uniform_rule(std::string_view name) {
    for (const UniformRule& rule : uniform_rules())
        if (rule.name == name) return true;
    return false;
}

} // namespace penumbra
