// penumbra/uniform_values.hpp — the value of every uniform whose layout.json "source" is "light"
// (and "camera" when the camera is given), by name: the registry's rows (penumbra/uniforms.hpp) say
// what each is read from, and one reader per row here reads it (GLM lives here, not in the
// registry). A new uniform is a row there and a reader here; the runtime sets whatever the
// layout's programs declare.
//
//   penumbra::UniformInputs in{.frame = penumbra::slice_frame(light, lo, hi, config.slices), .light = config.light};
//   penumbra::UniformResult v = penumbra::uniform_value("penumbra_sliceDepths", in);
//   if (!v) log(v.error); // e.g. "penumbra_shadowDepthRange: UniformInputs::shadow is not set; set it to …"
//
// GLM only, no GL.
#pragma once

#include "config.hpp"
#include "light_frame.hpp"
#include "uniforms.hpp"

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

// How each registry row's value is read from the frame its UniformDef::input names, indexed by
// penumbra::Uniform: from_frame for slice_frame and either_frame, from_shadow for shadow_frame and
// either_frame; the time window, the camera and per-draw values need no reader.
struct UniformReader {
    Uniform id;
    UniformValue (*from_frame)(const SliceFrame&, Light) = nullptr;
    UniformValue (*from_shadow)(const ShadowFrame&, Light) = nullptr;
};

inline constexpr UniformReader uniform_readers[] = {
    {Uniform::light_from_world, [](const SliceFrame& f, Light) -> UniformValue { return f.light_from_world; },
     [](const ShadowFrame& s, Light) -> UniformValue { return s.light_from_world; }},
    {Uniform::slice_clip_from_world, [](const SliceFrame& f, Light) -> UniformValue { return f.slice_clip_from_world; }},
    {Uniform::slice_depths, [](const SliceFrame& f, Light) -> UniformValue { return f.slice_depths; }},
    {Uniform::light_size, [](const SliceFrame& f, Light) -> UniformValue { return f.light_size; },
     [](const ShadowFrame& s, Light) -> UniformValue { return s.light_size; }},
    {Uniform::cop_distance, [](const SliceFrame& f, Light) -> UniformValue { return f.cop_distance; }},
    {Uniform::window_half_size, [](const SliceFrame& f, Light) -> UniformValue { return f.window_half_size; },
     [](const ShadowFrame& s, Light) -> UniformValue { return s.window_half_size; }},
    {Uniform::tan_angular_radius, [](const SliceFrame& f, Light) -> UniformValue { return f.tan_angular_radius; },
     [](const ShadowFrame& s, Light) -> UniformValue { return s.tan_angular_radius; }},
    {Uniform::to_light, // detail::to_light
     [](const SliceFrame& f, Light light) -> UniformValue { return to_light(f.light_from_world, light == Light::sun); },
     [](const ShadowFrame& s, Light light) -> UniformValue { return to_light(s.light_from_world, light == Light::sun); }},
    {Uniform::clip_from_world},
    {Uniform::shadow_clip_from_world, nullptr,
     [](const ShadowFrame& s, Light) -> UniformValue { return s.shadow_clip_from_world; }},
    {Uniform::shadow_depth_range, nullptr, [](const ShadowFrame& s, Light) -> UniformValue { return s.depth_range; }},
    {Uniform::shadow_tan_half_fov, nullptr, [](const ShadowFrame& s, Light) -> UniformValue { return s.tan_half_fov; }},
    {Uniform::light_size_uv, nullptr, [](const ShadowFrame& s, Light) -> UniformValue { return s.light_size_uv; }},
    {Uniform::time_window},
    {Uniform::alpha_texture},
    {Uniform::alpha_cutoff},
    {Uniform::caster_closed},
};

constexpr bool readers_match_registry() {
    if (std::size(uniform_readers) != std::size(uniform_defs)) return false;
    for (std::size_t i = 0; i < std::size(uniform_readers); ++i) {
        const UniformReader& r = uniform_readers[i];
        const UniformInput input = uniform_defs[i].input;
        const bool frame = input == UniformInput::slice_frame || input == UniformInput::either_frame;
        const bool shadow = input == UniformInput::shadow_frame || input == UniformInput::either_frame;
        if (r.id != uniform_defs[i].id || (r.from_frame != nullptr) != frame || (r.from_shadow != nullptr) != shadow)
            return false;
    }
    return true;
}
// The order at compile time; the readers for each frame in the tests (tests/emitter_layout_test.cpp):
// sanitizer builds do not fold a function pointer's comparison with null in a constant expression.
constexpr bool readers_in_registry_order() {
    if (std::size(uniform_readers) != std::size(uniform_defs)) return false;
    for (std::size_t i = 0; i < std::size(uniform_readers); ++i)
        if (uniform_readers[i].id != uniform_defs[i].id) return false;
    return true;
}
static_assert(readers_in_registry_order(), "uniform_readers: one row per uniform_defs row, in the same order");

// The value of registry uniform `def` from `in`, or the error naming the input to set.
inline UniformResult registry_value(const UniformDef& def, const UniformInputs& in) {
    const UniformReader& read = uniform_readers[static_cast<std::size_t>(def.id)];
    switch (def.input) {
    case UniformInput::slice_frame:
        if (!in.frame) return missing_input(def.name, "frame", slice_frame_how);
        return {read.from_frame(*in.frame, in.light), {}};
    case UniformInput::shadow_frame:
        if (!in.shadow) return missing_input(def.name, "shadow", shadow_frame_how);
        return {read.from_shadow(*in.shadow, in.light), {}};
    case UniformInput::either_frame:
        if (in.frame) return {read.from_frame(*in.frame, in.light), {}};
        if (in.shadow) return {read.from_shadow(*in.shadow, in.light), {}};
        return {std::nullopt, std::string(def.name) + ": neither UniformInputs::frame nor UniformInputs::shadow is set; " +
                                  "set frame to " + std::string(slice_frame_how) + " or shadow to " +
                                  std::string(shadow_frame_how)};
    case UniformInput::time_window:
        if (!in.time_window)
            return missing_input(def.name, "time_window",
                                 "penumbra::sun_window(...) of the sun's path (penumbra/sun_path.hpp)");
        return {*in.time_window, {}};
    case UniformInput::clip_from_world:
        if (!in.clip_from_world)
            return missing_input(def.name, "clip_from_world", "the viewer's clip-from-world matrix (projection * view)");
        return {*in.clip_from_world, {}};
    case UniformInput::per_draw: break;
    }
    return {std::nullopt, std::string(def.name) + ": set by the caller for every draw, not computed"};
}

} // namespace detail

// The registry's uniforms that have a value here (every source but "draw"), name → how to compute it.
inline const std::vector<UniformRule>& uniform_rules() {
    static const std::vector<UniformRule> rules = [] {
        std::vector<UniformRule> out;
        for (const UniformDef& def : uniform_defs)
            if (def.input != UniformInput::per_draw)
                out.push_back({def.name, [](std::string_view name, const UniformInputs& in) {
                                   return detail::registry_value(*find_uniform(name), in);
                               }});
        return out;
    }();
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
