// penumbra/detail/layout_builder.hpp — what a layout is made of and how one is built: the structs
// of layout.json (penumbra/layout.hpp is their public home), declaration groups of parameters turned
// into bindings and block offsets, and the builder with which each technique folder describes its
// textures and passes (detail/<technique>/layout.hpp). Nothing here knows a technique's programs.
#pragma once

#include "alpha_test.hpp"
#include "glsl_common.hpp"
#include "target_limits.hpp"
#include "uniform_compute.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace penumbra {

inline constexpr int layout_version = 3; // "layout_version" in layout.json

// The one compare function of every depth comparison (sampler2DShadow): lit where the receiver's
// depth <= the stored, biased occluder depth.
inline constexpr std::string_view shadow_compare_func = "LEQUAL";

// How one binding samples its texture: a sampler object (GL 3.3+, ES 3.0, WebGL2) or a VkSampler.
// The texture's own filters and wrap are its defaults; a binding may read the same texture another
// way (PCSS reads its shadow map NEAREST without comparison for the blocker search and LINEAR with
// comparison for the filter, through two samplers).
struct Sampling {
    std::string min_filter, mag_filter; // "NEAREST", "LINEAR", "LINEAR_MIPMAP_LINEAR", …
    std::string wrap;                   // "CLAMP_TO_BORDER" (border_color) or "CLAMP_TO_EDGE"
    std::array<float, 4> border_color{0.0f, 0.0f, 0.0f, 0.0f};
    std::string compare; // "" (a plain read) or the compare func of a depth comparison (sampler*Shadow)

    // an order, so that a runner keeps one sampler object per distinct sampling (a map key)
    friend bool operator<(const Sampling& a, const Sampling& b) {
        return std::tie(a.min_filter, a.mag_filter, a.wrap, a.border_color, a.compare) <
               std::tie(b.min_filter, b.mag_filter, b.wrap, b.border_color, b.compare);
    }
};

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
    // What the texture holds before the first pass writes it: "zero" (every level cleared to 0 once,
    // at allocation: passes that blend, OR or read outside what they wrote rely on it), "caller"
    // (source caller) or "bake" (source bake).
    std::string initial = "zero";
    std::string purpose;
};

struct ParamDesc {
    std::string name, type, meaning, units;
    std::string source;          // plain uniforms: "light" (uniform_values.hpp), "pass" (int_uniforms), "camera";
                                 // "draw" (also samplers): set by the caller per draw (alpha_test's material)
    std::string compute;         // plain uniforms: how to compute the value (formula, light_frame.hpp field)
    int binding = -1;            // sampler: texture unit / Vulkan binding; -1 for plain uniforms
    std::string texture;         // sampler: the texture bound to it when the program runs its usual pass
    Sampling sampling{};         // sampler: how it reads its texture (finish_sampling fills it)
    std::string block;           // Vulkan: uniform block holding this value
    int block_binding = -1;      // Vulkan: binding of that block
    int offset = -1;             // Vulkan: std140 byte offset in the block
    int set = -1;                // Vulkan: descriptor set of the block or sampler (vulkan_descriptor_set)
};

// A vertex attribute of a program that draws the caller's geometry ("draw_scene").
struct VertexInputDesc {
    std::string name;    // the GLSL input, e.g. penumbra_position
    int location = 0;    // layout(location = …) in the vertex stage
    std::string type;    // "vec3", "vec2"
    std::string meaning; // what the engine feeds it
};

