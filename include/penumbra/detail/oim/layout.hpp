// penumbra/detail/oim/layout.hpp — occlusion interval maps in the layout: no pass before shading
// (the maps come from a bake), a G-buffer of texture coordinates instead of world positions.
#pragma once

#include "../emit_shading.hpp"
#include "emit_oim.hpp"
#include "../layout_builder.hpp"

namespace penumbra::detail {

inline std::vector<ParamGroup> oim_param_groups(const Config& config, std::string_view program) {
    return shading_param_groups(program, oim_visibility_params(config), oim_deferred_params(),
                                oim_example_fragment_params(), oim_example_vertex_params());
}

// Occlusion interval maps (GPU Gems ch. 13): no pass before shading; the rise/fall textures come
// from an offline bake (nearest filtering: the edges must not be blended).
inline void describe_oim_textures(LayoutBuilder& b, const Config& config) {
    const int R = config.oim.resolution;
    for (int p = 0; p < oim_pairs(config.oim); ++p)
        for (const bool fall : {false, true}) {
            TextureDesc& t = b.texture((fall ? oim_fall_name(p) : oim_rise_name(p)).str(), "2D", "RGBA16F", R, R, 1, 1,
                                       "NEAREST", "NEAREST",
                                       std::string(fall ? "fall" : "rise") + " times of intervals " +
                                           std::to_string(4 * p) + " to " + std::to_string(4 * p + 3) +
                                           " (path time t, k / samples: exact in 16-bit floats; unused intervals [0, 0])");
            t.wrap = "CLAMP_TO_EDGE";
            t.source = "bake";
        }
}

// The maps are per surface, so the deferred pass reads texture coordinates; the screen phase
// depends on the bake, not on the light or the geometry.
inline void describe_oim_layout(LayoutBuilder& b, const Config& config) {
    describe_oim_textures(b, config);
    describe_screen_textures(b, config, "penumbra_texCoords",
                             "G-buffer filled by the engine every frame: xy the surface's unique texture coordinates "
                             "(the bake's), w = 1 on geometry, 0 on the background; read with texelFetch");
    b.screen_inputs = {"camera", "caller_textures", "bake"};
    describe_deferred_pass(b);
}

} // namespace penumbra::detail
