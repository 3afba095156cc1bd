// tests/runtime/image_io_test.cpp — PNG output, PFM round trips, false-colour maps.
#include <doctest/doctest.h>

#define STB_IMAGE_IMPLEMENTATION // the reader is only needed here, to check what we wrote
#include <stb/stb_image.h>

#include "app/image_io.hpp"
#include "temp_dir.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

using namespace penumbra::playground;
using penumbra::playground::testing::TempDir;

TEST_CASE("PNG: gray and RGB, top-down and bottom-up rows") {
    TempDir dir;
    // 3×2 gray: the top row dark, the bottom row bright.
    const std::vector<float> gray{0.0f, 0.5f, 1.0f, 2.0f, -1.0f, std::numeric_limits<float>::quiet_NaN()};
    REQUIRE(write_png_gray(dir.file("g.png"), 3, 2, gray));
    int w = 0, h = 0, c = 0;
    stbi_uc* data = stbi_load(dir.file("g.png").c_str(), &w, &h, &c, 0);
    REQUIRE(data != nullptr);
    CHECK(w == 3);
    CHECK(h == 2);
    CHECK(c == 1);
    const std::vector<int> expected{0, 128, 255, 255, 0, 0}; // clamped; NaN → 0
    for (int i = 0; i < 6; ++i) CHECK(int(data[i]) == expected[i]);
    stbi_image_free(data);

    // Same data given bottom row first (as glReadPixels returns it) comes out flipped.
    REQUIRE(write_png_gray(dir.file("f.png"), 3, 2, gray, RowOrder::bottom_up));
    data = stbi_load(dir.file("f.png").c_str(), &w, &h, &c, 0);
    REQUIRE(data != nullptr);
    CHECK(int(data[0]) == 255);
    CHECK(int(data[3]) == 0);
    stbi_image_free(data);

    const std::vector<float> rgb{1, 0, 0, 0, 1, 0};
    REQUIRE(write_png_rgb(dir.file("c.png"), 2, 1, rgb));
    data = stbi_load(dir.file("c.png").c_str(), &w, &h, &c, 0);
    REQUIRE(data != nullptr);
    CHECK(c == 3);
    CHECK((int(data[0]) == 255 && int(data[1]) == 0 && int(data[4]) == 255));
    stbi_image_free(data);

    std::string error;
    CHECK_FALSE(write_png_rgb(dir.file("bad.png"), 2, 2, rgb, RowOrder::top_down, &error));
    CHECK(error.find("expected 12") != std::string::npos);
}

TEST_CASE("PFM: lossless round trip, bottom-up storage, errors") {
    TempDir dir;
    for (int channels : {1, 3}) {
        CAPTURE(channels);
        FloatImage image{4, 3, channels, {}};
        for (int i = 0; i < 4 * 3 * channels; ++i) image.pixels.push_back(std::ldexp(float(i) + 0.1f, i % 7 - 3));
        image.pixels[1] = std::numeric_limits<float>::infinity();
        const std::string path = dir.file("img" + std::to_string(channels) + ".pfm");
        REQUIRE(write_pfm(path, image));
        std::string error;
        const std::optional<FloatImage> back = read_pfm(path, &error);
        REQUIRE_MESSAGE(back.has_value(), error);
        CHECK(back->width == 4);
        CHECK(back->height == 3);
        CHECK(back->channels == channels);
        CHECK(std::memcmp(back->pixels.data(), image.pixels.data(), image.pixels.size() * 4) == 0);

        // The file's first sample is the bottom-left pixel (PFM's row order).
        std::ifstream in(path, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string header = std::string(channels == 3 ? "PF" : "Pf") + "\n4 3\n-1.0\n";
        REQUIRE(bytes.size() == header.size() + image.pixels.size() * 4);
        CHECK(bytes.substr(0, header.size()) == header);
        float first = 0.0f;
        std::memcpy(&first, bytes.data() + header.size(), 4);
        CHECK(first == image.pixels[2 * 4 * channels]);

        // Rows given bottom first (a GL read-back) are written as they come: read back, they are flipped.
        FloatImage gl_rows = image;
        gl_rows.rows = RowOrder::bottom_up;
        REQUIRE(write_pfm(dir.file("gl.pfm"), gl_rows));
        const std::optional<FloatImage> flipped = read_pfm(dir.file("gl.pfm"), &error);
        REQUIRE_MESSAGE(flipped.has_value(), error);
        const std::size_t row = std::size_t(4) * channels;
        for (int y = 0; y < 3; ++y)
            CHECK(std::memcmp(flipped->pixels.data() + y * row, image.pixels.data() + (2 - y) * row,
                              row * 4) == 0);

        // Truncated file.
        std::ofstream(dir.file("short.pfm"), std::ios::binary) << bytes.substr(0, bytes.size() - 3);
        CHECK_FALSE(read_pfm(dir.file("short.pfm"), &error).has_value());
        CHECK(error.find("truncated") != std::string::npos);
    }
    std::string error;
    CHECK_FALSE(read_pfm(dir.file("missing.pfm"), &error).has_value());
    CHECK(error.find("missing.pfm") != std::string::npos);
    std::ofstream(dir.file("text.pfm")) << "P6\n1 1\n255\nxyz";
    CHECK_FALSE(read_pfm(dir.file("text.pfm"), &error).has_value());
    CHECK(error.find("not a PFM") != std::string::npos);
}

TEST_CASE("false colours") {
    const std::vector<float> errors{-1.0f, 0.0f, 1.0f, 5.0f, std::numeric_limits<float>::quiet_NaN()};
    const std::vector<float> c = signed_error_colors(errors, 1.0f);
    REQUIRE(c.size() == 15);
    CHECK(c[2] > c[0]); // negative: blue dominates
    CHECK((c[3] == 1.0f && c[4] == 1.0f && c[5] == 1.0f)); // zero: white
    CHECK(c[6] > c[8]); // positive: red dominates
    CHECK((c[9] == c[6] && c[10] == c[7] && c[11] == c[8])); // saturates
    CHECK((c[12] == 0.0f && c[13] == 1.0f && c[14] == 0.0f)); // NaN: green

    const std::vector<float> m = magnitude_colors(std::vector<float>{0.0f, 0.5f, 1.0f}, 1.0f);
    REQUIRE(m.size() == 9);
    auto luminance = [&](int i) { return 0.2126f * m[3 * i] + 0.7152f * m[3 * i + 1] + 0.0722f * m[3 * i + 2]; };
    CHECK(luminance(0) < luminance(1));
    CHECK(luminance(1) < luminance(2));
}
