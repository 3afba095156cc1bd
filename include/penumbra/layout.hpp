// penumbra/layout.hpp — everything an engine must allocate and run for a configuration:
// textures, programs with their parameters and bindings, and the passes in order.
//
//   penumbra::Layout layout = penumbra::describe_layout(config);
//   std::string json = penumbra::to_json(layout); // the same, as layout.json
//
// layout_version 3; the JSON schema is docs/layout.schema.json and docs/engine-integration.md ("Using it from an
// engine") walks through it. Run time only (it is data for an engine, not text for a compiler).
// The structs (TextureDesc, ProgramDesc, PassDesc, Layout, …) and the enums of their words are in
// penumbra/layout_types.hpp, the texture formats in penumbra/formats.hpp; the builder is
// detail/layout_builder.hpp, each technique's programs, textures and passes in its folder,
// detail/<technique>/layout.hpp.
#pragma once

#include "detail/api.hpp"
#include "layout_types.hpp"

#if PENUMBRA_DECLARATIONS_ONLY
// PENUMBRA_SEPARATE_IMPLEMENTATION: defined in the PENUMBRA_IMPLEMENTATION translation unit
// (detail/api.hpp).
namespace penumbra {
Layout describe_layout(const Config& config);
std::string to_json(const Layout& layout);
} // namespace penumbra
#else

#include "config_fields.hpp"
#include "detail/layout_builder.hpp"
#include "detail/techniques.hpp"
#include "detail/vertex_inputs.hpp"
#include "validate.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

// The layout of a valid configuration. Precondition: is_valid(config).
PENUMBRA_ENTRY_POINT Layout describe_layout(const Config& config) {
    using namespace detail;
    const TechniqueDescriptor technique = technique_descriptor(config.technique);
    Layout layout;
    layout.config = config;

    // Programs with their parameters, in pass order.
    for (const ProgramPlan& plan : technique.programs(config)) {
        ProgramDesc program{std::string(plan.name), {}, {}, describe_params(config, technique.param_groups(config, plan.name)), {}};
        for (const ShaderFileSpec& file : plan.stages) {
            program.files.push_back(file_name(config, file.name).str());
            program.stages.push_back(file.stage);
        }
        if (!plan.stages.empty()) program.vertex_inputs = vertex_inputs(plan.stages.front(), config);
        layout.programs.push_back(std::move(program));
    }
    // The technique's textures and passes: shadow phase, then the screen phase over the caller's
    // G-buffer at the output size.
    LayoutBuilder build{layout};
    technique.describe_layout(build, config);

    // Example phase: the engine draws its scene with shading_example (or its own shader including
    // penumbra_visibility.glsl, binding the same storage samplers) into its own framebuffer.
    build.pass({.name = "shading_example",
                .action = PassAction::draw_scene,
                .program = "shading_example",
                .inputs = build.own_inputs("shading_example"),
                .state = {.depth_test = true,
                          .depth_write = true,
                          .clear_color = std::array<float, 4>{0.0f, 0.0f, 0.0f, 1.0f},
                          .clear_depth = 1.0f},
                .phase = Phase::example});

    finish_sampling(layout);

    for (const ShaderFileSpec& file : shader_files(config)) layout.files.push_back(file_name(config, file.name).str());
    layout.files.emplace_back("layout.json");
    // The configuration is implied everywhere: a new one is a new layout.
    bool has_shadow = false;
    for (const PassDesc& p : layout.passes) has_shadow = has_shadow || p.phase == Phase::shadow;
    // alpha_test: the casters' materials (alpha textures, cutoffs) decide the shadow phase too
    if (has_shadow && config.alpha_test) layout.phase_inputs.push_back({Phase::shadow, {"light", "geometry", "materials"}});
    else if (has_shadow) layout.phase_inputs.push_back({Phase::shadow, {"light", "geometry"}});
    layout.phase_inputs.push_back({Phase::screen, build.screen_inputs});
    layout.phase_inputs.push_back({Phase::example, {"light", "geometry", "camera"}});
    return layout;
}

namespace detail {

inline std::string json_string(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) < 0x20) {
            out += ' ';
            continue;
        }
        out += c;
    }
    return out + "\"";
}

inline std::string json_number(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", static_cast<double>(value));
    return text;
}

