// penumbra/detail/shadow_map/parameters.hpp — uniforms, samplers and texture names of the shadow
// map techniques (shadowmap, pcf, pcss). The values come from penumbra::shadow_frame
// (penumbra/light_frame.hpp).
#pragma once

#include "../glsl_common.hpp"
#include "../uniform_params.hpp"

namespace penumbra::detail {

inline constexpr std::string_view shadow_map_texture = "penumbra_shadowMap";

constexpr Param light_from_world_param() {
    return uniform_param(Uniform::light_from_world,
                         "world to light frame: x, y along the light's axes, z depth along its direction, origin at "
                         "the light centre (rect) or above the scene (sun); right-handed");
}

constexpr Param depth_range_param() {
    return uniform_param(Uniform::shadow_depth_range, Light::rect);
}

// Shadow-map coordinates of a light-frame point: uv = 0.5 + xy / (2 tan(fov/2) z) for the rectangle's
// perspective, 0.5 + xy / (2 h) for the sun's orthographic window.
constexpr Param projection_param(const Config& config) {
    if (config.light == Light::rect) return uniform_param(Uniform::shadow_tan_half_fov, config.light);
    return uniform_param(Uniform::window_half_size, "half side of the square orthographic shadow-map window");
}

// The depth pass: the scene from the light, depth only.
constexpr std::vector<Param> shadow_depth_params() {
    return {
        uniform_param(Uniform::shadow_clip_from_world, Light::rect),
        light_from_world_param(),
        depth_range_param(),
    };
}

// Parameters of penumbraVisibility() for a shadow map technique.
constexpr std::vector<Param> shadow_visibility_params(const Config& config) {
    std::vector<Param> params{light_from_world_param(), projection_param(config), depth_range_param()};
    if (config.technique == Technique::pcss) {
        params.push_back(uniform_param(config.light == Light::rect ? Uniform::light_size : Uniform::tan_angular_radius,
                                       config.light));
        params.push_back(uniform_param(Uniform::light_size_uv, config.light));
        // the same depth texture as the filter's, through a second sampler: NEAREST, no comparison
        params.push_back({"penumbra_shadowDepth", "sampler2D",
                          "shadow map read as depth (no comparison): the blocker search", "",
                          Text(shadow_map_texture), UniformSource::light, "NEAREST", /*fetch_only=*/false,
                          /*depth_texture=*/true});
    }
    params.push_back({Text(shadow_map_texture), "sampler2DShadow",
                      "shadow map with hardware depth comparison (LEQUAL) and bilinear filtering", "",
                      Text(shadow_map_texture)});
    return params;
}

} // namespace penumbra::detail
