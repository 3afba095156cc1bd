// penumbra/detail/erosion/layout.hpp — erosion in the layout: the shadow map's depth pass (shadow
// phase), then its screen passes instead of the deferred shading.
#pragma once

#include "../shadow_map/layout.hpp"
#include "emit_passes.hpp"

namespace penumbra::detail {

inline std::vector<ParamGroup> erosion_param_groups(const Config& config, std::string_view program) {
    if (program.starts_with("erosion_")) return {{"PenumbraPass", erosion_params(config, program)}};
    return shadow_map_param_groups(config, program); // shadow_depth, shading_example
}

// Erosion, phase "screen" (erosion/emit_passes.hpp): output-sized textures, hard shadow, edges, the
// min-max chain one level at a time (read level n, write n + 1), erosion, blur into the result.
inline void describe_erosion_passes(LayoutBuilder& b, const Config& config) {
    const int K = erosion_levels(config.erosion);
    const std::string fmt(level_format(config));
    auto screen_texture = [&](std::string_view name, int mips, std::string purpose) {
        TextureDesc& t = b.texture(std::string(name), "2D", fmt, 0, 0, 1, mips, mips > 1 ? "NEAREST_MIPMAP_NEAREST" : "NEAREST",
                                   "NEAREST", std::move(purpose));
        t.wrap = "CLAMP_TO_EDGE";
        t.size = "output";
    };
    screen_texture(erosion_hard_texture, 1,
                   "r: hard visibility (0/1), g: penumbra half-width / max search radius (shadowed pixels), a: geometry");
    screen_texture(erosion_edges_texture, K + 1,
                   "min-max chain of the Laplacian edges: r edge, g half-width / max search radius (max), "
                   "b min and a max of the hard shadow");
    screen_texture(erosion_penumbra_texture, 1,
                   "r: eroded visibility, g: search radius / max search radius, b: geometry");
    const std::string hard(erosion_hard_texture), edges(erosion_edges_texture), pen(erosion_penumbra_texture);
    auto inputs = [&](std::string_view program) {
        std::vector<BindingDesc> in;
        for (const ParamDesc& p : b.params_of(program))
            if (p.binding >= 0) in.push_back({p.name, p.texture, p.binding});
        return in;
    };
    auto screen = [&](std::string name, std::string program, std::vector<BindingDesc> in, AttachmentDesc out) {
        b.pass(std::move(name), "fullscreen", std::move(program), std::move(in), {std::move(out)}, {}, 0, 0, {}, "screen");
    };
    screen("erosion_hard", "erosion_hard", inputs("erosion_hard"), {hard, 0, -1});
    screen("erosion_edges", "erosion_edges", inputs("erosion_edges"), {edges, 0, -1});
    for (int level = 0; level < K; ++level) {
        std::vector<BindingDesc> in = inputs("erosion_reduce");
        in.front().level = level;
        screen("erosion_reduce", "erosion_reduce", std::move(in), {edges, level + 1, -1});
    }
    screen("erosion_erode", "erosion_erode", inputs("erosion_erode"), {pen, 0, -1});
    screen("erosion_blur", "erosion_blur", inputs("erosion_blur"), {b.layout.result, 0, -1});
}

inline void describe_erosion_layout(LayoutBuilder& b, const Config& config) {
    describe_shadow_map_passes(b, config);
    describe_screen_textures(b, config);
    describe_erosion_passes(b, config);
}

} // namespace penumbra::detail
