// penumbra/texture_memory.hpp — how many bytes a layout's textures take on the GPU (the storage
// they ask for; drivers may pad). For comparing techniques on equal terms, e.g. in metrics.json.
//
//   long long bytes = penumbra::texture_bytes(penumbra::describe_layout(config), width, height);
#pragma once

#include "layout.hpp"

#include <string_view>

namespace penumbra {

// Bytes per texel of a format: bytes_per_texel(TextureFormat), penumbra/formats.hpp.

// One texture with its whole mip chain; a texture sized like the output (width 0) takes the
// output's size.
inline long long texture_bytes(const TextureDesc& t, int output_width, int output_height) {
    long long w = t.width > 0 ? t.width : output_width, h = t.height > 0 ? t.height : output_height;
    long long d = t.depth;
    long long texels = 0;
    for (int level = 0; level < t.mip_levels; ++level) {
        texels += w * h * d;
        w = w > 1 ? w / 2 : 1;
        h = h > 1 ? h / 2 : 1;
        if (t.target == TextureTarget::texture_3d) d = d > 1 ? d / 2 : 1; // array layers stay, 3D depth shrinks
    }
    return texels * bytes_per_texel(t.format);
}

// Every texture the layout allocates, output-sized ones at output_width × output_height; textures
// the caller supplies (source caller, e.g. the G-buffer) are the engine's and not counted.
inline long long texture_bytes(const Layout& layout, int output_width = 0, int output_height = 0) {
    long long total = 0;
    for (const TextureDesc& t : layout.textures)
        if (t.source != TextureSource::caller) total += texture_bytes(t, output_width, output_height);
    return total;
}

} // namespace penumbra
