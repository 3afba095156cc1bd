// penumbra/detail/emit_shading.hpp — the files every technique shares: complete shading programs
// around the technique's penumbraVisibility() (a forward example, Lambert + shadow, and a deferred
// pass that reads world positions), and the full-screen triangle of the screen and prefilter passes.
#pragma once

#include "glsl_common.hpp"
#include "uniform_params.hpp"

namespace penumbra::detail {

// main() of a triangle that covers the viewport, from the vertex index alone (no vertex buffer).
constexpr void write_fullscreen_vertex_main(LineWriter& out, const Config& config) {
    declare_builtin(out, config, true, "vertex_index", "int", vertex_index(config), "u32");
    declare_builtin(out, config, false, "position", "vec4", clip_position(config));
    out.chunk("fullscreen_vertex_main");
    out.line(main_signature(config));
    out.line("{");
    out.line(value(config, "int", "index", vertex_index(config)));
    // WGSL shifts by an unsigned amount
    out.line(value(config, "vec2", "corner",
                   cat("vec2(", construct(config, "float", choose(is_wgsl(config), Text("(index << 1u) & 2"), Text("(index << 1) & 2"))),
                       ", ", construct(config, "float", "index & 2"), ")")));
    out.line(clip_position(config), " = vec4(corner * 2.0 - 1.0, 0.0, 1.0);");
    out.line("}");
    write_entry_point(out, config, Stage::vertex);
}

constexpr Text fullscreen_vertex(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "full-screen triangle, vertex stage (draw 3 vertices, no attributes)");
    write_fullscreen_vertex_main(out, config);
    return out.take();
}


constexpr std::vector<Param> example_fragment_params() {
    return {uniform_param(Uniform::to_light, Light::rect)};
}
constexpr std::vector<Param> example_vertex_params() {
    return {uniform_param(Uniform::clip_from_world, Light::rect)};
}
constexpr std::vector<Param> deferred_params(const Config& config) {
    std::vector<Param> params{{"penumbra_worldPositions", "sampler2D",
                               "G-buffer: xyz world position, w = 1 where there is geometry and 0 for the background",
                               "scene units", "penumbra_worldPositions", UniformSource::light, {}, /*fetch_only=*/true}};
    if (reads_receiver_normal(config))
        params.push_back({"penumbra_worldNormals", "sampler2D",
                          "G-buffer: xyz world normal of the side the viewer sees (tangent clip, normal offset)", "",
                          "penumbra_worldNormals", UniformSource::light, {}, /*fetch_only=*/true});
    return params;
}

constexpr Text example_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "example shading pass: Lambert term times penumbraVisibility, fragment stage");
    out.chunk("example_inputs");
    out.line(stage_variable(out, config, "in", 0, "vec3", "penumbra_worldPos", has_varying_locations(config)), " // scene units");
    out.line(stage_variable(out, config, "in", 1, "vec3", "penumbra_worldNormal", has_varying_locations(config)));
    out.line(stage_variable(out, config, "out", 0, "vec4", "penumbra_color", true));
    declare_builtin(out, config, true, "front_facing", "bool", front_facing(config));
    out.blank();
    int binding = 0;
    technique_descriptor(config.technique).write_visibility(out, config, binding);
    out.blank();
    write_params(out, config, example_fragment_params(), "PenumbraExample", binding);
    out.chunk("example_main");
    out.line(main_signature(config));
    out.line("{");
    out.line(value(config, "vec3", "toLight", "normalize(penumbra_toLight.xyz - penumbra_worldPos * penumbra_toLight.w)"));
    out.line(value(config, "float", "lambert", "max(dot(normalize(penumbra_worldNormal), toLight), 0.0)"));
    if (reads_receiver_normal(config)) {
        out.comment("the tangent clip and the normal offset need the normal of the side the viewer sees");
        out.line(value(config, "float", "visibility",
                       cat(visibility_with_normal(config), "(penumbra_worldPos, ",
                           conditional(config, front_facing(config), "penumbra_worldNormal", "-penumbra_worldNormal"), ")")));
    } else {
        out.line(value(config, "float", "visibility", "penumbraVisibility(penumbra_worldPos)"));
    }
    out.line(value(config, "vec3", "albedo", "vec3(0.8)"));
    out.line(value(config, "vec3", "color", "albedo * (0.15 + 0.85 * lambert * visibility)"));
    out.line("penumbra_color = vec4(color, 1.0);");
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

