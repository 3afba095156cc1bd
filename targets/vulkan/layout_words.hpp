// targets/vulkan/layout_words.hpp — layout.json's words in Vulkan's terms (formats, filters, wrap,
// blending, comparison, stages), its std140 sizes, and the check of what the layout asks against the
// limits Vulkan 1.0 guarantees; failures as detail::Failure, which run_layout turns into its one line.
#pragma once

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

namespace penumbra::vulkan::detail {

using nlohmann::json;

// Thrown inside the runner for any failure; run_layout turns it into its diagnostic.
struct Failure {
    std::string message;
};

[[noreturn]] inline void fail(std::string message) { throw Failure{std::move(message)}; }

inline void check(VkResult result, const std::string& what) {
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
inline VkFormat vk_format(TextureFormat f) {
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

inline FormatInfo format_info(const std::string& name) {
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
template <class Enum> inline Enum word(const json& j, const char* key, const std::string& what, std::string_view fallback = {}) {
    if (!j.contains(key) && fallback.empty()) fail(what + ": no " + key);
    const std::string name = j.contains(key) ? j.at(key).get<std::string>() : std::string(fallback);
    if (const std::optional<Enum> value = parse_enum<Enum>(name)) return *value;
    fail(what + ": " + key + " '" + name + "' is unknown; allowed: " + penumbra::detail::joined_names<Enum>().str());
}

inline VkFilter filter_of(TextureFilter f) { return filters_linearly(f) ? VK_FILTER_LINEAR : VK_FILTER_NEAREST; }

inline VkCompareOp compare_op(CompareFunc f) {
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
inline Sampling parse_sampling(const json& j, const std::string& what) {
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
inline bool linear(const Sampling& s) { return filters_linearly(s.min_filter) || filters_linearly(s.mag_filter); }
inline bool mipmapped(const Sampling& s) {
    return s.min_filter != TextureFilter::nearest && s.min_filter != TextureFilter::linear;
}

inline VkSamplerAddressMode address_mode(Wrap wrap) {
    return wrap == Wrap::clamp_to_border ? VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER : VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
}

// Core Vulkan has three border colours; others need VK_EXT_custom_border_color.
// `integer`: the sampler reads an integer texture (usampler), whose border is an integer colour.
inline VkBorderColor border_color(const std::array<float, 4>& c, bool integer) {
    if (c == std::array<float, 4>{0, 0, 0, 0}) return integer ? VK_BORDER_COLOR_INT_TRANSPARENT_BLACK : VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
    if (c == std::array<float, 4>{0, 0, 0, 1}) return integer ? VK_BORDER_COLOR_INT_OPAQUE_BLACK : VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
    if (c == std::array<float, 4>{1, 1, 1, 1}) return integer ? VK_BORDER_COLOR_INT_OPAQUE_WHITE : VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    fail("border colour is not one of core Vulkan's (0,0,0,0), (0,0,0,1), (1,1,1,1)");
}

inline VkBlendOp blend_op(BlendEquation e) {
    switch (e) {
    case BlendEquation::add: return VK_BLEND_OP_ADD;
    case BlendEquation::max: return VK_BLEND_OP_MAX;
    case BlendEquation::min: return VK_BLEND_OP_MIN;
    }
    return VK_BLEND_OP_ADD;
}

inline VkBlendFactor blend_factor(BlendFactor f) {
    switch (f) {
    case BlendFactor::zero: return VK_BLEND_FACTOR_ZERO;
    case BlendFactor::one: return VK_BLEND_FACTOR_ONE;
    case BlendFactor::src_alpha: return VK_BLEND_FACTOR_SRC_ALPHA;
    case BlendFactor::one_minus_src_alpha: return VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::dst_color: return VK_BLEND_FACTOR_DST_COLOR;
    }
    return VK_BLEND_FACTOR_ZERO;
}

inline VkCullModeFlags cull_mode(Cull c) {
    return c == Cull::back ? VK_CULL_MODE_BACK_BIT : c == Cull::front ? VK_CULL_MODE_FRONT_BIT : VK_CULL_MODE_NONE;
}

// std140 sizes of the plain uniform types an emission declares.
inline int std140_size(const std::string& type) {
    static const std::map<std::string, int> sizes{{"float", 4}, {"int", 4}, {"uint", 4}, {"vec2", 8}, {"ivec2", 8},
                                                  {"vec3", 12}, {"vec4", 16}, {"ivec4", 16}, {"mat4", 64}};
    auto it = sizes.find(type);
    if (it == sizes.end()) fail("uniform type '" + type + "' is not supported by this runner");
    return it->second;
}

// layout.json's "stages" word of a file ("vertex", "fragment", "compute").
inline std::optional<Stage> stage_named(const std::string& word) {
    for (Stage s : {Stage::vertex, Stage::fragment, Stage::compute})
        if (word == stage_name(s)) return s;
    return std::nullopt;
}

inline VkShaderStageFlagBits vk_stage(Stage stage) {
    switch (stage) {
    case Stage::vertex: return VK_SHADER_STAGE_VERTEX_BIT;
    case Stage::fragment: return VK_SHADER_STAGE_FRAGMENT_BIT;
    case Stage::compute: return VK_SHADER_STAGE_COMPUTE_BIT;
    }
    return VK_SHADER_STAGE_FRAGMENT_BIT;
}

inline std::string read_text(const std::filesystem::path& path) {
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

inline void check_required_limits(const json& layout) {
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

} // namespace penumbra::vulkan::detail
