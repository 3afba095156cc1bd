// penumbra/layout.hpp — everything an engine must allocate and run for a configuration:
// textures, programs with their parameters and bindings, and the passes in order.
//
//   penumbra::Layout layout = penumbra::describe_layout(config);
//   std::string json = penumbra::to_json(layout); // the same, as layout.json
//
// layout_version 3; the JSON schema is docs/layout.schema.json and README.md ("Using it from an
// engine") walks through it. Run time only (it is data for an engine, not text for a compiler).
// The structs (TextureDesc, ProgramDesc, PassDesc, Layout, …) and the builder are in
// detail/layout_builder.hpp; each technique's programs, textures and passes in its folder,
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

#include "detail/layout_builder.hpp"
#include "detail/techniques.hpp"
#include "detail/vertex_inputs.hpp"
#include "validate.hpp"

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
    layout.technique = std::string(to_string(config.technique));

    // Programs with their parameters, in pass order.
    for (const ProgramPlan& plan : technique.programs(config)) {
        ProgramDesc program{std::string(plan.name), {}, {}, describe_params(config, technique.param_groups(config, plan.name)), {}};
        for (const ShaderFileSpec& file : plan.stages) {
            program.files.emplace_back(file.name);
            program.stages.push_back(file.stage);
        }
        if (!plan.stages.empty()) program.vertex_inputs = vertex_inputs(plan.stages.front(), config);
        layout.programs.push_back(std::move(program));
    }
    // The technique's textures and passes: shadow phase, then the screen phase over the caller's
    // G-buffer at the output size.
    LayoutBuilder build{layout, border_wrap(config)};
    technique.describe_layout(build, config);

    // Example phase: the engine draws its scene with shading_example (or its own shader including
    // penumbra_visibility.glsl, binding the same storage samplers) into its own framebuffer.
    std::vector<BindingDesc> example_inputs;
    for (const ParamDesc& p : build.params_of("shading_example"))
        if (p.binding >= 0) example_inputs.push_back({p.name, p.texture, p.binding});
    RenderState depth_tested;
    depth_tested.depth_test = depth_tested.depth_write = true;
    depth_tested.clear_color = std::array<float, 4>{0.0f, 0.0f, 0.0f, 1.0f};
    depth_tested.clear_depth = 1.0f;
    build.pass("shading_example", "draw_scene", "shading_example", example_inputs, {}, {}, 0, 0, depth_tested, "example");

    finish_sampling(layout);

    for (const ShaderFileSpec& file : shader_files(config)) layout.files.emplace_back(file.name);
    layout.files.emplace_back("layout.json");
    // The configuration is implied everywhere: a new one is a new layout.
    bool has_shadow = false;
    for (const PassDesc& p : layout.passes) has_shadow = has_shadow || p.phase == "shadow";
    // alpha_test: the casters' materials (alpha textures, cutoffs) decide the shadow phase too
    if (has_shadow && config.alpha_test) layout.phase_inputs.push_back({"shadow", {"light", "geometry", "materials"}});
    else if (has_shadow) layout.phase_inputs.push_back({"shadow", {"light", "geometry"}});
    layout.phase_inputs.push_back({"screen", build.screen_inputs});
    layout.phase_inputs.push_back({"example", {"light", "geometry", "camera"}});
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

inline std::string json_state(const RenderState& s) {
    auto b = [](bool v) { return std::string(v ? "true" : "false"); };
    std::string o = "{\"blend\": " + b(s.blend) + ", \"blend_equation\": " + json_string(s.blend_equation) +
                    ", \"blend_src\": " + json_string(s.blend_src) + ", \"blend_dst\": " + json_string(s.blend_dst) +
                    ", \"depth_test\": " + b(s.depth_test) + ", \"depth_func\": " + json_string(s.depth_func) +
                    ", \"depth_write\": " + b(s.depth_write) + ", \"color_mask\": [" + b(s.color_mask[0]) + ", " +
                    b(s.color_mask[1]) + ", " + b(s.color_mask[2]) + ", " + b(s.color_mask[3]) +
                    "], \"cull\": " + json_string(s.cull) + ", \"clear_color\": " +
                    (s.clear_color ? json_floats(*s.clear_color) : "null") +
                    ", \"clear_depth\": " + (s.clear_depth ? json_number(*s.clear_depth) : "null") +
                    ", \"polygon_offset_factor\": " + json_number(s.polygon_offset_factor) +
                    ", \"polygon_offset_units\": " + json_number(s.polygon_offset_units) +
                    ", \"logic_op\": " + json_string(s.logic_op) + "}";
    return o;
}

