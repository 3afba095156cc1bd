// playground/src/scenes/material_textures.cpp
// stb_image's implementation, static to this file (Debian's libtinygltf carries its own copy).
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include "scenes/material_textures.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <memory>

namespace penumbra::playground {

namespace {

std::uint8_t scaled(int alpha, double factor) {
    return static_cast<std::uint8_t>(std::clamp(std::lround(alpha * std::clamp(factor, 0.0, 1.0)), 0L, 255L));
}

} // namespace

std::optional<AlphaTexture> decode_alpha_texture(const unsigned char* bytes, std::size_t size,
                                                 AlphaChannel channel, double factor, std::string* error) {
    auto fail = [&](std::string why) -> std::optional<AlphaTexture> {
        if (error) *error = std::move(why);
        return std::nullopt;
    };
    if (!bytes || size == 0) return fail("the image is empty");
    if (size > static_cast<std::size_t>(INT_MAX)) return fail("the image is larger than 2 GiB");
    int width = 0, height = 0, channels = 0;
    const int length = static_cast<int>(size);
    if (!stbi_info_from_memory(bytes, length, &width, &height, &channels))
        return fail(std::string("not an image stb_image reads (") + stbi_failure_reason() + ")");
    if (width < 1 || height < 1 || width > alpha_texture_side_limit || height > alpha_texture_side_limit)
        return fail("the image is " + std::to_string(width) + "x" + std::to_string(height) +
                    "; allowed: 1 to " + std::to_string(alpha_texture_side_limit) + " texels per side");
    const bool has_alpha = channels == 2 || channels == 4;
    std::unique_ptr<stbi_uc, void (*)(void*)> pixels(
        stbi_load_from_memory(bytes, length, &width, &height, &channels, 4), stbi_image_free);
    if (!pixels) return fail(std::string("the image does not decode (") + stbi_failure_reason() + ")");
    AlphaTexture out{width, height, std::vector<std::uint8_t>(static_cast<std::size_t>(width) * height)};
    for (std::size_t i = 0; i < out.alpha.size(); ++i) {
        const stbi_uc* p = pixels.get() + 4 * i;
        const int alpha = has_alpha || channel == AlphaChannel::alpha ? p[3] : (p[0] + p[1] + p[2] + 1) / 3;
        out.alpha[i] = scaled(alpha, factor);
    }
    return out;
}

bool image_has_alpha(const unsigned char* bytes, std::size_t size) {
    int width = 0, height = 0, channels = 0;
    return bytes && size > 0 && size <= static_cast<std::size_t>(INT_MAX) &&
           stbi_info_from_memory(bytes, static_cast<int>(size), &width, &height, &channels) &&
           (channels == 2 || channels == 4);
}

AlphaTexture uniform_alpha_texture(double factor) { return {1, 1, {scaled(255, factor)}}; }

} // namespace penumbra::playground
