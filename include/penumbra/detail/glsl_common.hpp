// penumbra/detail/glsl_common.hpp — what every emitted file shares: version line, configuration
// header, declarations of parameters in the target's dialect.
#pragma once

#include "../config.hpp"
#include "technique.hpp"
#include "text.hpp"

#include <string_view>
#include <vector>

namespace penumbra::detail {

inline constexpr std::string_view version_string = "0.1.0";

// A uniform or sampler a program reads. The same list drives the declarations in the text and
// the layout description, so they cannot disagree.
struct Param {
    Text name;
    std::string_view type;    // GLSL type: "mat4", "vec2", "sampler2DArray", …
    std::string_view meaning; // one line, for the declaration comment and layout.json
    std::string_view units;   // "scene units", "texels", "" when unitless
    Text texture = {};        // samplers: the layout texture bound to it
    // Plain uniforms: where the value comes from. "light": computed from the light frame
    // (penumbra::uniform_value, penumbra/uniform_values.hpp); "pass": the pass's int_uniforms;
    // "camera": the engine's camera (also in uniform_value when the camera is given).
    std::string_view source = "light";
    // Samplers: the filter this binding reads its texture with when it is not the texture's own
    // (layout.json's "sampling"); "" for the texture's filters.
    std::string_view filter = {};
};

constexpr bool is_sampler(const Param& param) {
    return param.type.starts_with("sampler") || param.type.starts_with("usampler") || param.type.starts_with("isampler");
}

constexpr bool is_vulkan(const Config& config) { return config.target == Target::vulkan; }
// The one Vulkan descriptor set every emitted block and sampler is declared in ("set" in layout.json).
inline constexpr int vulkan_descriptor_set = 0;
constexpr bool has_explicit_bindings(const Config& config) {
    return config.target == Target::vulkan || config.target == Target::glsl450;
}
// Locations on vertex outputs / fragment inputs exist from GLSL 4.10 on (and SPIR-V needs them).
constexpr bool has_varying_locations(const Config& config) {
    return config.target == Target::vulkan || config.target == Target::glsl450;
}

constexpr Text on_off(bool value) { return choose(value, "on", "off"); }

// The configuration line of every file's header: only the fields the technique reads, then the
// alpha test of cut-out casters when it is on.
constexpr Text describe_technique(const Config& config) { return technique_descriptor(config.technique).summary(config); }

constexpr Text describe(const Config& config) {
    if (!config.alpha_test) return describe_technique(config);
    return cat(describe_technique(config), " | alpha test (cut-out casters)");
}

// The version directive of the target: the first line of every stage.
constexpr void write_version(LineWriter& out, const Config& config) {
    switch (config.target) {
    case Target::glsl330: out.line("#version 330 core"); break;
    case Target::glsl450: out.line("#version 450 core"); break;
    case Target::essl300: out.line("#version 300 es"); break;
    case Target::vulkan: out.line("#version 450"); break;
    }
}

// ES has no default float precision in fragment shaders; everything Penumbra computes needs highp.
constexpr void write_precision(LineWriter& out, const Config& config) {
    if (config.target != Target::essl300) return;
    out.chunk("precision");
    out.line("precision highp float;");
    out.line("precision highp int;");
    out.line("precision highp sampler2D;");
    out.line("precision highp sampler2DArray;");
    out.line("precision highp sampler3D;");
    for (std::string_view sampler : technique_descriptor(config.technique).es_sampler_precision(config))
        out.line("precision highp ", sampler, ";");
}

// First lines of every stage: the version directive must come first, then what this file is
// and the configuration it was specialized for.
constexpr void write_preamble(LineWriter& out, const Config& config, std::string_view title) {
    write_version(out, config);
    out.line("// Penumbra ", version_string, " - ", title);
    out.line("// ", describe(config));
    out.line("// ", technique_descriptor(config.technique).storage_note(config), " Generated: edit the configuration, not this file.");
    write_precision(out, config);
    out.blank();
}

// The deferred pass's main(): visibility of the G-buffer texel under the pixel (with
// `normals`, the G-buffer's normal too, for the tangent clip).
constexpr void write_deferred_main(LineWriter& out, bool normals = false) {
    out.chunk("deferred_main");
    out.block(R"(
void main()
{
    vec4 world = texelFetch(penumbra_worldPositions, ivec2(gl_FragCoord.xy), 0);
    // A real branch, not a select: the background must not pay for the whole slice loop.
    if (world.w < 0.5)
    {
        penumbra_visibility = vec4(1.0);
        return;
    }
)");
    if (normals) {
        out.line("vec3 normal = texelFetch(penumbra_worldNormals, ivec2(gl_FragCoord.xy), 0).xyz;");
        out.line("penumbra_visibility = vec4(vec3(penumbraVisibility(world.xyz, normal)), 1.0);");
    } else {
        out.line("penumbra_visibility = vec4(vec3(penumbraVisibility(world.xyz)), 1.0);");
    }
    out.line("}");
}

// True when `params` holds a plain uniform (which Vulkan must put in a block).
constexpr bool has_values(const std::vector<Param>& params) {
    for (const Param& p : params)
        if (!is_sampler(p)) return true;
    return false;
}

// Binding (texture unit on OpenGL) of each parameter, -1 for plain uniforms: on Vulkan the
// uniform block takes the first binding, then the samplers follow in declaration order.
constexpr std::vector<int> param_bindings(const Config& config, const std::vector<Param>& params, int& next_binding) {
    if (has_values(params) && is_vulkan(config)) ++next_binding;
    std::vector<int> bindings;
    for (const Param& p : params) bindings.push_back(is_sampler(p) ? next_binding++ : -1);
    return bindings;
}

// Declares `params`: plain uniforms on OpenGL targets, one std140 block on Vulkan (which has no
// loose uniforms); samplers with explicit bindings where the dialect has them. `next_binding`
// numbers blocks and samplers in declaration order.
constexpr void write_params(LineWriter& out, const Config& config, const std::vector<Param>& params,
                            std::string_view block_name, int& next_binding) {
    out.chunk("parameters");
    const int block_binding = next_binding;
    const std::vector<int> bindings = param_bindings(config, params, next_binding);
    auto comment = [](const Param& p) {
        return choose(p.units.empty(), cat(" // ", p.meaning), cat(" // ", p.meaning, " (", p.units, ")"));
    };
    if (has_values(params) && is_vulkan(config)) {
        out.line("layout(set = ", format_int(vulkan_descriptor_set), ", binding = ", format_int(block_binding), ", std140) uniform ", block_name, " {");
        for (const Param& p : params)
            if (!is_sampler(p)) out.line(p.type, " ", p.name, ";", comment(p));
        out.line("};");
    } else {
        for (const Param& p : params)
            if (!is_sampler(p)) out.line("uniform ", p.type, " ", p.name, ";", comment(p));
    }
    for (std::size_t i = 0; i < params.size(); ++i) {
        const Param& p = params[i];
        if (!is_sampler(p)) continue;
        const Text binding = format_int(bindings[i]);
        if (is_vulkan(config))
            out.line("layout(set = ", format_int(vulkan_descriptor_set), ", binding = ", binding, ") uniform ", p.type, " ", p.name, ";", comment(p));
        else if (has_explicit_bindings(config))
            out.line("layout(binding = ", binding, ") uniform ", p.type, " ", p.name, ";", comment(p));
        else
            out.line("uniform ", p.type, " ", p.name, ";", comment(p), ", texture unit ", binding);
    }
    out.blank();
}

// `in`/`out` declaration of a value passed between stages.
constexpr Text varying(const Config& config, std::string_view direction, int location, std::string_view type,
                       std::string_view name) {
    if (has_varying_locations(config))
        return cat("layout(location = ", format_int(location), ") ", direction, " ", type, " ", name, ";");
    return cat(direction, " ", type, " ", name, ";");
}

constexpr std::string_view vertex_index(const Config& config) {
    return is_vulkan(config) ? "gl_VertexIndex" : "gl_VertexID";
}

constexpr std::string_view channel_name(int channel) {
    constexpr std::string_view names[] = {"r", "g", "b", "a"};
    return names[channel];
}

constexpr Text one_hot(int channel) {
    Text out("vec4(");
    for (int c = 0; c < 4; ++c) out += c == channel ? (c < 3 ? "1.0, " : "1.0") : (c < 3 ? "0.0, " : "0.0");
    return out += ")", out;
}

} // namespace penumbra::detail
