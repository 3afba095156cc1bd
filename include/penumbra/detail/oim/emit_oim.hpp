// penumbra/detail/oim/emit_oim.hpp — occlusion interval maps (Donnelly & Demers, GPU Gems ch. 13):
// float penumbraVisibility(vec2 texCoord) over baked rise/fall textures, a deferred pass over a
// G-buffer of texture coordinates, and a forward example.
//
// The configuration fixes the number of rise/fall pairs (four intervals each), so the chapter's
// evaluation is written once per pair, labelled with the intervals it covers; the time window
// (start, end, 1 / width) is a uniform: it moves with the time of day.
#pragma once

#include "../glsl_common.hpp"
#include "../uniform_params.hpp"

namespace penumbra::detail {

constexpr Text oim_rise_name(int pair) { return cat("penumbra_rise", format_int(pair)); }
constexpr Text oim_fall_name(int pair) { return cat("penumbra_fall", format_int(pair)); }

// Parameters of penumbraVisibility(): the window, then one rise and one fall texture per pair.
constexpr std::vector<Param> oim_visibility_params(const Config& config) {
    std::vector<Param> params;
    params.push_back(uniform_param(Uniform::time_window, config.light));
    for (int p = 0; p < oim_pairs(config.oim); ++p) {
        params.push_back({oim_rise_name(p), "sampler2D", "rise times of four visibility intervals (path time t)", "",
                          oim_rise_name(p)});
        params.push_back({oim_fall_name(p), "sampler2D", "fall times of the same four intervals (path time t)", "",
                          oim_fall_name(p)});
    }
    return params;
}

constexpr std::vector<Param> oim_deferred_params() {
    return {{"penumbra_texCoords", "sampler2D",
             "G-buffer: xy unique texture coordinates of the surface, w = 1 where there is geometry and 0 for the "
             "background",
             "", "penumbra_texCoords"}};
}

constexpr void write_oim_visibility(LineWriter& out, const Config& config, int& binding) {
    write_params(out, config, oim_visibility_params(config), "PenumbraVisibility", binding);
    out.chunk("oim_visibility");
    out.comment("GPU Gems ch. 13, Listing 13-1: the fraction of the window during which the sun is visible.");
    out.comment("Per interval saturate(min(fall, end) - max(rise, start)); the dot with 1 / (end - start) divides");
    out.comment("by the window and adds four intervals at once. Nearest texels: the edges must not be blended.");
    out.line("float penumbraVisibility(vec2 texCoord)");
    out.line("{");
    out.line("vec4 start = vec4(penumbra_timeWindow.x);");
    out.line("vec4 end = vec4(penumbra_timeWindow.y);");
    out.line("vec4 inverseWidth = vec4(penumbra_timeWindow.z);");
    out.line("float visibility = 0.0;");
    for (int p = 0; p < oim_pairs(config.oim); ++p) {
        out.comment(cat("intervals ", format_int(4 * p), " to ", format_int(4 * p + 3), ": pair ", format_int(p)));
        out.line("visibility += dot(inverseWidth, clamp(min(textureLod(", oim_fall_name(p), ", texCoord, 0.0), end)",
                 " - max(textureLod(", oim_rise_name(p), ", texCoord, 0.0), start), 0.0, 1.0));");
    }
    out.line("return min(visibility, 1.0);");
    out.line("}");
}

// penumbra_visibility.glsl: parameters and penumbraVisibility(), no #version, for inclusion.
constexpr Text oim_visibility_snippet(const Config& config) {
    LineWriter out;
    out.line("// Penumbra ", version_string, " - penumbra_visibility.glsl: float penumbraVisibility(vec2 texCoord)");
    out.line("// ", describe(config));
    out.line("// Include after the version directive (and, for ES, precision statements). texCoord: the surface's unique texture");
    out.line("// coordinates, the ones the bake used. Generated: edit the configuration, not this file.");
    out.blank();
    int binding = 0;
    write_oim_visibility(out, config, binding);
    return out.take();
}

// One full-screen pass over the G-buffer of texture coordinates, drawn at its size.
constexpr Text oim_deferred_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "deferred visibility pass: penumbraVisibility of a G-buffer of texture coordinates");
    out.line("layout(location = 0) out vec4 penumbra_visibility;");
    out.blank();
    int binding = 0;
    write_oim_visibility(out, config, binding);
    out.blank();
    write_params(out, config, oim_deferred_params(), "PenumbraDeferred", binding);
    out.chunk("oim_deferred_main");
    out.block(R"(
void main()
{
    vec4 surface = texelFetch(penumbra_texCoords, ivec2(gl_FragCoord.xy), 0);
    if (surface.w < 0.5)
    {
        penumbra_visibility = vec4(1.0);
        return;
    }
    penumbra_visibility = vec4(vec3(penumbraVisibility(surface.xy)), 1.0);
}
)");
    return out.take();
}