inline std::string json_floats(const std::array<float, 4>& values) {
    std::string out = "[";
    for (std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + json_number(values[i]);
    return out + "]";
}

// A layout enum as a JSON string: its name (EnumNames), the word layout.json uses.
template <class Enum> std::string json_name(Enum value) { return json_string(to_string(value)); }

inline std::string json_state(const RenderState& s) {
    auto b = [](bool v) { return std::string(v ? "true" : "false"); };
    std::string o = "{\"blend\": " + b(s.blend) + ", \"blend_equation\": " + json_name(s.blend_equation) +
                    ", \"blend_src\": " + json_name(s.blend_src) + ", \"blend_dst\": " + json_name(s.blend_dst) +
                    ", \"depth_test\": " + b(s.depth_test) + ", \"depth_func\": " + json_name(s.depth_func) +
                    ", \"depth_write\": " + b(s.depth_write) + ", \"color_mask\": [" + b(s.color_mask[0]) + ", " +
                    b(s.color_mask[1]) + ", " + b(s.color_mask[2]) + ", " + b(s.color_mask[3]) +
                    "], \"cull\": " + json_name(s.cull) + ", \"clear_color\": " +
                    (s.clear_color ? json_floats(*s.clear_color) : "null") +
                    ", \"clear_depth\": " + (s.clear_depth ? json_number(*s.clear_depth) : "null") +
                    ", \"polygon_offset_factor\": " + json_number(s.polygon_offset_factor) +
                    ", \"polygon_offset_units\": " + json_number(s.polygon_offset_units) +
                    ", \"logic_op\": " + json_name(s.logic_op) + "}";
    return o;
}

inline std::string json_sampling(const Sampling& s) {
    std::string o = "{\"min_filter\": " + json_name(s.min_filter) + ", \"mag_filter\": " + json_name(s.mag_filter) +
                    ", \"wrap\": " + json_name(s.wrap);
    if (s.wrap == Wrap::clamp_to_border) o += ", \"border_color\": " + json_floats(s.border_color);
    return o + ", \"compare\": " + (s.compare ? json_name(*s.compare) : json_string("")) + "}";
}

// WGSL: a texture's WebGPU format and usages (what its passes, the caller and the readback do with it).
inline std::string json_webgpu_texture(const Layout& layout, const TextureDesc& t) {
    bool attachment = false, copied_from = false, copied_to = false;
    for (const PassDesc& pass : layout.passes) {
        const bool copy = pass.action == PassAction::copy;
        for (const AttachmentDesc& out : pass.outputs)
            if (out.texture == t.name) (copy ? copied_to : attachment) = true;
        for (const BindingDesc& in : pass.inputs) copied_from = copied_from || (copy && in.texture == t.name);
    }
    std::string usage = "[\"TEXTURE_BINDING\"";
    if (attachment) usage += ", \"RENDER_ATTACHMENT\"";
    // uploaded by the caller or the bake, or a copy pass's target
    if (t.source != TextureSource::passes || copied_to) usage += ", \"COPY_DST\"";
    // read back (the result; and what the passes write, so a runner can check intermediates), or a copy's source
    if (t.name == layout.result || copied_from || attachment) usage += ", \"COPY_SRC\"";
    return "{\"format\": " + json_string(format_info(t.format).webgpu) + ", \"usage\": " + usage + "]}";
}

// WGSL: how a sampler parameter binds: its texture's WGSL and WebGPU types, its sampler's binding and
// kind (comparison for depth comparisons; non-filtering for nearest reads and unfilterable formats).
// A parameter without a texture of its own (a ping-pong source) takes the format of what the program's
// passes bind to it (they bind textures of one format).
inline std::string json_wgsl_binding(const Layout& layout, const ProgramDesc& program, const ParamDesc& d) {
    const TextureDesc* texture = find_texture(layout, d.texture);
    for (const PassDesc& pass : layout.passes) {
        if (texture || pass.program != program.name) continue;
        for (const BindingDesc& in : pass.inputs)
            if (in.sampler == d.name) texture = find_texture(layout, in.texture);
    }
    std::string sample_type = texture ? std::string(webgpu_sample_type(texture->format)) : "float";
    if (d.texture_type == "texture_depth_2d") sample_type = "depth";
    else if (sample_type == "depth") sample_type = "unfilterable-float"; // a depth texture read as texture_2d<f32>
    std::string o = ", \"texture_type\": " + json_string(d.texture_type) + ", \"sample_type\": " + json_string(sample_type) +
                    ", \"sampler_binding\": " + std::to_string(d.sampler_binding);
    if (d.sampler_binding < 0) return o;
    const Sampling s = d.sampling.value_or(Sampling{});
    std::string_view kind = "filtering";
    if (s.compare) kind = "comparison";
    else if (sample_type != "float" || (s.min_filter == TextureFilter::nearest && s.mag_filter == TextureFilter::nearest))
        kind = "non-filtering";
    return o + ", \"sampler_type\": " + json_string(kind);
}

// HLSL: the registers of a parameter for a Direct3D 12 root signature, beside the binding a Vulkan
// build of the same HLSL keeps (glslang and DXC map b#, t#, s# to binding #, space to set).
inline std::string json_hlsl_registers(const ParamDesc& d) {
    const std::string space = ", \"space\": " + std::to_string(d.set) + "}";
    if (d.offset >= 0)
        return ", \"registers\": {\"cbuffer\": \"b" + std::to_string(d.block_binding) + "\"" + space;
    if (d.binding < 0) return {};
    std::string o = ", \"texture_type\": " + json_string(d.texture_type) +
                    ", \"sampler_binding\": " + std::to_string(d.sampler_binding) +
                    ", \"registers\": {\"texture\": \"t" + std::to_string(d.binding) + "\"";
    if (d.sampler_binding >= 0) {
        const bool compare = d.type.ends_with("Shadow"); // as write_hlsl_params declares it
        o += ", \"sampler\": \"s" + std::to_string(d.sampler_binding) +
             "\", \"sampler_type\": " + json_string(compare ? "SamplerComparisonState" : "SamplerState");
    }
    return o + space;
}

// MSL: the Metal argument-table indices of a parameter (emit_msl, penumbra/msl.hpp, sets them).
inline std::string json_msl_indices(const ParamDesc& d) {
    if (d.msl_buffer >= 0) return ", \"msl\": {\"buffer\": " + std::to_string(d.msl_buffer) + "}";
    if (d.msl_texture < 0) return {};
    std::string o = ", \"msl\": {\"texture\": " + std::to_string(d.msl_texture);
    if (d.msl_sampler >= 0) o += ", \"sampler\": " + std::to_string(d.msl_sampler);
    return o + "}";
}

} // namespace detail

