// penumbra/detail/shadow_map/layout.hpp — the shadow map techniques (shadowmap, pcf, pcss) in the
// layout: the depth pass from the light, then the deferred shading. Erosion starts from the same
// depth pass (erosion/layout.hpp).
#pragma once

#include "../emit_shading.hpp"
#include "emit_depth.hpp"
#include "emit_visibility.hpp"
#include "../layout_builder.hpp"

namespace penumbra::detail {

inline std::vector<ParamGroup> shadow_map_param_groups(const Config& config, std::string_view program) {
    if (program == "shadow_depth") return caster_param_groups(config, "PenumbraShadowDepth", shadow_depth_params());
    return shading_param_groups(program, shadow_visibility_params(config), deferred_params(config),
                                example_fragment_params(), example_vertex_params());
}

// Shadow map techniques, phase "shadow": the depth pass from the light (shadow_frame in
// light_frame.hpp). PCSS's blocker search and erosion read the same depth texture without comparison,
// through a second sampler (the bindings' "sampling"), so there is no copy of it.
inline void describe_shadow_map_passes(LayoutBuilder& b, const Config& config) {
    const int R = config.shadow_map.resolution;
    TextureDesc& map = b.texture(std::string(shadow_map_texture), "2D", "DEPTH_COMPONENT32F", R, R, 1, 1, "LINEAR",
                                 "LINEAR", "shadow map: (z - near) / (far - near) along the light axis, biased; "
                                           "the filter reads it with hardware comparison, bilinear");
    map.wrap = "CLAMP_TO_EDGE"; // kernels reaching past the map read its edge, not a shadowing border
    RenderState depth_only;
    depth_only.depth_test = depth_only.depth_write = true;
    depth_only.depth_func = "LESS";
    depth_only.clear_depth = 1.0f;
    b.pass("shadow_depth", "draw_scene", "shadow_depth", {}, {{std::string(shadow_map_texture), 0, -1, "depth"}}, {},
           R, R, depth_only);
}

inline void describe_shadow_map_layout(LayoutBuilder& b, const Config& config) {
    describe_shadow_map_passes(b, config);
    describe_screen_textures(b, config);
    describe_deferred_pass(b);
}

} // namespace penumbra::detail
