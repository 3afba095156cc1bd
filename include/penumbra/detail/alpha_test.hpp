// penumbra/detail/alpha_test.hpp — cut-out casters (Config::alpha_test): what the passes that draw the
// caster geometry from the light (slicing, depth bins, shadow-map depth) add, so that leaf cards,
// fences and grilles cast the shadow of their alpha-tested texture, not of their quads.
//
// The convention (layout.json states it): the caster draw feeds its material's texture coordinates
// as the vertex input penumbra_uv (location 2) and sets two per-draw caller parameters, the sampler
// penumbra_alphaTexture (its material's texture, the engine's own sampler) and the float
// penumbra_alphaCutoff; a fragment whose alpha is below the cutoff is discarded. A solid draw binds
// a 1x1 opaque texture (or sets the cutoff to 0). With alpha_test off nothing here is written.
#pragma once

#include "glsl_common.hpp"
#include "light_plane_clip.hpp"
#include "uniform_params.hpp"

namespace penumbra::detail {

// The declaration group of the per-draw material parameters (a uniform block on Vulkan).
inline constexpr std::string_view alpha_test_block = "PenumbraMaterial";
// Location of penumbra_uv, as in the occlusion interval maps' programs (vertex_inputs.hpp).
inline constexpr int alpha_test_uv_location = 2;
// Location of the texture coordinates passed from the vertex to the fragment stage (penumbra_depth is 0).
inline constexpr int alpha_test_varying_location = 1;

// The per-draw parameters of the caster programs; none with alpha_test off.
constexpr std::vector<Param> alpha_test_params(const Config& config) {
    if (!config.alpha_test) return {};
    return {uniform_param(Uniform::alpha_texture, config.light), uniform_param(Uniform::alpha_cutoff, config.light)};
}

// Vertex stage: the caster's texture coordinates in, passed on to the fragment stage.
constexpr void write_alpha_test_vertex_inputs(LineWriter& out, const Config& config) {
    if (!config.alpha_test) return;
    out.line(stage_variable(out, config, "in", alpha_test_uv_location, "vec2", "penumbra_uv", true),
             " // the caster's material texture coordinates (alpha test)");
    out.line(stage_variable(out, config, "out", alpha_test_varying_location, "vec2", "penumbra_texCoord",
                            has_varying_locations(config)));
}

constexpr void write_alpha_test_vertex_copy(LineWriter& out, const Config& config) {
    if (config.alpha_test) out.line("penumbra_texCoord = penumbra_uv;");
}

// The vertex main of a pass that draws the casters from the light (shadow-map depth, slicing, depth
// bins): the depth along the light axis, the light camera's clip position `clip_from_world` (on WGSL
// flipped in y, so that row 0 of `target` holds uv.y = 0 as on OpenGL), and the alpha test's copy.
constexpr void write_caster_vertex_main(LineWriter& out, const Config& config, std::string_view clip_from_world,
                                        std::string_view target) {
    out.line(main_signature(config));
    out.line("{");
    out.line(value(config, "vec4", "world", "vec4(penumbra_position, 1.0)"));
    out.line("penumbra_depth = (", transform(config, "penumbra_lightFromWorld", "world"), ").z;");
    out.line(clip_position(config), " = ", transform(config, Text(clip_from_world), "world"), ";");
    if (binds_samplers_apart(config)) {
        out.comment(cat(choose(is_hlsl(config), "Direct3D's", "WebGPU's"),
                        " framebuffer rows run top down: flipped, ", target,
                        " row 0 holds uv.y = 0 as on OpenGL"));
        out.line(clip_position(config), ".y = -", clip_position(config), ".y;");
    }
    write_alpha_test_vertex_copy(out, config);
    out.line("}");
    write_entry_point(out, config, Stage::vertex);
}

// Fragment stage: the texture coordinates in.
constexpr void write_alpha_test_fragment_inputs(LineWriter& out, const Config& config) {
    if (!config.alpha_test) return;
    out.line(stage_variable(out, config, "in", alpha_test_varying_location, "vec2", "penumbra_texCoord",
                            has_varying_locations(config)),
             " // the caster's material texture coordinates (alpha test)");
}

// Both stages: the material's parameters, after the program's own (so the bindings follow them).
constexpr void write_alpha_test_params(LineWriter& out, const Config& config, int& binding) {
    if (config.alpha_test) write_params(out, config, alpha_test_params(config), alpha_test_block, binding);
}

// Fragment stage, first in main(): the cut.
constexpr void write_alpha_test_discard(LineWriter& out, const Config& config) {
    if (!config.alpha_test) return;
    out.comment("alpha test: where the material's alpha is below the cutoff there is no caster (leaf cards, fences)");
    out.line(if_then(config, cat(sample(config, "penumbra_alphaTexture", "penumbra_texCoord"), ".a < penumbra_alphaCutoff"),
                     "discard;"));
}

} // namespace penumbra::detail
