// penumbra/layout_types.hpp — the structs of layout.json (Layout, TextureDesc, ProgramDesc,
// PassDesc, …) and the enums of its words (PassAction, Phase, TextureFilter, …): data only, cheap
// to include. penumbra/layout.hpp builds them (describe_layout) and writes them (to_json); the
// builder the technique folders describe their textures and passes with is detail/layout_builder.hpp.
//
// Every enum's names (EnumNames, penumbra/config.hpp: to_string, parse_enum) are exactly the words
// layout.json spells them with; strings exist only at that JSON edge. What follows from other fields
// is not stored but computed by the functions at the end (initial_contents, attachment_kind,
// copy_region, mipmap_range).
#pragma once

#include "config.hpp"
#include "formats.hpp"
#include "program.hpp"
#include "uniforms.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

namespace penumbra {

inline constexpr int layout_version = 3; // "layout_version" in layout.json

// GL_TEXTURE_… / VK_IMAGE_TYPE_… of a texture.
enum class TextureTarget : std::uint8_t { texture_2d, texture_2d_array, texture_3d };
template <> struct EnumNames<TextureTarget> {
    static constexpr std::array<std::string_view, 3> names{"2D", "2D_ARRAY", "3D"};
};

// GL_TEXTURE_MIN_FILTER / MAG_FILTER values (the mipmap ones for min_filter only).
enum class TextureFilter : std::uint8_t {
    nearest,
    linear,
    linear_mipmap_linear,
    nearest_mipmap_nearest,
    linear_mipmap_nearest,
    nearest_mipmap_linear,
};
template <> struct EnumNames<TextureFilter> {
    static constexpr std::array<std::string_view, 6> names{"NEAREST",
                                                           "LINEAR",
                                                           "LINEAR_MIPMAP_LINEAR",
                                                           "NEAREST_MIPMAP_NEAREST",
                                                           "LINEAR_MIPMAP_NEAREST",
                                                           "NEAREST_MIPMAP_LINEAR"};
};
// True when the filter reads texels linearly within a level (LINEAR, LINEAR_MIPMAP_*).
constexpr bool filters_linearly(TextureFilter f) {
    return f == TextureFilter::linear || f == TextureFilter::linear_mipmap_linear ||
           f == TextureFilter::linear_mipmap_nearest;
}
// True when the filter blends two mip levels (*_MIPMAP_LINEAR).
constexpr bool blends_levels(TextureFilter f) {
    return f == TextureFilter::linear_mipmap_linear || f == TextureFilter::nearest_mipmap_linear;
}

// Outside [0, 1]: the border colour (CLAMP_TO_BORDER; not in ES 3.0 / WebGL2) or the edge texel.
enum class Wrap : std::uint8_t { clamp_to_border, clamp_to_edge };
template <> struct EnumNames<Wrap> {
    static constexpr std::array<std::string_view, 2> names{"CLAMP_TO_BORDER", "CLAMP_TO_EDGE"};
};

// A depth test's or a depth comparison's function (GL_LESS, VK_COMPARE_OP_LESS, …).
enum class CompareFunc : std::uint8_t { never, less, equal, lequal, greater, notequal, gequal, always };
template <> struct EnumNames<CompareFunc> {
    static constexpr std::array<std::string_view, 8> names{"NEVER",   "LESS",     "EQUAL",  "LEQUAL",
                                                           "GREATER", "NOTEQUAL", "GEQUAL", "ALWAYS"};
};

// The one compare function of every depth comparison (sampler2DShadow): lit where the receiver's
// depth <= the stored, biased occluder depth.
inline constexpr CompareFunc shadow_compare_func = CompareFunc::lequal;

// "fixed": width × height; "output": the output image's size (per frame).
enum class TextureSize : std::uint8_t { fixed, output };
template <> struct EnumNames<TextureSize> {
    static constexpr std::array<std::string_view, 2> names{"fixed", "output"};
};

// Who writes a texture: the layout's passes, the engine every frame ("caller"), or an offline bake
// uploaded once ("bake").
enum class TextureSource : std::uint8_t { passes, caller, bake };
template <> struct EnumNames<TextureSource> {
    static constexpr std::array<std::string_view, 3> names{"passes", "caller", "bake"};
};

// What a texture holds before the first pass writes it: "zero" (every level cleared to 0 once, at
// allocation: passes that blend, OR or read outside what they wrote rely on it), or what the caller
// or the bake put there. Follows from the source (initial_contents).
enum class TextureInitial : std::uint8_t { zero, caller, bake };
template <> struct EnumNames<TextureInitial> {
    static constexpr std::array<std::string_view, 3> names{"zero", "caller", "bake"};
};

// "shadow": run when the scene or the light changes (Runtime::build); "screen": run every frame at
// the output size over the caller's textures (Runtime::run_screen); "example": drawn by the engine
// itself with its camera (the runtime does not run it).
enum class Phase : std::uint8_t { shadow, screen, example };
template <> struct EnumNames<Phase> {
    static constexpr std::array<std::string_view, 3> names{"shadow", "screen", "example"};
};

// What a pass does. draw_scene: draw the caller's geometry with its program; fullscreen: draw 3
// vertices with its program; generate_mipmap: the mipmap chain of outputs[0] (mipmap_range); copy:
// the region copy_region says, from inputs[0] into outputs[0]; dispatch: run the compute program over
// dispatch.groups with the inputs bound as samplers and dispatch.images as images (no outputs).
enum class PassAction : std::uint8_t { draw_scene, fullscreen, generate_mipmap, copy, dispatch };
template <> struct EnumNames<PassAction> {
    static constexpr std::array<std::string_view, 5> names{"draw_scene", "fullscreen", "generate_mipmap", "copy",
                                                           "dispatch"};
};

// A colour attachment (the i-th colour output) or the depth attachment; follows from the texture's
// format (attachment_kind).
enum class AttachmentKind : std::uint8_t { color, depth };
template <> struct EnumNames<AttachmentKind> {
    static constexpr std::array<std::string_view, 2> names{"color", "depth"};
};

enum class BlendEquation : std::uint8_t { add, max, min };
template <> struct EnumNames<BlendEquation> {
    static constexpr std::array<std::string_view, 3> names{"ADD", "MAX", "MIN"};
};

enum class BlendFactor : std::uint8_t { zero, one, src_alpha, one_minus_src_alpha, dst_color };
template <> struct EnumNames<BlendFactor> {
    static constexpr std::array<std::string_view, 5> names{"ZERO", "ONE", "SRC_ALPHA", "ONE_MINUS_SRC_ALPHA",
                                                           "DST_COLOR"};
};

enum class Cull : std::uint8_t { none, back, front };
template <> struct EnumNames<Cull> {
    static constexpr std::array<std::string_view, 3> names{"NONE", "BACK", "FRONT"};
};

// bitwise_or: each fragment OR-ed into the (integer) target instead of blending.
enum class LogicOp : std::uint8_t { none, bitwise_or };
template <> struct EnumNames<LogicOp> {
    static constexpr std::array<std::string_view, 2> names{"NONE", "OR"};
};

enum class ImageAccess : std::uint8_t { write_only, read_only, read_write };
template <> struct EnumNames<ImageAccess> {
    static constexpr std::array<std::string_view, 3> names{"WRITE_ONLY", "READ_ONLY", "READ_WRITE"};
};

// What the passes after a dispatch need of what it wrote: texture_fetch (they sample it),
// texture_update (it may be read back or copied), shader_image_access (images), framebuffer.
enum class MemoryBarrierBit : std::uint8_t { texture_fetch, texture_update, shader_image_access, framebuffer };
template <> struct EnumNames<MemoryBarrierBit> {
    static constexpr std::array<std::string_view, 4> names{"TEXTURE_FETCH", "TEXTURE_UPDATE", "SHADER_IMAGE_ACCESS",
                                                           "FRAMEBUFFER"};
};

// How one binding samples its texture: a sampler object (GL 3.3+, ES 3.0, WebGL2) or a VkSampler.
// The texture's own filters and wrap are its defaults; a binding may read the same texture another
// way (PCSS reads its shadow map NEAREST without comparison for the blocker search and LINEAR with
// comparison for the filter, through two samplers).
struct Sampling {
    TextureFilter min_filter = TextureFilter::nearest, mag_filter = TextureFilter::nearest;
    Wrap wrap = Wrap::clamp_to_edge;
    std::array<float, 4> border_color{0.0f, 0.0f, 0.0f, 0.0f}; // used when wrap is clamp_to_border
    std::optional<CompareFunc> compare; // none: a plain read; else a depth comparison (sampler*Shadow)

