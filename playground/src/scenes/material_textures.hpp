// playground/src/scenes/material_textures.hpp — the alpha of a material's texture, decoded with
// stb_image (PNG, JPEG, TGA, BMP, GIF, …), for the materials that cut (alpha test). The loaders
// decode only those; every other image of a file stays undecoded.
#pragma once

#include "scenes/scene.hpp"

#include <cstddef>
#include <optional>
#include <string>

namespace penumbra::playground {

// Images larger than this many texels per side are refused (a cut texture is read per texel).
inline constexpr int alpha_texture_side_limit = 16384;

// Where a texture's alpha comes from.
enum class AlphaChannel {
    alpha,         // its alpha channel (glTF baseColorTexture, OBJ map_Kd); 255 where the image has none
    alpha_or_grey, // its alpha channel when it has one, else its grey level (OBJ map_d, a dissolve map)
};

// The alpha of an encoded image, times `factor` (glTF baseColorFactor.a; 1 otherwise), rows in the
// image's order (row 0 at v = 0, glTF's convention). nullopt with a one-line *error when the bytes
// are not an image stb_image reads or it is larger than alpha_texture_side_limit.
std::optional<AlphaTexture> decode_alpha_texture(const unsigned char* bytes, std::size_t size,
                                                 AlphaChannel channel, double factor, std::string* error);

// True when the encoded image has an alpha channel (only its header is read).
bool image_has_alpha(const unsigned char* bytes, std::size_t size);

// A 1 x 1 texture of alpha `factor` (a material that cuts by its factor alone).
AlphaTexture uniform_alpha_texture(double factor);

} // namespace penumbra::playground
