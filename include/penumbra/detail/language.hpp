// penumbra/detail/language.hpp — the one place where GLSL, WGSL and HLSL part ways.
//
// Emitters write what both languages share as text: expressions, swizzles, vec2/vec3/vec4(…)
// constructors, operators, the built-in maths (min, clamp, dot, mix, sqrt …), comments and braces.
// They ask this file for what differs: declarations, function signatures, type names, conversions,
// the conditional operator, texture reads, derivatives, built-in variables, and WGSL's entry point.
//
// A WGSL entry point takes its inputs as parameters and returns its outputs, where GLSL's main()
// reads and writes globals. So that one body serves both, a WGSL module keeps GLSL's shape: the
// stage's inputs and outputs and the uniform values are module-scope `var<private>` globals under
// their GLSL names, the body is `fn penumbra_main()`, and the generated `fn main` (write_entry_point)
// copies the inputs in, loads the uniform blocks, runs the body and returns the outputs. Compilers
// fold the copies; a reader sees the same statements in both languages.
//
// HLSL keeps WGSL's shape (private globals, penumbra_main(), a generated `main` with semantics,
// textures and samplers bound apart, render targets written top down as on Direct3D) in C's syntax.
// The shared expressions' GLSL spellings (vec3(…) constructors, mix, fract, texelFetch) are HLSL
// functions and macros that every HLSL file declares first (write_hlsl_names): the same text
// compiles in the three languages, and HLSL's own splat rules (float3(x) is not HLSL) are kept.
#pragma once

#include "../config.hpp"
#include "../program.hpp"
#include "text.hpp"

#include <initializer_list>
#include <string_view>
#include <utility>

