// penumbra/layout.hpp — everything an engine must allocate and run for a configuration:
// textures, programs with their parameters and bindings, and the passes in order.
//
//   penumbra::Layout layout = penumbra::describe_layout(config);
//   std::string json = penumbra::to_json(layout); // the same, as layout.json
//
// layout_version 2; the JSON schema is docs/layout.schema.json and README.md ("Using it from an
// engine") walks through it. Run time only (it is data for an engine, not text for a compiler).
#pragma once

#include "detail/artifacts.hpp"
#include "detail/uniform_compute.hpp"
#include "validate.hpp"

#include <array>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra {

inline constexpr int layout_version = 2; // "layout_version" in layout.json

struct TextureDesc {
    std::string name;
    std::string target;          // "2D", "2D_ARRAY", "3D" (GL_TEXTURE_… / VK_IMAGE_TYPE_…)
    // "RGBA8", "RGBA16F", "RGBA32F", "R8", "R16F", "R32F", "RG16F", "RG32F", "RGBA32UI", "R32UI",
    // "DEPTH_COMPONENT24", "DEPTH_COMPONENT32F"
    std::string internal_format;
    int width = 0, height = 0;   // 0 × 0 when size is "output"
    int depth = 1;               // layers of a 2D array, depth of a 3D texture, 1 otherwise
    int mip_levels = 1;
    std::string min_filter, mag_filter; // "NEAREST", "LINEAR", "LINEAR_MIPMAP_LINEAR", "NEAREST_MIPMAP_NEAREST"
    std::string wrap;            // "CLAMP_TO_BORDER" (colour border_color) or "CLAMP_TO_EDGE"
    std::array<float, 4> border_color{0.0f, 0.0f, 0.0f, 0.0f}; // used when wrap is CLAMP_TO_BORDER
    std::string size = "fixed";    // "fixed": width × height; "output": the output image's size (per frame)
    std::string source = "passes"; // "passes": written by the layout's passes; "caller": the engine fills it
                                   // every frame; "bake": uploaded once from an offline bake
    std::string compare;           // "" or a compare func ("LEQUAL", …): depth texture read with
                                   // hardware comparison (sampler2DShadow)
    std::string purpose;
};

struct ParamDesc {
    std::string name, type, meaning, units;
    std::string source;          // plain uniforms: "light" (uniform_values.hpp), "pass" (int_uniforms), "camera"
    std::string compute;         // plain uniforms: how to compute the value (formula, light_frame.hpp field)
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
    int layer = -1;             // layer of an array / depth slice of a 3D texture; -1 for a 2D texture
    std::string kind = "color"; // "color" (colour attachment i = i-th colour output) or "depth"
};

struct BindingDesc {
    std::string sampler; // parameter name in the program
    std::string texture;
    int binding = 0;
    int level = -1;      // -1: all levels; n: the pass reads only level n (base = max level = n while it
                         // runs), so it may render another level of the same texture (min-max mip chains)
};

// Fixed-function state of a pass. Blend, depth test and culling are off unless set; polygon
// offset is on when factor or units is non-zero.
struct RenderState {
    bool blend = false;
    std::string blend_equation = "ADD"; // "ADD", "MAX", "MIN"
    std::string blend_src = "ONE", blend_dst = "ZERO";
    bool depth_test = false;
    std::string depth_func = "LESS";    // "LESS", "LEQUAL", "ALWAYS", …
    bool depth_write = false;
    std::array<bool, 4> color_mask{true, true, true, true};
    std::string cull = "NONE";          // "NONE", "BACK", "FRONT"
    std::optional<std::array<float, 4>> clear_color; // cleared before drawing when set
    std::optional<float> clear_depth;
    float polygon_offset_factor = 0.0f, polygon_offset_units = 0.0f; // slope-scaled depth bias
    // "NONE" or "OR": a logical operation combines each fragment with the (integer) target instead of
    // blending (glLogicOp / VkPipelineColorBlendStateCreateInfo::logicOp); blend is then false
    std::string logic_op = "NONE";
};

