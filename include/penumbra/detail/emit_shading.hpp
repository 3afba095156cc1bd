// penumbra/detail/emit_shading.hpp — the files every technique shares: complete shading programs
// around the technique's penumbraVisibility() (a forward example, Lambert + shadow, and a deferred
// pass that reads world positions), and the full-screen triangle of the screen and prefilter passes.
#pragma once

#include "glsl_common.hpp"

namespace penumbra::detail {

// main() of a triangle that covers the viewport, from the vertex index alone (no vertex buffer).
constexpr void write_fullscreen_vertex_main(LineWriter& out, const Config& config) {
    out.chunk("fullscreen_vertex_main");
    out.line("void main()");
    out.line("{");
    out.line("int index = ", vertex_index(config), ";");
    out.line("vec2 corner = vec2(float((index << 1) & 2), float(index & 2));");
    out.line("gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);");
    out.line("}");
}

constexpr Text fullscreen_vertex(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "full-screen triangle, vertex stage (draw 3 vertices, no attributes)");
    write_fullscreen_vertex_main(out, config);
    return out.take();
}


constexpr std::vector<Param> example_fragment_params() {
    return {{"penumbra_toLight", "vec4",
             "light for the Lambert term: xyz position and w = 1, or xyz direction towards the light and w = 0",
             "scene units"}};
}
constexpr std::vector<Param> example_vertex_params() {
    return {{"penumbra_clipFromWorld", "mat4", "world to clip space of the viewer's camera", "", {}, "camera"}};
}
constexpr std::vector<Param> deferred_params(const Config& config) {
    std::vector<Param> params{{"penumbra_worldPositions", "sampler2D",
                               "G-buffer: xyz world position, w = 1 where there is geometry and 0 for the background",
                               "scene units", "penumbra_worldPositions"}};
    if (reads_receiver_normal(config))
        params.push_back({"penumbra_worldNormals", "sampler2D",
                          "G-buffer: xyz world normal of the side the viewer sees (tangent clip, normal offset)", "",
                          "penumbra_worldNormals"});
    return params;
}

constexpr Text example_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "example shading pass: Lambert term times penumbraVisibility, fragment stage");
    out.chunk("example_inputs");
    out.line(varying(config, "in", 0, "vec3", "penumbra_worldPos"), " // scene units");
    out.line(varying(config, "in", 1, "vec3", "penumbra_worldNormal"));
    out.line("layout(location = 0) out vec4 penumbra_color;");
    out.blank();
    int binding = 0;
    technique_descriptor(config.technique).write_visibility(out, config, binding);
    out.blank();
    write_params(out, config, example_fragment_params(), "PenumbraExample", binding);
    out.chunk("example_main");
    out.block(R"(
void main()
{
    vec3 toLight = normalize(penumbra_toLight.xyz - penumbra_worldPos * penumbra_toLight.w);
    float lambert = max(dot(normalize(penumbra_worldNormal), toLight), 0.0);
)");
    if (reads_receiver_normal(config)) {
        out.comment("the tangent clip and the normal offset need the normal of the side the viewer sees");
        out.line("float visibility = penumbraVisibility(penumbra_worldPos, "
                 "gl_FrontFacing ? penumbra_worldNormal : -penumbra_worldNormal);");
    } else {
        out.line("float visibility = penumbraVisibility(penumbra_worldPos);");
    }
    out.block(R"(
    vec3 albedo = vec3(0.8);
    vec3 color = albedo * (0.15 + 0.85 * lambert * visibility);
    penumbra_color = vec4(color, 1.0);
}
)");
    return out.take();
}

// The vertex stage's bindings follow the fragment stage's (visibility block, its samplers, the
// example block), so both stages fit one Vulkan pipeline layout.
constexpr int example_fragment_binding_count(const Config& config) {
    int samplers = 0;
    for (const Param& p : technique_descriptor(config.technique).visibility_params(config)) samplers += is_sampler(p) ? 1 : 0;
    return 1 + samplers + 1;
}

constexpr Text example_vertex(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "example shading pass, vertex stage");
    out.chunk("example_vertex_inputs");
    out.line("layout(location = 0) in vec3 penumbra_position; // world space (scene units)");
    out.line("layout(location = 1) in vec3 penumbra_normal;   // world space");
    out.line(varying(config, "out", 0, "vec3", "penumbra_worldPos"));
    out.line(varying(config, "out", 1, "vec3", "penumbra_worldNormal"));
    out.blank();
    int binding = example_fragment_binding_count(config);
    write_params(out, config, example_vertex_params(), "PenumbraCamera", binding);
    out.chunk("example_vertex_main");
    out.block(R"(
void main()
{
    penumbra_worldPos = penumbra_position;
    penumbra_worldNormal = penumbra_normal;
    gl_Position = penumbra_clipFromWorld * vec4(penumbra_position, 1.0);
}
)");
    return out.take();
}

// Deferred variant: one full-screen pass over a G-buffer of world positions, drawn at the
// G-buffer's size; writes the visibility to all channels.
constexpr Text deferred_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "deferred visibility pass: penumbraVisibility of a G-buffer, fragment stage");
    out.line("layout(location = 0) out vec4 penumbra_visibility;");
    out.blank();
    int binding = 0;
    technique_descriptor(config.technique).write_visibility(out, config, binding);
    out.blank();
    write_params(out, config, deferred_params(config), "PenumbraDeferred", binding);
    write_deferred_main(out, reads_receiver_normal(config));
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
