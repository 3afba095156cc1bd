// playground/src/app/image_io.hpp — writing result images and reading/writing float images.
//
// Buffers are row-major with the first row at the top (image convention). OpenGL reads pixels
// bottom row first: pass RowOrder::bottom_up for glReadPixels output instead of flipping by hand.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace penumbra::playground {

enum class RowOrder { top_down, bottom_up };

// 8-bit PNG from floats in [0, 1] (clamped; NaN becomes 0), no gamma applied: visibility values
// are written as they are, so pixel value / 255 is the visibility. `rgb` holds 3 floats per pixel,
// `gray` one. Return false (and set *error if given) when the size does not match or writing fails.
bool write_png_rgb(const std::string& path, int width, int height, std::span<const float> rgb,
                   RowOrder order = RowOrder::top_down, std::string* error = nullptr);
bool write_png_gray(const std::string& path, int width, int height, std::span<const float> gray,
                    RowOrder order = RowOrder::top_down, std::string* error = nullptr);

// Portable float map: lossless float storage for visibility images and references. `channels` is
// 1 ("Pf") or 3 ("PF"); written little-endian (negative scale), rows stored bottom-up as the
// format requires (the conversion is done here).
struct FloatImage {
    int width = 0;
    int height = 0;
    int channels = 1;
    std::vector<float> pixels; // width·height·channels floats, top row first unless `rows` says
    // bottom_up for GL read-backs, written as they come (read_pfm gives top_down)
    RowOrder rows = RowOrder::top_down;
};

bool write_pfm(const std::string& path, const FloatImage& image, std::string* error = nullptr);

// The same files' bytes, for a caller that writes several files as one transaction
// (tools/include/penumbra_tools/file_transaction.hpp); nullopt (and *error) when the size does not match.
std::optional<std::string> encode_png_rgb(int width, int height, std::span<const float> rgb,
                                          RowOrder order = RowOrder::top_down, std::string* error = nullptr);
std::optional<std::string> encode_pfm(const FloatImage& image, std::string* error = nullptr);
// Reads either endianness; nullopt (and *error) on a missing, malformed or truncated file.
std::optional<FloatImage> read_pfm(const std::string& path, std::string* error = nullptr);

// False colour for signed errors (estimate − reference): blue for negative, white at zero, red
// for positive, saturating at ±max_abs. Returns 3 floats per value. NaN maps to green.
std::vector<float> signed_error_colors(std::span<const float> errors, float max_abs);

// False colour for magnitudes in [0, max_value] (|error|, cost, ...): black → purple → orange →
// yellow-white, a perceptually ordered ramp close to "inferno". NaN maps to green.
std::vector<float> magnitude_colors(std::span<const float> values, float max_value);

} // namespace penumbra::playground
