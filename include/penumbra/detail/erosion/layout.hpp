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

// Erosion, phase screen (erosion/emit_passes.hpp): output-sized textures, hard shadow, edges, the
// min-max chain one level at a time (read level n, write n + 1), erosion, blur into the result.
inline void describe_erosion_passes(LayoutBuilder& b, const Config& config) {
    const int K = erosion_levels(config.erosion);
    auto screen_texture = [&](std::string_view name, int mips, std::string purpose) {
        b.texture({.name = std::string(name),
                   .format = level_format(config),
                   .mip_levels = mips,
                   .min_filter = mips > 1 ? TextureFilter::nearest_mipmap_nearest : TextureFilter::nearest,
                   .size = TextureSize::output,
                   .purpose = std::move(purpose)});
    };
    screen_texture(erosion_hard_texture, 1,
                   "r: hard visibility (0/1), g: penumbra half-width / max search radius (shadowed pixels), a: geometry");
    screen_texture(erosion_edges_texture, K + 1,
                   "min-max chain of the Laplacian edges: r edge, g half-width / max search radius (max), "
                   "b min and a max of the hard shadow");
    screen_texture(erosion_penumbra_texture, 1,
                   "r: eroded visibility, g: search radius / max search radius, b: geometry");
    const std::string hard(erosion_hard_texture), edges(erosion_edges_texture), pen(erosion_penumbra_texture);
    // a full-screen pass of the screen phase, `program` reading its samplers' own textures
    auto screen = [&](std::string program, AttachmentDesc out, std::vector<BindingDesc> in = {}) {
        if (in.empty()) in = b.own_inputs(program);
        b.pass({.name = program, .program = program, .inputs = std::move(in), .outputs = {std::move(out)},
                .phase = Phase::screen});
    };
    screen("erosion_hard", {hard});
    screen("erosion_edges", {edges});
    for (int level = 0; level < K; ++level) {
        std::vector<BindingDesc> in = b.own_inputs("erosion_reduce");
        in.front().level = level; // read level n, write n + 1
        screen("erosion_reduce", {edges, level + 1}, std::move(in));
    }
    screen("erosion_erode", {pen});
    screen("erosion_blur", {b.layout.result});
}

inline void describe_erosion_layout(LayoutBuilder& b, const Config& config) {
    describe_shadow_map_passes(b, config);
    describe_screen_textures(b, config);
    describe_erosion_passes(b, config);
}

} // namespace penumbra::detail
