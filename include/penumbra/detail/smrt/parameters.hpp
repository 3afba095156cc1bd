// penumbra/detail/smrt/parameters.hpp — shadow-map ray tracing (SMRT; Unreal Engine 5's virtual
// shadow maps): the uniforms and the sampler of its screen pass. The shadow-map camera and the depth
// pass are the shadow map techniques' (shadow_map/parameters.hpp, penumbra/light_frame.hpp); the
// march reads the same depth texture without comparison, one texel per sample (NEAREST).
#pragma once

#include "../shadow_map/parameters.hpp"

namespace penumbra::detail {

// The depth map as the march reads it: stored depth, no comparison, NEAREST.
constexpr Param smrt_depth_param() {
    return {"penumbra_shadowDepth", "sampler2D",
            "shadow map read as depth (no comparison): every sample of every ray, one texel", "",
            Text(shadow_map_texture), UniformSource::light, "NEAREST", /*fetch_only=*/false, /*depth_texture=*/true};
}

// Parameters of penumbraVisibility() for SMRT: the shadow-map camera, the light's extent (the
// rectangle's size in scene units, the sun's tan(angular radius)) and the depth map.
constexpr std::vector<Param> smrt_visibility_params(const Config& config) {
    return {light_from_world_param(), projection_param(config), depth_range_param(),
            uniform_param(config.light == Light::rect ? Uniform::light_size : Uniform::tan_angular_radius,
                          config.light),
            smrt_depth_param()};
}

} // namespace penumbra::detail
