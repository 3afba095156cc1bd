// penumbra/layout_types.hpp — the structs of layout.json (Layout, TextureDesc, ProgramDesc,
// PassDesc, …): data only, cheap to include. penumbra/layout.hpp builds them (describe_layout) and
// writes them (to_json); the builder is detail/layout_builder.hpp.
#pragma once

#include "config.hpp"
#include "program.hpp"
#include "uniforms.hpp"

#include <array>
#include <optional>
#include <string>
#include <string_view>
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
    std::optional<UniformSource> source; // plain uniforms, and samplers set per draw: where the value comes
                                         // from (penumbra/uniforms.hpp); none for the layout's own samplers
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
    std::vector<Stage> stages;      // the stage of each file: stages[i] is that of files[i]
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

// The description of layout texture `name`; nullptr when the layout has none (the layout builder,
// the cost model, the GL runtime and the tests).
inline const TextureDesc* find_texture(const Layout& layout, std::string_view name) {
    for (const TextureDesc& t : layout.textures)
        if (t.name == name) return &t;
    return nullptr;
}

} // namespace detail

} // namespace penumbra