// The vertex stage's bindings follow the fragment stage's (visibility block, its samplers, the
// example block), so both stages fit one Vulkan pipeline layout.
constexpr int example_fragment_binding_count(const Config& config) {
    if (!binds_samplers_apart(config)) { // the block, the samplers, the example block
        int samplers = 0;
        for (const Param& p : technique_descriptor(config.technique).visibility_params(config)) samplers += is_sampler(p) ? 1 : 0;
        return 1 + samplers + 1;
    }
    int binding = 0; // WGSL and HLSL: a texture's sampler takes a binding too
    param_bindings(config, technique_descriptor(config.technique).visibility_params(config), binding);
    param_bindings(config, example_fragment_params(), binding);
    return binding;
}

constexpr Text example_vertex(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "example shading pass, vertex stage");
    out.chunk("example_vertex_inputs");
    out.line(stage_variable(out, config, "in", 0, "vec3", "penumbra_position", true), " // world space (scene units)");
    out.line(stage_variable(out, config, "in", 1, "vec3", "penumbra_normal", true), "   // world space");
    out.line(stage_variable(out, config, "out", 0, "vec3", "penumbra_worldPos", has_varying_locations(config)));
    out.line(stage_variable(out, config, "out", 1, "vec3", "penumbra_worldNormal", has_varying_locations(config)));
    declare_builtin(out, config, false, "position", "vec4", clip_position(config));
    out.blank();
    int binding = example_fragment_binding_count(config);
    write_params(out, config, example_vertex_params(), "PenumbraCamera", binding);
    out.chunk("example_vertex_main");
    out.line(main_signature(config));
    out.line("{");
    out.line("penumbra_worldPos = penumbra_position;");
    out.line("penumbra_worldNormal = penumbra_normal;");
    out.line(clip_position(config), " = ",
             transform(config, "penumbra_clipFromWorld", "vec4(penumbra_position, 1.0)"), ";");
    out.line("}");
    write_entry_point(out, config, Stage::vertex);
    return out.take();
}

// Deferred variant: one full-screen pass over a G-buffer of world positions, drawn at the
// G-buffer's size; writes the visibility to all channels.
constexpr Text deferred_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "deferred visibility pass: penumbraVisibility of a G-buffer, fragment stage");
    out.line(stage_variable(out, config, "out", 0, "vec4", "penumbra_visibility", true));
    declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
    out.blank();
    int binding = 0;
    technique_descriptor(config.technique).write_visibility(out, config, binding);
    out.blank();
    write_params(out, config, deferred_params(config), "PenumbraDeferred", binding);
    write_deferred_main(out, config, reads_receiver_normal(config));
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

// The shared files, as the techniques' program plans list them.
inline constexpr ShaderFileSpec fullscreen_vert{"penumbra_fullscreen.vert", Stage::vertex, fullscreen_vertex};
inline constexpr ShaderFileSpec shading_vert{"penumbra_shading.vert", Stage::vertex, example_vertex, VertexInputs::receiver};
inline constexpr ShaderFileSpec shading_frag{"penumbra_shading.frag", Stage::fragment, example_fragment};
inline constexpr ShaderFileSpec deferred_frag{"penumbra_deferred.frag", Stage::fragment, deferred_fragment};

// The two shading programs most techniques end with.
constexpr ProgramPlan shading_example_program() { return {"shading_example", {shading_vert, shading_frag}}; }
constexpr ProgramPlan shading_deferred_program() { return {"shading_deferred", {fullscreen_vert, deferred_frag}}; }

} // namespace penumbra::detail