struct PassDesc {
    std::string name;
    // "draw_scene": draw the caller's geometry with `program`; "fullscreen": draw 3 vertices
    // with `program`; "generate_mipmap": glGenerateMipmap(texture of outputs[0]);
    // "copy": copy inputs[0].texture level 0 into outputs[0] (same size).
    std::string action;
    std::string program;
    std::vector<BindingDesc> inputs;
    std::vector<AttachmentDesc> outputs;
    std::vector<std::pair<std::string, int>> int_uniforms;
    int viewport_width = 0, viewport_height = 0; // 0 × 0 in phase "screen": the output size
    RenderState state;
    // "shadow": run when the scene or the light changes (Runtime::build); "screen": run every frame
    // at the output size over the caller's textures (Runtime::run_screen); "example": drawn by the
    // engine itself with its camera (the runtime does not run it)
    std::string phase = "shadow";
};

struct Layout {
    int version = layout_version;
    std::string technique = "occlusion";
    Config config;
    int textures_per_layer = 0; // T: RGBA occlusion textures, four slices each
    int max_level = 0;          // L: the highest filter level built, log2(resolution) or config.level_bound
    std::vector<TextureDesc> textures;
    std::vector<ProgramDesc> programs;
    std::vector<PassDesc> passes;
    std::string result; // the texture holding the visibility after the screen phase
    std::vector<std::string> files; // every file an emission writes, layout.json included
    // What each phase's output depends on ("light", "geometry", "camera", "caller_textures", "bake"):
    // an engine reruns a phase only when one of them changed (a camera-only change skips "shadow").
    std::vector<std::pair<std::string, std::vector<std::string>>> phase_inputs;
};

