// penumbra/detail/glsl_common.hpp — what every emitted file shares: version line, configuration
// header, declarations of parameters in the target's dialect.
#pragma once

#include "../config.hpp"
#include "../uniforms.hpp"
#include "language.hpp"
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
    // Plain uniforms (and per-draw samplers): where the value comes from (penumbra/uniforms.hpp).
    UniformSource source = UniformSource::light;
    // Samplers: the filter this binding reads its texture with when it is not the texture's own
    // (layout.json's "sampling"); "" for the texture's filters.
    std::string_view filter = {};
    // Samplers that only read texels (texelFetch): WGSL binds no sampler for them.
    bool fetch_only = false;
    // A sampler2D over a depth texture (WGSL: texture_depth_2d, not texture_2d<f32>).
    bool depth_texture = false;
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
    case Target::wgsl: break; // WGSL has no version directive
    case Target::hlsl: break; // nor HLSL
    case Target::msl: break;  // never emitted as text here: emit_msl translates the vulkan target's SPIR-V
    }
}

// ES has no default float precision in fragment shaders; everything Penumbra computes needs highp.
// HLSL: what every file and snippet declares before its own text instead (write_hlsl_names).
constexpr void write_precision(LineWriter& out, const Config& config) {
    write_hlsl_names(out, config);
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

// The first lines of the includable snippet penumbra_visibility.*: what it is (`signatures`: the
// functions it defines), the configuration, and where to include it in the target's language.
constexpr void write_snippet_header(LineWriter& out, const Config& config, const Text& signatures) {
    out.line("// Penumbra ", version_string, " - ", file_name(config, visibility_snippet_name), ": ", signatures);
    out.line("// ", describe(config));
    if (is_wgsl(config))
        out.comment("Add to a module of the shading stage. Bindings start at 0 in group 0; call penumbra_loadVisibility()"
                    " first in the entry point.");
    else if (is_hlsl(config))
        out.comment("#include in a pixel shader. Registers start at 0 in space 0 (b#, t#, s# numbered together).");
    else
        out.comment("Include after the #version line of a stage for this target. Bindings start at 0.");
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
constexpr void write_deferred_main(LineWriter& out, const Config& config, bool normals = false) {
    out.chunk("deferred_main");
    const Text texel = cat(type_name(config, "ivec2"), "(", frag_coord(config), ".xy)");
    out.line(main_signature(config));
    out.line("{");
    out.line(value(config, "vec4", "world", fetch(config, "penumbra_worldPositions", texel, "0")));
    out.comment("A real branch, not a select: the background must not pay for the whole slice loop.");
    out.line("if (world.w < 0.5)");
    out.line("{");
    out.line("penumbra_visibility = vec4(1.0);");
    out.line("return;");
    out.line("}");
    if (normals) {
        out.line(value(config, "vec3", "normal", cat(fetch(config, "penumbra_worldNormals", texel, "0"), ".xyz")));
        out.line("penumbra_visibility = vec4(vec3(", visibility_with_normal(config), "(world.xyz, normal)), 1.0);");
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

// WGSL: a sampler parameter binds its texture and, unless it only fetches texels or reads
// integers (which WebGPU never filters), a sampler right after it.
constexpr bool binds_wgsl_sampler(const Param& p) {
    return is_sampler(p) && !p.fetch_only && !p.type.starts_with("usampler") && !p.type.starts_with("isampler");
}

// WGSL's texture type of a GLSL sampler parameter.
constexpr Text wgsl_texture_type(const Param& p) {
    if (p.type.ends_with("Shadow") || p.depth_texture) return Text("texture_depth_2d");
    const std::string_view scalar = p.type.starts_with("usampler") ? "u32" : p.type.starts_with("isampler") ? "i32" : "f32";
    const std::string_view shape = p.type.ends_with("2DArray") ? "texture_2d_array" : p.type.ends_with("3D") ? "texture_3d" : "texture_2d";
    return cat(shape, "<", scalar, ">");
}

// Binding (texture unit on OpenGL) of each parameter, -1 for plain uniforms: on Vulkan and WGSL the
// uniform block takes the first binding, then the samplers follow in declaration order (on WGSL each
// texture, then its sampler: binds_wgsl_sampler).
constexpr std::vector<int> param_bindings(const Config& config, const std::vector<Param>& params, int& next_binding) {
    if (has_values(params) && (is_vulkan(config) || binds_samplers_apart(config))) ++next_binding;
    std::vector<int> bindings;
    for (const Param& p : params) {
        bindings.push_back(is_sampler(p) ? next_binding++ : -1);
        if (binds_samplers_apart(config) && binds_wgsl_sampler(p)) ++next_binding;
    }
    return bindings;
}

constexpr Text param_comment(const Param& p) {
    return choose(p.units.empty(), cat(" // ", p.meaning), cat(" // ", p.meaning, " (", p.units, ")"));
}

// WGSL: the plain uniforms as one uniform buffer (a struct), copied by a load function into private
// globals of their GLSL names, which the entry point calls first (language.hpp); each sampler as its
// texture and sampler bindings.
constexpr void write_wgsl_params(LineWriter& out, const std::vector<Param>& params, std::string_view block_name,
                                 const std::vector<int>& bindings, int block_binding) {
    if (has_values(params)) {
        const Text buffer = cat("penumbra", block_name.substr(8), "Block"); // PenumbraX -> penumbraXBlock
        out.line("struct ", block_name, " {");
        for (const Param& p : params)
            if (!is_sampler(p)) out.line(p.name, ": ", wgsl_type_name(p.type), ",", param_comment(p));
        out.line("}");
        out.line("@group(0) @binding(", format_int(block_binding), ") var<uniform> ", buffer, ": ", block_name, ";");
        for (const Param& p : params)
            if (!is_sampler(p)) out.line("var<private> ", p.name, ": ", wgsl_type_name(p.type), ";");
        const Text load = cat("penumbra_load", block_name.substr(8));
        out.line("fn ", load, "()");
        out.line("{");
        for (const Param& p : params)
            if (!is_sampler(p)) out.line(p.name, " = ", buffer, ".", p.name, ";");
        out.line("}");
        out.entry_calls.push_back(load);
    }
    for (std::size_t i = 0; i < params.size(); ++i) {
        const Param& p = params[i];
        if (!is_sampler(p)) continue;
        out.line("@group(0) @binding(", format_int(bindings[i]), ") var ", p.name, ": ", wgsl_texture_type(p), ";",
                 param_comment(p));
        if (binds_wgsl_sampler(p))
            out.line("@group(0) @binding(", format_int(bindings[i] + 1), ") var ", sampler_of(p.name), ": ",
                     p.type.ends_with("Shadow") ? "sampler_comparison" : "sampler", ";");
    }
}

// HLSL's texture type of a GLSL sampler parameter (depth textures hold one float).
constexpr Text hlsl_texture_type(const Param& p) {
    if (p.type.ends_with("Shadow") || p.depth_texture) return Text("Texture2D<float>");
    const std::string_view element = p.type.starts_with("usampler")   ? "uint4"
                                     : p.type.starts_with("isampler") ? "int4"
                                                                      : "float4";
    const std::string_view shape = p.type.ends_with("2DArray") ? "Texture2DArray"
                                   : p.type.ends_with("3D")    ? "Texture3D"
                                                               : "Texture2D";
    return cat(shape, "<", element, ">");
}

// HLSL: the plain uniforms as one cbuffer at register b<binding>, members placed by packoffset where
// std140 puts them (layout.json's offsets, Vulkan's and WGSL's: one layout whichever API reads it);
// each sampler as its texture (t) and sampler (s) registers. Register numbers are the WGSL bindings,
// so that b#, t# and s# never share a number and a Vulkan build keeps them as its bindings.
constexpr void write_hlsl_params(LineWriter& out, const std::vector<Param>& params,
                                 std::string_view block_name, const std::vector<int>& bindings,
                                 int block_binding) {
    constexpr std::string_view space = ", space0)";
    if (has_values(params)) {
        out.line("cbuffer ", block_name, " : register(b", format_int(block_binding), space);
        out.line("{");
        int offset = 0;
        for (const Param& p : params) {
            if (is_sampler(p)) continue;
            const Std140 layout = std140(parse_enum<GlslType>(p.type).value_or(GlslType::float_));
            offset = (offset + layout.align - 1) / layout.align * layout.align;
            out.line(hlsl_type_name(p.type), " ", p.name, " : packoffset(c", format_int(offset / 16), ".",
                     std::string_view("xyzw").substr(offset % 16 / 4, 1), ");", param_comment(p));
            offset += layout.size;
        }
        out.line("};");
    }
    for (std::size_t i = 0; i < params.size(); ++i) {
        const Param& p = params[i];
        if (!is_sampler(p)) continue;
        out.line(hlsl_texture_type(p), " ", p.name, " : register(t", format_int(bindings[i]), space, ";",
                 param_comment(p));
        if (binds_wgsl_sampler(p))
            out.line(p.type.ends_with("Shadow") ? "SamplerComparisonState " : "SamplerState ",
                     sampler_of(p.name), " : register(s", format_int(bindings[i] + 1), space, ";");
    }
}

// Declares `params`: plain uniforms on OpenGL targets, one std140 block on Vulkan (which has no
// loose uniforms), one uniform buffer on WGSL; samplers with explicit bindings where the dialect has
// them. `next_binding` numbers blocks and samplers in declaration order.
constexpr void write_params(LineWriter& out, const Config& config, const std::vector<Param>& params,
                            std::string_view block_name, int& next_binding) {
    out.chunk("parameters");
    const int block_binding = next_binding;
    const std::vector<int> bindings = param_bindings(config, params, next_binding);
    if (is_wgsl(config)) {
        write_wgsl_params(out, params, block_name, bindings, block_binding);
        out.blank();
        return;
    }
    if (is_hlsl(config)) {
        write_hlsl_params(out, params, block_name, bindings, block_binding);
        out.blank();
        return;
    }
    auto comment = [](const Param& p) { return param_comment(p); };
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