namespace penumbra::detail {

constexpr bool is_wgsl(const Config& config) { return config.target == Target::wgsl; }
constexpr bool is_hlsl(const Config& config) { return config.target == Target::hlsl; }
// WGSL and HLSL bind a texture and its sampler apart, take the stage's inputs in an entry point and
// write render targets top down (WebGPU, Direct3D): HLSL follows WGSL's passes and bindings.
constexpr bool binds_samplers_apart(const Config& config) { return is_wgsl(config) || is_hlsl(config); }

// HLSL's name of a GLSL type ("vec3" → "float3"); texture types for samplers as function parameters.
constexpr std::string_view hlsl_type_name(std::string_view glsl) {
    constexpr std::pair<std::string_view, std::string_view> names[] = {
        {"vec2", "float2"},
        {"vec3", "float3"},
        {"vec4", "float4"},
        {"ivec2", "int2"},
        {"ivec3", "int3"},
        {"ivec4", "int4"},
        {"uvec2", "uint2"},
        {"uvec3", "uint3"},
        {"uvec4", "uint4"},
        {"bvec2", "bool2"},
        {"bvec3", "bool3"},
        {"bvec4", "bool4"},
        {"mat2", "float2x2"},
        {"mat3", "float3x3"},
        {"mat4", "float4x4"},
        {"sampler2D", "Texture2D<float4>"},
        {"usampler2D", "Texture2D<uint4>"},
    };
    for (const auto& [from, to] : names)
        if (from == glsl) return to;
    return glsl;
}

// WGSL's name of a GLSL type ("vec3" → "vec3f"); the GLSL name itself on the GLSL targets.
constexpr std::string_view wgsl_type_name(std::string_view glsl) {
    constexpr std::pair<std::string_view, std::string_view> names[] = {
        {"float", "f32"},   {"int", "i32"},       {"uint", "u32"},       {"bool", "bool"},
        {"vec2", "vec2f"},  {"vec3", "vec3f"},    {"vec4", "vec4f"},     {"ivec2", "vec2i"},
        {"ivec3", "vec3i"}, {"ivec4", "vec4i"},   {"uvec2", "vec2u"},    {"uvec3", "vec3u"},
        {"uvec4", "vec4u"}, {"mat2", "mat2x2f"},  {"mat3", "mat3x3f"},   {"mat4", "mat4x4f"},
        // samplers as function parameters: WGSL passes the texture alone
        {"sampler2D", "texture_2d<f32>"}, {"usampler2D", "texture_2d<u32>"},
    };
    for (const auto& [from, to] : names)
        if (from == glsl) return to;
    return glsl;
}

constexpr std::string_view type_name(const Config& config, std::string_view glsl) {
    if (is_hlsl(config)) return hlsl_type_name(glsl);
    return is_wgsl(config) ? wgsl_type_name(glsl) : glsl;
}

// Concatenates named values and literals by reference: cat() copies every part (it must, for Text
// temporaries), which on the long unrolled tap lines costs constant evaluation its operation budget.
template <class... Parts> constexpr Text joined(const Parts&... parts) {
    Text out;
    out.reserve((std::string_view(parts).size() + ... + 0));
    ((out += std::string_view(parts)), ...);
    return out;
}

// Text parameters are taken by value: GCC 12 ends the life of Text temporaries bound to references or
// string_views too early in constant evaluation (text.hpp, cat).

// A local variable the code assigns again: `T name = init;` / `var name: T = init;` (without
// `init`, declared only).
constexpr Text variable(const Config& config, Text type, Text name, Text init = {}) {
    if (is_hlsl(config)) type = Text(hlsl_type_name(type));
    if (!is_wgsl(config)) {
        if (init.empty()) return joined(type, " ", name, ";");
        return joined(type, " ", name, " = ", init, ";");
    }
    if (init.empty()) return joined("var ", name, ": ", wgsl_type_name(type), ";");
    return joined("var ", name, ": ", wgsl_type_name(type), " = ", init, ";");
}

// The start of a declaration whose initializer follows on the same line (and the next ones):
// `T name = ` / `let name: T = ` (`var` when `assigned_again`).
constexpr Text declaration(const Config& config, Text type, Text name, bool assigned_again = false) {
    if (is_hlsl(config)) return joined(hlsl_type_name(type), " ", name, " = ");
    if (!is_wgsl(config)) return joined(type, " ", name, " = ");
    return joined(assigned_again ? "var " : "let ", name, ": ", wgsl_type_name(type), " = ");
}

// clamp(x, 0.0, 1.0) of a vector: WGSL's clamp wants bounds of x's type; saturate takes any.
constexpr Text saturate(const Config& config, Text x) {
    if (!binds_samplers_apart(config)) return joined("clamp(", x, ", 0.0, 1.0)");
    return joined("saturate(", x, ")");
}

// GLSL's mod(a, b) for a >= 0: WGSL's % and HLSL's fmod truncate, which agrees there.
constexpr Text modulo(const Config& config, Text a, Text b) {
    if (is_hlsl(config)) return joined("fmod(", a, ", ", b, ")");
    if (!is_wgsl(config)) return joined("mod(", a, ", ", b, ")");
    return joined("(", a, " % ", b, ")");
}

// A local array of `size` elements: `T name[size];` / `var name: array<T, size>;`.
constexpr Text array_variable(const Config& config, Text type, Text name, Text size) {
    if (is_hlsl(config)) return joined(hlsl_type_name(type), " ", name, "[", size, "];");
    if (!is_wgsl(config)) return joined(type, " ", name, "[", size, "];");
    return joined("var ", name, ": array<", wgsl_type_name(type), ", ", size, ">;");
}

// clamp(x, lo, hi) of a vector x with scalar bounds: WGSL wants bounds of x's type (`type`).
constexpr Text clamp_vector(const Config& config, Text type, Text x, Text lo, Text hi) {
    if (!is_wgsl(config)) return joined("clamp(", x, ", ", lo, ", ", hi, ")");
    const std::string_view t = wgsl_type_name(type);
    return joined("clamp(", x, ", ", t, "(", lo, "), ", t, "(", hi, "))");
}

// A counted loop's head, `name` from 0 while below `end`: `for (int name = 0; name < end; ++name)` /
// `for (var name: i32 = 0; name < end; name++)`.
constexpr Text counted_loop(const Config& config, Text name, Text end) {
    if (!is_wgsl(config)) return joined("for (int ", name, " = 0; ", name, " < ", end, "; ++", name, ")");
    return joined("for (var ", name, ": i32 = 0; ", name, " < ", end, "; ", name, "++)");
}

// A local value set once: `T name = init;` / `let name: T = init;`.
constexpr Text value(const Config& config, Text type, Text name, Text init) {
    if (is_hlsl(config)) return joined(hlsl_type_name(type), " ", name, " = ", init, ";");
    if (!is_wgsl(config)) return joined(type, " ", name, " = ", init, ";");
    return joined("let ", name, ": ", wgsl_type_name(type), " = ", init, ";");
}

struct Parameter {
    std::string_view type, name;
};

// A function's signature (the line before its `{`): `float f(vec3 p)` / `fn f(p: vec3f) -> f32`.
constexpr Text signature(const Config& config, std::string_view result, std::string_view name,
                         std::initializer_list<Parameter> parameters) {
    Text out =
        choose(is_wgsl(config), joined("fn ", name, "("), joined(type_name(config, result), " ", name, "("));
    bool first = true;
    for (const Parameter& p : parameters) {
        if (!first) out += ", ";
        first = false;
        if (is_wgsl(config))
            out += joined(p.name, ": ", wgsl_type_name(p.type));
        else if (is_hlsl(config))
            out += joined(hlsl_type_name(p.type), " ", p.name);
        else
            out += joined(p.type, " ", p.name);
    }
    out += ")";
    if (is_wgsl(config) && result != "void") out += joined(" -> ", wgsl_type_name(result));
    return out;
}

// GLSL's main() is WGSL's and HLSL's penumbra_main(), which the entry point calls (write_entry_point).
constexpr std::string_view main_signature(const Config& config) {
    if (is_hlsl(config)) return "void penumbra_main()";
    return is_wgsl(config) ? "fn penumbra_main()" : "void main()";
}

// A conversion or constructor by type name: `float(x)` / `f32(x)`. HLSL keeps GLSL's name: its
// vector constructors are the functions of write_hlsl_names, which also splat one scalar.
constexpr Text construct(const Config& config, Text type, Text args) {
    if (is_hlsl(config)) return joined(type, "(", args, ")");
    return joined(type_name(config, type), "(", args, ")");
}

// A matrix times a column vector: `m * v` / HLSL's mul(m, v) (its cbuffers are column_major, as
// GLSL's uniforms: the same 16 floats give the same product).
constexpr Text transform(const Config& config, Text m, Text v) {
    if (is_hlsl(config)) return joined("mul(", m, ", ", v, ")");
    return joined(m, " * ", v);
}

// `when ? a : b` / `select(b, a, when)`.
constexpr Text conditional(const Config& config, Text when, Text a, Text b) {
    if (is_wgsl(config)) return joined("select(", b, ", ", a, ", ", when, ")");
    return joined(when, " ? ", a, " : ", b);
}

// A row vector times a matrix (the transpose's product): `v * m` / mul(v, m).
constexpr Text transform_row(const Config& config, Text v, Text m) {
    if (is_hlsl(config)) return joined("mul(", v, ", ", m, ")");
    return joined(v, " * ", m);
}

// The upper-left 3x3 of a mat4 (a direction's transform): WGSL has no mat3(mat4).
constexpr Text upper_3x3(const Config& config, Text m) {
    if (is_hlsl(config)) return joined("((float3x3)", m, ")");
    if (!is_wgsl(config)) return joined("mat3(", m, ")");
    return joined("mat3x3f(", m, "[0].xyz, ", m, "[1].xyz, ", m, "[2].xyz)");
}

// A component-wise comparison of two vectors (GLSL's lessThan, greaterThanEqual, equal, …): a bool vector.
constexpr Text compare(const Config& config, std::string_view glsl_function, Text a, Text b) {
    if (!binds_samplers_apart(config)) return joined(glsl_function, "(", a, ", ", b, ")");
    constexpr std::pair<std::string_view, std::string_view> operators[] = {
        {"lessThan", " < "}, {"lessThanEqual", " <= "}, {"greaterThan", " > "},
        {"greaterThanEqual", " >= "}, {"equal", " == "}, {"notEqual", " != "}};
    std::string_view op = " ? ";
    for (const auto& [name, symbol] : operators)
        if (name == glsl_function) op = symbol;
    return joined("(", a, op, b, ")");
}

// A one-statement if: WGSL wants braces around every body.
constexpr Text if_then(const Config& config, Text when, Text statement) {
    if (is_wgsl(config)) return joined("if (", when, ") { ", statement, " }");
    return joined("if (", when, ") ", statement);
}

// penumbraVisibility with the receiver's normal: an overload in GLSL; WGSL has no overloading.
constexpr std::string_view visibility_with_normal(const Config& config) {
    return is_wgsl(config) ? "penumbraVisibilityWithNormal" : "penumbraVisibility";
}

// Built-in functions whose names differ.
constexpr std::string_view builtin(const Config& config, std::string_view glsl) {
    if (is_hlsl(config)) {
        if (glsl == "dFdx") return "ddx";
        if (glsl == "dFdy") return "ddy";
        if (glsl == "inversesqrt") return "rsqrt";
        return glsl;
    }
    if (!is_wgsl(config)) return glsl;
    if (glsl == "dFdx") return "dpdx";
    if (glsl == "dFdy") return "dpdy";
    if (glsl == "inversesqrt") return "inverseSqrt";
    return glsl;
}

// A float vector's bits as unsigned integers and back (`type` the result's GLSL type): GLSL's
// floatBitsToUint / uintBitsToFloat, WGSL's bitcast.
constexpr Text float_bits(const Config& config, Text uint_type, Text value) {
    if (is_hlsl(config)) return joined("asuint(", value, ")");
    if (!is_wgsl(config)) return joined("floatBitsToUint(", value, ")");
    return joined("bitcast<", wgsl_type_name(uint_type), ">(", value, ")");
}
constexpr Text uint_bits_to_float(const Config& config, Text float_type, Text value) {
    if (is_hlsl(config)) return joined("asfloat(", value, ")");
    if (!is_wgsl(config)) return joined("uintBitsToFloat(", value, ")");
    return joined("bitcast<", wgsl_type_name(float_type), ">(", value, ")");
}

// Built-in variables, under a WGSL or HLSL private global of the entry point (write_entry_point).
constexpr std::string_view clip_position(const Config& config) {
    return binds_samplers_apart(config) ? "penumbra_clipPosition" : "gl_Position";
}
constexpr std::string_view frag_coord(const Config& config) {
    return binds_samplers_apart(config) ? "penumbra_fragCoord" : "gl_FragCoord";
}
constexpr std::string_view frag_depth(const Config& config) {
    return binds_samplers_apart(config) ? "penumbra_fragDepth" : "gl_FragDepth";
}
constexpr std::string_view front_facing(const Config& config) {
    return binds_samplers_apart(config) ? "penumbra_frontFacing" : "gl_FrontFacing";
}
constexpr std::string_view vertex_index(const Config& config) {
    if (binds_samplers_apart(config)) return "penumbra_vertexIndex";
    return config.target == Target::vulkan ? "gl_VertexIndex" : "gl_VertexID";
}

// The sampler WGSL pairs with a texture: the GLSL sampler's name and this suffix.
constexpr Text sampler_of(std::string_view texture) { return joined(texture, "_sampler"); }

// Texture reads. GLSL combines texture and sampler in one name; WGSL and HLSL bind them apart (HLSL's
// reads are the texture's methods).
// A depth comparison at level 0 (the hardware filters the 2x2 comparisons): `uv`, `depth` scalars.
constexpr Text sample_compare(const Config& config, Text texture, Text uv, Text depth) {
    if (is_hlsl(config))
        return joined(texture, ".SampleCmpLevelZero(", sampler_of(texture), ", ", uv, ", ", depth, ")");
    if (!is_wgsl(config)) return joined("textureLod(", texture, ", vec3(", uv, ", ", depth, "), 0.0)");
    return joined("textureSampleCompareLevel(", texture, ", ", sampler_of(texture), ", ", uv, ", ", depth, ")");
}
// The stored depth of a depth texture at level 0, unfiltered by comparison.
constexpr Text sample_depth(const Config& config, Text texture, Text uv) {
    if (is_hlsl(config)) return joined(texture, ".SampleLevel(", sampler_of(texture), ", ", uv, ", 0.0)");
    if (!is_wgsl(config)) return joined("textureLod(", texture, ", ", uv, ", 0.0).r");
    return joined("textureSampleLevel(", texture, ", ", sampler_of(texture), ", ", uv, ", 0)");
}
// One texel of a depth texture (its depth).
constexpr Text fetch_depth(const Config& config, Text texture, Text texel) {
    if (is_hlsl(config)) return joined(texture, ".Load(int3(", texel, ", 0))");
    if (!is_wgsl(config)) return joined("texelFetch(", texture, ", ", texel, ", 0).r");
    return joined("textureLoad(", texture, ", ", texel, ", 0)");
}
// One texel of layer `layer` of an array texture: GLSL's ivec3 coordinate, WGSL's separate index.
constexpr Text fetch_layer(const Config& config, Text texture, Text texel, Text layer, Text level) {
    if (is_hlsl(config)) return joined(texture, ".Load(int4(", texel, ", ", layer, ", ", level, "))");
    if (!is_wgsl(config)) return joined("texelFetch(", texture, ", ivec3(", texel, ", ", layer, "), ", level, ")");
    return joined("textureLoad(", texture, ", ", texel, ", ", layer, ", ", level, ")");
}
// A filtered read at an explicit level (a float texture).
constexpr Text sample_level(const Config& config, Text texture, Text uv, Text level) {
    if (is_hlsl(config))
        return joined(texture, ".SampleLevel(", sampler_of(texture), ", ", uv, ", ", level, ")");
    if (!is_wgsl(config)) return joined("textureLod(", texture, ", ", uv, ", ", level, ")");
    return joined("textureSampleLevel(", texture, ", ", sampler_of(texture), ", ", uv, ", ", level, ")");
}
// A filtered read of layer `layer` (a float expression holding an integer) of an array texture at an
// explicit level: GLSL's third coordinate, WGSL's integer array index.
constexpr Text sample_layer_level(const Config& config, Text texture, Text uv, Text layer, Text level) {
    if (is_hlsl(config))
        return joined(texture, ".SampleLevel(", sampler_of(texture), ", float3(", uv, ", ", layer, "), ",
                      level, ")");
    if (!is_wgsl(config)) return joined("textureLod(", texture, ", vec3(", uv, ", ", layer, "), ", level, ")");
    return joined("textureSampleLevel(", texture, ", ", sampler_of(texture), ", ", uv, ", i32(", layer, "), ", level, ")");
}
// A filtered read with implicit derivatives (fragment stage, uniform control flow).
constexpr Text sample(const Config& config, Text texture, Text uv) {
    if (is_hlsl(config)) return joined(texture, ".Sample(", sampler_of(texture), ", ", uv, ")");
    if (!is_wgsl(config)) return joined("texture(", texture, ", ", uv, ")");
    return joined("textureSample(", texture, ", ", sampler_of(texture), ", ", uv, ")");
}
// One texel, integer coordinates (HLSL: texelFetch of write_hlsl_names, overloaded on the texture's type).
constexpr Text fetch(const Config& config, Text texture, Text texel, Text level) {
    if (!is_wgsl(config)) return joined("texelFetch(", texture, ", ", texel, ", ", level, ")");
    return joined("textureLoad(", texture, ", ", texel, ", ", level, ")");
}

// A stage input or output: `layout(location = N) in T name;` / a private global the entry point
// wires to @location(N). Outputs of a fragment stage are `out` with their location.
constexpr Text stage_variable(LineWriter& out, const Config& config, std::string_view direction, int location,
                              std::string_view type, std::string_view name, bool glsl_location) {
    if (is_hlsl(config)) { // a fragment stage's outputs become SV_Target (write_hlsl_entry_point)
        EntryVariable v{
            joined("TEXCOORD", format_int(location)), Text(name), Text(hlsl_type_name(type)), {}, location};
        (direction == "in" ? out.entry_inputs : out.entry_outputs).push_back(std::move(v));
        return joined("static ", hlsl_type_name(type), " ", name, ";");
    }
    if (is_wgsl(config)) {
        EntryVariable v{joined("@location(", format_int(location), ")"), Text(name), Text(wgsl_type_name(type)), {}};
        (direction == "in" ? out.entry_inputs : out.entry_outputs).push_back(std::move(v));
        return joined("var<private> ", name, ": ", wgsl_type_name(type), ";");
    }
    if (glsl_location) return joined("layout(location = ", format_int(location), ") ", direction, " ", type, " ", name, ";");
    return joined(direction, " ", type, " ", name, ";");
}

// A built-in the stage reads or writes, declared once where the module needs it: the private global
// of the WGSL entry point (nothing on GLSL, whose built-ins are predeclared). `wire_type` is WGSL's
// type of the built-in when the global's differs (vertex_index is u32, the GLSL-shaped code wants i32).
constexpr void declare_builtin(LineWriter& out, const Config& config, bool input, std::string_view builtin_name,
                               std::string_view type, std::string_view name, std::string_view wire_type = {}) {
    if (is_hlsl(config)) { // WGSL's built-in names to HLSL's system values
        constexpr std::pair<std::string_view, std::string_view> semantics[] = {
            {"position", "SV_Position"},
            {"frag_depth", "SV_Depth"},
            {"front_facing", "SV_IsFrontFace"},
            {"vertex_index", "SV_VertexID"}};
        std::string_view semantic = builtin_name;
        for (const auto& [from, to] : semantics)
            if (from == builtin_name) semantic = to;
        const std::string_view wire = wire_type == "u32" ? "uint" : wire_type == "i32" ? "int" : wire_type;
        EntryVariable v{Text(semantic), Text(name), Text(hlsl_type_name(type)), Text(wire)};
        (input ? out.entry_inputs : out.entry_outputs).push_back(std::move(v));
        out.line("static ", hlsl_type_name(type), " ", name, ";");
        return;
    }
    if (!is_wgsl(config)) return;
    EntryVariable v{joined("@builtin(", builtin_name, ")"), Text(name), Text(wgsl_type_name(type)), Text(wire_type)};
    (input ? out.entry_inputs : out.entry_outputs).push_back(std::move(v));
    out.line("var<private> ", name, ": ", wgsl_type_name(type), ";");
}

// HLSL: the entry point `main`, as WGSL's: each input and output with its semantic and (for Vulkan's
// SPIR-V) its location; a vertex stage's position flipped in y, since Direct3D's framebuffer rows run
// top down (as WebGPU's: the emitters flip where WGSL's do, and a Vulkan build inverts y back, as
// glslang's --invert-y and DXC's -fvk-invert-y do).
constexpr void write_hlsl_entry_point(LineWriter& out, Stage stage) {
    out.blank();
    out.chunk("entry_point");
    out.comment("entry point: the inputs into the globals above, then penumbra_main(), then the outputs");
    auto declared = [stage](const EntryVariable& v, std::string_view suffix) {
        const Text location =
            choose(v.location >= 0, joined("[[vk::location(", format_int(v.location), ")]] "), Text());
        const std::string_view type = v.wire_type.empty() ? v.type.view() : v.wire_type.view();
        const bool target = stage == Stage::fragment && suffix.empty() && v.location >= 0; // an output
        return joined(location, type, " ", v.name, suffix, " : ",
                      choose(target, joined("SV_Target", format_int(v.location)), Text(v.attribute)));
    };
    const bool outputs = !out.entry_outputs.empty();
    if (outputs) {
        out.line("struct PenumbraStageOutput");
        out.line("{");
        for (const EntryVariable& v : out.entry_outputs) out.line(declared(v, ""), ";");
        out.line("};");
        out.blank();
    }
    Text head(outputs ? "PenumbraStageOutput main(" : "void main(");
    bool first = true;
    for (const EntryVariable& v : out.entry_inputs) {
        if (!first) head += ", ";
        first = false;
        head += declared(v, "In");
    }
    head += ")";
    out.line(head);
    out.line("{");
    for (const EntryVariable& v : out.entry_inputs)
        out.line(v.name, " = ",
                 choose(v.wire_type.empty(), joined(v.name, "In"), joined(v.type, "(", v.name, "In)")), ";");
    out.line("penumbra_main();");
    if (outputs) {
        out.line("PenumbraStageOutput output;");
        for (const EntryVariable& v : out.entry_outputs) out.line("output.", v.name, " = ", v.name, ";");
        out.line("return output;");
    }
    out.line("}");
}

// WGSL: the entry point `main` of the stage, after penumbra_main(): the inputs copied into their
// globals, every uniform block loaded, the body run, the outputs returned.
constexpr void write_entry_point(LineWriter& out, const Config& config, Stage stage) {
    if (is_hlsl(config)) return write_hlsl_entry_point(out, stage);
    if (!is_wgsl(config)) return;
    out.blank();
    out.chunk("entry_point");
    out.comment("entry point: the inputs into the globals above, the uniform values loaded, then penumbra_main()");
    const bool outputs = !out.entry_outputs.empty();
    if (outputs) {
        out.line("struct PenumbraStageOutput {");
        for (const EntryVariable& v : out.entry_outputs) out.line(v.attribute, " ", v.name, ": ", v.type, ",");
        out.line("}");
        out.blank();
    }
    out.line(stage == Stage::vertex ? "@vertex" : "@fragment");
    Text head("fn main(");
    bool first = true;
    for (const EntryVariable& v : out.entry_inputs) {
        if (!first) head += ", ";
        first = false;
        head += joined(v.attribute, " ", v.name, "In: ", v.wire_type.empty() ? v.type.view() : v.wire_type.view());
    }
    head += ")";
    if (outputs) head += " -> PenumbraStageOutput";
    out.line(head);
    out.line("{");
    for (const EntryVariable& v : out.entry_inputs)
        out.line(v.name, " = ", choose(v.wire_type.empty(), joined(v.name, "In"), joined(v.type, "(", v.name, "In)")), ";");
    for (const Text& call : out.entry_calls) out.line(call, "();");
    out.line("penumbra_main();");
    if (outputs) {
        Text result("return PenumbraStageOutput(");
        for (std::size_t i = 0; i < out.entry_outputs.size(); ++i)
            result += joined(i == 0 ? "" : ", ", out.entry_outputs[i].name);
        out.line(result, ");");
    }
    out.line("}");
}

// HLSL: GLSL's names that the shared expressions use, as HLSL functions and macros (the top of
// this file). Guarded, so that a snippet included beside another Penumbra file declares them once.
constexpr void write_hlsl_names(LineWriter& out, const Config& config) {
    if (!is_hlsl(config)) return;
    out.chunk("hlsl_names");
    out.block(R"(// GLSL's names for HLSL's: the expressions Penumbra writes for GLSL, WGSL and HLSL alike
#ifndef PENUMBRA_HLSL_NAMES
#define PENUMBRA_HLSL_NAMES
#define mix lerp
#define fract frac
float2 vec2(float x) { return float2(x, x); }
float2 vec2(float x, float y) { return float2(x, y); }
float2 vec2(float2 v) { return v; }
float3 vec3(float x) { return float3(x, x, x); }
float3 vec3(float x, float y, float z) { return float3(x, y, z); }
float3 vec3(float2 xy, float z) { return float3(xy, z); }
float3 vec3(float x, float2 yz) { return float3(x, yz); }
float3 vec3(float3 v) { return v; }
float3 vec3(float4 v) { return v.xyz; }
float4 vec4(float x) { return float4(x, x, x, x); }
float4 vec4(float x, float y, float z, float w) { return float4(x, y, z, w); }
float4 vec4(float3 xyz, float w) { return float4(xyz, w); }
float4 vec4(float2 xy, float z, float w) { return float4(xy, z, w); }
float4 vec4(float2 xy, float2 zw) { return float4(xy, zw); }
float4 vec4(float x, float3 yzw) { return float4(x, yzw); }
float4 vec4(float4 v) { return v; }
float2x2 mat2(float a, float b, float c, float d) { return float2x2(a, c, b, d); } // GLSL fills columns
int2 ivec2(int x) { return int2(x, x); }
int2 ivec2(int x, int y) { return int2(x, y); }
int2 ivec2(float2 v) { return int2(v); }
int2 ivec2(int2 v) { return v; }
int3 ivec3(int x, int y, int z) { return int3(x, y, z); }
int3 ivec3(int2 xy, int z) { return int3(xy, z); }
int3 ivec3(float3 v) { return int3(v); }
uint2 uvec2(uint x) { return uint2(x, x); }
uint2 uvec2(uint x, uint y) { return uint2(x, y); }
uint4 uvec4(uint x) { return uint4(x, x, x, x); }
uint4 uvec4(uint x, uint y, uint z, uint w) { return uint4(x, y, z, w); }
uint4 uvec4(float4 v) { return uint4(v); }
float4 texelFetch(Texture2D<float4> t, int2 texel, int level) { return t.Load(int3(texel, level)); }
float4 texelFetch(Texture2DArray<float4> t, int3 texel, int level) { return t.Load(int4(texel, level)); }
float4 texelFetch(Texture3D<float4> t, int3 texel, int level) { return t.Load(int4(texel, level)); }
uint4 texelFetch(Texture2D<uint4> t, int2 texel, int level) { return t.Load(int3(texel, level)); }
int2 textureSize(Texture2D<float4> t, int level) { uint w, h, levels; t.GetDimensions(level, w, h, levels); return int2(w, h); }
#endif
)");
    out.blank();
}

// The name a file of `config` is written under: the GLSL name, or for WGSL that name with `.wgsl`
// in place of `.glsl` or after the stage's extension (penumbra_deferred.frag.wgsl).
constexpr Text file_name(const Config& config, std::string_view glsl_name) {
    if (!binds_samplers_apart(config)) return Text(glsl_name);
    if (glsl_name.ends_with(".glsl")) glsl_name.remove_suffix(5);
    return joined(glsl_name, is_hlsl(config) ? ".hlsl" : ".wgsl");
}

} // namespace penumbra::detail
