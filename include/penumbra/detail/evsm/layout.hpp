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
            t.min_filter = t.mag_filter = "NEAREST";
            t.purpose = "shadow map: (z - near) / (far - near) along the light axis, biased; the moments pass reads "
                        "it one texel per fragment";
        }
    const int R = config.shadow_map.resolution;
    const bool hardware = evsm_filters_in_hardware(config);
    const std::string format(evsm_moments_format(config)), filter = hardware ? "LINEAR" : "NEAREST";
    const std::string stored = hardware ? "" : " (the bits of 32-bit floats: ES 3.0 renders RGBA32UI in its core, "
                                               "float targets only with EXT_color_buffer_float)";
    TextureDesc& moments =
        b.texture(std::string(evsm_moments_texture), "2D", format, R, R, 1, 1, filter, filter,
                  "EVSM moments e^(c+ d), its square, -e^(-c- d), its square of d = 2 depth - 1; blurred in place by "
                  "the blur passes" + stored);
    moments.wrap = "CLAMP_TO_EDGE";
    TextureDesc& blurred = b.texture(std::string(evsm_blur_x_texture), "2D", format, R, R, 1, 1, filter, filter,
                                     "EVSM moments blurred along x (the light's width)" + stored);
    blurred.wrap = "CLAMP_TO_EDGE";
    auto inputs = [&](std::string_view program) {
        std::vector<BindingDesc> in;
        for (const ParamDesc& p : b.params_of(program))
            if (p.binding >= 0) in.push_back({p.name, p.texture, p.binding});
        return in;
    };
    const std::string moments_name(evsm_moments_texture), blurred_name(evsm_blur_x_texture);
    b.fullscreen("evsm_moments", "evsm_moments", inputs("evsm_moments"), {moments_name, 0, -1}, {}, R, R);
    b.fullscreen("evsm_blur_x", "evsm_blur_x", inputs("evsm_blur_x"), {blurred_name, 0, -1}, {}, R, R);
    b.fullscreen("evsm_blur_y", "evsm_blur_y", inputs("evsm_blur_y"), {moments_name, 0, -1}, {}, R, R);
}

inline void describe_evsm_layout(LayoutBuilder& b, const Config& config) {
    describe_evsm_passes(b, config);
    describe_screen_textures(b, config);
    describe_deferred_pass(b);
}

} // namespace penumbra::detail
