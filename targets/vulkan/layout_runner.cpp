#include "layout_runner.hpp"

#include <penumbra/detail/problem.hpp>
#include <penumbra/layout_types.hpp>
#include <penumbra/program.hpp>
#include <penumbra/validation.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <array>
#include <functional>
#include <optional>
#include <sstream>

namespace penumbra::vulkan {
namespace {

using nlohmann::json;

// Thrown inside the runner for any failure; run_layout turns it into its diagnostic.
struct Failure {
    std::string message;
};

[[noreturn]] void fail(std::string message) { throw Failure{std::move(message)}; }

void check(VkResult result, const std::string& what) {
    if (result != VK_SUCCESS) fail(what + ": " + result_name(result));
}

// layout.json's internal formats: the Vulkan format, and what penumbra/formats.hpp says of the
// floats a texel holds.
struct FormatInfo {
    VkFormat format = VK_FORMAT_UNDEFINED;
    int channels = 0;
    int bytes_per_channel = 0;
    bool normalized = false; // UNORM: stored as bytes, read as value / 255
    bool depth = false;      // a depth format: depth attachments, comparison samplers, DEPTH aspect
    bool integer = false;    // an unsigned integer format: NEAREST only, no blending
    VkImageAspectFlags aspect() const { return depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT; }
};

// DEPTH_COMPONENT24 is X8_D24_UNORM_PACK32, which Vulkan does not require (it requires depth
// attachments of X8_D24_UNORM_PACK32 or D32_SFLOAT): the caller checks the device's support.
VkFormat vk_format(TextureFormat f) {
    switch (f) {
    case TextureFormat::rgba8: return VK_FORMAT_R8G8B8A8_UNORM;
    case TextureFormat::rgba16f: return VK_FORMAT_R16G16B16A16_SFLOAT;
    case TextureFormat::rgba32f: return VK_FORMAT_R32G32B32A32_SFLOAT;
    case TextureFormat::r8: return VK_FORMAT_R8_UNORM;
    case TextureFormat::r16f: return VK_FORMAT_R16_SFLOAT;
    case TextureFormat::r32f: return VK_FORMAT_R32_SFLOAT;
    case TextureFormat::rg16f: return VK_FORMAT_R16G16_SFLOAT;
    case TextureFormat::rg32f: return VK_FORMAT_R32G32_SFLOAT;
    case TextureFormat::rgba32ui: return VK_FORMAT_R32G32B32A32_UINT; // the slicing bits of 64 / 128 slices
    case TextureFormat::r32ui: return VK_FORMAT_R32_UINT;             // adaptive slice boundaries
    case TextureFormat::depth24: return VK_FORMAT_X8_D24_UNORM_PACK32;
    case TextureFormat::depth32f: return VK_FORMAT_D32_SFLOAT; // shadow maps
    }
    return VK_FORMAT_UNDEFINED;
}

FormatInfo format_info(const std::string& name) {
    const std::optional<TextureFormat> f = parse_enum<TextureFormat>(name);
    if (!f)
        fail("internal format '" + name + "' is not supported by this runner; allowed: " +
             penumbra::detail::joined_names<TextureFormat>().str());
    return {vk_format(*f),
            channels(*f),
            bytes_per_channel(*f),
            penumbra::format_info(*f).kind == FormatKind::unorm,
            is_depth(*f),
            is_integer(*f)};
}

// The layout enum layout.json spells `key` of `j` with (`fallback` when absent and not empty):
// strings end here. Fails with "<what>: <key> '<word>' is unknown; allowed: …".
template <class Enum> Enum word(const json& j, const char* key, const std::string& what, std::string_view fallback = {}) {
    if (!j.contains(key) && fallback.empty()) fail(what + ": no " + key);
    const std::string name = j.contains(key) ? j.at(key).get<std::string>() : std::string(fallback);
    if (const std::optional<Enum> value = parse_enum<Enum>(name)) return *value;
    fail(what + ": " + key + " '" + name + "' is unknown; allowed: " + penumbra::detail::joined_names<Enum>().str());
}

VkFilter filter_of(TextureFilter f) { return filters_linearly(f) ? VK_FILTER_LINEAR : VK_FILTER_NEAREST; }

VkCompareOp compare_op(CompareFunc f) {
    switch (f) {
    case CompareFunc::never: return VK_COMPARE_OP_NEVER;
    case CompareFunc::less: return VK_COMPARE_OP_LESS;
    case CompareFunc::equal: return VK_COMPARE_OP_EQUAL;
    case CompareFunc::lequal: return VK_COMPARE_OP_LESS_OR_EQUAL;
    case CompareFunc::greater: return VK_COMPARE_OP_GREATER;
    case CompareFunc::notequal: return VK_COMPARE_OP_NOT_EQUAL;
    case CompareFunc::gequal: return VK_COMPARE_OP_GREATER_OR_EQUAL;
    case CompareFunc::always: return VK_COMPARE_OP_ALWAYS;
    }
    return VK_COMPARE_OP_NEVER;
}

// How one binding reads its texture (penumbra::Sampling): layout.json's "sampling" (layout_version
// 3: per pass input and per sampler parameter), or for version 2 the texture's own filters, wrap
// and compare.
Sampling parse_sampling(const json& j, const std::string& what) {
    Sampling s;
    s.min_filter = word<TextureFilter>(j, "min_filter", what);
    s.mag_filter = word<TextureFilter>(j, "mag_filter", what);
    if (s.mag_filter != TextureFilter::nearest && s.mag_filter != TextureFilter::linear)
        fail(what + ": mag_filter '" + std::string(to_string(s.mag_filter)) + "' is unknown; allowed: NEAREST, LINEAR");
    s.wrap = word<Wrap>(j, "wrap", what);
    if (s.wrap == Wrap::clamp_to_border) {
        if (!j.contains("border_color")) fail(what + ": wrap CLAMP_TO_BORDER without a border_color");
        const std::vector<float> border = j.at("border_color").get<std::vector<float>>();
        if (border.size() != 4) fail(what + ": border_color is not 4 numbers");
        std::copy(border.begin(), border.end(), s.border_color.begin());
    }
    if (!j.value("compare", std::string()).empty()) s.compare = word<CompareFunc>(j, "compare", what);
    return s;
}
bool linear(const Sampling& s) { return filters_linearly(s.min_filter) || filters_linearly(s.mag_filter); }
bool mipmapped(const Sampling& s) {
    return s.min_filter != TextureFilter::nearest && s.min_filter != TextureFilter::linear;
}

VkSamplerAddressMode address_mode(Wrap wrap) {
    return wrap == Wrap::clamp_to_border ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
}

// Core Vulkan has three border colours; others need VK_EXT_custom_border_color.
// `integer`: the sampler reads an integer texture (usampler), whose border is an integer colour.
VkBorderColor border_color(const std::array<float, 4>& c, bool integer) {
    if (c == std::array<float, 4>{0, 0, 0, 0}) return integer ? VK_BORDER_COLOR_INT_TRANSPARENT_BLACK : VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    if (c == std::array<float, 4>{0, 0, 0, 1}) return integer ? VK_BORDER_COLOR_INT_OPAQUE_BLACK : VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
    if (c == std::array<float, 4>{1, 1, 1, 1}) return integer ? VK_BORDER_COLOR_INT_OPAQUE_WHITE : VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    fail("border colour is not one of core Vulkan's (0,0,0,0), (0,0,0,1), (1,1,1,1)");
}

VkBlendOp blend_op(BlendEquation e) {
    switch (e) {
    case BlendEquation::add: return VK_BLEND_OP_ADD;
    case BlendEquation::max: return VK_BLEND_OP_MAX;
    case BlendEquation::min: return VK_BLEND_OP_MIN;
    }
    return VK_BLEND_OP_ADD;
}

VkBlendFactor blend_factor(BlendFactor f) {
    switch (f) {
    case BlendFactor::zero: return VK_BLEND_FACTOR_ZERO;
    case BlendFactor::one: return VK_BLEND_FACTOR_ONE;
    case BlendFactor::src_alpha: return VK_BLEND_FACTOR_SRC_ALPHA;
    case BlendFactor::one_minus_src_alpha: return VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::dst_color: return VK_BLEND_FACTOR_DST_COLOR;
    }
    return VK_BLEND_FACTOR_ZERO;
}

VkCullModeFlags cull_mode(Cull c) {
    return c == Cull::back ? VK_CULL_MODE_BACK_BIT : c == Cull::front ? VK_CULL_MODE_FRONT_BIT : VK_CULL_MODE_NONE;
}

// std140 sizes of the plain uniform types an emission declares.
int std140_size(const std::string& type) {
    static const std::map<std::string, int> sizes{{"float", 4}, {"int", 4}, {"uint", 4}, {"vec2", 8}, {"ivec2", 8},
                                                  {"vec3", 12}, {"vec4", 16}, {"ivec4", 16}, {"mat4", 64}};
    auto it = sizes.find(type);
    if (it == sizes.end()) fail("uniform type '" + type + "' is not supported by this runner");
    return it->second;
}

// layout.json's "stages" word of a file ("vertex", "fragment", "compute").
std::optional<Stage> stage_named(const std::string& word) {
    for (Stage s : {Stage::vertex, Stage::fragment, Stage::compute})
        if (word == stage_name(s)) return s;
    return std::nullopt;
}

VkShaderStageFlagBits vk_stage(Stage stage) {
    switch (stage) {
    case Stage::vertex: return VK_SHADER_STAGE_VERTEX_BIT;
    case Stage::fragment: return VK_SHADER_STAGE_FRAGMENT_BIT;
    case Stage::compute: return VK_SHADER_STAGE_COMPUTE_BIT;
    }
    return VK_SHADER_STAGE_FRAGMENT_BIT;
}

std::string read_text(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) fail("cannot read " + path.string() + " (listed in layout.json)");
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

// Vulkan 1.0's required limits (specification, "Required Limits"): a layout for the vulkan target
// must stay within them to run on every conforming device, whatever this device offers. Kept
// apart from penumbra's own table (detail/target_limits.hpp) on purpose: this is the check of it.
struct RequiredLimits {
    static constexpr int image_dimension_2d = 4096, image_dimension_3d = 256, image_array_layers = 256;
    static constexpr int color_attachments = 4, framebuffer_size = 4096;
    static constexpr int per_stage_samplers = 16, per_stage_uniform_buffers = 12, uniform_buffer_range = 16384;
    static constexpr int bound_descriptor_sets = 4;
};

void check_required_limits(const json& layout) {
    using L = RequiredLimits;
    for (const json& t : layout.at("textures")) {
        const std::string name = t.at("name");
        const TextureTarget target = word<TextureTarget>(t, "target", "texture " + name);
        const int w = t.at("width"), h = t.at("height"), d = t.at("depth");
        const bool volume = target == TextureTarget::texture_3d;
        const int max_side = volume ? L::image_dimension_3d : L::image_dimension_2d;
        if (w > max_side || h > max_side || (volume && d > L::image_dimension_3d) ||
            (target == TextureTarget::texture_2d_array && d > L::image_array_layers))
            fail("texture " + name + ": " + std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(d) +
                 " exceeds what Vulkan guarantees for a " + std::string(to_string(target)) + " image (2D " + std::to_string(L::image_dimension_2d) +
                 ", 3D " + std::to_string(L::image_dimension_3d) + ", layers " + std::to_string(L::image_array_layers) + ")");
    }
    for (const json& p : layout.at("passes")) {
        const std::string name = p.at("name");
        std::size_t colour = 0;
        for (const json& o : p.at("outputs"))
            colour += word<AttachmentKind>(o, "kind", "pass " + name, "color") == AttachmentKind::color;
        if (colour > static_cast<std::size_t>(L::color_attachments))
            fail("pass " + name + ": " + std::to_string(colour) + " colour attachments; Vulkan guarantees " +
                 std::to_string(L::color_attachments));
        if (p.at("viewport").at(0).get<int>() > L::framebuffer_size || p.at("viewport").at(1).get<int>() > L::framebuffer_size)
            fail("pass " + name + ": viewport beyond Vulkan's guaranteed framebuffer size " + std::to_string(L::framebuffer_size));
    }
    for (const json& p : layout.at("programs")) {
        int samplers = 0;
        std::map<int, int> blocks; // binding → bytes used
        for (const json& param : p.at("parameters")) {
            if ((param.contains("binding") || param.contains("block_binding")) &&
                param.value("set", 0) >= L::bound_descriptor_sets)
                fail("program " + p.at("name").get<std::string>() + ": parameter " + param.at("name").get<std::string>() +
                     " is in descriptor set " + std::to_string(param.value("set", 0)) + "; Vulkan guarantees sets 0 to " +
                     std::to_string(L::bound_descriptor_sets - 1));
            if (param.value("set", 0) < 0)
                fail("program " + p.at("name").get<std::string>() + ": parameter " + param.at("name").get<std::string>() +
                     " has a negative descriptor set");
            if (param.contains("block_binding"))
                blocks[param.at("block_binding").get<int>()] =
                    std::max(blocks[param.at("block_binding").get<int>()], param.at("offset").get<int>() + std140_size(param.at("type")));
            else if (param.contains("binding"))
                ++samplers;
        }
        const std::string name = p.at("name");
        if (samplers > L::per_stage_samplers)
            fail("program " + name + ": " + std::to_string(samplers) + " samplers; Vulkan guarantees " +
                 std::to_string(L::per_stage_samplers) + " per stage");
        if (blocks.size() > static_cast<std::size_t>(L::per_stage_uniform_buffers))
            fail("program " + name + ": more uniform blocks than Vulkan guarantees");
        for (const auto& [binding, bytes] : blocks)
            if (bytes > L::uniform_buffer_range)
                fail("program " + name + ": uniform block " + std::to_string(binding) + " beyond Vulkan's guaranteed range");
    }
}

struct Texture {
    std::string name;
    TextureTarget target = TextureTarget::texture_2d;
    FormatInfo format;
    std::uint32_t width = 0, height = 0, depth = 1, levels = 1;
    // zero, caller, bake (layout_version 3; else from "source"); none: "undefined", this runner's
    // own word for a texture it need not clear (every texel the passes read is written first)
    std::optional<TextureInitial> initial;
    const json* desc = nullptr;
    VkImage image = VK_NULL_HANDLE;
    std::uint32_t layers() const { return target == TextureTarget::texture_2d_array ? depth : 1; }
    std::uint32_t extent_depth() const { return target == TextureTarget::texture_3d ? depth : 1; }
};

struct Block {
    int size = 0;
    std::vector<json> members;
};

// Where a parameter lives: descriptor set ("set", 0 when absent) and binding.
using SetBinding = std::pair<int, int>;

struct VertexInputs {
    int position = -1, normal = -1; // attribute locations; -1: not read
};

struct Program {
    const json* desc = nullptr;
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    std::vector<VkDescriptorSetLayout> set_layouts; // index = set number, empty layouts in gaps
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
    std::map<SetBinding, Block> blocks;  // uniform blocks
    std::map<SetBinding, json> samplers; // sampler parameters
    VertexInputs vertex_inputs;
};

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    void* mapped = nullptr;
};

class Runner {
public:
    Runner(const Context& context, const LayoutInputs& inputs) : c_(context), in_(inputs), device_(context.device()) {}
    ~Runner() {
        vkDeviceWaitIdle(device_);
        for (auto it = cleanup_.rbegin(); it != cleanup_.rend(); ++it) (*it)();
    }
    Runner(const Runner&) = delete;
    Runner& operator=(const Runner&) = delete;

