#include "layout_runner.hpp"

#include <penumbra/program.hpp>
#include <penumbra/validation.hpp>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
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

// layout.json's internal formats: the Vulkan format and the floats a texel holds.
struct FormatInfo {
    VkFormat format = VK_FORMAT_UNDEFINED;
    int channels = 0;
    int bytes_per_channel = 0;
    bool normalized = false; // UNORM: stored as bytes, read as value / 255
};

FormatInfo format_info(const std::string& name) {
    static const std::map<std::string, FormatInfo> formats{
        {"RGBA8", {VK_FORMAT_R8G8B8A8_UNORM, 4, 1, true}},       {"R8", {VK_FORMAT_R8_UNORM, 1, 1, true}},
        {"RGBA16F", {VK_FORMAT_R16G16B16A16_SFLOAT, 4, 2, false}}, {"R16F", {VK_FORMAT_R16_SFLOAT, 1, 2, false}},
        {"RG16F", {VK_FORMAT_R16G16_SFLOAT, 2, 2, false}},        {"RGBA32F", {VK_FORMAT_R32G32B32A32_SFLOAT, 4, 4, false}},
        {"R32F", {VK_FORMAT_R32_SFLOAT, 1, 4, false}},            {"RG32F", {VK_FORMAT_R32G32_SFLOAT, 2, 4, false}},
        {"RGBA32UI", {VK_FORMAT_R32G32B32A32_UINT, 4, 4, false}}}; // the slicing bits of 64 / 128 slices
    auto it = formats.find(name);
    if (it == formats.end()) fail("internal format '" + name + "' is not supported by this runner");
    return it->second;
}

VkFilter filter_of(const std::string& name) {
    return name.starts_with("LINEAR") ? VK_FILTER_LINEAR : VK_FILTER_NEAREST;
}

VkSamplerAddressMode address_mode(const std::string& wrap) {
    if (wrap == "CLAMP_TO_BORDER") return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    if (wrap == "CLAMP_TO_EDGE") return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
    if (wrap == "REPEAT") return VK_SAMPLER_ADDRESS_MODE_REPEAT;
    if (wrap == "MIRRORED_REPEAT") return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
    fail("wrap mode '" + wrap + "' is unknown; allowed: CLAMP_TO_BORDER, CLAMP_TO_EDGE, REPEAT, MIRRORED_REPEAT");
}

// Core Vulkan has three border colours; others need VK_EXT_custom_border_color.
VkBorderColor border_color(const std::vector<float>& c) {
    if (c == std::vector<float>{0, 0, 0, 0}) return VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    if (c == std::vector<float>{0, 0, 0, 1}) return VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
    if (c == std::vector<float>{1, 1, 1, 1}) return VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    fail("border colour is not one of core Vulkan's (0,0,0,0), (0,0,0,1), (1,1,1,1)");
}

VkBlendOp blend_op(const std::string& name) {
    if (name == "ADD") return VK_BLEND_OP_ADD;
    if (name == "MAX") return VK_BLEND_OP_MAX;
    if (name == "MIN") return VK_BLEND_OP_MIN;
    if (name == "SUBTRACT") return VK_BLEND_OP_SUBTRACT;
    if (name == "REVERSE_SUBTRACT") return VK_BLEND_OP_REVERSE_SUBTRACT;
    fail("blend equation '" + name + "' is unknown");
}

VkBlendFactor blend_factor(const std::string& name) {
    static const std::map<std::string, VkBlendFactor> factors{
        {"ZERO", VK_BLEND_FACTOR_ZERO},
        {"ONE", VK_BLEND_FACTOR_ONE},
        {"SRC_COLOR", VK_BLEND_FACTOR_SRC_COLOR},
        {"ONE_MINUS_SRC_COLOR", VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR},
        {"DST_COLOR", VK_BLEND_FACTOR_DST_COLOR},
        {"ONE_MINUS_DST_COLOR", VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR},
        {"SRC_ALPHA", VK_BLEND_FACTOR_SRC_ALPHA},
        {"ONE_MINUS_SRC_ALPHA", VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA},
        {"DST_ALPHA", VK_BLEND_FACTOR_DST_ALPHA},
        {"ONE_MINUS_DST_ALPHA", VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA}};
    auto it = factors.find(name);
    if (it == factors.end()) fail("blend factor '" + name + "' is unknown");
    return it->second;
}

