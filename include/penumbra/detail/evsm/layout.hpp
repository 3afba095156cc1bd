// penumbra/detail/evsm/layout.hpp — EVSM in the layout: the shadow map's depth pass, the moments
// pass and the two blur passes (phase shadow, at the shadow map's size), then the deferred shading.
#pragma once

#include "../shadow_map/layout.hpp"
#include "emit_passes.hpp"

namespace penumbra::detail {

inline std::vector<ParamGroup> evsm_param_groups(const Config& config, std::string_view program) {
    if (program == "evsm_moments") return {{"PenumbraPass", {evsm_depth_param()}}};
    if (program == "evsm_blur_x") return {{"PenumbraPass", evsm_blur_params(config, evsm_moments_texture)}};
    if (program == "evsm_blur_y") return {{"PenumbraPass", evsm_blur_params(config, evsm_blur_x_texture)}};
    if (program == "shadow_depth") return shadow_map_param_groups(config, program);
    return shading_param_groups(program, evsm_visibility_params(config), deferred_params(config),
                                example_fragment_params(), example_vertex_params());
}

// Phase shadow: the depth pass (shadow_map/layout.hpp), whose map only the moments pass reads, one
// texel per fragment; then moments -> blur along x -> blur along y back into the moments.
inline void describe_evsm_passes(LayoutBuilder& b, const Config& config) {
    describe_shadow_map_passes(b, config);
    for (TextureDesc& t : b.layout.textures)
        if (t.name == shadow_map_texture) {
            t.min_filter = t.mag_filter = TextureFilter::nearest;
            t.purpose = "shadow map: (z - near) / (far - near) along the light axis, biased; the moments pass reads "
                        "it one texel per fragment";
        }
    const int R = config.shadow_map.resolution;
    const bool hardware = evsm_filters_in_hardware(config);
    const TextureFilter filter = hardware ? TextureFilter::linear : TextureFilter::nearest;
    const std::string stored = hardware ? "" : " (the bits of 32-bit floats: ES 3.0 renders RGBA32UI in its core, "
                                               "float targets only with EXT_color_buffer_float)";
    const std::string moments(evsm_moments_texture), blurred(evsm_blur_x_texture);
    b.texture({.name = moments,
               .format = evsm_moments_format(config),
               .width = R,
               .height = R,
               .min_filter = filter,
               .mag_filter = filter,
               .purpose = "EVSM moments e^(c+ d), its square, -e^(-c- d), its square of d = 2 depth - 1; blurred in "
                          "place by the blur passes" + stored});
    b.texture({.name = blurred,
               .format = evsm_moments_format(config),
               .width = R,
               .height = R,
               .min_filter = filter,
               .mag_filter = filter,
               .purpose = "EVSM moments blurred along x (the light's width)" + stored});
    // moments -> blur along x -> blur along y, back into the moments
    const std::array<std::array<std::string_view, 2>, 3> passes{
        {{"evsm_moments", moments}, {"evsm_blur_x", blurred}, {"evsm_blur_y", moments}}};
    for (const auto& [program, output] : passes)
        b.pass({.name = std::string(program),
                .program = std::string(program),
                .inputs = b.own_inputs(program),
                .outputs = {{std::string(output)}},
                .viewport_width = R,
                .viewport_height = R});
}

inline void describe_evsm_layout(LayoutBuilder& b, const Config& config) {
    describe_evsm_passes(b, config);
    describe_screen_textures(b, config);
    describe_deferred_pass(b);
}

} // namespace penumbra::detail
