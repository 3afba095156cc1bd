// penumbra/detail/evsm/parameters.hpp — exponential variance shadow maps (EVSM; Lauritzen & McCool
// 2008, what Unity HDRP ships for rectangle area-light shadows): texture names, how the moments are
// stored on each target, and the uniforms and samplers of its programs. The shadow-map camera and the
// depth pass are the shadow map techniques' (shadow_map/parameters.hpp, penumbra/light_frame.hpp).
//
// The moments of the warped depth need 32-bit floats: e^(2 c) of the largest exponent c = 42 is
// 3e36 (a half float ends at 65504, which would hold exponents up to 5.5 only). Where the target
// renders to and filters RGBA32F (target_limits.hpp: float32_render_filter), they are stored so and
// read with bilinear filtering. OpenGL ES 3.0 and WebGL2 guarantee neither (rendering to any float
// texture needs EXT_color_buffer_float, filtering RGBA32F OES_texture_float_linear), but an RGBA32UI
// target is colour-renderable in core ES 3.0: there the moments are stored as the bits of the same
// 32-bit floats (floatBitsToUint) and the passes filter them by hand (texelFetch, bilinear weights),
// so ES gets the same exponents and the same result with nothing beyond the core.
#pragma once

#include "../shadow_map/parameters.hpp"
#include "../target_limits.hpp"

namespace penumbra::detail {

inline constexpr std::string_view evsm_moments_texture = "penumbra_evsmMoments";
inline constexpr std::string_view evsm_blur_x_texture = "penumbra_evsmBlurX";

// The largest exponent whose moments fit a 32-bit float: e^(2 * 42) = 3e36 < 3.4e38 (and a blur's sum
// of them stays finite: the blur averages).
inline constexpr double evsm_max_exponent = 42.0;

// True when the moments are stored as RGBA32F and filtered by the hardware; false: the bits of 32-bit
// floats in RGBA32UI, filtered by hand (OpenGL ES 3.0 / WebGL2).
constexpr bool evsm_filters_in_hardware(const Config& config) { return limits(config.target).float32_render_filter; }

constexpr TextureFormat evsm_moments_format(const Config& config) {
    return evsm_filters_in_hardware(config) ? TextureFormat::rgba32f : TextureFormat::rgba32ui;
}

// The sampler type the passes read the moments through.
constexpr std::string_view evsm_sampler_type(const Config& config) {
    return evsm_filters_in_hardware(config) ? "sampler2D" : "usampler2D";
}

constexpr Param evsm_moments_param(const Config& config, std::string_view texture) {
    return {Text(texture), evsm_sampler_type(config),
            evsm_filters_in_hardware(config)
                ? "moments of the warped depth: e^(c+ d), its square, -e^(-c- d), its square (d = 2 depth - 1)"
                : "moments of the warped depth as the bits of 32-bit floats: e^(c+ d), its square, -e^(-c- d), its "
                  "square (d = 2 depth - 1)",
            "", Text(texture)};
}

// The moments pass reads the depth map without comparison: one texel per fragment.
constexpr Param evsm_depth_param() {
    return {"penumbra_shadowDepth", "sampler2D", "shadow map read as depth (no comparison): one texel per fragment",
            "", Text(shadow_map_texture), UniformSource::light, "NEAREST", /*fetch_only=*/true, /*depth_texture=*/true};
}

// The blur passes' radius follows the light: its size on the map (penumbra_lightSizeUV, as PCSS's
// blocker search reads it) over the depth range.
constexpr std::vector<Param> evsm_blur_params(const Config& config, std::string_view source) {
    std::vector<Param> params{uniform_param(Uniform::light_size_uv, config.light), depth_range_param()};
    params.push_back(evsm_moments_param(config, source));
    return params;
}

// Parameters of penumbraVisibility() for EVSM: the shadow-map camera and the blurred moments.
constexpr std::vector<Param> evsm_visibility_params(const Config& config) {
    return {light_from_world_param(), projection_param(config), depth_range_param(),
            evsm_moments_param(config, evsm_moments_texture)};
}

} // namespace penumbra::detail
