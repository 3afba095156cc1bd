// penumbra/layout.hpp — everything an engine must allocate and run for a configuration:
// textures, programs with their parameters and bindings, and the passes in order.
//
//   penumbra::Layout layout = penumbra::describe_layout(config);
//   std::string json = penumbra::to_json(layout); // the same, as layout.json
//
// Run time only (it is data for an engine, not text for a compiler).
#pragma once

#include "detail/artifacts.hpp"
#include "validate.hpp"

#include <string>
#include <utility>
#include <vector>

namespace penumbra {

struct TextureDesc {
    std::string name;
    std::string target;          // "2D", "2D_ARRAY", "3D" (GL_TEXTURE_… / VK_IMAGE_TYPE_…)
    std::string internal_format; // "RGBA8", "RGBA16F", "RGBA32F"
    int width = 0, height = 0;
    int depth = 1;               // layers of a 2D array, depth of a 3D texture, 1 otherwise
    int mip_levels = 1;
    std::string min_filter, mag_filter; // "NEAREST", "LINEAR", "LINEAR_MIPMAP_LINEAR"
    std::string wrap;            // "CLAMP_TO_BORDER" (border 0,0,0,0) or "CLAMP_TO_EDGE"
    std::string purpose;
};

struct ParamDesc {
    std::string name, type, meaning, units;
    int binding = -1;            // sampler: texture unit / Vulkan binding; -1 for plain uniforms
    std::string texture;         // sampler: the texture bound to it when the program runs its usual pass
    std::string block;           // Vulkan: uniform block holding this value
    int block_binding = -1;      // Vulkan: binding of that block
    int offset = -1;             // Vulkan: std140 byte offset in the block
};

struct ProgramDesc {
    std::string name;
    std::vector<std::string> files; // stage files, in pipeline order
    std::vector<ParamDesc> parameters;
};

struct AttachmentDesc {
    std::string texture;
    int level = 0;
    int layer = -1; // layer of an array / depth slice of a 3D texture; -1 for a 2D texture
};

struct BindingDesc {
    std::string sampler; // parameter name in the program
    std::string texture;
    int binding = 0;
};

struct PassDesc {
    std::string name;
    // "draw_scene": draw the caller's geometry with `program`; "fullscreen": draw 3 vertices
    // with `program`; "generate_mipmap": glGenerateMipmap(texture of outputs[0]);
    // "copy": copy inputs[0].texture level 0 into outputs[0] (same size).
    std::string action;
    std::string program;
    std::vector<BindingDesc> inputs;
    std::vector<AttachmentDesc> outputs; // colour attachment i = outputs[i]
    std::vector<std::pair<std::string, int>> int_uniforms;
    int viewport_width = 0, viewport_height = 0; // 0: the caller's (shading passes)
    std::string state;                           // blend / clear / depth state the pass needs
};

struct Layout {
    Config config;
    int textures_per_layer = 0; // T: RGBA occlusion textures, four slices each
    int max_level = 0;          // L = log2(resolution)
    std::vector<TextureDesc> textures;
    std::vector<ProgramDesc> programs;
    std::vector<PassDesc> passes;
    std::vector<std::string> files; // every file an emission writes, layout.json included
};

namespace detail {

constexpr std::string_view level_format(const Config& config) {
    return config.target == Target::essl300 ? "RGBA8" : "RGBA16F"; // ES 3.0 cannot render to half floats
}

inline std::string border_wrap(const Config& config) {
    return limits(config.target).clamp_to_border ? "CLAMP_TO_BORDER" : "CLAMP_TO_EDGE";
}

// The shading programs' own parameters, after penumbraVisibility()'s.
inline std::vector<Param> shading_deferred_params(const Config& config) {
    return config.technique == Technique::oim ? oim_deferred_params() : deferred_params();
}
inline std::vector<Param> shading_fragment_params(const Config& config) {
    return config.technique == Technique::oim ? oim_example_fragment_params() : example_fragment_params();
}
inline std::vector<Param> shading_vertex_params(const Config& config) {
    return config.technique == Technique::oim ? oim_example_vertex_params() : example_vertex_params();
}

inline std::vector<Param> program_params(const Config& config, std::string_view program) {
    if (program == "slicing") return slicing_params();
    if (program == "pack_atlas") return pack_atlas_params();
    if (program == "nbuffer_level" || program == "gaussian_level") return level_params(config);
    if (program == "sat_shift") return sat_shift_params(config);
    if (program == "sat_pass") return sat_pass_params(config);
    if (program == "shadow_depth") return shadow_depth_params();
    std::vector<Param> params = technique_visibility_params(config);
    const std::vector<Param> extra =
        program == "shading_deferred" ? shading_deferred_params(config) : shading_fragment_params(config);
    params.insert(params.end(), extra.begin(), extra.end());
    if (program == "shading_example")
        for (Param& p : shading_vertex_params(config)) params.push_back(std::move(p));
    return params;
}

// Mirrors the declaration order of the emitters: blocks and samplers numbered as they appear.
inline std::vector<ParamDesc> describe_params(const Config& config, std::string_view program) {
    const std::vector<Param> params = program_params(config, program);
    // Group parameters into the same declaration groups the emitters use, so bindings match.
    std::vector<std::pair<std::string_view, std::vector<Param>>> groups;
    if (program == "shading_example" || program == "shading_deferred") {
        groups.push_back({"PenumbraVisibility", technique_visibility_params(config)});
        if (program == "shading_example") {
            groups.push_back({"PenumbraExample", shading_fragment_params(config)});
            groups.push_back({"PenumbraCamera", shading_vertex_params(config)});
        } else {
            groups.push_back({"PenumbraDeferred", shading_deferred_params(config)});
        }
    } else {
        groups.push_back({program == "slicing" ? "PenumbraSlicing" : program == "shadow_depth" ? "PenumbraShadowDepth"
                                                                                            : "PenumbraPass",
                          params});
    }
    std::vector<ParamDesc> out;
    int next_binding = 0;
    for (const auto& [block, group] : groups) {
        const int block_binding = next_binding;
        const std::vector<int> bindings = param_bindings(config, group, next_binding);
        int offset = 0;
        for (std::size_t i = 0; i < group.size(); ++i) {
            const Param& p = group[i];
            ParamDesc desc;
            desc.name = p.name.str();
            desc.type = std::string(p.type);
            desc.meaning = std::string(p.meaning);
            desc.units = std::string(p.units);
            desc.binding = bindings[i];
            desc.texture = p.texture.str();
            if (!is_sampler(p) && is_vulkan(config)) {
                // std140: scalars align to 4, vec2 to 8, vec3/vec4/mat4 to 16
                const int size = p.type == "mat4" ? 64 : p.type == "vec4" ? 16 : p.type == "vec3" ? 12
                                 : p.type == "vec2" ? 8 : 4;
                const int align = size >= 12 ? 16 : size;
                offset = (offset + align - 1) / align * align;
                desc.block = std::string(block);
                desc.block_binding = block_binding;
                desc.offset = offset;
                offset += size;
            }
            out.push_back(std::move(desc));
        }
    }
    return out;
}

inline int binding_of(const std::vector<ParamDesc>& params, std::string_view name) {
    for (const ParamDesc& p : params)
        if (p.name == name) return p.binding;
    return -1;
}

} // namespace detail

namespace detail {

// Shadow map techniques: a depth pass from the light, then shading. PCSS reads the depth twice:
// with comparison (the filter) and as plain depth (the blocker search), from a copy.
inline Layout describe_shadow_map_layout(const Config& config) {
    Layout layout;
    layout.config = config;
    const int R = config.shadow_map.resolution;
    for (const ProgramPlan& plan : program_plan(config)) {
        ProgramDesc program{std::string(plan.name), {}, describe_params(config, plan.name)};
        for (Artifact a : plan.stages) program.files.emplace_back(file_name(a));
        layout.programs.push_back(std::move(program));
    }
    layout.textures.push_back({std::string(shadow_map_texture), "2D", "DEPTH_COMPONENT32F", R, R, 1, 1, "LINEAR",
                               "LINEAR", "CLAMP_TO_EDGE",
                               "shadow map: (z - near) / (far - near) along the light axis, biased; compared LEQUAL"});
    layout.passes.push_back({"shadow_depth", "draw_scene", "shadow_depth", {}, {{std::string(shadow_map_texture), 0, -1}},
                             {}, R, R, "depth attachment, clear depth to 1, depth test LESS, depth write, no culling"});
    if (config.technique == Technique::pcss) {
        layout.textures.push_back({"penumbra_shadowDepth", "2D", "DEPTH_COMPONENT32F", R, R, 1, 1, "NEAREST",
                                   "NEAREST", "CLAMP_TO_EDGE", "copy of the shadow map read without comparison"});
        layout.passes.push_back({"copy_shadow_depth", "copy", "", {{"", std::string(shadow_map_texture), 0}},
                                 {{"penumbra_shadowDepth", 0, -1}}, {}, R, R, ""});
    }
    PassDesc shading{"shading", "draw_scene", "shading_example", {}, {}, {}, 0, 0,
                     "the caller's framebuffer; or run shading_deferred over a G-buffer of world positions"};
    for (const ParamDesc& p : layout.programs[1].parameters)
        if (p.binding >= 0) shading.inputs.push_back({p.name, p.texture, p.binding});
    layout.passes.push_back(std::move(shading));
    for (Artifact a : artifacts(config)) layout.files.emplace_back(file_name(a));
    layout.files.emplace_back("layout.json");
    return layout;
}

// Occlusion interval maps (GPU Gems ch. 13): the rise/fall textures come from an offline bake
// (nearest filtering: the edges must not be blended); shading reads them at the surface's unique
// texture coordinates, in the example pass or over the caller's G-buffer of texture coordinates.
inline Layout describe_oim_layout(const Config& config) {
    Layout layout;
    layout.config = config;
    const int R = config.oim.resolution;
    for (const ProgramPlan& plan : program_plan(config)) {
        ProgramDesc program{std::string(plan.name), {}, describe_params(config, plan.name)};
        for (Artifact a : plan.stages) program.files.emplace_back(file_name(a));
        layout.programs.push_back(std::move(program));
    }
    for (int p = 0; p < oim_pairs(config.oim); ++p)
        for (const bool fall : {false, true}) {
            TextureDesc t;
            t.name = (fall ? oim_fall_name(p) : oim_rise_name(p)).str();
            t.target = "2D";
            t.internal_format = "RGBA16F";
            t.width = t.height = R;
            t.min_filter = t.mag_filter = "NEAREST";
            t.wrap = "CLAMP_TO_EDGE";
            t.purpose = std::string("supplied by the bake: ") + (fall ? "fall" : "rise") + " times of intervals " +
                        std::to_string(4 * p) + " to " + std::to_string(4 * p + 3) +
                        " (path time t; k / samples, exact in 16-bit floats; unused intervals [0, 0])";
            layout.textures.push_back(std::move(t));
        }
    PassDesc shading;
    shading.name = "shading";
    shading.action = "draw_scene";
    shading.program = "shading_example";
    shading.state = "the caller's framebuffer (vertex attribute 2: the bake's texture coordinates); or run "
                    "shading_deferred over a G-buffer of texture coordinates";
    for (const ParamDesc& p : layout.programs[0].parameters)
        if (p.binding >= 0) shading.inputs.push_back({p.name, p.texture, p.binding});
    layout.passes.push_back(std::move(shading));
    for (Artifact a : artifacts(config)) layout.files.emplace_back(file_name(a));
    layout.files.emplace_back("layout.json");
    return layout;
}

} // namespace detail

// The layout of a valid configuration. Precondition: is_valid(config).
inline Layout describe_layout(const Config& config) {
    using namespace detail;
    if (uses_shadow_map(config)) return describe_shadow_map_layout(config);
    if (config.technique == Technique::oim) return describe_oim_layout(config);
    Layout layout;
    layout.config = config;
    const int R = config.resolution, T = texture_count(config), L = max_level(config);
    layout.textures_per_layer = T;
    layout.max_level = L;
    const std::string wrap = border_wrap(config);
    const std::string level_fmt(level_format(config));
    auto texture = [&](std::string name, std::string target, std::string format, int w, int h, int d, int mips,
                       std::string min, std::string mag, std::string purpose) {
        layout.textures.push_back({std::move(name), std::move(target), std::move(format), w, h, d, mips,
                                   std::move(min), std::move(mag), wrap, std::move(purpose)});
    };

    // Programs with their parameters, in pass order.
    for (const ProgramPlan& plan : program_plan(config)) {
        ProgramDesc program{std::string(plan.name), {}, describe_params(config, plan.name)};
        for (Artifact a : plan.stages) program.files.emplace_back(file_name(a));
        layout.programs.push_back(std::move(program));
    }
    auto params_of = [&](std::string_view program) -> const std::vector<ParamDesc>& {
        for (const ProgramDesc& p : layout.programs)
            if (p.name == program) return p.parameters;
        return layout.programs.front().parameters;
    };
    auto fullscreen = [&](std::string name, std::string program, std::vector<BindingDesc> inputs,
                          AttachmentDesc output, std::vector<std::pair<std::string, int>> ints, int w, int h) {
        for (BindingDesc& b : inputs) b.binding = binding_of(params_of(program), b.sampler);
        layout.passes.push_back({std::move(name), "fullscreen", std::move(program), std::move(inputs), {std::move(output)},
                                 std::move(ints), w, h, "no blending, no depth test, empty vertex array, 3 vertices"});
    };

    // Storage, and where the slicing pass writes slice texture t.
    std::vector<AttachmentDesc> slicing_outputs;
    const bool sliced_into_array = config.packing == Packing::atlas || config.filter == Filter::sat;
    if (sliced_into_array) {
        texture("penumbra_slices", "2D_ARRAY", "RGBA8", R, R, T, 1, "NEAREST", "NEAREST",
                "slicing output: binary coverage, one layer per four slices");
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_slices", 0, t});
    }
    if (config.filter == Filter::mipmap && config.packing == Packing::atlas) {
        texture("penumbra_occlusionAtlas", "2D", "RGBA8", T * R, R, 1, L + 1, "LINEAR_MIPMAP_LINEAR", "LINEAR",
                "occlusion tiles side by side, mip chain");
    } else if (config.filter == Filter::mipmap) {
        texture("penumbra_occlusion", "2D_ARRAY", "RGBA8", R, R, T, L + 1, "LINEAR_MIPMAP_LINEAR", "LINEAR",
                "occlusion textures, mip chain");
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_occlusion", 0, t});
    } else if (config.filter == Filter::sat) {
        const bool atlas = config.packing == Packing::atlas;
        for (const char* name : {"penumbra_sat", "penumbra_satScratch"}) {
            const std::string n = atlas ? std::string(name) == "penumbra_sat" ? "penumbra_satAtlas" : name : name;
            texture(n, atlas ? "2D" : "2D_ARRAY", "RGBA32F", atlas ? T * (R + 1) : R + 1, R + 1, atlas ? 1 : T, 1,
                    "LINEAR", "LINEAR", n == "penumbra_satScratch" ? "summed-area ping-pong target"
                                                                   : "exclusive summed-area tables, (R+1)-texel tiles");
        }
    } else if (config.packing == Packing::atlas) {
        for (int l = 0; l <= L; ++l)
            texture(atlas_level_name(l).str(), "2D", level_fmt, T * R, R, 1, 1, "LINEAR", "LINEAR",
                    "filter level " + std::to_string(l) + ", tiles side by side");
    } else if (config.packing == Packing::array) {
        texture("penumbra_levels", "2D_ARRAY", level_fmt, R, R, (L + 1) * T, 1, "LINEAR", "LINEAR",
                "filter levels, layer = level * T + texture");
        texture("penumbra_scratch", "2D", level_fmt, R, R, 1, 1, "NEAREST", "NEAREST",
                "level being built (a texture cannot be sampled and rendered at once)");
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_levels", 0, t});
    } else {
        for (int t = 0; t < T; ++t) {
            texture(volume_name(t).str(), "3D", level_fmt, R, R, L + 1, 1, "LINEAR", "LINEAR",
                    "slices " + std::to_string(4 * t) + " to " + std::to_string(4 * t + 3) + ", levels along depth");
            slicing_outputs.push_back({volume_name(t).str(), 0, 0});
        }
        texture("penumbra_scratch", "2D", level_fmt, R, R, 1, 1, "NEAREST", "NEAREST",
                "level being built (a texture cannot be sampled and rendered at once)");
    }

    layout.passes.push_back({"slicing", "draw_scene", "slicing", {}, slicing_outputs, {}, R, R,
                             "clear colour to 0, blend equation MAX (factors ONE, ONE), no depth test, no culling"});

    // Prefilter passes.
    const std::string level_program = config.filter == Filter::gaussian ? "gaussian_level" : "nbuffer_level";
    if (config.packing == Packing::atlas && config.filter != Filter::sat) {
        const std::string level0 = config.filter == Filter::mipmap ? "penumbra_occlusionAtlas" : "penumbra_level0";
        fullscreen("pack_atlas", "pack_atlas", {{"penumbra_slices", "penumbra_slices"}}, {level0, 0, -1}, {}, T * R, R);
    }
    if (config.filter == Filter::mipmap) {
        const std::string storage = config.packing == Packing::atlas ? "penumbra_occlusionAtlas" : "penumbra_occlusion";
        layout.passes.push_back({"mipmaps", "generate_mipmap", "", {}, {{storage, 0, -1}}, {}, 0, 0, ""});
    } else if (config.filter == Filter::sat) {
        const bool atlas = config.packing == Packing::atlas;
        const std::string final_name = atlas ? "penumbra_satAtlas" : "penumbra_sat";
        const int w = atlas ? T * (R + 1) : R + 1;
        for (int t = 0; t < (atlas ? 1 : T); ++t) {
            const int layer = atlas ? -1 : t;
            std::vector<std::pair<std::string, int>> ints;
            if (!atlas) ints.push_back({"penumbra_sourceLayer", t});
            fullscreen("sat_shift", "sat_shift", {{"penumbra_slices", "penumbra_slices"}}, {final_name, 0, layer},
                       ints, w, R + 1);
            std::string from = final_name, to = "penumbra_satScratch";
            for (int vertical = 0; vertical <= 1; ++vertical)
                for (int l = 0; l <= L; ++l) {
                    std::vector<std::pair<std::string, int>> pass_ints{{"penumbra_step", 1 << l},
                                                                       {"penumbra_vertical", vertical}};
                    if (!atlas) pass_ints.push_back({"penumbra_sourceLayer", t});
                    fullscreen("sat_pass", "sat_pass", {{"penumbra_source", from}}, {to, 0, layer}, pass_ints, w,
                               R + 1);
                    std::swap(from, to);
                }
        }
    } else {
        for (int l = 1; l <= L; ++l) {
            const std::pair<std::string, int> step{"penumbra_step", 1 << (l - 1)};
            if (config.packing == Packing::atlas) {
                fullscreen(level_program, level_program, {{"penumbra_source", atlas_level_name(l - 1).str()}},
                           {atlas_level_name(l).str(), 0, -1}, {step}, T * R, R);
                continue;
            }
            for (int t = 0; t < T; ++t) {
                const bool array = config.packing == Packing::array;
                const std::string storage = array ? "penumbra_levels" : volume_name(t).str();
                fullscreen(level_program, level_program, {{"penumbra_source", storage}}, {"penumbra_scratch", 0, -1},
                           {step, {"penumbra_sourceLayer", array ? (l - 1) * T + t : l - 1}}, R, R);
                layout.passes.push_back({"copy_level", "copy", "", {{"", "penumbra_scratch", 0}},
                                         {{storage, 0, array ? l * T + t : l}}, {}, R, R, ""});
            }
        }
    }

    // Shading: the example program; shading_deferred or the engine's own shader including
    // penumbra_visibility.glsl bind the same storage samplers.
    PassDesc shading{"shading", "draw_scene", "shading_example", {}, {}, {}, 0, 0,
                     "the caller's framebuffer; or run shading_deferred over a G-buffer of world positions"};
    for (const ParamDesc& p : params_of("shading_example"))
        if (p.binding >= 0) shading.inputs.push_back({p.name, p.texture, p.binding});
    layout.passes.push_back(std::move(shading));

    for (Artifact a : artifacts(config)) layout.files.emplace_back(file_name(a));
    layout.files.emplace_back("layout.json");
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

} // namespace detail

// layout.json: the layout as JSON (two-space indentation, keys as in the C++ structs).
inline std::string to_json(const Layout& layout) {
    using detail::json_string;
    const Config& c = layout.config;
    std::string o = "{\n";
    auto field = [&](std::string_view indent, std::string_view key, const std::string& value, bool comma = true) {
        o += std::string(indent) + json_string(key) + ": " + value + (comma ? ",\n" : "\n");
    };
    o += "  \"generator\": \"penumbra " + std::string(detail::version_string) + "\",\n";
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
    field("    ", "target", json_string(to_string(c.target)));
    auto real = [](double v) { return detail::format_float(v).str(); };
    auto flag = [](bool v) { return std::string(v ? "true" : "false"); };
    field("    ", "shadow_map",
          "{\"resolution\": " + std::to_string(c.shadow_map.resolution) + ", \"constant_bias\": " +
              real(c.shadow_map.constant_bias) + ", \"slope_bias\": " + real(c.shadow_map.slope_bias) + "}");
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
              std::to_string(c.oim.intervals) + ", \"samples\": " + std::to_string(c.oim.samples) + "}",
          false);
    o += "  },\n";
    field("  ", "textures_per_layer", std::to_string(layout.textures_per_layer));
    field("  ", "max_level", std::to_string(layout.max_level));
    o += "  \"textures\": [\n";
    for (std::size_t i = 0; i < layout.textures.size(); ++i) {
        const TextureDesc& t = layout.textures[i];
        o += "    {\"name\": " + json_string(t.name) + ", \"target\": " + json_string(t.target) +
             ", \"internal_format\": " + json_string(t.internal_format) + ", \"width\": " + std::to_string(t.width) +
             ", \"height\": " + std::to_string(t.height) + ", \"depth\": " + std::to_string(t.depth) +
             ", \"mip_levels\": " + std::to_string(t.mip_levels) + ", \"min_filter\": " + json_string(t.min_filter) +
             ", \"mag_filter\": " + json_string(t.mag_filter) + ", \"wrap\": " + json_string(t.wrap) +
             ", \"purpose\": " + json_string(t.purpose) + "}" + (i + 1 < layout.textures.size() ? ",\n" : "\n");
    }
    o += "  ],\n  \"programs\": [\n";
    for (std::size_t i = 0; i < layout.programs.size(); ++i) {
        const ProgramDesc& p = layout.programs[i];
        o += "    {\"name\": " + json_string(p.name) + ", \"files\": [";
        for (std::size_t f = 0; f < p.files.size(); ++f) o += (f ? ", " : "") + json_string(p.files[f]);
        o += "], \"parameters\": [\n";
        for (std::size_t u = 0; u < p.parameters.size(); ++u) {
            const ParamDesc& d = p.parameters[u];
            o += "      {\"name\": " + json_string(d.name) + ", \"type\": " + json_string(d.type) +
                 ", \"meaning\": " + json_string(d.meaning) + ", \"units\": " + json_string(d.units);
            if (d.binding >= 0) o += ", \"binding\": " + std::to_string(d.binding) + ", \"texture\": " + json_string(d.texture);
            if (d.offset >= 0)
                o += ", \"block\": " + json_string(d.block) + ", \"block_binding\": " + std::to_string(d.block_binding) +
                     ", \"offset\": " + std::to_string(d.offset);
            o += std::string("}") + (u + 1 < p.parameters.size() ? ",\n" : "\n");
        }
        o += std::string("    ]}") + (i + 1 < layout.programs.size() ? ",\n" : "\n");
    }
    o += "  ],\n  \"passes\": [\n";
    for (std::size_t i = 0; i < layout.passes.size(); ++i) {
        const PassDesc& p = layout.passes[i];
        o += "    {\"name\": " + json_string(p.name) + ", \"action\": " + json_string(p.action) +
             ", \"program\": " + json_string(p.program) + ", \"inputs\": [";
        for (std::size_t b = 0; b < p.inputs.size(); ++b)
            o += (b ? ", " : "") + std::string("{\"sampler\": ") + json_string(p.inputs[b].sampler) +
                 ", \"texture\": " + json_string(p.inputs[b].texture) + ", \"binding\": " +
                 std::to_string(p.inputs[b].binding) + "}";
        o += "], \"outputs\": [";
        for (std::size_t a = 0; a < p.outputs.size(); ++a)
            o += (a ? ", " : "") + std::string("{\"texture\": ") + json_string(p.outputs[a].texture) +
                 ", \"level\": " + std::to_string(p.outputs[a].level) + ", \"layer\": " +
                 std::to_string(p.outputs[a].layer) + "}";
        o += "], \"int_uniforms\": {";
        for (std::size_t u = 0; u < p.int_uniforms.size(); ++u)
            o += (u ? ", " : "") + json_string(p.int_uniforms[u].first) + ": " + std::to_string(p.int_uniforms[u].second);
        o += "}, \"viewport\": [" + std::to_string(p.viewport_width) + ", " + std::to_string(p.viewport_height) +
             "], \"state\": " + json_string(p.state) + "}" + (i + 1 < layout.passes.size() ? ",\n" : "\n");
    }
    o += "  ],\n  \"files\": [";
    for (std::size_t f = 0; f < layout.files.size(); ++f) o += (f ? ", " : "") + json_string(layout.files[f]);
    o += "]\n}\n";
    return o;
}

} // namespace penumbra