struct ProgramDesc {
    std::string name;
    std::vector<std::string> files; // stage files, in pipeline order
    std::vector<ParamDesc> parameters;
    std::vector<VertexInputDesc> vertex_inputs; // empty for full-screen programs (no attributes)
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
    Sampling sampling{}; // how this binding reads the texture (that of its sampler parameter)
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

// What a "copy" pass copies: a width × height region, texel for texel (no filtering, no format
// conversion), from level/layer of inputs[0].texture to level/layer of outputs[0].texture (layer -1:
// a 2D texture). glCopyImageSubData, vkCmdCopyImage, or a framebuffer blit with NEAREST.
struct CopyDesc {
    int source_level = 0, source_layer = -1;
    int target_level = 0, target_layer = -1;
    int width = 0, height = 0;
};

// What a "generate_mipmap" pass computes: levels base_level + 1 … base_level + levels - 1 of
// outputs[0].texture, each from the one below by a 2×2 box average (glGenerateMipmap; on Vulkan a
// chain of vkCmdBlitImage with LINEAR filtering, which averages the same 2×2 texels).
struct MipmapDesc {
    int base_level = 0;
    int levels = 1;
    std::string downsample = "box"; // "box": the mean of the 2×2 texels below
};

// An image a "dispatch" pass writes (glBindImageTexture(unit, texture, level, layered, layer, access,
// format)): the compute program's image uniform `image` at image unit `unit`.
struct ImageBindingDesc {
    std::string image;   // the image uniform in the program, e.g. penumbra_output0
    std::string texture;
    int level = 0;
    int layer = -1;      // -1: a 2D texture (not layered)
    int unit = 0;        // image unit (layout(binding = …) of the image uniform)
    std::string format;  // the image format, the texture's internal format: "RGBA8", "RGBA16F"
    std::string access = "WRITE_ONLY"; // "WRITE_ONLY", "READ_ONLY", "READ_WRITE"
};

// What a "dispatch" pass runs: glDispatchCompute(groups) of its compute program, then
// glMemoryBarrier with the bits the passes after it need ("TEXTURE_FETCH": they sample what it
// wrote; "TEXTURE_UPDATE": it may be read back or copied; "SHADER_IMAGE_ACCESS": images).
struct DispatchDesc {
    std::array<int, 3> groups{1, 1, 1};     // workgroups in x, y, z
    std::array<int, 3> local_size{1, 1, 1}; // invocations per workgroup (the program's local_size, for information)
    std::vector<std::string> memory_barrier;
};

struct PassDesc {
    std::string name;
    // "draw_scene": draw the caller's geometry with `program`; "fullscreen": draw 3 vertices
    // with `program`; "generate_mipmap": the mipmap chain of outputs[0] (mipmap); "copy": the region
    // `copy` says, from inputs[0] into outputs[0]; "dispatch": run the compute `program` over
    // dispatch.groups with `inputs` bound as samplers and image_outputs as images (no outputs).
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
    std::optional<CopyDesc> copy;     // action "copy"
    std::optional<MipmapDesc> mipmap; // action "generate_mipmap"
    std::optional<DispatchDesc> dispatch;     // action "dispatch"
    std::vector<ImageBindingDesc> image_outputs; // action "dispatch": the images it writes
};

// Where slice k of the occlusion textures is after the slicing (and unpack) passes: texture, layer
// (-1: a 2D texture; the depth index of a 3D texture) and channel ("r", "g", "b", "a"). The
// occlusion technique only; slice k is in channel k % 4 of RGBA texture k / 4.
struct SliceLocation {
    int slice = 0;
    std::string texture;
    int layer = -1;
    std::string channel;
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
    // What each phase's output depends on ("light", "geometry", "camera", "caller_textures", "bake";
    // "materials": the casters' alpha textures and cutoffs, with alpha_test):
    // an engine reruns a phase only when one of them changed (a camera-only change skips "shadow").
    std::vector<std::pair<std::string, std::vector<std::string>>> phase_inputs;
    std::vector<SliceLocation> slice_map; // occlusion: where each slice is (empty for other techniques)
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

// One declaration group of a program: a uniform block on Vulkan ("PenumbraSlicing", …) and its
// samplers. The emitters declare the same groups in the same order, so the bindings match.
struct ParamGroup {
    std::string_view block;
    std::vector<Param> params;
};

// The groups of the shading programs every technique ends with: penumbraVisibility()'s parameters,
// then the program's own (shading_example: fragment, then vertex stage; shading_deferred: the G-buffer).
inline std::vector<ParamGroup> shading_param_groups(std::string_view program, std::vector<Param> visibility,
                                                    std::vector<Param> deferred, std::vector<Param> fragment,
                                                    std::vector<Param> vertex) {
    if (program == "shading_example")
        return {{"PenumbraVisibility", std::move(visibility)},
                {"PenumbraExample", std::move(fragment)},
                {"PenumbraCamera", std::move(vertex)}};
    return {{"PenumbraVisibility", std::move(visibility)}, {"PenumbraDeferred", std::move(deferred)}};
}

// The groups of the programs that draw the casters from the light (slicing, depth bins, shadow-map
// depth): the program's own, then with alpha_test the draw's material (detail/alpha_test.hpp).
inline std::vector<ParamGroup> caster_param_groups(const Config& config, std::string_view block,
                                                   std::vector<Param> own) {
    std::vector<ParamGroup> groups{{block, std::move(own)}};
    if (config.alpha_test) groups.push_back({alpha_test_block, alpha_test_params(config)});
    return groups;
}

// The parameters of a program from its declaration groups: blocks and samplers numbered as they appear.
inline std::vector<ParamDesc> describe_params(const Config& config, const std::vector<ParamGroup>& groups) {
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
            if (!is_sampler(p) || p.source == "draw") {
                desc.source = std::string(p.source);
                desc.compute = p.source == "pass" ? "the value in int_uniforms of the pass that runs this program"
                                                  : std::string(uniform_compute(p.name.view(), config.light));
            }
            if (is_sampler(p)) { // completed from the texture by finish_sampling
                desc.sampling.min_filter = desc.sampling.mag_filter = std::string(p.filter);
                if (p.type.ends_with("Shadow")) desc.sampling.compare = std::string(shadow_compare_func);
            }
            if (is_vulkan(config)) desc.set = vulkan_descriptor_set;
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

// The description of layout texture `name`; nullptr when the layout has none.
inline const TextureDesc* find_texture(const Layout& layout, std::string_view name) {
    for (const TextureDesc& t : layout.textures)
        if (t.name == name) return &t;
    return nullptr;
}

inline int binding_of(const std::vector<ParamDesc>& params, std::string_view name) {
    for (const ParamDesc& p : params)
        if (p.name == name) return p.binding;
    return -1;
}

// Adds textures and passes to a layout whose programs are already described.
struct LayoutBuilder {
    Layout& layout;
    std::string wrap; // the default wrap mode of new textures
    // What the screen phase depends on (layout.phase_inputs); a technique whose screen phase reads a
    // bake instead of the light and the geometry says so.
    std::vector<std::string> screen_inputs{"light", "geometry", "camera", "caller_textures"};

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
        if (p.action == "copy" && !p.inputs.empty() && !p.outputs.empty())
            p.copy = CopyDesc{std::max(p.inputs[0].level, 0), -1, p.outputs[0].level, p.outputs[0].layer, w, h};
        if (p.action == "generate_mipmap" && !p.outputs.empty())
            if (const TextureDesc* t = find_texture(layout, p.outputs[0].texture))
                p.mipmap = MipmapDesc{p.outputs[0].level, t->mip_levels - p.outputs[0].level};
        layout.passes.push_back(std::move(p));
    }
    // Full-screen passes: no blending, no depth test, an empty vertex array, 3 vertices.
    void fullscreen(std::string name, std::string program, std::vector<BindingDesc> inputs, AttachmentDesc output,
                    std::vector<std::pair<std::string, int>> ints, int w, int h) {
        pass(std::move(name), "fullscreen", std::move(program), std::move(inputs), {std::move(output)}, std::move(ints),
             w, h);
    }
};

// How a binding reads `texture`: the texture's own filters and wrap, unless the sampler parameter
// asks for another filter; `partial` holds what describe_params knew (filter override, compare).
inline Sampling complete_sampling(const Sampling& partial, const TextureDesc& texture) {
    Sampling s = partial;
    if (s.min_filter.empty()) s.min_filter = texture.min_filter;
    if (s.mag_filter.empty()) s.mag_filter = texture.mag_filter;
    s.wrap = texture.wrap;
    s.border_color = texture.border_color;
    return s;
}

// Every sampler parameter's and every pass input's "sampling", from the textures they read and what
// their parameter says; the initial contents of textures that the engine provides.
inline void finish_sampling(Layout& layout) {
    for (TextureDesc& t : layout.textures)
        if (t.source != "passes") t.initial = t.source;
    for (PassDesc& pass : layout.passes)
        for (BindingDesc& in : pass.inputs) {
            Sampling partial;
            for (const ProgramDesc& program : layout.programs)
                if (program.name == pass.program)
                    for (const ParamDesc& param : program.parameters)
                        if (param.name == in.sampler) partial = param.sampling;
            if (const TextureDesc* t = find_texture(layout, in.texture)) in.sampling = complete_sampling(partial, *t);
        }
    // a parameter without a texture of its own (a level pass's source, bound per pass): its first pass's
    for (ProgramDesc& program : layout.programs)
        for (ParamDesc& param : program.parameters) {
            if (param.binding < 0) continue;
            if (const TextureDesc* t = find_texture(layout, param.texture)) {
                param.sampling = complete_sampling(param.sampling, *t);
                continue;
            }
            for (const PassDesc& pass : layout.passes)
                for (const BindingDesc& in : pass.inputs)
                    if (pass.program == program.name && in.sampler == param.name && param.sampling.wrap.empty())
                        param.sampling = in.sampling;
        }
}

// The screen phase's textures: the caller's G-buffer (`gbuffer`: world positions, or what the
// technique reads instead), its normals where penumbraVisibility uses them, and the visibility
// result at the output size.
inline void describe_screen_textures(
    LayoutBuilder& b, const Config& config, std::string gbuffer = "penumbra_worldPositions",
    std::string gbuffer_purpose = "G-buffer filled by the engine every frame: xyz world position, w = 1 on geometry, "
                                  "0 on the background; read with texelFetch (no filtering)") {
    TextureDesc& world =
        b.texture(std::move(gbuffer), "2D", "RGBA32F", 0, 0, 1, 1, "NEAREST", "NEAREST", std::move(gbuffer_purpose));
    world.wrap = "CLAMP_TO_EDGE";
    world.size = "output";
    world.source = "caller";
    if (reads_receiver_normal(config)) {
        TextureDesc& normals = b.texture("penumbra_worldNormals", "2D", "RGBA32F", 0, 0, 1, 1, "NEAREST", "NEAREST",
                                         "G-buffer filled by the engine every frame: xyz the unit normal of the "
                                         "side the viewer sees (tangent clip, normal offset); read with texelFetch "
                                         "(no filtering)");
        normals.wrap = "CLAMP_TO_EDGE";
        normals.size = "output";
        normals.source = "caller";
    }
    TextureDesc& visibility = b.texture("penumbra_visibility", "2D", std::string(visibility_format(config)), 0, 0, 1, 1,
                                        "NEAREST", "NEAREST", "visibility of each output pixel, 0 shadowed to 1 lit");
    visibility.wrap = "CLAMP_TO_EDGE";
    visibility.size = "output";
    b.layout.result = visibility.name;
}

// The screen phase of most techniques: shading_deferred over the caller's G-buffer into the result.
inline void describe_deferred_pass(LayoutBuilder& b) {
    std::vector<BindingDesc> deferred_inputs;
    for (const ParamDesc& p : b.params_of("shading_deferred"))
        if (p.binding >= 0) deferred_inputs.push_back({p.name, p.texture, p.binding});
    b.pass("shading", "fullscreen", "shading_deferred", deferred_inputs, {{b.layout.result, 0, -1}}, {}, 0, 0, {},
           "screen");
}

} // namespace detail
} // namespace penumbra
