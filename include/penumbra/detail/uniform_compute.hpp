// penumbra/detail/uniform_compute.hpp — how to compute each plain uniform, as text for layout.json
// ("compute"), per light. The values themselves: penumbra/uniform_values.hpp (same names); the
// derivation: docs/model.md §1.
#pragma once

#include "../config.hpp"

#include <string_view>

namespace penumbra::detail {

struct UniformCompute {
    std::string_view name;
    std::string_view rect, sun; // one empty: the other serves both
};

inline constexpr UniformCompute uniform_computes[] = {
    {"penumbra_lightFromWorld",
     "SliceFrame::light_from_world of penumbra::slice_frame(RectLight, bounds_min, bounds_max, slices) "
     "(light_frame.hpp): rows U = normalize(u_axis), V = normalize(v_axis), N = normalize(cross(u_axis, v_axis)) "
     "(into the scene), origin the light's centre C: p_light = (U.(p-C), V.(p-C), N.(p-C)), i.e. the matrix "
     "with rows (U, -U.C), (V, -V.C), (N, -N.C), (0, 0, 0, 1)",
     "SliceFrame::light_from_world of penumbra::slice_frame(SunLight, bounds_min, bounds_max, slices) "
     "(light_frame.hpp): N = normalize(direction) (the way light travels), U = normalize(cross(H, N)) with "
     "H = (0,1,0), or (1,0,0) when |N.y| >= 0.9, V = cross(N, U); origin o = c - 1.1*r*N with "
     "c = (bounds_min + bounds_max)/2 and r = max(length(bounds_max - bounds_min)/2, 1e-3): "
     "p_light = (U.(p-o), V.(p-o), N.(p-o))"},
    {"penumbra_sliceClipFromWorld",
     "SliceFrame::slice_clip_from_world: clip_from_light * light_from_world, clip_from_light maps light-frame "
     "(a, b, z) to (2*a*d/w, 2*b*d/h, 0, d + z) with d = penumbra_copDistance, (w, h) = penumbra_lightSize",
     "SliceFrame::slice_clip_from_world: clip_from_light * light_from_world, clip_from_light maps light-frame "
     "(a, b, z) to (a/s, b/s, 0, 1) with s = penumbra_windowHalfSize"},
    {"penumbra_sliceDepths",
     "SliceFrame::slice_depths = (z0, thickness): [zmin, zmax] = light-frame z range of the 8 bounds corners, "
     "zmin clamped to >= 0; pad = 1e-4 * max(zmax - zmin, 1e-6); z0 = zmin - pad; "
     "thickness = (zmax + pad - z0) / slices",
     "SliceFrame::slice_depths = (z0, thickness): [zmin, zmax] = light-frame z range of the 8 bounds corners; "
     "pad = 1e-4 * max(zmax - zmin, 1e-6); z0 = zmin - pad; thickness = (zmax + pad - z0) / slices"},
    {"penumbra_lightSize", "SliceFrame::light_size = (RectLight::width, RectLight::height)", ""},
    {"penumbra_copDistance",
     "SliceFrame::cop_distance d: for each bounds corner p in the light frame, d <= (w/2)*p.z/(|p.x| - w/2) "
     "when |p.x| > w/2 and d <= (h/2)*p.z/(|p.y| - h/2) when |p.y| > h/2; d = the smallest such bound, "
     "at most 1000*max(w, h)",
     ""},
    {"penumbra_windowHalfSize",
     "",
     "SliceFrame::window_half_size s = max(1.001 * max over the 8 bounds corners p (light frame) of "
     "max(|p.x|, |p.y|), 1e-6)"},
    {"penumbra_tanAngularRadius", "", "SliceFrame::tan_angular_radius = tan(SunLight::angular_diameter / 2)"},
    {"penumbra_toLight",
     "(C, 1): the light's centre, w = 1 (the origin of penumbra_lightFromWorld in world space)",
     "(-normalize(direction), 0): the direction towards the sun, w = 0"},
    {"penumbra_clipFromWorld", "the viewer's camera: projection * view (world to clip space)", ""},
    // The shadow-map family (shadowmap, pcf, pcss, erosion): penumbra::shadow_frame (light_frame.hpp).
    {"penumbra_shadowClipFromWorld",
     "ShadowFrame::shadow_clip_from_world of penumbra::shadow_frame(RectLight, bounds_min, bounds_max): "
     "clip_from_light * light_from_world, clip_from_light maps light-frame (a, b, z) to (a/t, b/t, 0, z) "
     "with t = penumbra_shadowTanHalfFov (a perspective from the light's centre C)",
     "ShadowFrame::shadow_clip_from_world of penumbra::shadow_frame(SunLight, bounds_min, bounds_max): the sun's "
     "slicing matrix, light-frame (a, b, z) to (a/s, b/s, 0, 1) with s = penumbra_windowHalfSize"},
    {"penumbra_shadowDepthRange",
     "ShadowFrame::depth_range = (near, far) along the light's normal: [zmin, zmax] = light-frame z range of the "
     "8 bounds corners, e = max(length(bounds_max - bounds_min), 1e-6); near = max(zmin, 1e-3*e); "
     "far = max(zmax, near + 1e-3*e) + 0.01*(zmax - zmin); stored depth = (z - near)/(far - near)",
     "ShadowFrame::depth_range = (near, far): [zmin, zmax] = light-frame z range of the 8 bounds corners, "
     "pad = 1e-4*max(zmax - zmin, 1e-6); near = zmin - pad; far = zmax + 0.01*(zmax - zmin) + pad"},
    {"penumbra_shadowTanHalfFov",
     "ShadowFrame::tan_half_fov t = 1.001 * max over the 8 bounds corners p (light frame) of "
     "max(|p.x|, |p.y|) / max(p.z, near): the square frustum from C that holds the bounds",
     ""},
    {"penumbra_lightSizeUV",
     "ShadowFrame::light_size_uv = (w, h) / (2*t*near): the light's size on the shadow map's near plane in uv "
     "(Fernando 2005's LIGHT_SIZE_UV), t = penumbra_shadowTanHalfFov, near = penumbra_shadowDepthRange.x",
     "ShadowFrame::light_size_uv = (g, g), g = 2*tan(angular_diameter/2) / (2*s): the sun cone's footprint "
     "growth per unit of depth in uv, s = penumbra_windowHalfSize"},
    // Occlusion interval maps: penumbra::sun_window (sun_path.hpp).
    {"penumbra_timeWindow",
     "",
     "(start, end, 1/dt, t) of penumbra::sun_window(SunPath, t, angular_diameter) (sun_path.hpp): "
     "dt = max(angular_diameter / sun_speed(path, t), 1e-6), the time the sun takes to move by its diameter; "
     "start = t - dt/2, end = t + dt/2"},
    // alpha_test: per-draw caller parameters of the caster programs (detail/alpha_test.hpp)
    {"penumbra_alphaTexture",
     "per draw: the caster's material texture whose alpha cuts it (glTF baseColorTexture, OBJ map_d or map_Kd; "
     "its .a is compared), bound with the engine's own sampler; a solid draw binds a 1x1 opaque texture",
     ""},
    {"penumbra_alphaCutoff",
     "per draw: the caster's material alpha cutoff (glTF alphaCutoff, 0.5 when absent; 0.5 for a blended "
     "material cast as a cut-out; 0 for a solid draw)",
     ""},
};

// The "compute" text of uniform `name` for `light`; empty when the table has none.
constexpr std::string_view uniform_compute(std::string_view name, Light light) {
    for (const UniformCompute& u : uniform_computes)
        if (u.name == name) {
            const std::string_view chosen = light == Light::sun ? u.sun : u.rect;
            return chosen.empty() ? (light == Light::sun ? u.rect : u.sun) : chosen;
        }
    return {};
}

} // namespace penumbra::detail