namespace detail {

// The filtered levels' format (Config::level_format); ES 3.0 cannot render to half floats. Other
// techniques' screen-sized intermediates (erosion) stay in half floats where the target has them.
constexpr std::string_view level_format(const Config& config) {
    if (config.target == Target::essl300) return "RGBA8";
    if (config.technique == Technique::occlusion && config.level_format == LevelFormat::rgba8) return "RGBA8";
    return "RGBA16F";
}

// The screen-phase result: a format every target can render to. ES 3.0 renders R32F / R16F only
// with EXT_color_buffer_float; R8 is colour-renderable in core ES 3.0 (8 bits of visibility).
constexpr std::string_view visibility_format(const Config& config) {
    return config.target == Target::essl300 ? "R8" : "R32F";
}

inline std::string border_wrap(const Config& config) {
    return limits(config.target).clamp_to_border ? "CLAMP_TO_BORDER" : "CLAMP_TO_EDGE";
}

// The shading programs' own parameters, after penumbraVisibility()'s.
inline std::vector<Param> shading_deferred_params(const Config& config) {
    return config.technique == Technique::oim ? oim_deferred_params() : deferred_params(config);
}
inline std::vector<Param> shading_fragment_params(const Config& config) {
    return config.technique == Technique::oim ? oim_example_fragment_params() : example_fragment_params();
}
inline std::vector<Param> shading_vertex_params(const Config& config) {
    return config.technique == Technique::oim ? oim_example_vertex_params() : example_vertex_params();
}

inline std::vector<Param> program_params(const Config& config, std::string_view program) {
    if (program == "slicing") return slicing_params(config);
    if (program == "depth_bins") return depth_bins_params();
    if (program == "slice_boundaries") return slice_boundaries_params();
    if (program == "pack_atlas") return pack_atlas_params();
    if (program == "unpack_slices") return unpack_params();
    if (program == "nbuffer_level" || program == "gaussian_level") return level_params(config);
    if (program == "sat_shift") return sat_shift_params(config);
    if (program == "sat_pass") return sat_pass_params(config);
    if (program == "shadow_depth") return shadow_depth_params();
    if (program.starts_with("erosion_")) return erosion_params(config, program);
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
            if (!is_sampler(p)) {
                desc.source = std::string(p.source);
                desc.compute = p.source == "pass" ? "the value in int_uniforms of the pass that runs this program"
                                                  : std::string(uniform_compute(p.name.view(), config.light));
            }
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

// Adds textures and passes to a layout whose programs are already described.
struct LayoutBuilder {
    Layout& layout;
    std::string wrap; // the default wrap mode of new textures

    const std::vector<ParamDesc>& params_of(std::string_view program) const {
        for (const ProgramDesc& p : layout.programs)
            if (p.name == program) return p.parameters;
        return layout.programs.front().parameters;
    }
    TextureDesc& texture(std::string name, std::string target, std::string format, int w, int h, int d, int mips,
                         std::string min, std::string mag, std::string purpose) {
        TextureDesc t;
        t.name = std::move(name);
        t.target = std::move(target);
        t.internal_format = std::move(format);
        t.width = w;
        t.height = h;
        t.depth = d;
        t.mip_levels = mips;
        t.min_filter = std::move(min);
        t.mag_filter = std::move(mag);
        t.wrap = wrap;
        t.purpose = std::move(purpose);
        layout.textures.push_back(std::move(t));
        return layout.textures.back();
    }
    void pass(std::string name, std::string action, std::string program, std::vector<BindingDesc> inputs,
              std::vector<AttachmentDesc> outputs, std::vector<std::pair<std::string, int>> ints, int w, int h,
              RenderState state = {}, std::string phase = "shadow") {
        for (BindingDesc& b : inputs)
            if (!program.empty()) b.binding = binding_of(params_of(program), b.sampler);
        PassDesc p;
        p.name = std::move(name);
        p.action = std::move(action);
        p.program = std::move(program);
        p.inputs = std::move(inputs);
        p.outputs = std::move(outputs);
        p.int_uniforms = std::move(ints);
        p.viewport_width = w;
        p.viewport_height = h;
        p.state = std::move(state);
        p.phase = std::move(phase);
        layout.passes.push_back(std::move(p));
    }
    // Full-screen passes: no blending, no depth test, an empty vertex array, 3 vertices.
    void fullscreen(std::string name, std::string program, std::vector<BindingDesc> inputs, AttachmentDesc output,
                    std::vector<std::pair<std::string, int>> ints, int w, int h) {
        pass(std::move(name), "fullscreen", std::move(program), std::move(inputs), {std::move(output)}, std::move(ints),
             w, h);
    }
};

// Adaptive slice placement (emit_slice_placement.hpp), phase "shadow", before slicing: the depth
// bins in draws of 16 bins (four layers each), their mip chain, then the S + 1 boundaries.
inline void describe_slice_placement_passes(LayoutBuilder& b, const Config& config, const RenderState& max_blend) {
    const int D = depth_bins_resolution, layers = depth_bins / 4;
    TextureDesc& bins = b.texture("penumbra_depthBins", "2D_ARRAY", "RGBA8", D, D, layers, depth_bins_read_level + 1,
                                  "NEAREST_MIPMAP_NEAREST", "NEAREST",
                                  "adaptive slice placement: coverage of " + std::to_string(depth_bins) +
                                      " depth bins seen from the slicing camera, four per layer, mip chain");
    bins.wrap = "CLAMP_TO_EDGE";
    TextureDesc& boundaries =
        b.texture("penumbra_sliceBoundaries", "2D", "R32UI", config.slices + 1, 1, 1, 1, "NEAREST", "NEAREST",
                  "adaptive slice placement: texel k = bits of the depth of slice k's top (texel S: the last slice's "
                  "bottom), scene units; read with texelFetch and uintBitsToFloat");
    boundaries.wrap = "CLAMP_TO_EDGE";
    for (int first = 0; first < depth_bins; first += depth_bins_per_draw) {
        std::vector<AttachmentDesc> outputs;
        for (int t = 0; t < depth_bins_per_draw / 4; ++t) outputs.push_back({"penumbra_depthBins", 0, first / 4 + t});
        b.pass("depth_bins", "draw_scene", "depth_bins", {}, outputs, {{"penumbra_firstBin", first}}, D, D, max_blend);
    }
    b.pass("depth_bins_mipmaps", "generate_mipmap", "", {}, {{"penumbra_depthBins", 0, -1}}, {}, 0, 0);
    b.fullscreen("slice_boundaries", "slice_boundaries", {{"penumbra_depthBins", "penumbra_depthBins"}},
                 {"penumbra_sliceBoundaries", 0, -1}, {}, config.slices + 1, 1);
}

// Occlusion textures, phase "shadow": slicing into the slices' storage (beyond 32 slices: into bits,
// then unpack draws into that storage), then the prefilter passes.
inline void describe_occlusion_passes(LayoutBuilder& b, const Config& config) {
    // L: the highest filter level (level_bound); the summed-area table doubles over all log2(R) steps
    const int R = config.resolution, T = texture_count(config), L = max_level(config);
    const std::string level_fmt(level_format(config));
    // Storage, and where the slicing pass writes slice texture t.
    std::vector<AttachmentDesc> slicing_outputs;
    const bool sliced_into_array = config.packing == Packing::atlas || config.filter == Filter::sat;
    if (sliced_into_array) {
        b.texture("penumbra_slices", "2D_ARRAY", "RGBA8", R, R, T, 1, "NEAREST", "NEAREST",
                "slicing output: binary coverage, one layer per four slices");
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_slices", 0, t});
    }
    if (config.filter == Filter::mipmap && config.packing == Packing::atlas) {
        b.texture("penumbra_occlusionAtlas", "2D", "RGBA8", T * R, R, 1, L + 1, "LINEAR_MIPMAP_LINEAR", "LINEAR",
                "occlusion tiles side by side, mip chain");
    } else if (config.filter == Filter::mipmap) {
        b.texture("penumbra_occlusion", "2D_ARRAY", "RGBA8", R, R, T, L + 1, "LINEAR_MIPMAP_LINEAR", "LINEAR",
                "occlusion textures, mip chain");
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_occlusion", 0, t});
    } else if (config.filter == Filter::sat) {
        const bool atlas = config.packing == Packing::atlas;
        for (const char* name : {"penumbra_sat", "penumbra_satScratch"}) {
            const std::string n = atlas ? std::string(name) == "penumbra_sat" ? "penumbra_satAtlas" : name : name;
            b.texture(n, atlas ? "2D" : "2D_ARRAY", "RGBA32F", atlas ? T * (R + 1) : R + 1, R + 1, atlas ? 1 : T, 1,
                    "LINEAR", "LINEAR", n == "penumbra_satScratch" ? "summed-area ping-pong target"
                                                                   : "exclusive summed-area tables, (R+1)-texel tiles");
        }
    } else if (config.packing == Packing::atlas) {
        for (int l = 0; l <= L; ++l) {
            const int side = R / level_spacing(config, l); // reduced levels: R / 2^(l - level_reduction)
            b.texture(atlas_level_name(l).str(), "2D", level_fmt, T * side, side, 1, 1, "LINEAR", "LINEAR",
                    "filter level " + std::to_string(l) + ", tiles side by side" +
                        (side < R ? ", " + std::to_string(side) + " texels per tile (texel j: level-0 texel " +
                                        std::to_string(R / side) + " * j)"
                                  : std::string()));
        }
    } else if (config.packing == Packing::array) {
        b.texture("penumbra_levels", "2D_ARRAY", level_fmt, R, R, (L + 1) * T, 1, "LINEAR", "LINEAR",
                "filter levels, layer = level * T + texture");
        b.texture("penumbra_scratch", "2D", level_fmt, R, R, 1, 1, "NEAREST", "NEAREST",
                "level being built (a texture cannot be sampled and rendered at once)");
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_levels", 0, t});
    } else {
        for (int t = 0; t < T; ++t) {
            b.texture(volume_name(t).str(), "3D", level_fmt, R, R, L + 1, 1, "LINEAR", "LINEAR",
                    "slices " + std::to_string(4 * t) + " to " + std::to_string(4 * t + 3) + ", levels along depth");
            slicing_outputs.push_back({volume_name(t).str(), 0, 0});
        }
        b.texture("penumbra_scratch", "2D", level_fmt, R, R, 1, 1, "NEAREST", "NEAREST",
                "level being built (a texture cannot be sampled and rendered at once)");
    }

    RenderState max_blend; // a texel is covered when any triangle covers it: blend MAX over a cleared target
    max_blend.blend = true;
    max_blend.blend_equation = "MAX";
    max_blend.blend_src = max_blend.blend_dst = "ONE";
    max_blend.clear_color = std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f};
    std::vector<BindingDesc> slicing_inputs;
    if (places_slices_adaptively(config)) {
        describe_slice_placement_passes(b, config, max_blend);
        slicing_inputs.push_back({"penumbra_sliceBoundaries", "penumbra_sliceBoundaries"});
    }
    if (slices_as_bits(config)) {
        // paper §3.7: every slice a bit of one RGBA32UI target, OR-ed, then unpacked into the textures
        // the slicing would otherwise write, one group of colour attachments per draw
        TextureDesc& bits = b.texture("penumbra_sliceBits", "2D", "RGBA32UI", R, R, 1, 1, "NEAREST", "NEAREST",
                                      "slicing output: bit k % 32 of component k / 32 marks slice k");
        bits.wrap = "CLAMP_TO_EDGE";
        RenderState or_bits;
        or_bits.logic_op = "OR";
        or_bits.clear_color = max_blend.clear_color;
        b.pass("slicing", "draw_scene", "slicing", slicing_inputs, {{"penumbra_sliceBits", 0, -1}}, {}, R, R, or_bits);
        const int group = unpack_group(config);
        for (int d = 0; d < unpack_draws(config); ++d) {
            const auto first = slicing_outputs.begin() + d * group;
            b.pass("unpack_slices", "fullscreen", "unpack_slices", {{"penumbra_sliceBits", "penumbra_sliceBits"}},
                   {first, first + group}, {{"penumbra_firstSlice", 4 * group * d}}, R, R);
        }
    } else {
        b.pass("slicing", "draw_scene", "slicing", slicing_inputs, slicing_outputs, {}, R, R, max_blend);
    }

    // Prefilter passes.
    const std::string level_program = config.filter == Filter::gaussian ? "gaussian_level" : "nbuffer_level";
    if (config.packing == Packing::atlas && config.filter != Filter::sat) {
        const std::string level0 = config.filter == Filter::mipmap ? "penumbra_occlusionAtlas" : "penumbra_level0";
        b.fullscreen("pack_atlas", "pack_atlas", {{"penumbra_slices", "penumbra_slices"}}, {level0, 0, -1}, {}, T * R, R);
    }
    if (config.filter == Filter::mipmap) {
        const std::string storage = config.packing == Packing::atlas ? "penumbra_occlusionAtlas" : "penumbra_occlusion";
        b.pass("mipmaps", "generate_mipmap", "", {}, {{storage, 0, -1}}, {}, 0, 0);
    } else if (config.filter == Filter::sat) {
        const bool atlas = config.packing == Packing::atlas;
        const std::string final_name = atlas ? "penumbra_satAtlas" : "penumbra_sat";
        const int w = atlas ? T * (R + 1) : R + 1;
        for (int t = 0; t < (atlas ? 1 : T); ++t) {
            const int layer = atlas ? -1 : t;
            std::vector<std::pair<std::string, int>> ints;
            if (!atlas) ints.push_back({"penumbra_sourceLayer", t});
            b.fullscreen("sat_shift", "sat_shift", {{"penumbra_slices", "penumbra_slices"}}, {final_name, 0, layer},
                       ints, w, R + 1);
            std::string from = final_name, to = "penumbra_satScratch";
            for (int vertical = 0; vertical <= 1; ++vertical)
                for (int l = 0; l <= resolution_levels(config); ++l) {
                    std::vector<std::pair<std::string, int>> pass_ints{{"penumbra_step", 1 << l},
                                                                       {"penumbra_vertical", vertical}};
                    if (!atlas) pass_ints.push_back({"penumbra_sourceLayer", t});
                    b.fullscreen("sat_pass", "sat_pass", {{"penumbra_source", from}}, {to, 0, layer}, pass_ints, w,
                               R + 1);
                    std::swap(from, to);
                }
        }
    } else {
        for (int l = 1; l <= L; ++l) {
            const std::pair<std::string, int> step{"penumbra_step", 1 << (l - 1)};
            if (config.packing == Packing::atlas) {
                const int spacing = level_spacing(config, l), source_spacing = level_spacing(config, l - 1);
                std::vector<std::pair<std::string, int>> ints{step};
                if (reduces_levels(config)) // offsets in texels of the previous level, and its tile side
                    ints = {{"penumbra_step", (1 << (l - 1)) / source_spacing},
                            {"penumbra_sourceTile", R / source_spacing},
                            {"penumbra_scale", spacing / source_spacing}};
                b.fullscreen(level_program, level_program, {{"penumbra_source", atlas_level_name(l - 1).str()}},
                           {atlas_level_name(l).str(), 0, -1}, ints, T * R / spacing, R / spacing);
                continue;
            }
            for (int t = 0; t < T; ++t) {
                const bool array = config.packing == Packing::array;
                const std::string storage = array ? "penumbra_levels" : volume_name(t).str();
                b.fullscreen(level_program, level_program, {{"penumbra_source", storage}}, {"penumbra_scratch", 0, -1},
                           {step, {"penumbra_sourceLayer", array ? (l - 1) * T + t : l - 1}}, R, R);
                b.pass("copy_level", "copy", "", {{"", "penumbra_scratch", 0}}, {{storage, 0, array ? l * T + t : l}}, {},
                     R, R);
            }
        }
    }
}

// Shadow map techniques, phase "shadow": the depth pass from the light (shadow_frame in
// light_frame.hpp), and for PCSS a copy of the depth that the blocker search reads without
// comparison (a texture has one compare mode).
inline void describe_shadow_map_passes(LayoutBuilder& b, const Config& config) {
    const int R = config.shadow_map.resolution;
    TextureDesc& map = b.texture(std::string(shadow_map_texture), "2D", "DEPTH_COMPONENT32F", R, R, 1, 1, "LINEAR",
                                 "LINEAR", "shadow map: (z - near) / (far - near) along the light axis, biased; "
                                           "read with hardware comparison, bilinear");
    map.wrap = "CLAMP_TO_EDGE"; // kernels reaching past the map read its edge, not a shadowing border
    map.compare = "LEQUAL";     // lit where the receiver's depth <= the stored (biased) occluder depth
    RenderState depth_only;
    depth_only.depth_test = depth_only.depth_write = true;
    depth_only.depth_func = "LESS";
    depth_only.clear_depth = 1.0f;
    b.pass("shadow_depth", "draw_scene", "shadow_depth", {}, {{std::string(shadow_map_texture), 0, -1, "depth"}}, {},
           R, R, depth_only);
    if (config.technique == Technique::pcss || config.technique == Technique::erosion) {
        TextureDesc& plain = b.texture("penumbra_shadowDepth", "2D", "DEPTH_COMPONENT32F", R, R, 1, 1, "NEAREST",
                                       "NEAREST", "copy of the shadow map, read as depth for the blocker search");
        plain.wrap = "CLAMP_TO_EDGE";
        b.pass("copy_shadow_depth", "copy", "", {{"", std::string(shadow_map_texture), 0}},
               {{"penumbra_shadowDepth", 0, -1, "depth"}}, {}, R, R);
    }
}

// Occlusion interval maps (GPU Gems ch. 13): no pass before shading; the rise/fall textures come
// from an offline bake (nearest filtering: the edges must not be blended).
inline void describe_oim_textures(LayoutBuilder& b, const Config& config) {
    const int R = config.oim.resolution;
    for (int p = 0; p < oim_pairs(config.oim); ++p)
        for (const bool fall : {false, true}) {
            TextureDesc& t = b.texture((fall ? oim_fall_name(p) : oim_rise_name(p)).str(), "2D", "RGBA16F", R, R, 1, 1,
                                       "NEAREST", "NEAREST",
                                       std::string(fall ? "fall" : "rise") + " times of intervals " +
                                           std::to_string(4 * p) + " to " + std::to_string(4 * p + 3) +
                                           " (path time t, k / samples: exact in 16-bit floats; unused intervals [0, 0])");
            t.wrap = "CLAMP_TO_EDGE";
            t.source = "bake";
        }
}

// Erosion, phase "screen" (erosion/emit_passes.hpp): output-sized textures, hard shadow, edges, the
// min-max chain one level at a time (read level n, write n + 1), erosion, blur into the result.
inline void describe_erosion_passes(LayoutBuilder& b, const Config& config) {
    const int K = erosion_levels(config.erosion);
    const std::string fmt(level_format(config));
    auto screen_texture = [&](std::string_view name, int mips, std::string purpose) {
        TextureDesc& t = b.texture(std::string(name), "2D", fmt, 0, 0, 1, mips, mips > 1 ? "NEAREST_MIPMAP_NEAREST" : "NEAREST",
                                   "NEAREST", std::move(purpose));
        t.wrap = "CLAMP_TO_EDGE";
        t.size = "output";
    };
    screen_texture(erosion_hard_texture, 1,
                   "r: hard visibility (0/1), g: penumbra half-width / max search radius (shadowed pixels), a: geometry");
    screen_texture(erosion_edges_texture, K + 1,
                   "min-max chain of the Laplacian edges: r edge, g half-width / max search radius (max), "
                   "b min and a max of the hard shadow");
    screen_texture(erosion_penumbra_texture, 1,
                   "r: eroded visibility, g: search radius / max search radius, b: geometry");
    const std::string hard(erosion_hard_texture), edges(erosion_edges_texture), pen(erosion_penumbra_texture);
    auto inputs = [&](std::string_view program) {
        std::vector<BindingDesc> in;
        for (const ParamDesc& p : b.params_of(program))
            if (p.binding >= 0) in.push_back({p.name, p.texture, p.binding});
        return in;
    };
    auto screen = [&](std::string name, std::string program, std::vector<BindingDesc> in, AttachmentDesc out) {
        b.pass(std::move(name), "fullscreen", std::move(program), std::move(in), {std::move(out)}, {}, 0, 0, {}, "screen");
    };
    screen("erosion_hard", "erosion_hard", inputs("erosion_hard"), {hard, 0, -1});
    screen("erosion_edges", "erosion_edges", inputs("erosion_edges"), {edges, 0, -1});
    for (int level = 0; level < K; ++level) {
        std::vector<BindingDesc> in = inputs("erosion_reduce");
        in.front().level = level;
        screen("erosion_reduce", "erosion_reduce", std::move(in), {edges, level + 1, -1});
    }
    screen("erosion_erode", "erosion_erode", inputs("erosion_erode"), {pen, 0, -1});
    screen("erosion_blur", "erosion_blur", inputs("erosion_blur"), {b.layout.result, 0, -1});
}

} // namespace detail

