// penumbra/detail/shadow_map/parameters.hpp — uniforms, samplers and texture names of the shadow
// map techniques (shadowmap, pcf, pcss). The values come from penumbra::shadow_frame
// (penumbra/light_frame.hpp).
#pragma once

#include "../glsl_common.hpp"

namespace penumbra::detail {

inline constexpr std::string_view shadow_map_texture = "penumbra_shadowMap";

constexpr Param light_from_world_param() {
    return {"penumbra_lightFromWorld", "mat4",
            "world to light frame: x, y along the light's axes, z depth along its direction, origin at the light "
            "centre (rect) or above the scene (sun); right-handed",
            "scene units"};
}

constexpr Param depth_range_param() {
    return {"penumbra_shadowDepthRange", "vec2",
            "x: near, y: far depth along the light axis; the shadow map stores (z - near) / (far - near)",
            "scene units"};
}

// Shadow-map coordinates of a light-frame point: uv = 0.5 + xy / (2 tan(fov/2) z) for the rectangle's
// perspective, 0.5 + xy / (2 h) for the sun's orthographic window.
constexpr Param projection_param(const Config& config) {
    if (config.light == Light::rect)
        return {"penumbra_shadowTanHalfFov", "float",
                "tangent of the half field of view of the square shadow-map frustum (apex at the light centre)", ""};
    return {"penumbra_windowHalfSize", "float", "half side of the square orthographic shadow-map window",
            "scene units"};
}

// The depth pass: the scene from the light, depth only.
constexpr std::vector<Param> shadow_depth_params() {
    return {
        {"penumbra_shadowClipFromWorld", "mat4",
         "world to clip space of the shadow-map camera (clip z is 0: depth is written by the fragment stage)", ""},
        light_from_world_param(),
        depth_range_param(),
    };
}

// Parameters of penumbraVisibility() for a shadow map technique.
constexpr std::vector<Param> shadow_visibility_params(const Config& config) {
    std::vector<Param> params{light_from_world_param(), projection_param(config), depth_range_param()};
    if (config.technique == Technique::pcss) {
        if (config.light == Light::rect) {
            params.push_back({"penumbra_lightSize", "vec2", "light rectangle width, height", "scene units"});
            params.push_back({"penumbra_lightSizeUV", "vec2",
                              "light width, height seen on the shadow map's near plane, in shadow-map uv "
                              "(Fernando 2005: LIGHT_SIZE_UV)",
                              "uv"});
        } else {
            params.push_back({"penumbra_tanAngularRadius", "float", "tangent of the sun's angular radius", ""});
            params.push_back({"penumbra_lightSizeUV", "vec2",
                              "the sun's cone: growth of the light's footprint per unit of depth, in shadow-map uv",
                              "uv per scene unit"});
        }
        // the same depth texture as the filter's, through a second sampler: NEAREST, no comparison
        params.push_back({"penumbra_shadowDepth", "sampler2D",
                          "shadow map read as depth (no comparison): the blocker search", "",
                          Text(shadow_map_texture), "light", "NEAREST"});
    }
    params.push_back({Text(shadow_map_texture), "sampler2DShadow",
                      "shadow map with hardware depth comparison (LEQUAL) and bilinear filtering", "",
                      Text(shadow_map_texture)});
    return params;
}

} // namespace penumbra::detail