constexpr std::vector<Param> oim_example_fragment_params() {
    return {uniform_param(Uniform::to_light, "direction towards the sun (xyz, w = 0) for the Lambert term", "")};
}
constexpr std::vector<Param> oim_example_vertex_params() {
    return {uniform_param(Uniform::clip_from_world, Light::sun)};
}

constexpr Text oim_example_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "example shading pass: Lambert term times penumbraVisibility, fragment stage");
    out.chunk("oim_example_inputs");
    out.line(varying(config, "in", 0, "vec3", "penumbra_worldPos"), " // scene units");
    out.line(varying(config, "in", 1, "vec3", "penumbra_worldNormal"));
    out.line(varying(config, "in", 2, "vec2", "penumbra_texCoord"));
    out.line("layout(location = 0) out vec4 penumbra_color;");
    out.blank();
    int binding = 0;
    write_oim_visibility(out, config, binding);
    out.blank();
    write_params(out, config, oim_example_fragment_params(), "PenumbraExample", binding);
    out.chunk("oim_example_main");
    out.block(R"(
void main()
{
    vec3 toLight = normalize(penumbra_toLight.xyz - penumbra_worldPos * penumbra_toLight.w);
    float lambert = max(dot(normalize(penumbra_worldNormal), toLight), 0.0);
    float visibility = penumbraVisibility(penumbra_texCoord);
    vec3 albedo = vec3(0.8);
    vec3 color = albedo * (0.15 + 0.85 * lambert * visibility);
    penumbra_color = vec4(color, 1.0);
}
)");
    return out.take();
}

// The vertex stage's bindings follow the fragment stage's (visibility block, the pairs' samplers,
// the example block), so both stages fit one Vulkan pipeline layout.
constexpr int oim_example_fragment_binding_count(const Config& config) { return 1 + 2 * oim_pairs(config.oim) + 1; }

constexpr Text oim_example_vertex(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "example shading pass, vertex stage");
    out.chunk("oim_example_vertex_inputs");
    out.line("layout(location = 0) in vec3 penumbra_position; // world space (scene units)");
    out.line("layout(location = 1) in vec3 penumbra_normal;   // world space");
    out.line("layout(location = 2) in vec2 penumbra_uv;       // unique texture coordinates (the bake's)");
    out.line(varying(config, "out", 0, "vec3", "penumbra_worldPos"));
    out.line(varying(config, "out", 1, "vec3", "penumbra_worldNormal"));
    out.line(varying(config, "out", 2, "vec2", "penumbra_texCoord"));
    out.blank();
    int binding = oim_example_fragment_binding_count(config);
    write_params(out, config, oim_example_vertex_params(), "PenumbraCamera", binding);
    out.chunk("oim_example_vertex_main");
    out.block(R"(
void main()
{
    penumbra_worldPos = penumbra_position;
    penumbra_worldNormal = penumbra_normal;
    penumbra_texCoord = penumbra_uv;
    gl_Position = penumbra_clipFromWorld * vec4(penumbra_position, 1.0);
}
)");
    return out.take();
}

} // namespace penumbra::detail