    // an order, so that a runner keeps one sampler object per distinct sampling (a map key)
    friend bool operator<(const Sampling& a, const Sampling& b) {
        return std::tie(a.min_filter, a.mag_filter, a.wrap, a.border_color, a.compare) <
               std::tie(b.min_filter, b.mag_filter, b.wrap, b.border_color, b.compare);
    }
    friend bool operator==(const Sampling&, const Sampling&) = default;
};

// A texture; fill it with designated initializers (LayoutBuilder::texture), e.g.
//   {.name = "penumbra_scratch", .format = TextureFormat::rgba16f, .width = R, .height = R,
//    .purpose = "level being built"}
struct TextureDesc {
    std::string name{};
    TextureTarget target = TextureTarget::texture_2d;
    TextureFormat format = TextureFormat::rgba8; // layout.json "internal_format"
    int width = 0, height = 0; // 0 × 0 when size is output
    int depth = 1;             // layers of a 2D array, depth of a 3D texture, 1 otherwise
    int mip_levels = 1;
    TextureFilter min_filter = TextureFilter::nearest, mag_filter = TextureFilter::nearest;
    Wrap wrap = Wrap::clamp_to_edge;
    std::array<float, 4> border_color{0.0f, 0.0f, 0.0f, 0.0f}; // used when wrap is clamp_to_border
    TextureSize size = TextureSize::fixed;
    TextureSource source = TextureSource::passes;
    std::string purpose{};
};

struct ParamDesc {
    std::string name, type, meaning, units;
    std::optional<UniformSource> source; // plain uniforms, and samplers set per draw: where the value comes
                                         // from (penumbra/uniforms.hpp); none for the layout's own samplers
    std::string compute;         // plain uniforms: how to compute the value (formula, light_frame.hpp field)
    int binding = -1;            // sampler: texture unit / Vulkan binding; -1 for plain uniforms
    std::string texture;         // sampler: the texture bound to it when the program runs its usual pass
    // sampler: the filter it reads its texture with when not the texture's own (both min and mag)
    std::optional<TextureFilter> filter;
    // sampler: how it reads its texture (finish_sampling fills it); none for plain uniforms and for a
    // draw's sampler (the caller's texture and sampler)
    std::optional<Sampling> sampling;
    std::string block;           // Vulkan: uniform block holding this value
    int block_binding = -1;      // Vulkan: binding of that block
    int offset = -1;             // Vulkan: std140 byte offset in the block
    int set = -1;                // Vulkan: descriptor set of the block or sampler (vulkan_descriptor_set); WGSL: bind group
    // WGSL and HLSL: a sampler parameter binds its texture at `binding` and its sampler at `sampler_binding`
    // (-1: none, texels are fetched); the texture's WGSL type ("texture_depth_2d", "texture_2d<f32>") or
    // HLSL type ("Texture2D<float>"). HLSL's registers are these numbers: b<block_binding>, t<binding>,
    // s<sampler_binding>, in space <set>.
    int sampler_binding = -1;
    std::string texture_type;
    // MSL (target msl; penumbra/msl.hpp fills them): the Metal argument-table indices of the parameter's
    // buffer, or of its texture and sampler, the same in every stage of the program; -1: none
    int msl_buffer = -1, msl_texture = -1, msl_sampler = -1;
};

// A vertex attribute of a program that draws the caller's geometry (draw_scene).
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

// Where a pass renders: level `level` (and layer `layer` of an array / depth slice of a 3D texture;
// -1 for a 2D texture) of `texture`, as a colour or the depth attachment (attachment_kind).
struct AttachmentDesc {
    std::string texture{};
    int level = 0;
    int layer = -1;
};

struct BindingDesc {
    std::string sampler{}; // parameter name in the program
    std::string texture{};
    int binding = 0;     // filled by LayoutBuilder::pass from the program's parameters
    int level = -1;      // -1: all levels; n: the pass reads only level n (base = max level = n while it
                         // runs), so it may render another level of the same texture (min-max mip chains)
    Sampling sampling{}; // how this binding reads the texture (that of its sampler parameter; finish_sampling)
};

// Fixed-function state of a pass. Blend, depth test and culling are off unless set; polygon
// offset is on when factor or units is non-zero.
struct RenderState {
    bool blend = false;
    BlendEquation blend_equation = BlendEquation::add;
    BlendFactor blend_src = BlendFactor::one, blend_dst = BlendFactor::zero;
    bool depth_test = false;
    CompareFunc depth_func = CompareFunc::less;
    bool depth_write = false;
    std::array<bool, 4> color_mask{true, true, true, true};
    Cull cull = Cull::none;
    std::optional<std::array<float, 4>> clear_color{}; // cleared before drawing when set
    std::optional<float> clear_depth{};
    float polygon_offset_factor = 0.0f, polygon_offset_units = 0.0f; // slope-scaled depth bias
    // a logical operation combines each fragment with the (integer) target instead of blending
    // (glLogicOp / VkPipelineColorBlendStateCreateInfo::logicOp); blend is then false
    LogicOp logic_op = LogicOp::none;
};

// An image a dispatch pass writes (glBindImageTexture(unit, texture, level, layered, layer, access,
// format)): the compute program's image uniform `image` at image unit `unit`, in the texture's format.
struct ImageBindingDesc {
    std::string image{}; // the image uniform in the program, e.g. penumbra_output0
    std::string texture{};
    int level = 0;
    int layer = -1;      // -1: a 2D texture (not layered)
    int unit = 0;        // image unit (layout(binding = …) of the image uniform)
    ImageAccess access = ImageAccess::write_only;
};

// What a dispatch pass runs: glDispatchCompute(groups) of its compute program, then glMemoryBarrier
// with the bits the passes after it need.
struct DispatchDesc {
    std::array<int, 3> groups{1, 1, 1};     // workgroups in x, y, z
    std::array<int, 3> local_size{1, 1, 1}; // invocations per workgroup (the program's local_size, for information)
    std::vector<MemoryBarrierBit> memory_barrier{};
    std::vector<ImageBindingDesc> images{}; // layout.json "image_outputs": the images it writes
};

// A pass; fill it with designated initializers (LayoutBuilder::pass), e.g.
//   {.name = "copy_level", .action = PassAction::copy, .inputs = {{"", "penumbra_scratch"}},
//    .outputs = {{storage, 0, layer}}, .viewport_width = R, .viewport_height = R}
// (Every member has a default member initializer, so that GCC's -Wmissing-field-initializers
// leaves designated initializers that name only some of them alone.)
struct PassDesc {
    std::string name{};
    PassAction action = PassAction::fullscreen;
    std::string program{}; // "" for generate_mipmap and copy
    std::vector<BindingDesc> inputs{};
    std::vector<AttachmentDesc> outputs{};
    std::vector<std::pair<std::string, int>> int_uniforms{};
    int viewport_width = 0, viewport_height = 0; // 0 × 0: the size of outputs[0] (phase screen: the output size)
    RenderState state{};
    Phase phase = Phase::shadow;
    DispatchDesc dispatch{}; // action dispatch only
};

// Where slice k of the occlusion textures is after the slicing (and unpack) passes: texture and layer
// (-1: a 2D texture; the depth index of a 3D texture); its channel is "rgba"[k % 4] (slice_channel).
// The occlusion technique only; slice k is in channel k % 4 of RGBA texture k / 4.
struct SliceLocation {
    int slice = 0;
    std::string texture;
    int layer = -1;
};
constexpr char slice_channel(const SliceLocation& at) { return "rgba"[at.slice % 4]; }

struct Layout {
    int version = layout_version;
    Config config; // its technique is layout.json's "technique"
    int textures_per_layer = 0; // T: RGBA occlusion textures, four slices each
    int max_level = 0;          // L: the highest filter level built, log2(resolution) or config.level_bound
    std::vector<TextureDesc> textures;
    std::vector<ProgramDesc> programs;
    std::vector<PassDesc> passes;
    std::string result; // the texture holding the visibility after the screen phase
    std::vector<std::string> files; // every file an emission writes, layout.json included
    // What each phase's output depends on ("light", "geometry", "camera", "caller_textures", "bake";
    // "materials": the casters' alpha textures and cutoffs, with alpha_test):
    // an engine reruns a phase only when one of them changed (a camera-only change skips shadow).
    std::vector<std::pair<Phase, std::vector<std::string>>> phase_inputs;
    std::vector<SliceLocation> slice_map; // occlusion: where each slice is (empty for other techniques)
};

// The description of layout texture `name`; nullptr when the layout has none.
inline const TextureDesc* find_texture(const Layout& layout, std::string_view name) {
    for (const TextureDesc& t : layout.textures)
        if (t.name == name) return &t;
    return nullptr;
}

// What a texture holds before the first pass writes it: zeros for the passes' own textures, else
// what its source (the caller, the bake) put there.
constexpr TextureInitial initial_contents(const TextureDesc& t) {
    return t.source == TextureSource::caller ? TextureInitial::caller
           : t.source == TextureSource::bake ? TextureInitial::bake
                                             : TextureInitial::zero;
}

// A depth texture is the depth attachment, any other a colour attachment.
inline AttachmentKind attachment_kind(const Layout& layout, const AttachmentDesc& out) {
    const TextureDesc* t = find_texture(layout, out.texture);
    return t && is_depth(t->format) ? AttachmentKind::depth : AttachmentKind::color;
}

// What a copy pass copies: a width × height region (its viewport), texel for texel (no filtering, no
// format conversion), from level/layer of inputs[0].texture to level/layer of outputs[0].texture
// (layer -1: a 2D texture). glCopyImageSubData, vkCmdCopyImage, or a framebuffer blit with NEAREST.
struct CopyDesc {
    int source_level = 0, source_layer = -1;
    int target_level = 0, target_layer = -1;
    int width = 0, height = 0;
};
// Precondition: pass.action is copy, with one input and one output.
inline CopyDesc copy_region(const PassDesc& pass) {
    const BindingDesc& in = pass.inputs.at(0);
    const AttachmentDesc& out = pass.outputs.at(0);
    return {in.level < 0 ? 0 : in.level, -1, out.level, out.layer, pass.viewport_width, pass.viewport_height};
}

// What a generate_mipmap pass computes: levels base_level + 1 … base_level + levels - 1 of
// outputs[0].texture, each the 2×2 box average of the one below (glGenerateMipmap; on Vulkan a chain of
// vkCmdBlitImage with LINEAR filtering, which averages the same 2×2 texels; layout.json's
// "downsample": "box").
struct MipmapDesc {
    int base_level = 0;
    int levels = 1;
};
// Precondition: pass.action is generate_mipmap, with one output.
inline MipmapDesc mipmap_range(const Layout& layout, const PassDesc& pass) {
    const AttachmentDesc& out = pass.outputs.at(0);
    const TextureDesc* t = find_texture(layout, out.texture);
    return {out.level, (t ? t->mip_levels : 1) - out.level};
}

namespace detail {
using penumbra::find_texture; // (was detail::find_texture)
} // namespace detail

} // namespace penumbra
