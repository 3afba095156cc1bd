// penumbra/detail/smrt/layout.hpp — shadow-map ray tracing in the layout: the shadow map's depth pass
// (phase shadow), then the deferred shading, whose penumbraVisibility marches the rays through it.
#pragma once

#include "../shadow_map/layout.hpp"
#include "emit_visibility.hpp"

namespace penumbra::detail {

inline std::vector<ParamGroup> smrt_param_groups(const Config& config, std::string_view program) {
    if (program == "shadow_depth") return shadow_map_param_groups(config, program);
    return shading_param_groups(program, smrt_visibility_params(config), deferred_params(config),
                                example_fragment_params(), example_vertex_params());
}

// The depth pass (shadow_map/layout.hpp), its map read by the march without comparison: NEAREST (a
// depth texture is filterable only through comparison on ES 3.0 and WebGPU).
inline void describe_smrt_layout(LayoutBuilder& b, const Config& config) {
    describe_shadow_map_passes(b, config);
    for (TextureDesc& t : b.layout.textures)
        if (t.name == shadow_map_texture) {
            t.min_filter = t.mag_filter = TextureFilter::nearest;
            t.purpose = "shadow map: (z - near) / (far - near) along the light axis, biased; the rays' march reads "
                        "it one texel per sample";
        }
    describe_screen_textures(b, config);
    describe_deferred_pass(b);
}

} // namespace penumbra::detail
