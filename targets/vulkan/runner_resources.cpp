// targets/vulkan/runner_resources.cpp — the Runner's resources: images and their views, buffers and memory, samplers, the uploads of caller and bake textures and the read-back of the result (runner.hpp).
#include "runner.hpp"

namespace penumbra::vulkan::detail {

Texture& Runner::texture(const std::string& name) {
    auto it = textures_.find(name);
    if (it == textures_.end()) fail("texture '" + name + "' is used by a pass but not listed in textures");
    return it->second;
}

VkDeviceMemory Runner::allocate(VkMemoryRequirements req, VkMemoryPropertyFlags flags, const std::string& what) {
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

Buffer Runner::create_buffer(std::size_t bytes, VkBufferUsageFlags usage) {
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

void Runner::create_texture(const json& t, const std::vector<const json*>& passes) {
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

void Runner::check_sampler_type(const Sampling& sampling, const std::string& type, const std::string& what) {
    const bool shadow_type = type.find("Shadow") != std::string::npos;
    if (shadow_type && !sampling.compare)
        fail(what + ": the program declares a " + type + ", but its sampling has no compare function");
    if (!shadow_type && sampling.compare)
        fail(what + ": compare '" + std::string(to_string(*sampling.compare)) + "' on a " + type + "; hardware comparison needs a shadow sampler type");
}

VkSampler Runner::sampler(const Sampling& sampling, const std::string& type, const std::string& what) {
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

VkImageView Runner::view(const Texture& t, VkImageViewType type, std::uint32_t level, std::uint32_t levels, std::uint32_t layer, std::uint32_t layers) {
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

VkImageView Runner::sampled_view(const Texture& t, int level) {
    const VkImageViewType type = t.target == TextureTarget::texture_3d       ? VK_IMAGE_VIEW_TYPE_3D
                                 : t.target == TextureTarget::texture_2d_array ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                                                               : VK_IMAGE_VIEW_TYPE_2D;
    if (level >= static_cast<int>(t.levels)) fail("texture " + t.name + ": input level " + std::to_string(level) + " does not exist");
    return level < 0 ? view(t, type, 0, t.levels, 0, t.layers())
                     : view(t, type, static_cast<std::uint32_t>(level), 1, 0, t.layers());
}

VkImageView Runner::attachment_view(const Texture& t, int level, int layer) {
    const auto l = static_cast<std::uint32_t>(std::max(layer, 0));
    if (static_cast<std::uint32_t>(level) >= t.levels || l >= std::max(t.layers(), t.extent_depth()))
        fail("texture " + t.name + ": output level " + std::to_string(level) + " layer " + std::to_string(layer) +
             " does not exist");
    return view(t, VK_IMAGE_VIEW_TYPE_2D, static_cast<std::uint32_t>(level), 1, l, 1);
}

std::vector<Buffer> Runner::stage_caller_textures() {
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

std::uint16_t Runner::to_half(float value) {
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

void Runner::initialise_images(VkCommandBuffer cmd, const std::vector<Buffer>& uploads) {
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

std::vector<float> Runner::to_floats(const Texture& t, const void* data) {
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

} // namespace penumbra::vulkan::detail