    void run(LayoutOutput& out) {
        const json& layout = in_.layout;
        const int version = layout.value("layout_version", 1);
        if (version < 2 || version > 3)
            fail("layout.json has layout_version " + std::to_string(version) +
                 "; this runner follows versions 2 (structured render state, pass phases, texture sizes and sources) "
                 "and 3 (per-binding sampling, vertex inputs, descriptor sets, initial contents, copy and mipmap details)");
        // The vulkan target's GLSL, or the hlsl target's HLSL (compiled by glslang's HLSL front end,
        // each texture and its sampler bound apart as layout.json's sampler_binding says).
        target_ =
            parse_enum<Target>(layout.at("config").at("target").get<std::string>()).value_or(Target::glsl450);
        if (target_ != Target::vulkan && target_ != Target::hlsl)
            fail("layout.json is for target '" + layout.at("config").at("target").get<std::string>() +
                 "'; this runner needs the vulkan or hlsl target's");
        check_required_limits(layout);
        std::vector<const json*> passes;
        for (const Phase phase : {Phase::shadow, Phase::screen})
            for (const json& pass : layout.at("passes"))
                if (word<Phase>(pass, "phase", "pass " + pass.value("name", std::string())) == phase) passes.push_back(&pass);
        for (const json& t : layout.at("textures")) create_texture(t, passes);
        vertices_ = create_buffer(std::max<std::size_t>(2 * in_.triangles.size() * sizeof(float), 16),
                                  VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        fill_vertices(static_cast<float*>(vertices_.mapped));
        create_descriptor_pool(passes.size());
        const Texture& result = texture(layout.at("result").get<std::string>());
        if (result.format.depth || result.format.integer || (result.format.bytes_per_channel == 2))
            fail("result texture " + result.name + ": reading back " + result.desc->at("internal_format").get<std::string>() +
                 " is not supported by this runner; allowed: 8-bit unorm or 32-bit float formats");
        const std::size_t result_bytes = static_cast<std::size_t>(result.width) * result.height *
                                         result.format.channels * result.format.bytes_per_channel;
        const Buffer readback = create_buffer(result_bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
        std::vector<std::function<void(VkCommandBuffer)>> commands;
        // Build every pipeline and descriptor set before recording: failures surface as messages here.
        for (const json* pass : passes) {
            commands.push_back(prepare_pass(*pass));
            out.passes.push_back(pass->at("name").get<std::string>());
        }
        std::vector<Buffer> uploads = stage_caller_textures();
        const std::string error = c_.submit([&](VkCommandBuffer cmd) {
            initialise_images(cmd, uploads);
            for (auto& record : commands) {
                record(cmd);
                barrier(cmd);
            }
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {result.width, result.height, 1};
            const VkImageSubresourceRange level0{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
            transition(cmd, result.image, level0, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            vkCmdCopyImageToBuffer(cmd, result.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback.buffer, 1, &region);
        });
        if (!error.empty()) fail(error);
        out.result = to_floats(result, readback.mapped);
    }

private:
    template <class F> void on_cleanup(F f) { cleanup_.emplace_back(std::move(f)); }

    // What draw_scene passes draw: per vertex the world position (location of penumbra_position)
    // and the triangle's unit face normal (penumbra_normal: the bundle has positions only, and its
    // scenes are flat-shaded), interleaved, 6 floats a vertex.
    void fill_vertices(float* out) const {
        const std::vector<float>& t = in_.triangles;
        for (std::size_t tri = 0; tri + 9 <= t.size(); tri += 9) {
            const float e1[3] = {t[tri + 3] - t[tri], t[tri + 4] - t[tri + 1], t[tri + 5] - t[tri + 2]};
            const float e2[3] = {t[tri + 6] - t[tri], t[tri + 7] - t[tri + 1], t[tri + 8] - t[tri + 2]};
            float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
            const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            for (float& c : n) c = length > 0 ? c / length : 0.0f;
            for (int v = 0; v < 3; ++v) {
                float* vertex = out + 2 * (tri + 3 * v);
                std::memcpy(vertex, &t[tri + 3 * v], 3 * sizeof(float));
                std::memcpy(vertex + 3, n, 3 * sizeof(float));
            }
        }
    }

    Texture& texture(const std::string& name) {
        auto it = textures_.find(name);
        if (it == textures_.end()) fail("texture '" + name + "' is used by a pass but not listed in textures");
        return it->second;
    }

    VkDeviceMemory allocate(VkMemoryRequirements req, VkMemoryPropertyFlags flags, const std::string& what) {
        int type = c_.memory_type(req.memoryTypeBits, flags);
        if (type < 0) fail(what + ": no suitable memory type");
        VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
        info.allocationSize = req.size;
        info.memoryTypeIndex = static_cast<std::uint32_t>(type);
        VkDeviceMemory memory = VK_NULL_HANDLE;
        check(vkAllocateMemory(device_, &info, nullptr, &memory), what + ": vkAllocateMemory");
        on_cleanup([this, memory] { vkFreeMemory(device_, memory, nullptr); });
        return memory;
    }

    // A host-visible, coherent buffer, mapped for its lifetime.
    Buffer create_buffer(std::size_t bytes, VkBufferUsageFlags usage) {
        Buffer b;
        VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
        info.size = bytes;
        info.usage = usage;
        check(vkCreateBuffer(device_, &info, nullptr, &b.buffer), "vkCreateBuffer");
        VkBuffer handle = b.buffer;
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(device_, b.buffer, &req);
        VkDeviceMemory memory = allocate(req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, "buffer");
        on_cleanup([this, handle] { vkDestroyBuffer(device_, handle, nullptr); }); // before its memory is freed
        check(vkBindBufferMemory(device_, b.buffer, memory, 0), "vkBindBufferMemory");
        check(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &b.mapped), "vkMapMemory");
        std::memset(b.mapped, 0, bytes);
        return b;
    }

    // The parameter `name` of program `program` (nullptr when there is none).
    const json* parameter(const std::string& program, const std::string& name) const {
        for (const json& p : in_.layout.at("programs"))
            if (p.at("name") == program)
                for (const json& param : p.at("parameters"))
                    if (param.at("name") == name) return &param;
        return nullptr;
    }

    // How a pass input is read: its "sampling" (version 3), else its sampler parameter's, else
    // (version 2) the texture's filters, wrap and compare.
    Sampling input_sampling(const json& pass, const json& input) const {
        const std::string sampler = input.at("sampler"), tex = input.at("texture");
        const std::string what = "pass " + pass.at("name").get<std::string>() + ", sampler " + sampler;
        if (input.contains("sampling")) return parse_sampling(input.at("sampling"), what);
        if (const json* param = parameter(pass.value("program", ""), sampler); param && param->contains("sampling"))
            return parse_sampling(param->at("sampling"), what);
        for (const json& t : in_.layout.at("textures"))
            if (t.at("name") == tex) return parse_sampling(t, "texture " + tex);
        fail(what + ": texture '" + tex + "' is not listed in textures");
    }

    // What the passes do with a texture decides its usage flags and the format features it needs.
    void create_texture(const json& t, const std::vector<const json*>& passes) {
        Texture tex;
        tex.desc = &t;
        tex.name = t.at("name").get<std::string>();
        const std::string format_name = t.at("internal_format").get<std::string>();
        const std::string what = "texture " + tex.name;
        try {
            tex.format = format_info(format_name);
        } catch (const Failure& f) {
            fail(what + ": " + f.message);
        }
        tex.target = word<TextureTarget>(t, "target", what);
        if (tex.format.depth && tex.target != TextureTarget::texture_2d)
            fail(what + ": a " + std::string(to_string(tex.target)) + " depth texture; this runner has 2D depth textures only");
        const bool output_sized = word<TextureSize>(t, "size", what) == TextureSize::output;
        tex.width = static_cast<std::uint32_t>(output_sized ? in_.width : t.at("width").get<int>());
        tex.height = static_cast<std::uint32_t>(output_sized ? in_.height : t.at("height").get<int>());
        tex.depth = static_cast<std::uint32_t>(t.at("depth").get<int>());
        tex.levels = static_cast<std::uint32_t>(t.at("mip_levels").get<int>());
        // layout_version 2 has no "initial": it follows from the source
        const TextureDesc source{.source = word<TextureSource>(t, "source", what, "passes")};
        if (t.value("initial", std::string()) != "undefined")
            tex.initial = word<TextureInitial>(t, "initial", what, to_string(initial_contents(source)));

        // DEPTH_COMPONENT24: X8_D24_UNORM_PACK32 where the device has it, else D32_SFLOAT (Vulkan
        // requires one of the two as a depth attachment; 32-bit float holds every 24-bit value).
        if (tex.format.format == VK_FORMAT_X8_D24_UNORM_PACK32) {
            VkFormatProperties p;
            vkGetPhysicalDeviceFormatProperties(c_.physical_device(), tex.format.format, &p);
            if (!(p.optimalTilingFeatures & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT))
                tex.format.format = VK_FORMAT_D32_SFLOAT;
        }

        VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT; // cleared or uploaded first
        VkFormatFeatureFlags features = VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
        bool attachment = false, compared = false;
        for (const json* pass : passes) {
            const std::string pass_name = pass->at("name");
            const PassAction action = word<PassAction>(*pass, "action", "pass " + pass_name);
            for (const json& o : pass->at("outputs")) {
                if (o.at("texture") != tex.name) continue;
                const AttachmentKind kind = word<AttachmentKind>(o, "kind", "pass " + pass_name, "color");
                if (action == PassAction::generate_mipmap) {
                    if (tex.format.depth || tex.format.integer)
                        fail("pass " + pass_name + ": generate_mipmap of " + format_name + " texture " + tex.name +
                             ": its box downsample is a linear blit, which Vulkan does not allow for depth or integer formats");
                    usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
                    features |= VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
                } else if (action == PassAction::copy) {
                    // TRANSFER_DST already
                } else if (kind == AttachmentKind::depth) {
                    if (!tex.format.depth)
                        fail("pass " + pass_name + ": depth output " + tex.name + " has the colour format " + format_name +
                             "; allowed: DEPTH_COMPONENT32F, DEPTH_COMPONENT24");
                    attachment = true;
                    usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
                    features |= VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT;
                } else {
                    if (tex.format.depth)
                        fail("pass " + pass_name + ": colour output " + tex.name + " has the depth format " + format_name +
                             "; a depth texture is written as an output of kind \"depth\"");
                    if (tex.format.integer && pass->at("state").at("blend").get<bool>())
                        fail("pass " + pass_name + ": blending into the integer texture " + tex.name +
                             "; Vulkan blends only float and normalized formats (integer targets: logic_op)");
                    attachment = true;
                    usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
                    features |= VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT;
                    if (pass->at("state").at("blend").get<bool>()) features |= VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT;
                }
            }
            for (const json& i : pass->at("inputs")) {
                if (i.at("texture") != tex.name) continue;
                if (action == PassAction::copy) {
                    usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
                    features |= VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
                    continue;
                }
                const Sampling sampling = input_sampling(*pass, i);
                const std::string reading = "pass " + pass_name + ", sampler " + i.at("sampler").get<std::string>();
                if (const json* param = parameter(pass->value("program", ""), i.at("sampler")))
                    check_sampler_type(sampling, param->at("type"), reading);
                usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
                features |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
                if (linear(sampling)) {
                    if (tex.format.integer)
                        fail(reading + ": LINEAR filtering of the integer texture " + tex.name + " (" + format_name +
                             "); Vulkan filters integer formats with NEAREST only");
                    // With depth comparison, LINEAR needs no FILTER_LINEAR feature (the specification
                    // allows it wherever comparison is supported, filtered "in an implementation-
                    // dependent manner" without the feature; lavapipe lacks it for D32_SFLOAT).
                    if (!sampling.compare) features |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
                }
                if (sampling.compare) {
                    if (!tex.format.depth)
                        fail(reading + ": compare '" + std::string(to_string(*sampling.compare)) + "' on the colour texture " + tex.name + " (" +
                             format_name + "); hardware comparison needs a depth format");
                    compared = true;
                }
            }
        }
        if (tex.name == in_.layout.at("result")) {
            usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
            features |= VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
        }
        VkFormatProperties3 props3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
        VkFormatProperties2 props2{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2};
        props2.pNext = &props3;
        vkGetPhysicalDeviceFormatProperties2(c_.physical_device(), tex.format.format, &props2);
        const VkFormatFeatureFlags have = props2.formatProperties.optimalTilingFeatures;
        if ((have & features) != features)
            fail(what + ": the device lacks format features 0x" + [&] {
                char hex[16];
                std::snprintf(hex, sizeof hex, "%x", features & ~have);
                return std::string(hex);
            }() + " of " + format_name + " that its passes need" +
                 ((features & ~have & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) && tex.format.depth
                      ? " (LINEAR filtering of a depth format read without comparison, which Vulkan does not require)"
                      : ""));
        if (compared && !(props3.optimalTilingFeatures & VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_DEPTH_COMPARISON_BIT))
            fail(what + ": the device cannot compare " + format_name + " in a sampler (SAMPLED_IMAGE_DEPTH_COMPARISON)");

        VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        // A depth slice of a 3D image is rendered through a 2D view of it.
        if (tex.target == TextureTarget::texture_3d && attachment) info.flags = VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT;
        info.imageType = tex.target == TextureTarget::texture_3d ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
        info.format = tex.format.format;
        info.extent = {tex.width, tex.height, tex.extent_depth()};
        info.mipLevels = tex.levels;
        info.arrayLayers = tex.layers();
        info.samples = VK_SAMPLE_COUNT_1_BIT;
        info.tiling = VK_IMAGE_TILING_OPTIMAL;
        info.usage = usage;
        info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        VkImageFormatProperties limits;
        if (vkGetPhysicalDeviceImageFormatProperties(c_.physical_device(), info.format, info.imageType, info.tiling,
                                                     info.usage, info.flags, &limits) != VK_SUCCESS ||
            tex.width > limits.maxExtent.width || tex.height > limits.maxExtent.height ||
            tex.extent_depth() > limits.maxExtent.depth || tex.levels > limits.maxMipLevels ||
            tex.layers() > limits.maxArrayLayers)
            fail(what + ": the device cannot create a " + std::string(to_string(tex.target)) + " " + format_name + " image of " +
                 std::to_string(tex.width) + "x" + std::to_string(tex.height) + "x" + std::to_string(tex.depth) + " with " +
                 std::to_string(tex.levels) + " levels");
        check(vkCreateImage(device_, &info, nullptr, &tex.image), what + ": vkCreateImage");
        VkImage image = tex.image;
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device_, image, &req);
        VkDeviceMemory memory = allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, what);
        on_cleanup([this, image] { vkDestroyImage(device_, image, nullptr); });
        check(vkBindImageMemory(device_, image, memory, 0), what + ": vkBindImageMemory");
        textures_[tex.name] = tex;
    }

    // One VkSampler per distinct sampling state. A sampler parameter declared as a shadow sampler
    // (sampler2DShadow, ...) must be read with a compare function, and any other without one.
    static void check_sampler_type(const Sampling& sampling, const std::string& type, const std::string& what) {
        const bool shadow_type = type.find("Shadow") != std::string::npos;
        if (shadow_type && !sampling.compare)
            fail(what + ": the program declares a " + type + ", but its sampling has no compare function");
        if (!shadow_type && sampling.compare)
            fail(what + ": compare '" + std::string(to_string(*sampling.compare)) + "' on a " + type + "; hardware comparison needs a shadow sampler type");
    }

    VkSampler sampler(const Sampling& sampling, const std::string& type, const std::string& what) {
        check_sampler_type(sampling, type, what);
        const bool integer = type.starts_with("usampler") || type.starts_with("isampler");
        const std::pair<Sampling, bool> key{sampling, integer};
        if (auto it = samplers_.find(key); it != samplers_.end()) return it->second;
        VkSamplerCreateInfo s{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        s.magFilter = filter_of(sampling.mag_filter);
        s.minFilter = filter_of(sampling.min_filter);
        s.mipmapMode = blends_levels(sampling.min_filter) ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
        s.addressModeU = s.addressModeV = s.addressModeW = address_mode(sampling.wrap);
        if (sampling.wrap == Wrap::clamp_to_border) {
            try {
                s.borderColor = border_color(sampling.border_color, integer);
            } catch (const Failure& f) {
                fail(what + ": " + f.message);
            }
        }
        s.minLod = 0.0f;
        s.maxLod = mipmapped(sampling) ? VK_LOD_CLAMP_NONE : 0.25f; // 0.25: a GL non-mipmap filter (Vulkan spec, "Samplers")
        if (sampling.compare) {
            s.compareEnable = VK_TRUE;
            s.compareOp = compare_op(*sampling.compare);
        }
        VkSampler handle = VK_NULL_HANDLE;
        check(vkCreateSampler(device_, &s, nullptr, &handle), what + ": vkCreateSampler");
        on_cleanup([this, handle] { vkDestroySampler(device_, handle, nullptr); });
        return samplers_[key] = handle;
    }

    // Views, made once per (texture, type, level range, layer range).
    VkImageView view(const Texture& t, VkImageViewType type, std::uint32_t level, std::uint32_t levels,
                     std::uint32_t layer, std::uint32_t layers) {
        const std::string key = t.name + "/" + std::to_string(type) + "/" + std::to_string(level) + "/" +
                                std::to_string(levels) + "/" + std::to_string(layer) + "/" + std::to_string(layers);
        if (auto it = views_.find(key); it != views_.end()) return it->second;
        VkImageViewCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        info.image = t.image;
        info.viewType = type;
        info.format = t.format.format;
        info.subresourceRange = {t.format.aspect(), level, levels, layer, layers};
        VkImageView v = VK_NULL_HANDLE;
        check(vkCreateImageView(device_, &info, nullptr, &v), "texture " + t.name + ": vkCreateImageView");
        on_cleanup([this, v] { vkDestroyImageView(device_, v, nullptr); });
        return views_[key] = v;
    }

    // What a sampler reads: the whole texture, or only level `level` (>= 0).
    VkImageView sampled_view(const Texture& t, int level) {
        const VkImageViewType type = t.target == TextureTarget::texture_3d       ? VK_IMAGE_VIEW_TYPE_3D
                                     : t.target == TextureTarget::texture_2d_array ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                                                                   : VK_IMAGE_VIEW_TYPE_2D;
        if (level >= static_cast<int>(t.levels)) fail("texture " + t.name + ": input level " + std::to_string(level) + " does not exist");
        return level < 0 ? view(t, type, 0, t.levels, 0, t.layers())
                         : view(t, type, static_cast<std::uint32_t>(level), 1, 0, t.layers());
    }

    // What a pass renders to: one level of one layer (array layer, or depth slice of a 3D texture).
    VkImageView attachment_view(const Texture& t, int level, int layer) {
        const auto l = static_cast<std::uint32_t>(std::max(layer, 0));
        if (static_cast<std::uint32_t>(level) >= t.levels || l >= std::max(t.layers(), t.extent_depth()))
            fail("texture " + t.name + ": output level " + std::to_string(level) + " layer " + std::to_string(layer) +
                 " does not exist");
        return view(t, VK_IMAGE_VIEW_TYPE_2D, static_cast<std::uint32_t>(level), 1, l, 1);
    }

    Program& program(const std::string& name) {
        if (auto it = programs_.find(name); it != programs_.end()) return it->second;
        const json* desc = nullptr;
        for (const json& p : in_.layout.at("programs"))
            if (p.at("name") == name) desc = &p;
        if (!desc) fail("program '" + name + "' is used by a pass but not listed in programs");
        penumbra::Program source{name, {}};
        // layout.json states each file's stage: stages[i] is the stage of files[i].
        const json& files = desc->at("files");
        const json& stages = desc->at("stages");
        if (stages.size() != files.size())
            fail("program " + name + ": " + std::to_string(files.size()) + " files but " + std::to_string(stages.size()) +
                 " stages; layout.json lists one stage per file");
        for (std::size_t i = 0; i < files.size(); ++i) {
            const std::string file = files[i].get<std::string>();
            const std::optional<Stage> stage = stage_named(stages[i].get<std::string>());
            if (!stage)
                fail("program " + name + ": stage '" + stages[i].get<std::string>() + "' of '" + file +
                     "'; allowed: vertex, fragment, compute");
            source.stages.push_back({file, *stage, read_text(in_.emission_dir / file)});
        }
        std::vector<std::vector<unsigned int>> spirv;
        const std::vector<ShaderDiagnostic> diagnostics = validate_program(source, target_, &spirv);
        if (has_errors(diagnostics)) fail("program " + name + ": " + format(diagnostics.front()));
        Program prog;
        for (std::size_t i = 0; i < source.stages.size(); ++i) {
            VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
            info.codeSize = spirv.at(i).size() * sizeof(unsigned int);
            info.pCode = spirv[i].data();
            VkShaderModule module = VK_NULL_HANDLE;
            check(vkCreateShaderModule(device_, &info, nullptr, &module), "program " + name + ": vkCreateShaderModule");
            on_cleanup([this, module] { vkDestroyShaderModule(device_, module, nullptr); });
            VkPipelineShaderStageCreateInfo stage{VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
            stage.stage = vk_stage(source.stages[i].stage);
            stage.module = module;
            stage.pName = "main";
            prog.stages.push_back(stage);
        }
        // Descriptor sets from the parameters' "set" (layout_version 3; set 0 when absent).
        prog.desc = desc;
        std::map<int, std::vector<VkDescriptorSetLayoutBinding>> bindings; // by set
        for (const json& p : desc->at("parameters")) {
            const std::string type = p.at("type");
            const int set = p.value("set", 0);
            if (p.contains("block_binding")) {
                Block& block = prog.blocks[{set, p.at("block_binding").get<int>()}];
                block.size = std::max(block.size, p.at("offset").get<int>() + std140_size(type));
                block.members.push_back(p);
            } else if (type.find("sampler") != std::string::npos && p.contains("binding")) { // usampler2D too
                const SetBinding where{set, p.at("binding").get<int>()};
                if (prog.samplers.count(where))
                    fail("program " + name + ": parameters " + prog.samplers[where].at("name").get<std::string>() + " and " +
                         p.at("name").get<std::string>() + " share set " + std::to_string(set) + " binding " +
                         std::to_string(where.second));
                prog.samplers[where] = p;
            } else {
                fail("program " + name + ": parameter " + p.at("name").get<std::string>() +
                     " has neither a uniform block nor a binding");
            }
        }
        for (auto& [where, block] : prog.blocks) {
            block.size = (block.size + 15) / 16 * 16; // std140 rounds a block up to a vec4
            if (prog.samplers.count(where))
                fail("program " + name + ": a uniform block and a sampler share set " + std::to_string(where.first) +
                     " binding " + std::to_string(where.second));
            bindings[where.first].push_back({static_cast<std::uint32_t>(where.second), VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                             VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
        }
        for (const auto& [where, param] : prog.samplers) {
            const int separate = param.value("sampler_binding", -2); // -2: combined; -1: a texture alone
            bindings[where.first].push_back({static_cast<std::uint32_t>(where.second),
                                             separate == -2 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER
                                                            : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE,
                                             1, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                             nullptr});
            if (separate >= 0)
                bindings[where.first].push_back(
                    {static_cast<std::uint32_t>(separate), VK_DESCRIPTOR_TYPE_SAMPLER, 1,
                     VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
        }
        const int set_count = bindings.empty() ? 0 : bindings.rbegin()->first + 1;
        if (set_count > static_cast<int>(c_.properties().limits.maxBoundDescriptorSets))
            fail("program " + name + ": descriptor set " + std::to_string(set_count - 1) + "; the device binds " +
                 std::to_string(c_.properties().limits.maxBoundDescriptorSets) + " sets");
        for (int set = 0; set < set_count; ++set) { // sets without parameters get empty layouts
            const std::vector<VkDescriptorSetLayoutBinding>& b = bindings[set];
            VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
            set_info.bindingCount = static_cast<std::uint32_t>(b.size());
            set_info.pBindings = b.data();
            VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
            check(vkCreateDescriptorSetLayout(device_, &set_info, nullptr, &set_layout),
                  "program " + name + ": descriptor set layout " + std::to_string(set));
            on_cleanup([this, set_layout] { vkDestroyDescriptorSetLayout(device_, set_layout, nullptr); });
            prog.set_layouts.push_back(set_layout);
        }
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = static_cast<std::uint32_t>(prog.set_layouts.size());
        layout_info.pSetLayouts = prog.set_layouts.data();
        check(vkCreatePipelineLayout(device_, &layout_info, nullptr, &prog.pipeline_layout), "program " + name + ": pipeline layout");
        VkPipelineLayout pipeline_layout = prog.pipeline_layout;
        on_cleanup([this, pipeline_layout] { vkDestroyPipelineLayout(device_, pipeline_layout, nullptr); });

        // Vertex inputs by name (layout_version 3); version 2: world position at location 0.
        if (!desc->contains("vertex_inputs")) {
            prog.vertex_inputs.position = 0;
        } else {
            for (const json& v : desc->at("vertex_inputs")) {
                const std::string input = v.at("name"), type = v.at("type");
                const int location = v.at("location").get<int>();
                int* slot = input == "penumbra_position" ? &prog.vertex_inputs.position
                            : input == "penumbra_normal" ? &prog.vertex_inputs.normal
                                                         : nullptr;
                if (!slot)
                    fail("program " + name + ": vertex input '" + input +
                         "' is unknown to this runner; allowed: penumbra_position, penumbra_normal");
                if (type != "vec3")
                    fail("program " + name + ": vertex input " + input + " is a " + type + "; allowed: vec3");
                if (location < 0 || location >= static_cast<int>(c_.properties().limits.maxVertexInputAttributes))
                    fail("program " + name + ": vertex input " + input + " at location " + std::to_string(location) +
                         "; the device has locations 0 to " +
                         std::to_string(c_.properties().limits.maxVertexInputAttributes - 1));
                if (*slot >= 0) fail("program " + name + ": vertex input " + input + " is listed twice");
                *slot = location;
            }
            if (prog.vertex_inputs.position >= 0 && prog.vertex_inputs.position == prog.vertex_inputs.normal)
                fail("program " + name + ": penumbra_position and penumbra_normal share location " +
                     std::to_string(prog.vertex_inputs.position));
        }
        return programs_[name] = std::move(prog);
    }

    // At most RequiredLimits::bound_descriptor_sets sets a pass, each within the per-stage limits.
    void create_descriptor_pool(std::size_t passes) {
        const auto sets = static_cast<std::uint32_t>(std::max<std::size_t>(passes, 1)) * RequiredLimits::bound_descriptor_sets;
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 12 * sets},
                                              {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16 * sets},
                                              {VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE, 16 * sets},
                                              {VK_DESCRIPTOR_TYPE_SAMPLER, 16 * sets}};
        VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        info.maxSets = sets;
        info.poolSizeCount = 4;
        info.pPoolSizes = sizes;
        check(vkCreateDescriptorPool(device_, &info, nullptr, &pool_), "vkCreateDescriptorPool");
        on_cleanup([this] { vkDestroyDescriptorPool(device_, pool_, nullptr); });
    }

    // The value of one block member: "light" parameters from the inputs, "pass" ones from the
    // pass's int_uniforms (std140: an int is 4 bytes, a mat4 four vec4 columns).
    void write_member(const json& param, const json& pass, unsigned char* block) {
        const std::string name = param.at("name"), type = param.at("type"), source = param.value("source", "");
        const int offset = param.at("offset").get<int>();
        if (source == "pass") {
            if (!pass.at("int_uniforms").contains(name))
                fail("pass " + pass.at("name").get<std::string>() + ": no value for " + name + " in int_uniforms");
            const std::int32_t value = pass.at("int_uniforms").at(name).get<std::int32_t>();
            std::memcpy(block + offset, &value, sizeof value);
            return;
        }
        if (source != "light")
            fail("pass " + pass.at("name").get<std::string>() + ": parameter " + name + " has source '" + source +
                 "'; this runner provides 'light' and 'pass' values");
        auto it = in_.uniforms.find(name);
        if (it == in_.uniforms.end()) fail("no value for the light parameter " + name + " (uniforms.json)");
        const std::size_t floats = static_cast<std::size_t>(std140_size(type)) / 4;
        if (it->second.size() != floats)
            fail(name + ": " + std::to_string(it->second.size()) + " values for a " + type);
        std::memcpy(block + offset, it->second.data(), floats * sizeof(float));
    }

    // `depth_format`: the depth attachment's format, VK_FORMAT_UNDEFINED when the pass has none.
    VkPipeline pipeline(const std::string& program_name, Program& prog, const json& pass,
                        const std::vector<VkFormat>& formats, VkFormat depth_format) {
        const json& state = pass.at("state");
        const std::string pass_name = pass.at("name");
        std::string key = program_name + "|" + pass.at("action").get<std::string>() + "|" + state.dump() + "|" +
                          std::to_string(depth_format);
        for (VkFormat f : formats) key.append("|").append(std::to_string(f));
        if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;
        const bool depth_test = state.at("depth_test").get<bool>(), depth_write = state.at("depth_write").get<bool>();
        if ((depth_test || depth_write) && depth_format == VK_FORMAT_UNDEFINED)
            fail("pass " + pass_name + ": depth_test or depth_write without an output of kind \"depth\" (this runner has no "
                 "default framebuffer)");

        // draw_scene: the vertex buffer holds position and face normal (fill_vertices); each is fed
        // to the location the program's vertex_inputs name.
        const bool scene = word<PassAction>(pass, "action", "pass " + pass_name) == PassAction::draw_scene;
        if (!scene && (prog.vertex_inputs.position >= 0 || prog.vertex_inputs.normal >= 0) && prog.desc->contains("vertex_inputs"))
            fail("pass " + pass_name + ": program " + program_name + " has vertex inputs, but a fullscreen pass draws no vertices");
        if (scene && prog.vertex_inputs.position < 0)
            fail("pass " + pass_name + ": program " + program_name + " draws the scene but reads no penumbra_position");
        const VkVertexInputBindingDescription vertex_binding{0, 6 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX};
        std::vector<VkVertexInputAttributeDescription> attributes;
        if (prog.vertex_inputs.position >= 0)
            attributes.push_back({static_cast<std::uint32_t>(prog.vertex_inputs.position), 0, VK_FORMAT_R32G32B32_SFLOAT, 0});
        if (prog.vertex_inputs.normal >= 0)
            attributes.push_back({static_cast<std::uint32_t>(prog.vertex_inputs.normal), 0, VK_FORMAT_R32G32B32_SFLOAT,
                                  3 * sizeof(float)});
        VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        if (scene) {
            vertex_input.vertexBindingDescriptionCount = 1;
            vertex_input.pVertexBindingDescriptions = &vertex_binding;
            vertex_input.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(attributes.size());
            vertex_input.pVertexAttributeDescriptions = attributes.data();
        }
        // Depth: GL's test, function and mask; polygon offset as depth bias (both APIs scale
        // `units` by the format's minimum resolvable difference).
        VkPipelineDepthStencilStateCreateInfo depth{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
        depth.depthTestEnable = depth_test ? VK_TRUE : VK_FALSE;
        depth.depthWriteEnable = depth_test && depth_write ? VK_TRUE : VK_FALSE; // GL writes depth only where it tests
        const std::string where = "pass " + pass_name + ": state";
        depth.depthCompareOp = compare_op(word<CompareFunc>(state, "depth_func", where, "LESS"));
        depth.minDepthBounds = 0.0f;
        depth.maxDepthBounds = 1.0f;
        VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;
        VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = cull_mode(word<Cull>(state, "cull", where));
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f;
        const float offset_factor = state.value("polygon_offset_factor", 0.0f), offset_units = state.value("polygon_offset_units", 0.0f);
        if (offset_factor != 0.0f || offset_units != 0.0f) {
            if (depth_format == VK_FORMAT_UNDEFINED)
                fail("pass " + pass_name + ": polygon offset without an output of kind \"depth\"");
            raster.depthBiasEnable = VK_TRUE;
            raster.depthBiasConstantFactor = offset_units;
            raster.depthBiasSlopeFactor = offset_factor;
        }
        VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        const LogicOp logic_op = word<LogicOp>(state, "logic_op", where, "NONE");
        if (logic_op == LogicOp::bitwise_or && !c_.logic_op())
            fail("pass state: logic_op OR needs the device feature logicOp, which this device lacks");
        VkPipelineColorBlendAttachmentState blend{};
        blend.blendEnable = state.at("blend").get<bool>() ? VK_TRUE : VK_FALSE;
        blend.colorBlendOp = blend.alphaBlendOp = blend_op(word<BlendEquation>(state, "blend_equation", where));
        blend.srcColorBlendFactor = blend.srcAlphaBlendFactor = blend_factor(word<BlendFactor>(state, "blend_src", where));
        blend.dstColorBlendFactor = blend.dstAlphaBlendFactor = blend_factor(word<BlendFactor>(state, "blend_dst", where));
        const std::vector<bool> mask = state.at("color_mask").get<std::vector<bool>>();
        for (std::size_t i = 0; i < 4 && i < mask.size(); ++i)
            if (mask[i]) blend.colorWriteMask |= VK_COLOR_COMPONENT_R_BIT << i;
        const std::vector<VkPipelineColorBlendAttachmentState> blends(formats.size(), blend);
        VkPipelineColorBlendStateCreateInfo blending{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        blending.logicOpEnable = logic_op == LogicOp::bitwise_or ? VK_TRUE : VK_FALSE; // integer targets: fragments OR-ed in
        blending.logicOp = VK_LOGIC_OP_OR;
        blending.attachmentCount = static_cast<std::uint32_t>(blends.size());
        blending.pAttachments = blends.data();
        const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
        dynamic.dynamicStateCount = 2;
        dynamic.pDynamicStates = dynamic_states;
        VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
        rendering.colorAttachmentCount = static_cast<std::uint32_t>(formats.size());
        rendering.pColorAttachmentFormats = formats.data();
        rendering.depthAttachmentFormat = depth_format;

        VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
        info.pNext = &rendering;
        info.stageCount = static_cast<std::uint32_t>(prog.stages.size());
        info.pStages = prog.stages.data();
        info.pVertexInputState = &vertex_input;
        info.pInputAssemblyState = &assembly;
        info.pViewportState = &viewport;
        info.pRasterizationState = &raster;
        info.pMultisampleState = &multisample;
        info.pColorBlendState = &blending;
        if (depth_format != VK_FORMAT_UNDEFINED) info.pDepthStencilState = &depth;
        info.pDynamicState = &dynamic;
        info.layout = prog.pipeline_layout;
        VkPipeline p = VK_NULL_HANDLE;
        check(vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &p),
              "pass " + pass.at("name").get<std::string>() + ": vkCreateGraphicsPipelines");
        on_cleanup([this, p] { vkDestroyPipeline(device_, p, nullptr); });
        return pipelines_[key] = p;
    }

    // Creates what one pass needs and returns the function that records it.
    std::function<void(VkCommandBuffer)> prepare_pass(const json& pass) {
        const std::string name = pass.at("name");
        const PassAction action = word<PassAction>(pass, "action", "pass " + name);
        switch (action) {
        case PassAction::generate_mipmap: return prepare_mipmaps(pass);
        case PassAction::copy: return prepare_copy(pass);
        case PassAction::dispatch:
            fail("pass " + name + ": action 'dispatch' runs a compute shader, which this runner has no pipelines for; "
                 "emit with prefilter_stage fragment");
        case PassAction::draw_scene:
        case PassAction::fullscreen: break;
        }

        Program& prog = program(pass.at("program"));
        const std::string program_name = pass.at("program");
        // A 0 x 0 viewport: the size of the first output's level (as the GL runtime), else the output size.
        std::uint32_t width = pass.at("viewport").at(0).get<std::uint32_t>();
        std::uint32_t height = pass.at("viewport").at(1).get<std::uint32_t>();
        if (width == 0 || height == 0) {
            width = static_cast<std::uint32_t>(in_.width);
            height = static_cast<std::uint32_t>(in_.height);
            if (!pass.at("outputs").empty()) {
                const json& o = pass.at("outputs").at(0);
                const Texture& t = texture(o.at("texture"));
                const int level = std::clamp(o.at("level").get<int>(), 0, 31);
                width = std::max(t.width >> level, 1u);
                height = std::max(t.height >> level, 1u);
            }
        }
        // Rendering beyond an attachment is undefined in Vulkan (GL clips it): refused.
        for (const json& o : pass.at("outputs")) {
            const Texture& t = texture(o.at("texture"));
            const int level = std::clamp(o.at("level").get<int>(), 0, 31);
            if (width > std::max(t.width >> level, 1u) || height > std::max(t.height >> level, 1u))
                fail("pass " + name + ": viewport " + std::to_string(width) + "x" + std::to_string(height) +
                     " is larger than level " + std::to_string(level) + " of output " + t.name + " (" +
                     std::to_string(std::max(t.width >> level, 1u)) + "x" + std::to_string(std::max(t.height >> level, 1u)) + ")");
        }
        std::vector<VkRenderingAttachmentInfo> attachments;
        std::vector<VkFormat> formats;
        const json& state = pass.at("state");
        VkClearValue clear{};
        const bool clears = !state.at("clear_color").is_null();
        if (clears)
            for (int i = 0; i < 4; ++i) clear.color.float32[i] = state.at("clear_color").at(i).get<float>();
        std::size_t colour_outputs = 0;
        auto kind_of = [&](const json& o) { return word<AttachmentKind>(o, "kind", "pass " + name, "color"); };
        for (const json& o : pass.at("outputs")) colour_outputs += kind_of(o) == AttachmentKind::color;
        if (colour_outputs > c_.properties().limits.maxColorAttachments)
            fail("pass " + name + ": " + std::to_string(colour_outputs) + " colour attachments; the device has " +
                 std::to_string(c_.properties().limits.maxColorAttachments));
        std::optional<VkRenderingAttachmentInfo> depth_attachment;
        VkFormat depth_format = VK_FORMAT_UNDEFINED;
        for (const json& o : pass.at("outputs")) {
            const Texture& t = texture(o.at("texture"));
            VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            a.imageView = attachment_view(t, o.at("level").get<int>(), o.at("layer").get<int>());
            a.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
            a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            if (kind_of(o) == AttachmentKind::depth) { // create_texture checked the kinds and formats
                if (depth_attachment) fail("pass " + name + ": more than one output of kind \"depth\"");
                const bool clears_depth = state.contains("clear_depth") && !state.at("clear_depth").is_null();
                a.loadOp = clears_depth ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
                if (clears_depth) {
                    const float d = state.at("clear_depth").get<float>();
                    if (!(d >= 0.0f && d <= 1.0f))
                        fail("pass " + name + ": clear_depth " + std::to_string(d) + "; allowed: 0 to 1");
                    a.clearValue.depthStencil = {d, 0};
                }
                depth_attachment = a;
                depth_format = t.format.format;
                continue;
            }
            a.loadOp = clears ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
            a.clearValue = clear;
            if (clears && t.format.integer) // integer targets clear to integer values (GL's glClearBufferuiv)
                for (int i = 0; i < 4; ++i) {
                    const float v = state.at("clear_color").at(i).get<float>();
                    if (!(v >= 0.0f) || v != std::floor(v))
                        fail("pass " + name + ": clear_color " + std::to_string(v) + " for the integer texture " + t.name +
                             "; allowed: whole numbers >= 0");
                    a.clearValue.color.uint32[i] = static_cast<std::uint32_t>(v);
                }
            attachments.push_back(a);
            formats.push_back(t.format.format);
        }
        const VkPipeline pipe = pipeline(program_name, prog, pass, formats, depth_format);

        // Descriptor sets (one per set the program uses): one uniform buffer per block, filled
        // now, and the pass's inputs, each through the sampler its sampling describes.
        std::vector<VkDescriptorSet> sets;
        for (const VkDescriptorSetLayout set_layout : prog.set_layouts) {
            VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
            allocate.descriptorPool = pool_;
            allocate.descriptorSetCount = 1;
            allocate.pSetLayouts = &set_layout;
            VkDescriptorSet set = VK_NULL_HANDLE;
            check(vkAllocateDescriptorSets(device_, &allocate, &set), "pass " + name + ": vkAllocateDescriptorSets");
            sets.push_back(set);
        }
        std::vector<VkDescriptorBufferInfo> buffer_infos;
        std::vector<VkDescriptorImageInfo> image_infos;
        buffer_infos.reserve(prog.blocks.size());
        image_infos.reserve(prog.samplers.size());
        std::vector<VkWriteDescriptorSet> writes;
        for (const auto& [where, block] : prog.blocks) {
            const Buffer b = create_buffer(static_cast<std::size_t>(block.size), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
            for (const json& member : block.members) write_member(member, pass, static_cast<unsigned char*>(b.mapped));
            buffer_infos.push_back({b.buffer, 0, static_cast<VkDeviceSize>(block.size)});
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = sets.at(static_cast<std::size_t>(where.first));
            w.dstBinding = static_cast<std::uint32_t>(where.second);
            w.descriptorCount = 1;
            w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            w.pBufferInfo = &buffer_infos.back();
            writes.push_back(w);
        }
        for (const auto& [where, param] : prog.samplers) {
            const std::string sampler_name = param.at("name");
            const json* input = nullptr;
            for (const json& i : pass.at("inputs"))
                if (i.at("sampler") == sampler_name) input = &i;
            if (!input)
                fail("pass " + name + ": no input for sampler " + sampler_name + " (set " + std::to_string(where.first) +
                     ", binding " + std::to_string(where.second) + ")");
            if (input->at("binding").get<int>() != where.second)
                fail("pass " + name + ": input " + sampler_name + " is at binding " +
                     std::to_string(input->at("binding").get<int>()) + ", the program has it at binding " +
                     std::to_string(where.second));
            const Texture& t = texture(input->at("texture"));
            const std::string what = "pass " + name + ", sampler " + sampler_name;
            const std::string type = param.at("type");
            if (t.format.integer != type.starts_with("usampler"))
                fail(what + ": texture " + t.name + " (" + t.desc->at("internal_format").get<std::string>() + ") is read through a " +
                     type + "; integer textures need a usampler, others a sampler");
            if (t.format.depth && type.find("Shadow") == std::string::npos && type != "sampler2D")
                fail(what + ": the depth texture " + t.name + " is read through a " + type + "; allowed: sampler2D, sampler2DShadow");
            const VkSampler handle = sampler(input_sampling(pass, *input), type, what);
            image_infos.push_back({handle, sampled_view(t, input->value("level", -1)), VK_IMAGE_LAYOUT_GENERAL});
            const int separate = param.value("sampler_binding", -2); // as in program()
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = sets.at(static_cast<std::size_t>(where.first));
            w.dstBinding = static_cast<std::uint32_t>(where.second);
            w.descriptorCount = 1;
            w.descriptorType =
                separate == -2 ? VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
            w.pImageInfo = &image_infos.back();
            writes.push_back(w);
            if (separate >= 0) {
                w.dstBinding = static_cast<std::uint32_t>(separate);
                w.descriptorType = VK_DESCRIPTOR_TYPE_SAMPLER;
                writes.push_back(w);
            }
        }
        vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);

        const bool scene = action == PassAction::draw_scene;
        const auto vertex_count = static_cast<std::uint32_t>(in_.triangles.size() / 3);
        const VkPipelineLayout pipeline_layout = prog.pipeline_layout;
        const VkBuffer vertices = vertices_.buffer;
        return [=](VkCommandBuffer cmd) {
            VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
            rendering.renderArea = {{0, 0}, {width, height}};
            rendering.layerCount = 1;
            rendering.colorAttachmentCount = static_cast<std::uint32_t>(attachments.size());
            rendering.pColorAttachments = attachments.data();
            if (depth_attachment) rendering.pDepthAttachment = &*depth_attachment;
            vkCmdBeginRendering(cmd, &rendering);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            const VkViewport vp{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f};
            const VkRect2D scissor{{0, 0}, {width, height}};
            vkCmdSetViewport(cmd, 0, 1, &vp);
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            if (!sets.empty())
                vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, 0,
                                        static_cast<std::uint32_t>(sets.size()), sets.data(), 0, nullptr);
            if (scene) {
                const VkDeviceSize offset = 0;
                vkCmdBindVertexBuffers(cmd, 0, 1, &vertices, &offset);
                if (vertex_count > 0) vkCmdDraw(cmd, vertex_count, 1, 0, 0);
            } else {
                vkCmdDraw(cmd, 3, 1, 0, 0);
            }
            vkCmdEndRendering(cmd);
        };
    }

    // Each level from the one above it, halving: "mipmap" {base_level, levels, downsample "box"}
    // (layout_version 3; levels counts the chain from base_level on, base included), else the
    // whole chain from level 0. A 2:1 linear blit averages 2×2 texels (2×2×2 in 3D): the box.
    std::function<void(VkCommandBuffer)> prepare_mipmaps(const json& pass) {
        const std::string name = pass.at("name");
        if (pass.at("outputs").size() != 1) fail("pass " + name + ": generate_mipmap needs exactly one output");
        const Texture& t = texture(pass.at("outputs").at(0).at("texture"));
        int base = 0, levels = static_cast<int>(t.levels);
        if (pass.contains("mipmap")) {
            const json& m = pass.at("mipmap");
            base = m.at("base_level").get<int>();
            levels = m.at("levels").get<int>();
            const std::string downsample = m.value("downsample", std::string("box"));
            if (downsample != "box") fail("pass " + name + ": downsample '" + downsample + "' is unknown; allowed: box");
        }
        if (base < 0 || levels < 1 || base + levels > static_cast<int>(t.levels))
            fail("pass " + name + ": mipmap levels " + std::to_string(base) + " to " + std::to_string(base + levels - 1) +
                 " of texture " + t.name + ", which has levels 0 to " + std::to_string(t.levels - 1));
        const auto first = static_cast<std::uint32_t>(base), last = static_cast<std::uint32_t>(base + levels - 1);
        return [this, t, first, last](VkCommandBuffer cmd) {
            for (std::uint32_t level = first + 1; level <= last; ++level) {
                auto size = [&](std::uint32_t l, std::uint32_t extent) {
                    return static_cast<std::int32_t>(std::max(extent >> l, 1u));
                };
                VkImageBlit blit{};
                blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 0, t.layers()};
                blit.srcOffsets[1] = {size(level - 1, t.width), size(level - 1, t.height), size(level - 1, t.extent_depth())};
                blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, level, 0, t.layers()};
                blit.dstOffsets[1] = {size(level, t.width), size(level, t.height), size(level, t.extent_depth())};
                const VkImageSubresourceRange src{VK_IMAGE_ASPECT_COLOR_BIT, level - 1, 1, 0, t.layers()};
                const VkImageSubresourceRange dst{VK_IMAGE_ASPECT_COLOR_BIT, level, 1, 0, t.layers()};
                transition(cmd, t.image, src, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
                transition(cmd, t.image, dst, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
                vkCmdBlitImage(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, t.image,
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
                transition(cmd, t.image, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
                transition(cmd, t.image, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
            }
        };
    }

    // inputs[0] into outputs[0]: "copy" {source_level, source_layer, target_level, target_layer,
    // width, height} (layout_version 3; a layer is an array layer or a 3D depth slice, -1 meaning
    // 0), else the input's level (0 when it names all), the output's level and layer and the
    // viewport's size. Depth textures copy their depth aspect.
    std::function<void(VkCommandBuffer)> prepare_copy(const json& pass) {
        const std::string name = pass.at("name");
        if (pass.at("inputs").size() != 1 || pass.at("outputs").size() != 1)
            fail("pass " + name + ": copy needs exactly one input and one output");
        const Texture& src = texture(pass.at("inputs").at(0).at("texture"));
        const json& o = pass.at("outputs").at(0);
        const Texture& dst = texture(o.at("texture"));
        int src_level = std::max(pass.at("inputs").at(0).value("level", -1), 0), src_layer = 0;
        int dst_level = o.at("level").get<int>(), dst_layer = o.at("layer").get<int>();
        int width = pass.at("viewport").at(0).get<int>(), height = pass.at("viewport").at(1).get<int>();
        if (pass.contains("copy")) {
            const json& c = pass.at("copy");
            src_level = c.at("source_level").get<int>();
            src_layer = c.at("source_layer").get<int>();
            dst_level = c.at("target_level").get<int>();
            dst_layer = c.at("target_layer").get<int>();
            width = c.at("width").get<int>();
            height = c.at("height").get<int>();
        }
        src_layer = std::max(src_layer, 0);
        dst_layer = std::max(dst_layer, 0);
        if (width == 0 || height == 0) {
            width = in_.width;
            height = in_.height;
        }
        auto check_region = [&](const Texture& t, int level, int layer, const std::string& role) {
            if (level < 0 || level >= static_cast<int>(t.levels) || layer >= static_cast<int>(std::max(t.layers(), t.extent_depth())))
                fail("pass " + name + ": copy " + role + " level " + std::to_string(level) + " layer " + std::to_string(layer) +
                     " of texture " + t.name + ", which has " + std::to_string(t.levels) + " levels and " +
                     std::to_string(std::max(t.layers(), t.extent_depth())) + " layers");
            if (width < 1 || height < 1 || static_cast<std::uint32_t>(width) > std::max(t.width >> level, 1u) ||
                static_cast<std::uint32_t>(height) > std::max(t.height >> level, 1u))
                fail("pass " + name + ": copy of " + std::to_string(width) + "x" + std::to_string(height) + " texels beyond " +
                     role + " " + t.name + " level " + std::to_string(level));
        };
        check_region(src, src_level, src_layer, "source");
        check_region(dst, dst_level, dst_layer, "target");
        if (src.format.format != dst.format.format)
            fail("pass " + name + ": copy from " + src.name + " (" + src.desc->at("internal_format").get<std::string>() +
                 ") to " + dst.name + " (" + dst.desc->at("internal_format").get<std::string>() +
                 "); Vulkan copies between identical formats here");
        const VkImageAspectFlags aspect = src.format.aspect();
        VkImageCopy region{};
        const auto layer_of = [](const Texture& t, int layer) {
            return t.target == TextureTarget::texture_2d_array ? static_cast<std::uint32_t>(layer) : 0u;
        };
        region.srcSubresource = {aspect, static_cast<std::uint32_t>(src_level), layer_of(src, src_layer), 1};
        region.dstSubresource = {aspect, static_cast<std::uint32_t>(dst_level), layer_of(dst, dst_layer), 1};
        if (src.target == TextureTarget::texture_3d) region.srcOffset.z = src_layer;
        if (dst.target == TextureTarget::texture_3d) region.dstOffset.z = dst_layer;
        region.extent = {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height), 1};
        const VkImage from = src.image, to = dst.image;
        const VkImageSubresourceRange from_range{aspect, region.srcSubresource.mipLevel, 1, region.srcSubresource.baseArrayLayer, 1};
        const VkImageSubresourceRange to_range{aspect, region.dstSubresource.mipLevel, 1, region.dstSubresource.baseArrayLayer, 1};
        if (from == to) fail("pass " + name + ": copy within texture " + src.name + " is not supported by this runner");
        return [=](VkCommandBuffer cmd) {
            transition(cmd, from, from_range, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            transition(cmd, to, to_range, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            vkCmdCopyImage(cmd, from, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
            transition(cmd, from, from_range, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
            transition(cmd, to, to_range, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
        };
    }

    // Textures whose initial contents come from outside ("initial" caller: the G-buffers; bake:
    // precomputed maps), from the inputs' RGBA floats into staging buffers in the texture's format
    // (32-bit floats as given, 16-bit floats rounded to nearest even, as GL converts them).
    std::vector<Buffer> stage_caller_textures() {
        std::vector<Buffer> out;
        for (const auto& [name, t] : textures_) {
            if (t.initial != TextureInitial::caller && t.initial != TextureInitial::bake) continue;
            const bool bake = t.initial == TextureInitial::bake;
            const auto& given = bake ? in_.bake_textures : in_.caller_textures;
            auto it = given.find(name);
            if (it == given.end())
                fail("texture " + name + ": its initial contents come from the " +
                     (bake ? std::string("bake (the bundle's bake_textures)") : std::string("caller (the bundle's caller_textures)")) +
                     ", and the bundle has none for it");
            if (t.format.integer || t.format.depth || t.format.normalized || t.depth != 1 || t.levels != 1)
                fail("texture " + name + ": only single-level 16- or 32-bit float textures can be uploaded by this runner");
            const std::size_t texels = static_cast<std::size_t>(t.width) * t.height;
            if (it->second.size() != 4 * texels)
                fail("texture " + name + ": " + std::to_string(it->second.size()) + " floats given, " +
                     std::to_string(4 * texels) + " needed (RGBA, " + std::to_string(t.width) + "x" + std::to_string(t.height) + ")");
            const auto channels = static_cast<std::size_t>(t.format.channels);
            const std::size_t bytes = texels * channels * static_cast<std::size_t>(t.format.bytes_per_channel);
            Buffer b = create_buffer(bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
            auto* to = static_cast<unsigned char*>(b.mapped);
            for (std::size_t i = 0; i < texels; ++i)
                for (std::size_t c = 0; c < channels; ++c) {
                    const float v = it->second[4 * i + c];
                    if (t.format.bytes_per_channel == 4) {
                        std::memcpy(to + 4 * (i * channels + c), &v, 4);
                    } else {
                        const std::uint16_t h = to_half(v);
                        std::memcpy(to + 2 * (i * channels + c), &h, 2);
                    }
                }
            out.push_back(b);
            caller_order_.push_back(name);
        }
        return out;
    }

    // IEEE binary16 of a float, rounded to nearest even; overflow to infinity, NaN kept.
    static std::uint16_t to_half(float value) {
        std::uint32_t f;
        std::memcpy(&f, &value, 4);
        const auto sign = static_cast<std::uint16_t>((f >> 16) & 0x8000u);
        const std::uint32_t abs = f & 0x7fffffffu;
        if (abs >= 0x7f800000u) return static_cast<std::uint16_t>(sign | (abs > 0x7f800000u ? 0x7e00u : 0x7c00u));
        if (abs >= 0x477ff000u) return static_cast<std::uint16_t>(sign | 0x7c00u); // rounds to beyond 65504
        if (abs < 0x38800000u) { // a subnormal half (or zero): value / 2^-24, rounded to nearest even
            if (abs < 0x33000000u) return sign;                                   // below half of 2^-24
            const std::uint32_t mantissa = (abs & 0x7fffffu) | 0x800000u;
            const int shift = 126 - static_cast<int>(abs >> 23);                  // 14 to 24
            const std::uint32_t half = mantissa >> shift, rest = mantissa & ((1u << shift) - 1), mid = 1u << (shift - 1);
            return static_cast<std::uint16_t>(sign | (half + (rest > mid || (rest == mid && (half & 1u)))));
        }
        const std::uint32_t rebased = abs - 0x38000000u; // exponent 127 → 15
        const std::uint32_t half = rebased >> 13, rest = rebased & 0x1fffu;
        return static_cast<std::uint16_t>(sign | (half + (rest > 0x1000u || (rest == 0x1000u && (half & 1u)))));
    }

    // Every image by its "initial": zero cleared to 0 (all levels and layers; depth to 0.0), caller
    // and bake uploaded, undefined left as it is; then all in GENERAL, the layout in which passes
    // sample and render them.
    void initialise_images(VkCommandBuffer cmd, const std::vector<Buffer>& uploads) {
        auto all = [](const Texture& t) {
            return VkImageSubresourceRange{t.format.aspect(), 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
        };
        for (const auto& [name, t] : textures_)
            transition(cmd, t.image, all(t), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkClearColorValue zero{};
        const VkClearDepthStencilValue zero_depth{0.0f, 0};
        for (const auto& [name, t] : textures_) {
            if (t.initial != TextureInitial::zero) continue;
            const VkImageSubresourceRange range = all(t);
            if (t.format.depth) vkCmdClearDepthStencilImage(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero_depth, 1, &range);
            else vkCmdClearColorImage(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &range);
        }
        for (std::size_t i = 0; i < uploads.size(); ++i) {
            const Texture& t = textures_.at(caller_order_[i]);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {t.width, t.height, 1};
            vkCmdCopyBufferToImage(cmd, uploads[i].buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        }
        for (const auto& [name, t] : textures_)
            transition(cmd, t.image, all(t), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
    }

    // A layout change of `range`, ordered after everything before and before everything after.
    static void transition(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceRange& range, VkImageLayout from,
                           VkImageLayout to) {
        VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
        b.srcAccessMask = from == VK_IMAGE_LAYOUT_UNDEFINED ? 0 : VK_ACCESS_MEMORY_WRITE_BIT;
        b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        b.oldLayout = from;
        b.newLayout = to;
        b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
        b.image = image;
        b.subresourceRange = range;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 0, nullptr, 0,
                             nullptr, 1, &b);
    }

    // Everything written before is visible to everything after.
    static void barrier(VkCommandBuffer cmd) {
        VkMemoryBarrier b{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
        b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
        b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, 0, 1, &b, 0,
                             nullptr, 0, nullptr);
    }

    // The first channel of every texel, as float.
    static std::vector<float> to_floats(const Texture& t, const void* data) {
        const std::size_t texels = static_cast<std::size_t>(t.width) * t.height;
        std::vector<float> out(texels);
        const auto* bytes = static_cast<const unsigned char*>(data);
        const std::size_t stride = static_cast<std::size_t>(t.format.channels) * t.format.bytes_per_channel;
        for (std::size_t i = 0; i < texels; ++i) {
            if (t.format.bytes_per_channel == 4) std::memcpy(&out[i], bytes + i * stride, sizeof(float));
            else if (t.format.normalized) out[i] = bytes[i * stride] / 255.0f;
            else fail("result texture " + t.name + ": reading back 16-bit floats is not supported by this runner");
        }
        return out;
    }

    const Context& c_;
    const LayoutInputs& in_;
    VkDevice device_;
    std::vector<std::function<void()>> cleanup_;
    std::map<std::string, Texture> textures_;
    Target target_ = Target::vulkan;             // the layout's: vulkan (GLSL) or hlsl
    std::vector<std::string> caller_order_;      // the textures stage_caller_textures filled, in order
    std::map<std::string, VkImageView> views_;
    std::map<std::string, Program> programs_;
    std::map<std::string, VkPipeline> pipelines_;
    std::map<std::pair<Sampling, bool>, VkSampler> samplers_; // by sampling, and whether it reads integers
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    Buffer vertices_;
};

} // namespace

std::string run_layout(const Context& context, const LayoutInputs& inputs, LayoutOutput& output) {
    try {
        Runner runner(context, inputs);
        runner.run(output);
        return {};
    } catch (const Failure& f) {
        return f.message;
    } catch (const nlohmann::json::exception& e) {
        return std::string("layout.json: ") + e.what();
    }
}

} // namespace penumbra::vulkan
