// penumbra/detail/vertex_inputs.hpp — the vertex attributes of the programs that draw the caller's
// geometry, as layout.json's "vertex_inputs" states them. The vertex stages declare the same
// (layout(location = …) in …); tests/emitter_layout_test.cpp checks that they agree.
#pragma once

#include "layout_builder.hpp"
#include "technique.hpp"

#include <vector>

namespace penumbra::detail {

inline VertexInputDesc position_input() {
    return {"penumbra_position", 0, "vec3", "vertex position, world space (scene units)"};
}
inline VertexInputDesc normal_input() { return {"penumbra_normal", 1, "vec3", "vertex normal, world space"}; }
inline VertexInputDesc uv_input() {
    return {"penumbra_uv", 2, "vec2", "unique texture coordinates (those of the occlusion interval map's bake)"};
}
// alpha_test: the caster draw's material texture coordinates, at which penumbra_alphaTexture is read.
inline VertexInputDesc material_uv_input() {
    return {"penumbra_uv", alpha_test_uv_location, "vec2",
            "alpha_test: the caster's material texture coordinates, where its penumbra_alphaTexture is read"};
}

// The attributes a vertex stage reads; none for the full-screen triangle.
inline std::vector<VertexInputDesc> vertex_inputs(const ShaderFileSpec& vertex_stage, const Config& config) {
    switch (vertex_stage.vertex_inputs) {
    case VertexInputs::caster:
        if (config.alpha_test) return {position_input(), material_uv_input()};
        return {position_input()};
    case VertexInputs::receiver: return {position_input(), normal_input()};
    case VertexInputs::receiver_with_uv: return {position_input(), normal_input(), uv_input()};
    case VertexInputs::none: return {};
    }
    return {};
}

} // namespace penumbra::detail