inline std::string json_sampling(const Sampling& s) {
    std::string o = "{\"min_filter\": " + json_string(s.min_filter) + ", \"mag_filter\": " + json_string(s.mag_filter) +
                    ", \"wrap\": " + json_string(s.wrap);
    if (s.wrap == "CLAMP_TO_BORDER") o += ", \"border_color\": " + json_floats(s.border_color);
    return o + ", \"compare\": " + json_string(s.compare) + "}";
}

} // namespace detail

// layout.json: the layout as JSON (two-space indentation, keys as in the C++ structs).
PENUMBRA_ENTRY_POINT std::string to_json(const Layout& layout) {
    using detail::json_string;
    const Config& c = layout.config;
    std::string o = "{\n";
    auto field = [&](std::string_view indent, std::string_view key, const std::string& value, bool comma = true) {
        o += std::string(indent) + json_string(key) + ": " + value + (comma ? ",\n" : "\n");
    };
    o += "  \"generator\": \"penumbra " + std::string(detail::version_string) + "\",\n";
    field("  ", "layout_version", std::to_string(layout.version));
    field("  ", "technique", json_string(layout.technique));
    o += "  \"config\": {\n";
    field("    ", "technique", json_string(to_string(c.technique)));
    field("    ", "slices", std::to_string(c.slices));
    field("    ", "resolution", std::to_string(c.resolution));
    field("    ", "filter", json_string(to_string(c.filter)));
    field("    ", "fusion", json_string(to_string(c.fusion)));
    field("    ", "packing", json_string(to_string(c.packing)));
    field("    ", "light", json_string(to_string(c.light)));
    field("    ", "leak_fix", c.leak_fix ? "true" : "false");
    field("    ", "self_shadow_fade", c.self_shadow_fade ? "true" : "false");
    field("    ", "tangent_clip", c.tangent_clip ? "true" : "false");
    field("    ", "slice_placement", json_string(to_string(c.slice_placement)));
    field("    ", "level_format", json_string(to_string(c.level_format)));
    field("    ", "level_bound", std::to_string(c.level_bound));
    field("    ", "level_reduction", std::to_string(c.level_reduction));
    // written when not the default (fragment), so that the fragment path's layouts read as before
    if (c.prefilter_stage != PrefilterStage::fragment)
        field("    ", "prefilter_stage", json_string(to_string(c.prefilter_stage)));
    auto real = [](double v) { return detail::format_float(v).str(); };
    field("    ", "tangent_clip_offset", real(c.tangent_clip_offset));
    field("    ", "clip_footprint", c.clip_footprint ? "true" : "false");
    field("    ", "fade_ramp", real(c.fade_ramp));
    field("    ", "target", json_string(to_string(c.target)));
    auto flag = [](bool v) { return std::string(v ? "true" : "false"); };
    field("    ", "shadow_map",
          "{\"resolution\": " + std::to_string(c.shadow_map.resolution) + ", \"constant_bias\": " +
              real(c.shadow_map.constant_bias) + ", \"slope_bias\": " + real(c.shadow_map.slope_bias) +
              ", \"normal_offset\": " + real(c.shadow_map.normal_offset) +
              ", \"receiver_plane_bias\": " + flag(c.shadow_map.receiver_plane_bias) + "}");
    field("    ", "pcf",
          "{\"pattern\": " + json_string(to_string(c.pcf.pattern)) + ", \"grid_size\": " +
              std::to_string(c.pcf.grid_size) + ", \"poisson_taps\": " + std::to_string(c.pcf.poisson_taps) +
              ", \"radius\": " + real(c.pcf.radius) + ", \"rotate\": " + flag(c.pcf.rotate) + "}");
    field("    ", "pcss",
          "{\"blocker_samples\": " + std::to_string(c.pcss.blocker_samples) + ", \"filter_samples\": " +
              std::to_string(c.pcss.filter_samples) + ", \"max_filter_texels\": " +
              std::to_string(c.pcss.max_filter_texels) + ", \"rotate\": " + flag(c.pcss.rotate) + "}");
    field("    ", "oim",
          "{\"resolution\": " + std::to_string(c.oim.resolution) + ", \"intervals\": " +
              std::to_string(c.oim.intervals) + ", \"samples\": " + std::to_string(c.oim.samples) + "}");
    field("    ", "erosion",
          "{\"max_search_radius\": " + std::to_string(c.erosion.max_search_radius) + ", \"edge_threshold\": " +
              real(c.erosion.edge_threshold) + ", \"search_taps\": " + std::to_string(c.erosion.search_taps) +
              ", \"blur_taps\": " + std::to_string(c.erosion.blur_taps) + "}",
          c.alpha_test);
    // written when on, so that the layouts of solid casters read as before
    if (c.alpha_test) field("    ", "alpha_test", "true", false);
    o += "  },\n";
    field("  ", "textures_per_layer", std::to_string(layout.textures_per_layer));
    field("  ", "max_level", std::to_string(layout.max_level));
    field("  ", "max_kernel_texels", std::to_string(layout.technique == "occlusion" ? 1 << layout.max_level : 0));
    o += "  \"textures\": [\n";
    for (std::size_t i = 0; i < layout.textures.size(); ++i) {
        const TextureDesc& t = layout.textures[i];
        o += "    {\"name\": " + json_string(t.name) + ", \"target\": " + json_string(t.target) +
             ", \"internal_format\": " + json_string(t.internal_format) + ", \"width\": " + std::to_string(t.width) +
             ", \"height\": " + std::to_string(t.height) + ", \"depth\": " + std::to_string(t.depth) +
             ", \"mip_levels\": " + std::to_string(t.mip_levels) + ", \"min_filter\": " + json_string(t.min_filter) +
             ", \"mag_filter\": " + json_string(t.mag_filter) + ", \"wrap\": " + json_string(t.wrap);
        if (t.wrap == "CLAMP_TO_BORDER") o += ", \"border_color\": " + detail::json_floats(t.border_color);
        o += ", \"size\": " + json_string(t.size) + ", \"source\": " + json_string(t.source) +
             ", \"initial\": " + json_string(t.initial) + ", \"purpose\": " + json_string(t.purpose) + "}" +
             (i + 1 < layout.textures.size() ? ",\n" : "\n");
    }
    o += "  ],\n  \"programs\": [\n";
    for (std::size_t i = 0; i < layout.programs.size(); ++i) {
        const ProgramDesc& p = layout.programs[i];
        o += "    {\"name\": " + json_string(p.name) + ", \"files\": [";
        for (std::size_t f = 0; f < p.files.size(); ++f) o += (f ? ", " : "") + json_string(p.files[f]);
        o += "], \"stages\": [";
        for (std::size_t f = 0; f < p.stages.size(); ++f) o += (f ? ", " : "") + json_string(stage_name(p.stages[f]));
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
            if (!d.source.empty()) o += ", \"source\": " + json_string(d.source) + ", \"compute\": " + json_string(d.compute);
            if (d.binding >= 0) o += ", \"binding\": " + std::to_string(d.binding);
            if (d.binding >= 0 && d.source != "draw") // a draw's sampler: the caller's texture and sampler
                o += ", \"texture\": " + json_string(d.texture) + ", \"sampling\": " + detail::json_sampling(d.sampling);
            if (d.offset >= 0)
                o += ", \"block\": " + json_string(d.block) + ", \"block_binding\": " + std::to_string(d.block_binding) +
                     ", \"offset\": " + std::to_string(d.offset);
            if (d.set >= 0) o += ", \"set\": " + std::to_string(d.set);
            o += std::string("}") + (u + 1 < p.parameters.size() ? ",\n" : "\n");
        }
        o += std::string("    ]}") + (i + 1 < layout.programs.size() ? ",\n" : "\n");
    }
    o += "  ],\n  \"passes\": [\n";
    for (std::size_t i = 0; i < layout.passes.size(); ++i) {
        const PassDesc& p = layout.passes[i];
        o += "    {\"name\": " + json_string(p.name) + ", \"phase\": " + json_string(p.phase) +
             ", \"action\": " + json_string(p.action) + ", \"program\": " + json_string(p.program) + ", \"inputs\": [";
        for (std::size_t b = 0; b < p.inputs.size(); ++b)
            o += (b ? ", " : "") + std::string("{\"sampler\": ") + json_string(p.inputs[b].sampler) +
                 ", \"texture\": " + json_string(p.inputs[b].texture) + ", \"binding\": " +
                 std::to_string(p.inputs[b].binding) + ", \"level\": " + std::to_string(p.inputs[b].level) +
                 ", \"sampling\": " + detail::json_sampling(p.inputs[b].sampling) + "}";
        o += "], \"outputs\": [";
        for (std::size_t a = 0; a < p.outputs.size(); ++a)
            o += (a ? ", " : "") + std::string("{\"texture\": ") + json_string(p.outputs[a].texture) +
                 ", \"kind\": " + json_string(p.outputs[a].kind) + ", \"level\": " + std::to_string(p.outputs[a].level) +
                 ", \"layer\": " + std::to_string(p.outputs[a].layer) + "}";
        o += "], \"int_uniforms\": {";
        for (std::size_t u = 0; u < p.int_uniforms.size(); ++u)
            o += (u ? ", " : "") + json_string(p.int_uniforms[u].first) + ": " + std::to_string(p.int_uniforms[u].second);
        o += "}, \"viewport\": [" + std::to_string(p.viewport_width) + ", " + std::to_string(p.viewport_height) +
             "], \"state\": " + detail::json_state(p.state);
        if (const std::optional<CopyDesc>& c = p.copy)
            o += ", \"copy\": {\"source_level\": " + std::to_string(c->source_level) + ", \"source_layer\": " +
                 std::to_string(c->source_layer) + ", \"target_level\": " + std::to_string(c->target_level) +
                 ", \"target_layer\": " + std::to_string(c->target_layer) + ", \"width\": " + std::to_string(c->width) +
                 ", \"height\": " + std::to_string(c->height) + "}";
        if (const std::optional<MipmapDesc>& m = p.mipmap)
            o += ", \"mipmap\": {\"base_level\": " + std::to_string(m->base_level) + ", \"levels\": " +
                 std::to_string(m->levels) + ", \"downsample\": " + json_string(m->downsample) + "}";
        if (const std::optional<DispatchDesc>& d = p.dispatch) {
            auto triple = [](const std::array<int, 3>& v) {
                return "[" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) + "]";
            };
            o += ", \"dispatch\": {\"groups\": " + triple(d->groups) + ", \"local_size\": " + triple(d->local_size) +
                 ", \"memory_barrier\": [";
            for (std::size_t b = 0; b < d->memory_barrier.size(); ++b) o += (b ? ", " : "") + json_string(d->memory_barrier[b]);
            o += "]}, \"image_outputs\": [";
            for (std::size_t im = 0; im < p.image_outputs.size(); ++im) {
                const ImageBindingDesc& img = p.image_outputs[im];
                o += (im ? ", " : "") + std::string("{\"image\": ") + json_string(img.image) + ", \"texture\": " +
                     json_string(img.texture) + ", \"level\": " + std::to_string(img.level) + ", \"layer\": " +
                     std::to_string(img.layer) + ", \"unit\": " + std::to_string(img.unit) + ", \"format\": " +
                     json_string(img.format) + ", \"access\": " + json_string(img.access) + "}";
            }
            o += "]";
        }
        o += std::string("}") + (i + 1 < layout.passes.size() ? ",\n" : "\n");
    }
    o += "  ],\n";
    field("  ", "result", json_string(layout.result));
    o += "  \"phase_inputs\": {";
    for (std::size_t p = 0; p < layout.phase_inputs.size(); ++p) {
        o += (p ? ", " : "") + json_string(layout.phase_inputs[p].first) + ": [";
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
             json_string(at.channel) + "}";
    }
    o += "],\n";
    o += "  \"files\": [";
    for (std::size_t f = 0; f < layout.files.size(); ++f) o += (f ? ", " : "") + json_string(layout.files[f]);
    o += "]\n}\n";
    return o;
}

} // namespace penumbra

#endif // PENUMBRA_DECLARATIONS_ONLY
