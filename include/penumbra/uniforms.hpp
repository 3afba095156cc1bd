// penumbra/uniforms.hpp — the uniform registry: one row per uniform whose value the caller sets
// from the light, the camera or the draw (name, GLSL type, meaning, units, source, what its value is
// computed from and how, as layout.json's "compute" says it). The emitters declare these uniforms
// from their rows, layout.json describes them from their rows, and penumbra::uniform_value
// (uniform_values.hpp) computes them from their rows. Uniforms a pass sets (int_uniforms) are
// declared by the program that reads them ("pass" source). Text and data only: no GLM, no GL.
//
//   const penumbra::UniformDef* u = penumbra::find_uniform("penumbra_sliceDepths");
//   u->meaning(penumbra::Light::rect); // "x: depth z0 of the first slice's top, y: slice thickness"
#pragma once

#include "config.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

namespace penumbra {

// Where a uniform's value comes from (layout.json "source"): "light" computed from the light's
// frames (uniform_value), "pass" the pass's int_uniforms, "camera" the viewer's camera (also in
// uniform_value when it is given), "draw" set by the caller per draw (alpha_test's material).
enum class UniformSource : std::uint8_t { light, pass, camera, draw };
template <> struct EnumNames<UniformSource> {
    static constexpr std::array<std::string_view, 4> names{"light", "pass", "camera", "draw"};
};

// The GLSL types of declared parameters that have a std140 layout (plain uniforms), and samplers.
enum class GlslType : std::uint8_t { int_, float_, vec2, vec3, vec4, mat4, sampler2D };
template <> struct EnumNames<GlslType> {
    static constexpr std::array<std::string_view, 7> names{"int", "float", "vec2", "vec3", "vec4", "mat4",
                                                           "sampler2D"};
};

// Bytes a plain uniform of `type` takes in a std140 block and the boundary it starts on: scalars
// 4 and 4, vec2 8 and 8, vec3 12 and 16, vec4 16 and 16, mat4 64 and 16 (four vec4 columns).
struct Std140 {
    int size = 0, align = 0;
};
constexpr Std140 std140(GlslType type) {
    constexpr std::array<Std140, 7> table{{{4, 4}, {4, 4}, {8, 8}, {12, 16}, {16, 16}, {64, 16}, {0, 0}}};
    return table[static_cast<std::size_t>(type)];
}

// What a light uniform's value is read from (UniformInputs, uniform_values.hpp).
enum class UniformInput : std::uint8_t {
    slice_frame,     // UniformInputs::frame: penumbra::slice_frame (occlusion textures)
    shadow_frame,    // UniformInputs::shadow: penumbra::shadow_frame (shadow map techniques)
    either_frame,    // the same in both frames: whichever is set
    time_window,     // UniformInputs::time_window: penumbra::sun_window (occlusion interval maps)
    clip_from_world, // UniformInputs::clip_from_world: the viewer's camera
    per_draw,        // no value here: the caller sets it for every draw
};

// Text that depends on the light: `rect` and `sun`; one empty means the other serves both.
struct PerLight {
    std::string_view rect, sun;
    constexpr std::string_view operator()(Light light) const {
        const std::string_view chosen = light == Light::sun ? sun : rect;
        return chosen.empty() ? (light == Light::sun ? rect : sun) : chosen;
    }
};

// The uniforms of the registry, in the order of its rows.
enum class Uniform : std::uint8_t {
    light_from_world,
    slice_clip_from_world,
    slice_depths,
    light_size,
    cop_distance,
    window_half_size,
    tan_angular_radius,
    to_light,
    clip_from_world,
    shadow_clip_from_world,
    shadow_depth_range,
    shadow_tan_half_fov,
    light_size_uv,
    time_window,
    alpha_texture,
    alpha_cutoff,
    caster_closed,
};

struct UniformDef {
    Uniform id;
    std::string_view name; // the GLSL identifier
    GlslType type;
    UniformSource source;
    UniformInput input;
    PerLight meaning; // one line, for the declaration comment and layout.json "meaning"
    PerLight units;   // "scene units", "uv", … ("" when unitless)
    PerLight compute; // layout.json "compute": how to compute the value (docs/model.md §1)
};

// The registry. The derivations: docs/model.md §1; the values: penumbra/light_frame.hpp.
inline constexpr UniformDef uniform_defs[] = {
    {Uniform::light_from_world, "penumbra_lightFromWorld", GlslType::mat4, UniformSource::light,
     UniformInput::either_frame,
     {"world to light frame: x, y lateral, z depth along the light normal, origin at the light centre",
      "world to light frame: x, y lateral, z depth along the sun's direction, origin above the scene on the axis "
      "through the bounds' centre"},
     {"scene units", ""},
     {"SliceFrame::light_from_world of penumbra::slice_frame(RectLight, bounds_min, bounds_max, slices) "
      "(light_frame.hpp): rows U = normalize(u_axis), V = normalize(v_axis), N = normalize(cross(u_axis, v_axis)) "
      "(into the scene), origin the light's centre C: p_light = (U.(p-C), V.(p-C), N.(p-C)), i.e. the matrix "
      "with rows (U, -U.C), (V, -V.C), (N, -N.C), (0, 0, 0, 1)",
      "SliceFrame::light_from_world of penumbra::slice_frame(SunLight, bounds_min, bounds_max, slices) "
      "(light_frame.hpp): N = normalize(direction) (the way light travels), U = normalize(cross(H, N)) with "
      "H = (0,1,0), or (1,0,0) when |N.y| >= 0.9, V = cross(N, U); origin o = c - 1.1*r*N with "
      "c = (bounds_min + bounds_max)/2 and r = max(length(bounds_max - bounds_min)/2, 1e-3): "
      "p_light = (U.(p-o), V.(p-o), N.(p-o))"}},
    {Uniform::slice_clip_from_world, "penumbra_sliceClipFromWorld", GlslType::mat4, UniformSource::light,
     UniformInput::slice_frame,
     {"world to clip space of the slicing camera (perspective from the centre of projection, or orthographic)", ""},
     {"", ""},
     {"SliceFrame::slice_clip_from_world: clip_from_light * light_from_world, clip_from_light maps light-frame "
      "(a, b, z) to (2*a*d/w, 2*b*d/h, 0, d + z) with d = penumbra_copDistance, (w, h) = penumbra_lightSize",
      "SliceFrame::slice_clip_from_world: clip_from_light * light_from_world, clip_from_light maps light-frame "
      "(a, b, z) to (a/s, b/s, 0, 1) with s = penumbra_windowHalfSize"}},
    {Uniform::slice_depths, "penumbra_sliceDepths", GlslType::vec2, UniformSource::light, UniformInput::slice_frame,
     {"x: depth z0 of the first slice's top, y: slice thickness", ""},
     {"scene units", ""},
     {"SliceFrame::slice_depths = (z0, thickness): [zmin, zmax] = light-frame z range of the 8 bounds corners, "
      "zmin clamped to >= 0; pad = 1e-4 * max(zmax - zmin, 1e-6); z0 = zmin - pad; "
      "thickness = (zmax + pad - z0) / slices",
      "SliceFrame::slice_depths = (z0, thickness): [zmin, zmax] = light-frame z range of the 8 bounds corners; "
      "pad = 1e-4 * max(zmax - zmin, 1e-6); z0 = zmin - pad; thickness = (zmax + pad - z0) / slices"}},
    {Uniform::light_size, "penumbra_lightSize", GlslType::vec2, UniformSource::light, UniformInput::either_frame,
     {"light rectangle width, height", ""},
     {"scene units", ""},
     {"SliceFrame::light_size = (RectLight::width, RectLight::height)", ""}},
    {Uniform::cop_distance, "penumbra_copDistance", GlslType::float_, UniformSource::light,
     UniformInput::slice_frame,
     {"distance d of the slicing centre of projection behind the light", ""},
     {"scene units", ""},
     {"SliceFrame::cop_distance d: for each bounds corner p in the light frame with p.z > 0 (corners on or "
      "behind the light's plane are skipped: the light passes discard what lies there), d <= "
      "(w/2)*p.z/(|p.x| - w/2) when |p.x| > w/2 and d <= (h/2)*p.z/(|p.y| - h/2) when |p.y| > h/2; d = the "
      "smallest such bound, at most 1000*max(w, h) and at least d_cap = max(w, h)/(2*tan(70 degrees)) (the "
      "pyramid's half angle capped); when a corner lies on or behind the light's plane (a room), d = d_cap",
      ""}},
    {Uniform::window_half_size, "penumbra_windowHalfSize", GlslType::float_, UniformSource::light,
     UniformInput::either_frame,
     {"half side of the square orthographic slicing window", ""},
     {"scene units", ""},
     {"",
      "SliceFrame::window_half_size s = max(1.001 * max over the 8 bounds corners p (light frame) of "
      "max(|p.x|, |p.y|), 1e-6)"}},
    {Uniform::tan_angular_radius, "penumbra_tanAngularRadius", GlslType::float_, UniformSource::light,
     UniformInput::either_frame,
     {"tangent of the sun's angular radius", ""},
     {"", ""},
     {"", "SliceFrame::tan_angular_radius = tan(SunLight::angular_diameter / 2)"}},
    {Uniform::to_light, "penumbra_toLight", GlslType::vec4, UniformSource::light, UniformInput::either_frame,
     {"light for the Lambert term: xyz position and w = 1, or xyz direction towards the light and w = 0", ""},
     {"scene units", ""},
     {"(C, 1): the light's centre, w = 1 (the origin of penumbra_lightFromWorld in world space)",
      "(-normalize(direction), 0): the direction towards the sun, w = 0"}},
    {Uniform::clip_from_world, "penumbra_clipFromWorld", GlslType::mat4, UniformSource::camera,
     UniformInput::clip_from_world,
     {"world to clip space of the viewer's camera", ""},
     {"", ""},
     {"the viewer's camera: projection * view (world to clip space)", ""}},
    // The shadow-map family (shadowmap, pcf, pcss, erosion): penumbra::shadow_frame (light_frame.hpp).
    {Uniform::shadow_clip_from_world, "penumbra_shadowClipFromWorld", GlslType::mat4, UniformSource::light,
     UniformInput::shadow_frame,
     {"world to clip space of the shadow-map camera (clip z is 0: depth is written by the fragment stage)", ""},
     {"", ""},
     {"ShadowFrame::shadow_clip_from_world of penumbra::shadow_frame(RectLight, bounds_min, bounds_max): "
      "clip_from_light * light_from_world, clip_from_light maps light-frame (a, b, z) to (a/t, b/t, 0, z) "
      "with t = penumbra_shadowTanHalfFov (a perspective from the light's centre C)",
      "ShadowFrame::shadow_clip_from_world of penumbra::shadow_frame(SunLight, bounds_min, bounds_max): the sun's "
      "slicing matrix, light-frame (a, b, z) to (a/s, b/s, 0, 1) with s = penumbra_windowHalfSize"}},
    {Uniform::shadow_depth_range, "penumbra_shadowDepthRange", GlslType::vec2, UniformSource::light,
     UniformInput::shadow_frame,
     {"x: near, y: far depth along the light axis; the shadow map stores (z - near) / (far - near)", ""},
     {"scene units", ""},
     {"ShadowFrame::depth_range = (near, far) along the light's normal: [zmin, zmax] = light-frame z range of the "
      "8 bounds corners, e = max(length(bounds_max - bounds_min), 1e-6); near = max(zmin, 1e-3*e); "
      "far = max(zmax, near + 1e-3*e) + 0.01*(zmax - zmin); stored depth = (z - near)/(far - near)",
      "ShadowFrame::depth_range = (near, far): [zmin, zmax] = light-frame z range of the 8 bounds corners, "
      "pad = 1e-4*max(zmax - zmin, 1e-6); near = zmin - pad; far = zmax + 0.01*(zmax - zmin) + pad"}},
    {Uniform::shadow_tan_half_fov, "penumbra_shadowTanHalfFov", GlslType::float_, UniformSource::light,
     UniformInput::shadow_frame,
     {"tangent of the half field of view of the square shadow-map frustum (apex at the light centre)", ""},
     {"", ""},
     {"ShadowFrame::tan_half_fov t = 1.001 * max over the bounds corners p (light frame) with p.z > 0 of "
      "max(|p.x|, |p.y|) / max(p.z, near), at most tan(70 degrees): the square frustum from C that holds "
      "the bounds in front of the light, its half angle capped; tan(70 degrees) when a corner lies on or "
      "behind the light's plane (a room)",
      ""}},
    {Uniform::light_size_uv, "penumbra_lightSizeUV", GlslType::vec2, UniformSource::light,
     UniformInput::shadow_frame,
     {"light width, height seen on the shadow map's near plane, in shadow-map uv (Fernando 2005: LIGHT_SIZE_UV)",
      "the sun's cone: growth of the light's footprint per unit of depth, in shadow-map uv"},
     {"uv", "uv per scene unit"},
     {"ShadowFrame::light_size_uv = (w, h) / (2*t*near): the light's size on the shadow map's near plane in uv "
      "(Fernando 2005's LIGHT_SIZE_UV), t = penumbra_shadowTanHalfFov, near = penumbra_shadowDepthRange.x",
      "ShadowFrame::light_size_uv = (g, g), g = 2*tan(angular_diameter/2) / (2*s): the sun cone's footprint "
      "growth per unit of depth in uv, s = penumbra_windowHalfSize"}},
    // Occlusion interval maps: penumbra::sun_window (sun_path.hpp).
    {Uniform::time_window, "penumbra_timeWindow", GlslType::vec4, UniformSource::light, UniformInput::time_window,
     {"time window of the sun's disk along its path (penumbra/sun_path.hpp): x = start, y = end, "
      "z = 1 / (end - start), w = its centre t (path times)",
      ""},
     {"", ""},
     {"",
      "(start, end, 1/dt, t) of penumbra::sun_window(SunPath, t, angular_diameter) (sun_path.hpp): "
      "dt = max(angular_diameter / sun_speed(path, t), 1e-6), the time the sun takes to move by its diameter; "
      "start = t - dt/2, end = t + dt/2"}},
    // alpha_test: per-draw caller parameters of the caster programs (detail/alpha_test.hpp)
    {Uniform::alpha_texture, "penumbra_alphaTexture", GlslType::sampler2D, UniformSource::draw,
     UniformInput::per_draw,
     {"the caster draw's material texture: where its alpha (.a) is below penumbra_alphaCutoff the caster is cut "
      "out; bound by the caller per draw with its own sampler",
      ""},
     {"", ""},
     {"per draw: the caster's material texture whose alpha cuts it (glTF baseColorTexture, OBJ map_d or map_Kd; "
      "its .a is compared), bound with the engine's own sampler; a solid draw binds a 1x1 opaque texture",
      ""}},
    {Uniform::alpha_cutoff, "penumbra_alphaCutoff", GlslType::float_, UniformSource::draw, UniformInput::per_draw,
     {"the caster draw's alpha cutoff (glTF alphaCutoff, 0.5 by default; 0 for a solid draw)", ""},
     {"", ""},
     {"per draw: the caster's material alpha cutoff (glTF alphaCutoff, 0.5 when absent; 0.5 for a blended "
      "material cast as a cut-out; 0 for a solid draw)",
      ""}},
    {Uniform::caster_closed, "penumbra_casterClosed", GlslType::float_, UniformSource::draw, UniformInput::per_draw,
     {"1 when the caster draw is a closed mesh whose slices between its surfaces are filled (solid_casters), 0 "
      "for open casters",
      ""},
     {"", ""},
     {"per draw: 1 for a closed caster mesh (watertight, counter-clockwise outward faces), drawn with the logic op "
      "XOR instead of the pass's OR: it toggles every slice from where the slicing camera's ray enters it (a face "
      "towards the light: from its own slice) or leaves it (from the next slice), which fills the solid; 0 for "
      "open casters (cards, planes, unclosed meshes), drawn after every closed one with the pass's OR",
      ""}},
};

namespace detail {
constexpr bool uniform_rows_in_enum_order() {
    for (std::size_t i = 0; i < std::size(uniform_defs); ++i)
        if (uniform_defs[i].id != static_cast<Uniform>(i)) return false;
    return true;
}
} // namespace detail
static_assert(detail::uniform_rows_in_enum_order(), "uniform_defs: row i must be the Uniform with value i");

constexpr const UniformDef& uniform_def(Uniform u) { return uniform_defs[static_cast<std::size_t>(u)]; }

// The row of the uniform named `name`; nullptr when the registry has none (a "pass" uniform, or
// no uniform of Penumbra's).
constexpr const UniformDef* find_uniform(std::string_view name) {
    for (const UniformDef& u : uniform_defs)
        if (u.name == name) return &u;
    return nullptr;
}

} // namespace penumbra
