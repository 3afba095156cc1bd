// bench/compare/texture_memory.hpp — the bytes a layout's textures occupy, from layout.json's
// description alone (format, size, layers or depth, mip levels), as an engine would allocate them.
#pragma once

#include <penumbra/layout.hpp>

#include <algorithm>
#include <cstdint>
#include <optional>
#include <string>

namespace penumbra::bench {

// Bytes per texel of an internal format, or nullopt for a format this table does not know.
inline std::optional<int> bytes_per_texel(const std::string& format) {
    struct Entry {
        const char* name;
        int bytes;
    };
    static constexpr Entry formats[] = {
        {"R8", 1},     {"RG8", 2},     {"RGBA8", 4},    {"R16F", 2},  {"RG16F", 4},
        {"RGBA16F", 8}, {"R32F", 4},    {"RG32F", 8},    {"RGBA32F", 16}, {"R32UI", 4},
        {"RGBA32UI", 16}, {"DEPTH_COMPONENT16", 2}, {"DEPTH_COMPONENT24", 4}, {"DEPTH_COMPONENT32F", 4},
        {"DEPTH24_STENCIL8", 4}, {"DEPTH32F_STENCIL8", 8},
    };
    for (const Entry& e : formats)
        if (format == e.name) return e.bytes;
    return std::nullopt;
}

// One texture: every mip level; a 3D texture halves its depth per level, a 2D array keeps its layers.
inline std::optional<std::uint64_t> texture_bytes(const TextureDesc& t) {
    const std::optional<int> texel = bytes_per_texel(t.internal_format);
    if (!texel) return std::nullopt;
    std::uint64_t total = 0;
    for (int level = 0; level < std::max(1, t.mip_levels); ++level) {
        const std::uint64_t w = std::max(1, t.width >> level), h = std::max(1, t.height >> level);
        const std::uint64_t d = t.target == "3D" ? std::max(1, t.depth >> level) : std::max(1, t.depth);
        total += w * h * d * static_cast<std::uint64_t>(*texel);
    }
    return total;
}

// Every texture of the layout; nullopt and *unknown set to the format when one is not in the table.
inline std::optional<std::uint64_t> layout_texture_bytes(const Layout& layout, std::string* unknown = nullptr) {
    std::uint64_t total = 0;
    for (const TextureDesc& t : layout.textures) {
        const std::optional<std::uint64_t> bytes = texture_bytes(t);
        if (!bytes) {
            if (unknown) *unknown = t.name + " (" + t.internal_format + ")";
            return std::nullopt;
        }
        total += *bytes;
    }
    return total;
}

} // namespace penumbra::bench
