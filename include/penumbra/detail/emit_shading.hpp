// penumbra/detail/emit_shading.hpp — complete shading programs around penumbraVisibility():
// a forward example (Lambert + shadow) and a deferred pass that reads world positions.
#pragma once

#include "technique_visibility.hpp"
#include "uniform_params.hpp"

namespace penumbra::detail {

constexpr std::vector<Param> example_fragment_params() {
    return {uniform_param(Uniform::to_light, Light::rect)};
}
constexpr std::vector<Param> example_vertex_params() {
    return {uniform_param(Uniform::clip_from_world, Light::rect)};
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
    write_technique_visibility(out, config, binding);
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
    for (const Param& p : technique_visibility_params(config)) samplers += is_sampler(p) ? 1 : 0;
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
    write_technique_visibility(out, config, binding);
    out.blank();
    write_params(out, config, deferred_params(config), "PenumbraDeferred", binding);
    write_deferred_main(out, reads_receiver_normal(config));
    return out.take();
}

} // namespace penumbra::detail