// MSL: the function a .metal file of target msl defines, named after its file
// ("penumbra_slicing.vert.metal" defines penumbra_slicing_vert), so that every file of an emission
// links into one Metal library without two functions of one name.
inline std::string msl_function_name(std::string_view file_name) {
    std::string name(file_name.substr(0, file_name.rfind(".metal")));
    for (char& c : name)
        if (c == '.') c = '_';
    return name;
}

// MSL: the first buffer index no program's parameters use, where a Metal engine binds the vertex
// buffers of the programs that draw its geometry ([[stage_in]] attributes).
inline int msl_first_free_buffer(const Layout& layout) {
    int first_free = 0;
    for (const ProgramDesc& program : layout.programs)
        for (const ParamDesc& d : program.parameters) first_free = std::max(first_free, d.msl_buffer + 1);
    return first_free;
}

// layout.json: the layout as JSON (two-space indentation, keys as in the C++ structs).
PENUMBRA_ENTRY_POINT std::string to_json(const Layout& layout) {
    using detail::json_name;
    using detail::json_string;
    const Config& c = layout.config;
    std::string o = "{\n";
    auto field = [&](std::string_view indent, std::string_view key, const std::string& value, bool comma = true) {
        o += std::string(indent) + json_string(key) + ": " + value + (comma ? ",\n" : "\n");
    };
    o += "  \"generator\": \"penumbra " + std::string(detail::version_string) + "\",\n";
    const bool wgsl = c.target == Target::wgsl;
    field("  ", "layout_version", std::to_string(layout.version));
    field("  ", "technique", json_name(c.technique));
    o += "  \"config\": " + config_to_json(layout.config, "  ") + ",\n"; // penumbra/config_fields.hpp
    field("  ", "textures_per_layer", std::to_string(layout.textures_per_layer));
    field("  ", "max_level", std::to_string(layout.max_level));
    field("  ", "max_kernel_texels", std::to_string(c.technique == Technique::occlusion ? 1 << layout.max_level : 0));
    o += "  \"textures\": [\n";
    for (std::size_t i = 0; i < layout.textures.size(); ++i) {
        const TextureDesc& t = layout.textures[i];
        o += "    {\"name\": " + json_string(t.name) + ", \"target\": " + json_name(t.target) +
             ", \"internal_format\": " + json_name(t.format) + ", \"width\": " + std::to_string(t.width) +
             ", \"height\": " + std::to_string(t.height) + ", \"depth\": " + std::to_string(t.depth) +
             ", \"mip_levels\": " + std::to_string(t.mip_levels) + ", \"min_filter\": " + json_name(t.min_filter) +
             ", \"mag_filter\": " + json_name(t.mag_filter) + ", \"wrap\": " + json_name(t.wrap);
        if (t.wrap == Wrap::clamp_to_border) o += ", \"border_color\": " + detail::json_floats(t.border_color);
        if (wgsl) o += ", \"webgpu\": " + detail::json_webgpu_texture(layout, t);
        o += ", \"size\": " + json_name(t.size) + ", \"source\": " + json_name(t.source) +
             ", \"initial\": " + json_name(initial_contents(t)) + ", \"purpose\": " + json_string(t.purpose) + "}" +
             (i + 1 < layout.textures.size() ? ",\n" : "\n");
    }
    o += "  ],\n  \"programs\": [\n";
    for (std::size_t i = 0; i < layout.programs.size(); ++i) {
        const ProgramDesc& p = layout.programs[i];
        o += "    {\"name\": " + json_string(p.name) + ", \"files\": [";
        for (std::size_t f = 0; f < p.files.size(); ++f) o += (f ? ", " : "") + json_string(p.files[f]);
        o += "], \"stages\": [";
        for (std::size_t f = 0; f < p.stages.size(); ++f) o += (f ? ", " : "") + json_string(stage_name(p.stages[f]));
        if (c.target == Target::msl) {
            o += "], \"msl_functions\": [";
            for (std::size_t f = 0; f < p.files.size(); ++f) o += (f ? ", " : "") + json_string(msl_function_name(p.files[f]));
        }
        o += "], \"vertex_inputs\": [";
        for (std::size_t v = 0; v < p.vertex_inputs.size(); ++v) {
            const VertexInputDesc& in = p.vertex_inputs[v];
            o += (v ? ", " : "") + std::string("{\"name\": ") + json_string(in.name) + ", \"location\": " +
                 std::to_string(in.location) + ", \"type\": " + json_string(in.type) + ", \"meaning\": " +
                 json_string(in.meaning) + "}";
        }
        o += "], \"parameters\": [\n";
        for (std::size_t u = 0; u < p.parameters.size(); ++u) {
            const ParamDesc& d = p.parameters[u];
            o += "      {\"name\": " + json_string(d.name) + ", \"type\": " + json_string(d.type) +
                 ", \"meaning\": " + json_string(d.meaning) + ", \"units\": " + json_string(d.units);
            if (d.source)
                o += ", \"source\": " + json_string(to_string(*d.source)) + ", \"compute\": " + json_string(d.compute);
            if (d.binding >= 0) o += ", \"binding\": " + std::to_string(d.binding);
            if (d.binding >= 0 && d.source != UniformSource::draw) // a draw's sampler: the caller's texture and sampler
                o += ", \"texture\": " + json_string(d.texture) + ", \"sampling\": " +
                     detail::json_sampling(d.sampling.value_or(Sampling{}));
            if (d.offset >= 0)
                o += ", \"block\": " + json_string(d.block) + ", \"block_binding\": " + std::to_string(d.block_binding) +
                     ", \"offset\": " + std::to_string(d.offset);
            if (d.set >= 0) o += (wgsl ? ", \"group\": " : ", \"set\": ") + std::to_string(d.set);
            if (wgsl && d.binding >= 0) o += detail::json_wgsl_binding(layout, p, d);
            if (c.target == Target::hlsl) o += detail::json_hlsl_registers(d);
            if (c.target == Target::msl) o += detail::json_msl_indices(d);
            o += std::string("}") + (u + 1 < p.parameters.size() ? ",\n" : "\n");
        }
        o += std::string("    ]}") + (i + 1 < layout.programs.size() ? ",\n" : "\n");
    }
    o += "  ],\n  \"passes\": [\n";
    for (std::size_t i = 0; i < layout.passes.size(); ++i) {
        const PassDesc& p = layout.passes[i];
        o += "    {\"name\": " + json_string(p.name) + ", \"phase\": " + json_name(p.phase) +
             ", \"action\": " + json_name(p.action) + ", \"program\": " + json_string(p.program) + ", \"inputs\": [";
        for (std::size_t b = 0; b < p.inputs.size(); ++b)
            o += (b ? ", " : "") + std::string("{\"sampler\": ") + json_string(p.inputs[b].sampler) +
                 ", \"texture\": " + json_string(p.inputs[b].texture) + ", \"binding\": " +
                 std::to_string(p.inputs[b].binding) + ", \"level\": " + std::to_string(p.inputs[b].level) +
                 ", \"sampling\": " + detail::json_sampling(p.inputs[b].sampling) + "}";
        o += "], \"outputs\": [";
        for (std::size_t a = 0; a < p.outputs.size(); ++a)
            o += (a ? ", " : "") + std::string("{\"texture\": ") + json_string(p.outputs[a].texture) +
                 ", \"kind\": " + json_name(attachment_kind(layout, p.outputs[a])) + ", \"level\": " + std::to_string(p.outputs[a].level) +
                 ", \"layer\": " + std::to_string(p.outputs[a].layer) + "}";
        o += "], \"int_uniforms\": {";
        for (std::size_t u = 0; u < p.int_uniforms.size(); ++u)
            o += (u ? ", " : "") + json_string(p.int_uniforms[u].first) + ": " + std::to_string(p.int_uniforms[u].second);
        o += "}, \"viewport\": [" + std::to_string(p.viewport_width) + ", " + std::to_string(p.viewport_height) +
             "], \"state\": " + detail::json_state(p.state);
        if (p.action == PassAction::copy && !p.inputs.empty() && !p.outputs.empty()) {
            const CopyDesc c = copy_region(p);
            o += ", \"copy\": {\"source_level\": " + std::to_string(c.source_level) + ", \"source_layer\": " +
                 std::to_string(c.source_layer) + ", \"target_level\": " + std::to_string(c.target_level) +
                 ", \"target_layer\": " + std::to_string(c.target_layer) + ", \"width\": " + std::to_string(c.width) +
                 ", \"height\": " + std::to_string(c.height) + "}";
        }
        if (p.action == PassAction::generate_mipmap && !p.outputs.empty()) {
            const MipmapDesc m = mipmap_range(layout, p);
            o += ", \"mipmap\": {\"base_level\": " + std::to_string(m.base_level) + ", \"levels\": " +
                 std::to_string(m.levels) + ", \"downsample\": \"box\"}"; // the only downsample there is
        }
        if (p.action == PassAction::dispatch) {
            const DispatchDesc& d = p.dispatch;
            auto triple = [](const std::array<int, 3>& v) {
                return "[" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) + "]";
            };
            o += ", \"dispatch\": {\"groups\": " + triple(d.groups) + ", \"local_size\": " + triple(d.local_size) +
                 ", \"memory_barrier\": [";
            for (std::size_t b = 0; b < d.memory_barrier.size(); ++b) o += (b ? ", " : "") + json_name(d.memory_barrier[b]);
            o += "]}, \"image_outputs\": [";
            for (std::size_t im = 0; im < d.images.size(); ++im) {
                const ImageBindingDesc& img = d.images[im];
                const TextureDesc* texture = find_texture(layout, img.texture); // the image's format is its texture's
                o += (im ? ", " : "") + std::string("{\"image\": ") + json_string(img.image) + ", \"texture\": " +
                     json_string(img.texture) + ", \"level\": " + std::to_string(img.level) + ", \"layer\": " +
                     std::to_string(img.layer) + ", \"unit\": " + std::to_string(img.unit) + ", \"format\": " +
                     (texture ? json_name(texture->format) : json_string("")) + ", \"access\": " + json_name(img.access) + "}";
            }
            o += "]";
        }
        o += std::string("}") + (i + 1 < layout.passes.size() ? ",\n" : "\n");
    }
    o += "  ],\n";
    field("  ", "result", json_string(layout.result));
    o += "  \"phase_inputs\": {";
    for (std::size_t p = 0; p < layout.phase_inputs.size(); ++p) {
        o += (p ? ", " : "") + json_name(layout.phase_inputs[p].first) + ": [";
        const std::vector<std::string>& inputs = layout.phase_inputs[p].second;
        for (std::size_t i = 0; i < inputs.size(); ++i) o += (i ? ", " : "") + json_string(inputs[i]);
        o += "]";
    }
    o += "},\n";
    o += "  \"slice_map\": [";
    for (std::size_t k = 0; k < layout.slice_map.size(); ++k) {
        const SliceLocation& at = layout.slice_map[k];
        o += (k ? ", " : "") + std::string("{\"slice\": ") + std::to_string(at.slice) + ", \"texture\": " +
             json_string(at.texture) + ", \"layer\": " + std::to_string(at.layer) + ", \"channel\": " +
             json_string(std::string(1, slice_channel(at))) + "}";
    }
    o += "],\n";
    if (c.target == Target::msl)
        o += "  \"msl\": {\"language_version\": \"2.1\", \"flip_vertex_y\": true, \"first_free_buffer\": " +
             std::to_string(msl_first_free_buffer(layout)) + "},\n";
    o += "  \"files\": [";
    for (std::size_t f = 0; f < layout.files.size(); ++f) o += (f ? ", " : "") + json_string(layout.files[f]);
    o += "]\n}\n";
    return o;
}

} // namespace penumbra

#endif // PENUMBRA_DECLARATIONS_ONLY