// The layout of a valid configuration. Precondition: is_valid(config).
inline Layout describe_layout(const Config& config) {
    using namespace detail;
    Layout layout;
    layout.config = config;
    layout.technique = std::string(to_string(config.technique));
    if (config.technique == Technique::occlusion) {
        layout.textures_per_layer = texture_count(config);
        layout.max_level = max_level(config);
    }

    // Programs with their parameters, in pass order.
    for (const ProgramPlan& plan : program_plan(config)) {
        ProgramDesc program{std::string(plan.name), {}, describe_params(config, plan.name)};
        for (Artifact a : plan.stages) program.files.emplace_back(file_name(a));
        layout.programs.push_back(std::move(program));
    }
    LayoutBuilder build{layout, border_wrap(config)};
    if (uses_shadow_map(config))
        describe_shadow_map_passes(build, config);
    else if (config.technique == Technique::oim)
        describe_oim_textures(build, config);
    else
        describe_occlusion_passes(build, config);
    // Screen phase: the deferred visibility over the caller's G-buffer, at the output size (world
    // positions; for occlusion interval maps, whose maps are per surface, texture coordinates).
    TextureDesc& world =
        config.technique == Technique::oim
            ? build.texture("penumbra_texCoords", "2D", "RGBA32F", 0, 0, 1, 1, "NEAREST", "NEAREST",
                            "G-buffer filled by the engine every frame: xy the surface's unique texture coordinates "
                            "(the bake's), w = 1 on geometry, 0 on the background; read with texelFetch")
            : build.texture("penumbra_worldPositions", "2D", "RGBA32F", 0, 0, 1, 1, "NEAREST", "NEAREST",
                            "G-buffer filled by the engine every frame: xyz world position, w = 1 on geometry, "
                            "0 on the background; read with texelFetch (no filtering)");
    world.wrap = "CLAMP_TO_EDGE";
    world.size = "output";
    world.source = "caller";
    if (reads_receiver_normal(config)) {
        TextureDesc& normals = build.texture("penumbra_worldNormals", "2D", "RGBA32F", 0, 0, 1, 1, "NEAREST", "NEAREST",
                                             "G-buffer filled by the engine every frame: xyz the unit normal of the "
                                             "side the viewer sees (tangent clip, normal offset); read with texelFetch "
                                             "(no filtering)");
        normals.wrap = "CLAMP_TO_EDGE";
        normals.size = "output";
        normals.source = "caller";
    }
    TextureDesc& visibility = build.texture("penumbra_visibility", "2D", std::string(visibility_format(config)), 0, 0, 1, 1,
                                      "NEAREST", "NEAREST", "visibility of each output pixel, 0 shadowed to 1 lit");
    visibility.wrap = "CLAMP_TO_EDGE";
    visibility.size = "output";
    layout.result = visibility.name;
    if (config.technique == Technique::erosion) {
        describe_erosion_passes(build, config);
    } else {
        std::vector<BindingDesc> deferred_inputs;
        for (const ParamDesc& p : build.params_of("shading_deferred"))
            if (p.binding >= 0) deferred_inputs.push_back({p.name, p.texture, p.binding});
        build.pass("shading", "fullscreen", "shading_deferred", deferred_inputs, {{layout.result, 0, -1}}, {}, 0, 0, {},
                   "screen");
    }

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

    for (Artifact a : artifacts(config)) layout.files.emplace_back(file_name(a));
    layout.files.emplace_back("layout.json");
    // The configuration is implied everywhere: a new one is a new layout.
    bool has_shadow = false;
    for (const PassDesc& p : layout.passes) has_shadow = has_shadow || p.phase == "shadow";
    if (has_shadow) layout.phase_inputs.push_back({"shadow", {"light", "geometry"}});
    if (config.technique == Technique::oim)
        layout.phase_inputs.push_back({"screen", {"camera", "caller_textures", "bake"}});
    else
        layout.phase_inputs.push_back({"screen", {"light", "geometry", "camera", "caller_textures"}});
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
          false);
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
             ", \"compare\": " + json_string(t.compare) + ", \"purpose\": " + json_string(t.purpose) + "}" +
             (i + 1 < layout.textures.size() ? ",\n" : "\n");
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
            if (!d.source.empty()) o += ", \"source\": " + json_string(d.source) + ", \"compute\": " + json_string(d.compute);
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
        o += "    {\"name\": " + json_string(p.name) + ", \"phase\": " + json_string(p.phase) +
             ", \"action\": " + json_string(p.action) + ", \"program\": " + json_string(p.program) + ", \"inputs\": [";
        for (std::size_t b = 0; b < p.inputs.size(); ++b)
            o += (b ? ", " : "") + std::string("{\"sampler\": ") + json_string(p.inputs[b].sampler) +
                 ", \"texture\": " + json_string(p.inputs[b].texture) + ", \"binding\": " +
                 std::to_string(p.inputs[b].binding) + ", \"level\": " + std::to_string(p.inputs[b].level) + "}";
        o += "], \"outputs\": [";
        for (std::size_t a = 0; a < p.outputs.size(); ++a)
            o += (a ? ", " : "") + std::string("{\"texture\": ") + json_string(p.outputs[a].texture) +
                 ", \"kind\": " + json_string(p.outputs[a].kind) + ", \"level\": " + std::to_string(p.outputs[a].level) +
                 ", \"layer\": " + std::to_string(p.outputs[a].layer) + "}";
        o += "], \"int_uniforms\": {";
        for (std::size_t u = 0; u < p.int_uniforms.size(); ++u)
            o += (u ? ", " : "") + json_string(p.int_uniforms[u].first) + ": " + std::to_string(p.int_uniforms[u].second);
        o += "}, \"viewport\": [" + std::to_string(p.viewport_width) + ", " + std::to_string(p.viewport_height) +
             "], \"state\": " + detail::json_state(p.state) + "}" + (i + 1 < layout.passes.size() ? ",\n" : "\n");
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
    o += "  \"files\": [";
    for (std::size_t f = 0; f < layout.files.size(); ++f) o += (f ? ", " : "") + json_string(layout.files[f]);
    o += "]\n}\n";
    return o;
}

} // namespace penumbra