VkCullModeFlags cull_mode(const std::string& name) {
    if (name == "NONE") return VK_CULL_MODE_NONE;
    if (name == "BACK") return VK_CULL_MODE_BACK_BIT;
    if (name == "FRONT") return VK_CULL_MODE_FRONT_BIT;
    fail("cull mode '" + name + "' is unknown; allowed: NONE, BACK, FRONT");
}

// std140 sizes of the plain uniform types an emission declares.
int std140_size(const std::string& type) {
    static const std::map<std::string, int> sizes{{"float", 4}, {"int", 4}, {"uint", 4}, {"vec2", 8}, {"ivec2", 8},
                                                  {"vec3", 12}, {"vec4", 16}, {"ivec4", 16}, {"mat4", 64}};
    auto it = sizes.find(type);
    if (it == sizes.end()) fail("uniform type '" + type + "' is not supported by this runner");
    return it->second;
}

std::optional<Stage> stage_of(const std::string& file) {
    for (Stage s : {Stage::vertex, Stage::fragment, Stage::compute})
        if (file.ends_with(stage_extension(s)) && file.size() > stage_extension(s).size() &&
            file[file.size() - stage_extension(s).size() - 1] == '.')
            return s;
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
};

void check_required_limits(const json& layout) {
    using L = RequiredLimits;
    for (const json& t : layout.at("textures")) {
        const std::string name = t.at("name"), target = t.at("target");
        const int w = t.at("width"), h = t.at("height"), d = t.at("depth");
        const int max_side = target == "3D" ? L::image_dimension_3d : L::image_dimension_2d;
        if (w > max_side || h > max_side || (target == "3D" && d > L::image_dimension_3d) ||
            (target == "2D_ARRAY" && d > L::image_array_layers))
            fail("texture " + name + ": " + std::to_string(w) + "x" + std::to_string(h) + "x" + std::to_string(d) +
                 " exceeds what Vulkan guarantees for a " + target + " image (2D " + std::to_string(L::image_dimension_2d) +
                 ", 3D " + std::to_string(L::image_dimension_3d) + ", layers " + std::to_string(L::image_array_layers) + ")");
    }
    for (const json& p : layout.at("passes")) {
        const std::string name = p.at("name");
        if (p.at("outputs").size() > static_cast<std::size_t>(L::color_attachments))
            fail("pass " + name + ": " + std::to_string(p.at("outputs").size()) +
                 " colour attachments; Vulkan guarantees " + std::to_string(L::color_attachments));
        if (p.at("viewport").at(0).get<int>() > L::framebuffer_size || p.at("viewport").at(1).get<int>() > L::framebuffer_size)
            fail("pass " + name + ": viewport beyond Vulkan's guaranteed framebuffer size " + std::to_string(L::framebuffer_size));
    }
    for (const json& p : layout.at("programs")) {
        int samplers = 0;
        std::map<int, int> blocks; // binding → bytes used
        for (const json& param : p.at("parameters")) {
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
    std::string target; // 2D, 2D_ARRAY, 3D
    FormatInfo format;
    std::uint32_t width = 0, height = 0, depth = 1, levels = 1;
    VkImage image = VK_NULL_HANDLE;
    VkSampler sampler = VK_NULL_HANDLE;
    std::uint32_t layers() const { return target == "2D_ARRAY" ? depth : 1; }
    std::uint32_t extent_depth() const { return target == "3D" ? depth : 1; }
};

struct Block {
    int size = 0;
    std::vector<json> members;
};

struct Program {
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    VkDescriptorSetLayout set_layout = VK_NULL_HANDLE;
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
    std::map<int, Block> blocks;     // uniform blocks by binding
    std::map<int, json> samplers;    // sampler parameters by binding
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
        if (layout.value("layout_version", 1) < 2)
            fail("layout.json has layout_version " + std::to_string(layout.value("layout_version", 1)) +
                 "; this runner follows version 2 (structured render state, pass phases, texture sizes and sources)");
        if (layout.at("config").at("target") != "vulkan")
            fail("layout.json is for target '" + layout.at("config").at("target").get<std::string>() +
                 "'; this runner needs the vulkan target's");
        check_required_limits(layout);
        std::vector<const json*> passes;
        for (const char* phase : {"shadow", "screen"})
            for (const json& pass : layout.at("passes"))
                if (pass.at("phase") == phase) passes.push_back(&pass);
        for (const json& t : layout.at("textures")) create_texture(t, passes);
        vertices_ = create_buffer(std::max<std::size_t>(in_.triangles.size() * sizeof(float), 16),
                                  VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
        std::memcpy(vertices_.mapped, in_.triangles.data(), in_.triangles.size() * sizeof(float));
        create_descriptor_pool(passes.size());
        const Texture& result = texture(layout.at("result").get<std::string>());
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

    // What the passes do with a texture decides its usage flags and the format features it needs.
    void create_texture(const json& t, const std::vector<const json*>& passes) {
        Texture tex;
        tex.name = t.at("name").get<std::string>();
        tex.target = t.at("target").get<std::string>();
        tex.format = format_info(t.at("internal_format").get<std::string>());
        const std::string what = "texture " + tex.name;
        if (tex.target != "2D" && tex.target != "2D_ARRAY" && tex.target != "3D")
            fail(what + ": target '" + tex.target + "' is unknown; allowed: 2D, 2D_ARRAY, 3D");
        const bool output_sized = t.at("size") == "output";
        tex.width = static_cast<std::uint32_t>(output_sized ? in_.width : t.at("width").get<int>());
        tex.height = static_cast<std::uint32_t>(output_sized ? in_.height : t.at("height").get<int>());
        tex.depth = static_cast<std::uint32_t>(t.at("depth").get<int>());
        tex.levels = static_cast<std::uint32_t>(t.at("mip_levels").get<int>());

        VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT; // cleared or uploaded first
        VkFormatFeatureFlags features = VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
        bool attachment = false;
        for (const json* pass : passes) {
            const std::string action = pass->at("action");
            for (const json& o : pass->at("outputs")) {
                if (o.at("texture") != tex.name) continue;
                if (action == "generate_mipmap") {
                    usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
                    features |= VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT |
                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
                } else if (action != "copy") {
                    attachment = true;
                    usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
                    features |= VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT;
                    if (pass->at("state").at("blend").get<bool>()) features |= VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT;
                }
            }
            for (const json& i : pass->at("inputs")) {
                if (i.at("texture") != tex.name) continue;
                if (pass->at("action") == "copy") {
                    usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
                    features |= VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
                } else {
                    usage |= VK_IMAGE_USAGE_SAMPLED_BIT;
                    features |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT;
                    if (filter_of(t.at("min_filter")) == VK_FILTER_LINEAR || filter_of(t.at("mag_filter")) == VK_FILTER_LINEAR)
                        features |= VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
                }
            }
        }
        if (tex.name == in_.layout.at("result")) {
            usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
            features |= VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
        }
        VkFormatProperties props;
        vkGetPhysicalDeviceFormatProperties(c_.physical_device(), tex.format.format, &props);
        if ((props.optimalTilingFeatures & features) != features)
            fail(what + ": the device lacks format features 0x" + [&] {
                char hex[16];
                std::snprintf(hex, sizeof hex, "%x", features & ~props.optimalTilingFeatures);
                return std::string(hex);
            }() + " of " + t.at("internal_format").get<std::string>() + " that its passes need");

        VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
        // A depth slice of a 3D image is rendered through a 2D view of it.
        if (tex.target == "3D" && attachment) info.flags = VK_IMAGE_CREATE_2D_ARRAY_COMPATIBLE_BIT;
        info.imageType = tex.target == "3D" ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
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
            fail(what + ": the device cannot create a " + tex.target + " " + t.at("internal_format").get<std::string>() +
                 " image of " + std::to_string(tex.width) + "x" + std::to_string(tex.height) + "x" +
                 std::to_string(tex.depth) + " with " + std::to_string(tex.levels) + " levels");
        check(vkCreateImage(device_, &info, nullptr, &tex.image), what + ": vkCreateImage");
        VkImage image = tex.image;
        VkMemoryRequirements req;
        vkGetImageMemoryRequirements(device_, image, &req);
        VkDeviceMemory memory = allocate(req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, what);
        on_cleanup([this, image] { vkDestroyImage(device_, image, nullptr); });
        check(vkBindImageMemory(device_, image, memory, 0), what + ": vkBindImageMemory");

        const std::string min = t.at("min_filter"), mag = t.at("mag_filter"), wrap = t.at("wrap");
        VkSamplerCreateInfo s{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
        s.magFilter = filter_of(mag);
        s.minFilter = filter_of(min);
        const bool mipmapped = min.find("_MIPMAP_") != std::string::npos;
        s.mipmapMode = min.ends_with("MIPMAP_LINEAR") ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
        s.addressModeU = s.addressModeV = s.addressModeW = address_mode(wrap);
        if (wrap == "CLAMP_TO_BORDER") s.borderColor = border_color(t.at("border_color").get<std::vector<float>>());
        s.minLod = 0.0f;
        s.maxLod = mipmapped ? VK_LOD_CLAMP_NONE : 0.25f; // 0.25: a GL non-mipmap filter (Vulkan spec, "Samplers")
        if (const std::string compare = t.value("compare", ""); !compare.empty())
            fail(what + ": depth comparison ('" + compare + "') is not supported by this runner");
        check(vkCreateSampler(device_, &s, nullptr, &tex.sampler), what + ": vkCreateSampler");
        VkSampler sampler = tex.sampler;
        on_cleanup([this, sampler] { vkDestroySampler(device_, sampler, nullptr); });
        textures_[tex.name] = tex;
        sources_[tex.name] = t.at("source").get<std::string>();
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
        info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, level, levels, layer, layers};
        VkImageView v = VK_NULL_HANDLE;
        check(vkCreateImageView(device_, &info, nullptr, &v), "texture " + t.name + ": vkCreateImageView");
        on_cleanup([this, v] { vkDestroyImageView(device_, v, nullptr); });
        return views_[key] = v;
    }

    // What a sampler reads: the whole texture, or only level `level` (>= 0).
    VkImageView sampled_view(const Texture& t, int level) {
        const VkImageViewType type = t.target == "3D"       ? VK_IMAGE_VIEW_TYPE_3D
                                     : t.target == "2D_ARRAY" ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
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
        for (const json& f : desc->at("files")) {
            const std::string file = f.get<std::string>();
            const std::optional<Stage> stage = stage_of(file);
            if (!stage) fail("program " + name + ": cannot tell the stage of '" + file + "' (.vert, .frag, .comp)");
            source.stages.push_back({file, *stage, read_text(in_.emission_dir / file)});
        }
        std::vector<std::vector<unsigned int>> spirv;
        const std::vector<ShaderDiagnostic> diagnostics = validate_program(source, Target::vulkan, &spirv);
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
        // Set 0 holds everything: the emitted GLSL declares every binding in set 0.
        std::vector<VkDescriptorSetLayoutBinding> bindings;
        for (const json& p : desc->at("parameters")) {
            const std::string type = p.at("type");
            if (p.contains("block_binding")) {
                Block& block = prog.blocks[p.at("block_binding").get<int>()];
                block.size = std::max(block.size, p.at("offset").get<int>() + std140_size(type));
                block.members.push_back(p);
            } else if (type.find("sampler") != std::string::npos && p.contains("binding")) { // usampler2D too
                prog.samplers[p.at("binding").get<int>()] = p;
            } else {
                fail("program " + name + ": parameter " + p.at("name").get<std::string>() +
                     " has neither a uniform block nor a binding");
            }
        }
        for (auto& [binding, block] : prog.blocks) {
            block.size = (block.size + 15) / 16 * 16; // std140 rounds a block up to a vec4
            bindings.push_back({static_cast<std::uint32_t>(binding), VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
        }
        for (const auto& [binding, param] : prog.samplers)
            bindings.push_back({static_cast<std::uint32_t>(binding), VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                                VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr});
        VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
        set_info.bindingCount = static_cast<std::uint32_t>(bindings.size());
        set_info.pBindings = bindings.data();
        check(vkCreateDescriptorSetLayout(device_, &set_info, nullptr, &prog.set_layout), "program " + name + ": descriptor set layout");
        VkDescriptorSetLayout set_layout = prog.set_layout;
        on_cleanup([this, set_layout] { vkDestroyDescriptorSetLayout(device_, set_layout, nullptr); });
        VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
        layout_info.setLayoutCount = 1;
        layout_info.pSetLayouts = &prog.set_layout;
        check(vkCreatePipelineLayout(device_, &layout_info, nullptr, &prog.pipeline_layout), "program " + name + ": pipeline layout");
        VkPipelineLayout pipeline_layout = prog.pipeline_layout;
        on_cleanup([this, pipeline_layout] { vkDestroyPipelineLayout(device_, pipeline_layout, nullptr); });
        return programs_[name] = std::move(prog);
    }

    void create_descriptor_pool(std::size_t passes) {
        const auto sets = static_cast<std::uint32_t>(std::max<std::size_t>(passes, 1));
        const VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 4 * sets},
                                              {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 32 * sets}};
        VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
        info.maxSets = sets;
        info.poolSizeCount = 2;
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

    VkPipeline pipeline(const std::string& program_name, Program& prog, const json& pass,
                        const std::vector<VkFormat>& formats) {
        const json& state = pass.at("state");
        std::string key = program_name + "|" + pass.at("action").get<std::string>() + "|" + state.dump();
        for (VkFormat f : formats) key.append("|").append(std::to_string(f));
        if (auto it = pipelines_.find(key); it != pipelines_.end()) return it->second;
        if (state.at("depth_test").get<bool>() || state.at("depth_write").get<bool>())
            fail("pass " + pass.at("name").get<std::string>() + ": depth testing is not supported by this runner");

        const bool scene = pass.at("action") == "draw_scene";
        // draw_scene: attribute 0 = world position, three floats (the GL runtime's convention).
        const VkVertexInputBindingDescription vertex_binding{0, 3 * sizeof(float), VK_VERTEX_INPUT_RATE_VERTEX};
        const VkVertexInputAttributeDescription position{0, 0, VK_FORMAT_R32G32B32_SFLOAT, 0};
        VkPipelineVertexInputStateCreateInfo vertex_input{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
        if (scene) {
            vertex_input.vertexBindingDescriptionCount = 1;
            vertex_input.pVertexBindingDescriptions = &vertex_binding;
            vertex_input.vertexAttributeDescriptionCount = 1;
            vertex_input.pVertexAttributeDescriptions = &position;
        }
        VkPipelineInputAssemblyStateCreateInfo assembly{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
        assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;
        VkPipelineRasterizationStateCreateInfo raster{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = cull_mode(state.at("cull"));
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f;
        VkPipelineMultisampleStateCreateInfo multisample{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
        multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        const std::string logic_op = state.value("logic_op", "NONE");
        if (logic_op != "NONE" && logic_op != "OR")
            fail("pass state: logic_op " + logic_op + " is not supported by this runner; allowed: NONE, OR");
        if (logic_op == "OR" && !c_.logic_op())
            fail("pass state: logic_op OR needs the device feature logicOp, which this device lacks");
        VkPipelineColorBlendAttachmentState blend{};
        blend.blendEnable = state.at("blend").get<bool>() ? VK_TRUE : VK_FALSE;
        blend.colorBlendOp = blend.alphaBlendOp = blend_op(state.at("blend_equation"));
        blend.srcColorBlendFactor = blend.srcAlphaBlendFactor = blend_factor(state.at("blend_src"));
        blend.dstColorBlendFactor = blend.dstAlphaBlendFactor = blend_factor(state.at("blend_dst"));
        const std::vector<bool> mask = state.at("color_mask").get<std::vector<bool>>();
        for (std::size_t i = 0; i < 4 && i < mask.size(); ++i)
            if (mask[i]) blend.colorWriteMask |= VK_COLOR_COMPONENT_R_BIT << i;
        const std::vector<VkPipelineColorBlendAttachmentState> blends(formats.size(), blend);
        VkPipelineColorBlendStateCreateInfo blending{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
        blending.logicOpEnable = logic_op == "OR" ? VK_TRUE : VK_FALSE; // integer targets: fragments OR-ed in
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
        const std::string name = pass.at("name"), action = pass.at("action");
        if (action == "generate_mipmap") return prepare_mipmaps(texture(pass.at("outputs").at(0).at("texture")));
        if (action == "copy") return prepare_copy(pass);
        if (action != "draw_scene" && action != "fullscreen")
            fail("pass " + name + ": action '" + action + "' is unknown; allowed: draw_scene, fullscreen, generate_mipmap, copy");

        Program& prog = program(pass.at("program"));
        const std::string program_name = pass.at("program");
        std::uint32_t width = pass.at("viewport").at(0).get<std::uint32_t>();
        std::uint32_t height = pass.at("viewport").at(1).get<std::uint32_t>();
        if (width == 0 || height == 0) {
            width = static_cast<std::uint32_t>(in_.width);
            height = static_cast<std::uint32_t>(in_.height);
        }
        std::vector<VkRenderingAttachmentInfo> attachments;
        std::vector<VkFormat> formats;
        const json& state = pass.at("state");
        VkClearValue clear{};
        const bool clears = !state.at("clear_color").is_null();
        if (clears)
            for (int i = 0; i < 4; ++i) clear.color.float32[i] = state.at("clear_color").at(i).get<float>();
        if (pass.at("outputs").size() > c_.properties().limits.maxColorAttachments)
            fail("pass " + name + ": " + std::to_string(pass.at("outputs").size()) + " colour attachments; the device has " +
                 std::to_string(c_.properties().limits.maxColorAttachments));
        for (const json& o : pass.at("outputs")) {
            if (o.value("kind", "color") != "color") fail("pass " + name + ": depth attachments are not supported by this runner");
            const Texture& t = texture(o.at("texture"));
            VkRenderingAttachmentInfo a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
            a.imageView = attachment_view(t, o.at("level").get<int>(), o.at("layer").get<int>());
            a.imageLayout = VK_IMAGE_LAYOUT_GENERAL;
            a.loadOp = clears ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
            a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
            a.clearValue = clear;
            attachments.push_back(a);
            formats.push_back(t.format.format);
        }
        const VkPipeline pipe = pipeline(program_name, prog, pass, formats);

        // Descriptor set: one uniform buffer per block, filled now, and the pass's inputs.
        VkDescriptorSetAllocateInfo allocate{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
        allocate.descriptorPool = pool_;
        allocate.descriptorSetCount = 1;
        allocate.pSetLayouts = &prog.set_layout;
        VkDescriptorSet set = VK_NULL_HANDLE;
        check(vkAllocateDescriptorSets(device_, &allocate, &set), "pass " + name + ": vkAllocateDescriptorSets");
        std::vector<VkDescriptorBufferInfo> buffer_infos;
        std::vector<VkDescriptorImageInfo> image_infos;
        buffer_infos.reserve(prog.blocks.size());
        image_infos.reserve(prog.samplers.size());
        std::vector<VkWriteDescriptorSet> writes;
        for (const auto& [binding, block] : prog.blocks) {
            const Buffer b = create_buffer(static_cast<std::size_t>(block.size), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
            for (const json& member : block.members) write_member(member, pass, static_cast<unsigned char*>(b.mapped));
            buffer_infos.push_back({b.buffer, 0, static_cast<VkDeviceSize>(block.size)});
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = set;
            w.dstBinding = static_cast<std::uint32_t>(binding);
            w.descriptorCount = 1;
            w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
            w.pBufferInfo = &buffer_infos.back();
            writes.push_back(w);
        }
        for (const auto& [binding, param] : prog.samplers) {
            const json* input = nullptr;
            for (const json& i : pass.at("inputs"))
                if (i.at("binding").get<int>() == binding) input = &i;
            if (!input)
                fail("pass " + name + ": no input for sampler " + param.at("name").get<std::string>() + " (binding " +
                     std::to_string(binding) + ")");
            if (input->at("sampler") != param.at("name"))
                fail("pass " + name + ": input at binding " + std::to_string(binding) + " is for " +
                     input->at("sampler").get<std::string>() + ", the program has " + param.at("name").get<std::string>());
            const Texture& t = texture(input->at("texture"));
            image_infos.push_back({t.sampler, sampled_view(t, input->value("level", -1)), VK_IMAGE_LAYOUT_GENERAL});
            VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
            w.dstSet = set;
            w.dstBinding = static_cast<std::uint32_t>(binding);
            w.descriptorCount = 1;
            w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
            w.pImageInfo = &image_infos.back();
            writes.push_back(w);
        }
        vkUpdateDescriptorSets(device_, static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);

        const bool scene = action == "draw_scene";
        const auto vertex_count = static_cast<std::uint32_t>(in_.triangles.size() / 3);
        const VkPipelineLayout pipeline_layout = prog.pipeline_layout;
        const VkBuffer vertices = vertices_.buffer;
        return [=](VkCommandBuffer cmd) {
            VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
            rendering.renderArea = {{0, 0}, {width, height}};
            rendering.layerCount = 1;
            rendering.colorAttachmentCount = static_cast<std::uint32_t>(attachments.size());
            rendering.pColorAttachments = attachments.data();
            vkCmdBeginRendering(cmd, &rendering);
            vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipe);
            const VkViewport vp{0.0f, 0.0f, static_cast<float>(width), static_cast<float>(height), 0.0f, 1.0f};
            const VkRect2D scissor{{0, 0}, {width, height}};
            vkCmdSetViewport(cmd, 0, 1, &vp);
            vkCmdSetScissor(cmd, 0, 1, &scissor);
            vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_layout, 0, 1, &set, 0, nullptr);
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

    // Each level from the one above it, halving (a 2:1 linear blit averages 2×2 texels).
    std::function<void(VkCommandBuffer)> prepare_mipmaps(const Texture& t) {
        return [this, t](VkCommandBuffer cmd) {
            for (std::uint32_t level = 1; level < t.levels; ++level) {
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

    // inputs[0] (its level, level 0 when it names all) into outputs[0] (level, layer or depth
    // slice), viewport-sized.
    std::function<void(VkCommandBuffer)> prepare_copy(const json& pass) {
        const Texture& src = texture(pass.at("inputs").at(0).at("texture"));
        const json& o = pass.at("outputs").at(0);
        const Texture& dst = texture(o.at("texture"));
        const int layer = std::max(o.at("layer").get<int>(), 0);
        VkImageCopy region{};
        const auto src_level = static_cast<std::uint32_t>(std::max(pass.at("inputs").at(0).value("level", -1), 0));
        region.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, src_level, 0, 1};
        region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, o.at("level").get<std::uint32_t>(),
                                 dst.target == "2D_ARRAY" ? static_cast<std::uint32_t>(layer) : 0u, 1};
        if (dst.target == "3D") region.dstOffset.z = layer;
        region.extent = {pass.at("viewport").at(0).get<std::uint32_t>(), pass.at("viewport").at(1).get<std::uint32_t>(), 1};
        if (src.format.format != dst.format.format)
            fail("pass " + pass.at("name").get<std::string>() + ": copy between different formats");
        const VkImage from = src.image, to = dst.image;
        const VkImageSubresourceRange from_range{VK_IMAGE_ASPECT_COLOR_BIT, src_level, 1, 0, 1};
        const VkImageSubresourceRange to_range{VK_IMAGE_ASPECT_COLOR_BIT, region.dstSubresource.mipLevel, 1,
                                               region.dstSubresource.baseArrayLayer, 1};
        return [=](VkCommandBuffer cmd) {
            transition(cmd, from, from_range, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
            transition(cmd, to, to_range, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
            vkCmdCopyImage(cmd, from, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, to, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                           &region);
            transition(cmd, from, from_range, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
            transition(cmd, to, to_range, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
        };
    }

    // Caller textures ("source": "caller") from the inputs, into staging buffers.
    std::vector<Buffer> stage_caller_textures() {
        std::vector<Buffer> out;
        for (const auto& [name, source] : sources_) {
            if (source == "passes") continue;
            if (source != "caller") fail("texture " + name + ": source '" + source + "' is not supported by this runner");
            const Texture& t = textures_.at(name);
            auto it = in_.caller_textures.find(name);
            if (it == in_.caller_textures.end()) fail("texture " + name + ": the caller must fill it, and no data was given");
            if (t.format.bytes_per_channel != 4 || t.depth != 1 || t.levels != 1)
                fail("texture " + name + ": only single-level 32-bit float caller textures are supported");
            const std::size_t floats = static_cast<std::size_t>(t.width) * t.height * t.format.channels;
            if (it->second.size() != floats)
                fail("texture " + name + ": " + std::to_string(it->second.size()) + " floats given, " + std::to_string(floats) + " needed");
            Buffer b = create_buffer(floats * sizeof(float), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
            std::memcpy(b.mapped, it->second.data(), floats * sizeof(float));
            out.push_back(b);
            caller_order_.push_back(name);
        }
        return out;
    }

    // Every image cleared to 0 (all levels and layers; the caller's uploaded instead), then left in
    // GENERAL, the layout in which passes sample and render it.
    void initialise_images(VkCommandBuffer cmd, const std::vector<Buffer>& uploads) {
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
        for (const auto& [name, t] : textures_)
            transition(cmd, t.image, all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
        const VkClearColorValue zero{};
        for (const auto& [name, t] : textures_)
            if (sources_.at(name) == "passes")
                vkCmdClearColorImage(cmd, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &zero, 1, &all);
        for (std::size_t i = 0; i < uploads.size(); ++i) {
            const Texture& t = textures_.at(caller_order_[i]);
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {t.width, t.height, 1};
            vkCmdCopyBufferToImage(cmd, uploads[i].buffer, t.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        }
        for (const auto& [name, t] : textures_)
            transition(cmd, t.image, all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
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
    std::map<std::string, std::string> sources_; // texture → "passes" / "caller"
    std::vector<std::string> caller_order_;      // the textures stage_caller_textures filled, in order
    std::map<std::string, VkImageView> views_;
    std::map<std::string, Program> programs_;
    std::map<std::string, VkPipeline> pipelines_;
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
