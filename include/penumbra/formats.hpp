// penumbra/formats.hpp — the texture formats of a layout (layout.json "internal_format") and, per
// format, what every runner needs: channels, bytes per texel and kind. One row per format; the GL
// and Vulkan enums are looked up from TextureFormat in their runners (penumbra/gl/layout_enums.hpp,
// targets/vulkan).
//
//   const penumbra::FormatInfo& f = penumbra::format_info(penumbra::TextureFormat::rgba16f);
//   // f.channels == 4, f.bytes_per_texel == 8, f.kind == penumbra::FormatKind::float_
#pragma once

#include "config.hpp"

#include <array>
#include <cstdint>
#include <string_view>

namespace penumbra {

// A texture's internal format; the names (EnumNames below) are GL's sized formats without GL_.
enum class TextureFormat : std::uint8_t {
    rgba8,
    rgba16f,
    rgba32f,
    r8,
    r16f,
    r32f,
    rg16f,
    rg32f,
    rgba32ui,
    r32ui,
    depth24,  // DEPTH_COMPONENT24
    depth32f, // DEPTH_COMPONENT32F
};
template <> struct EnumNames<TextureFormat> {
    static constexpr std::array<std::string_view, 12> names{
        "RGBA8", "RGBA16F", "RGBA32F", "R8", "R16F", "R32F", "RG16F", "RG32F", "RGBA32UI", "R32UI",
        "DEPTH_COMPONENT24", "DEPTH_COMPONENT32F"};
};

// What a texel holds: normalized 8-bit values (read as 0..1 floats), floats (16 or 32 bits),
// unsigned integers (read with usampler, cleared with integer values, never filtered) or depth.
enum class FormatKind : std::uint8_t { unorm, float_, uint, depth };
template <> struct EnumNames<FormatKind> {
    static constexpr std::array<std::string_view, 4> names{"unorm", "float", "uint", "depth"};
};

struct FormatInfo {
    int channels;        // colour components (R 1, RG 2, RGBA 4); 1 for depth
    int bytes_per_texel; // the storage the format asks for (drivers may pad)
    FormatKind kind;
    std::string_view webgpu; // WebGPU's GPUTextureFormat (target wgsl)
};

namespace detail {
// Indexed by TextureFormat, in its order.
inline constexpr std::array<FormatInfo, 12> format_table{{
    {4, 4, FormatKind::unorm, "rgba8unorm"},    // RGBA8
    {4, 8, FormatKind::float_, "rgba16float"},  // RGBA16F
    {4, 16, FormatKind::float_, "rgba32float"}, // RGBA32F
    {1, 1, FormatKind::unorm, "r8unorm"},       // R8
    {1, 2, FormatKind::float_, "r16float"},     // R16F
    {1, 4, FormatKind::float_, "r32float"},     // R32F
    {2, 4, FormatKind::float_, "rg16float"},    // RG16F
    {2, 8, FormatKind::float_, "rg32float"},    // RG32F
    {4, 16, FormatKind::uint, "rgba32uint"},    // RGBA32UI
    {1, 4, FormatKind::uint, "r32uint"},        // R32UI
    {1, 4, FormatKind::depth, "depth24plus"},   // DEPTH_COMPONENT24 (stored in 32 bits)
    {1, 4, FormatKind::depth, "depth32float"},  // DEPTH_COMPONENT32F
}};
static_assert(format_table.size() == EnumNames<TextureFormat>::names.size(), "one format_table row per TextureFormat");
} // namespace detail

constexpr const FormatInfo& format_info(TextureFormat format) {
    return detail::format_table[static_cast<std::size_t>(format)];
}
constexpr int bytes_per_texel(TextureFormat format) { return format_info(format).bytes_per_texel; }
constexpr int channels(TextureFormat format) { return format_info(format).channels; }
// Bytes of one component: 1 (8-bit), 2 (half float) or 4 (float, uint, depth).
constexpr int bytes_per_channel(TextureFormat format) { return bytes_per_texel(format) / channels(format); }
constexpr bool is_depth(TextureFormat format) { return format_info(format).kind == FormatKind::depth; }
constexpr bool is_integer(TextureFormat format) { return format_info(format).kind == FormatKind::uint; }
constexpr bool is_float(TextureFormat format) { return format_info(format).kind == FormatKind::float_; }

// WebGPU's sample type of a texture binding of `format` (GPUTextureSampleType): 32-bit floats are not
// filterable without the optional float32-filterable feature.
constexpr std::string_view webgpu_sample_type(TextureFormat format) {
    switch (format_info(format).kind) {
    case FormatKind::depth: return "depth";
    case FormatKind::uint: return "uint";
    case FormatKind::float_: return bytes_per_channel(format) == 4 ? "unfilterable-float" : "float";
    case FormatKind::unorm: return "float";
    }
    return "float";
}

} // namespace penumbra
