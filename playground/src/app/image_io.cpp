// playground/src/app/image_io.cpp
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "app/image_io.hpp"
#include "app/palette.hpp"

#include <penumbra_tools/file_transaction.hpp>

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

namespace penumbra::playground {

namespace {

bool set_error(std::string* error, const std::string& message) {
    if (error) *error = message;
    return false;
}

std::uint8_t to_byte(float v) {
    if (!(v > 0.0f)) return 0; // also NaN
    if (v >= 1.0f) return 255;
    return static_cast<std::uint8_t>(std::lround(v * 255.0f));
}

// The PNG's bytes; `what` names it in errors.
std::optional<std::string> encode_png(const std::string& what, int width, int height, int channels,
                                      std::span<const float> data, RowOrder order, std::string* error) {
    if (width <= 0 || height <= 0) {
        set_error(error, "write_png '" + what + "': invalid size");
        return std::nullopt;
    }
    const std::size_t expected = static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * channels;
    if (data.size() != expected) {
        set_error(error, "write_png '" + what + "': buffer has " + std::to_string(data.size()) + " floats, expected " +
                             std::to_string(expected));
        return std::nullopt;
    }
    std::vector<std::uint8_t> bytes(expected);
    const std::size_t row = static_cast<std::size_t>(width) * channels;
    for (int y = 0; y < height; ++y) {
        const int src_y = order == RowOrder::top_down ? y : height - 1 - y;
        for (std::size_t x = 0; x < row; ++x) bytes[y * row + x] = to_byte(data[src_y * row + x]);
    }
    // Encoded in memory, then written all or nothing: a full disk leaves no cut PNG behind.
    std::string encoded;
    auto append = [](void* context, void* data, int size) {
        static_cast<std::string*>(context)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
    };
    if (!stbi_write_png_to_func(append, &encoded, width, height, channels, bytes.data(), static_cast<int>(row))) {
        set_error(error, "write_png '" + what + "': cannot encode the image");
        return std::nullopt;
    }
    return encoded;
}

bool write_png(const std::string& path, int width, int height, int channels, std::span<const float> data,
               RowOrder order, std::string* error) {
    std::optional<std::string> encoded = encode_png(path, width, height, channels, data, order, error);
    if (!encoded) return false;
    if (std::string e = penumbra_gen::write_file_atomically(path, std::move(*encoded)); !e.empty())
        return set_error(error, e);
    return true;
}

std::optional<std::string> encode_pfm_named(const std::string& what, const FloatImage& image, std::string* error) {
    auto fail = [&](const std::string& why) -> std::optional<std::string> {
        set_error(error, "write_pfm '" + what + "': " + why);
        return std::nullopt;
    };
    if (image.channels != 1 && image.channels != 3) return fail("channels must be 1 or 3");
    if (image.width <= 0 || image.height <= 0) return fail("invalid size");
    const std::size_t row = static_cast<std::size_t>(image.width) * image.channels;
    if (image.pixels.size() != row * static_cast<std::size_t>(image.height)) return fail("pixel count does not match the size");
    std::ostringstream out;
    // Negative scale = little-endian samples; we write the host's floats, so say what they are.
    const bool little = std::endian::native == std::endian::little;
    out << (image.channels == 3 ? "PF" : "Pf") << '\n'
        << image.width << ' ' << image.height << '\n'
        << (little ? "-1.0" : "1.0") << '\n';
    for (int i = 0; i < image.height; ++i) { // PFM stores the bottom row first
        const int y = image.rows == RowOrder::bottom_up ? i : image.height - 1 - i;
        out.write(reinterpret_cast<const char*>(image.pixels.data() + static_cast<std::size_t>(y) * row),
                  static_cast<std::streamsize>(row * sizeof(float)));
    }
    return std::move(out).str();
}

} // namespace

bool write_png_rgb(const std::string& path, int width, int height, std::span<const float> rgb, RowOrder order,
                   std::string* error) {
    return write_png(path, width, height, 3, rgb, order, error);
}

bool write_png_gray(const std::string& path, int width, int height, std::span<const float> gray, RowOrder order,
                    std::string* error) {
    return write_png(path, width, height, 1, gray, order, error);
}

bool write_pfm(const std::string& path, const FloatImage& image, std::string* error) {
    std::optional<std::string> encoded = encode_pfm_named(path, image, error);
    if (!encoded) return false;
    if (std::string e = penumbra_gen::write_file_atomically(path, std::move(*encoded)); !e.empty())
        return set_error(error, e);
    return true;
}

std::optional<std::string> encode_png_rgb(int width, int height, std::span<const float> rgb, RowOrder order,
                                          std::string* error) {
    return encode_png("PNG", width, height, 3, rgb, order, error);
}

std::optional<std::string> encode_pfm(const FloatImage& image, std::string* error) {
    return encode_pfm_named("PFM", image, error);
}

std::optional<FloatImage> read_pfm(const std::string& path, std::string* error) {
    auto fail = [&](const std::string& why) -> std::optional<FloatImage> {
        set_error(error, "read_pfm '" + path + "': " + why);
        return std::nullopt;
    };
    std::ifstream in(path, std::ios::binary);
    if (!in) return fail("cannot open the file");
    std::string magic;
    FloatImage image;
    double scale = 0.0;
    in >> magic >> image.width >> image.height >> scale;
    if (!in || (magic != "PF" && magic != "Pf")) return fail("not a PFM file (bad header)");
    if (image.width <= 0 || image.height <= 0 || image.width > 1 << 16 || image.height > 1 << 16 || scale == 0.0)
        return fail("invalid size or scale in the header");
    in.get(); // the single whitespace character that ends the header
    image.channels = magic == "PF" ? 3 : 1;
    const std::size_t row = static_cast<std::size_t>(image.width) * image.channels;
    image.pixels.resize(row * static_cast<std::size_t>(image.height));
    const bool file_little = scale < 0.0;
    const bool swap = file_little != (std::endian::native == std::endian::little);
    for (int y = image.height - 1; y >= 0; --y) {
        float* dst = image.pixels.data() + static_cast<std::size_t>(y) * row;
        in.read(reinterpret_cast<char*>(dst), static_cast<std::streamsize>(row * sizeof(float)));
        if (!in) return fail("file is truncated");
        if (swap) {
            for (std::size_t i = 0; i < row; ++i) {
                std::uint32_t bits;
                std::memcpy(&bits, dst + i, 4);
                bits = ((bits & 0xffU) << 24) | ((bits & 0xff00U) << 8) | ((bits >> 8) & 0xff00U) | (bits >> 24);
                std::memcpy(dst + i, &bits, 4);
            }
        }
    }
    return image;
}

std::vector<float> signed_error_colors(std::span<const float> errors, float max_abs) {
    static constexpr std::array<glm::vec3, 5> stops{
        glm::vec3(0.02f, 0.19f, 0.58f), glm::vec3(0.45f, 0.68f, 0.95f), glm::vec3(1.0f, 1.0f, 1.0f),
        glm::vec3(0.97f, 0.55f, 0.40f), glm::vec3(0.60f, 0.02f, 0.05f)};
    const float scale = max_abs > 0.0f ? 1.0f / max_abs : 0.0f;
    return false_colors(errors, stops, [scale](float e) { return 0.5f + 0.5f * e * scale; });
}

std::vector<float> magnitude_colors(std::span<const float> values, float max_value) {
    static constexpr std::array<glm::vec3, 5> stops{
        glm::vec3(0.0f, 0.0f, 0.02f), glm::vec3(0.34f, 0.06f, 0.43f), glm::vec3(0.73f, 0.21f, 0.33f),
        glm::vec3(0.98f, 0.55f, 0.04f), glm::vec3(0.99f, 1.0f, 0.64f)};
    const float scale = max_value > 0.0f ? 1.0f / max_value : 0.0f;
    return false_colors(values, stops, [scale](float v) { return v * scale; });
}

} // namespace penumbra::playground
