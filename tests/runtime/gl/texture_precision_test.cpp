// The renderer's texture weights, measured (texture_precision.hpp): what the oracle's bound takes for the
// weight between two texels and between two mip levels. Label "gl".
#include "rendering/egl_context.hpp"
#include "texture_precision.hpp"

#include <doctest/doctest.h>

#include <cstdio>
#include <string>

using namespace penumbra::playground;

TEST_CASE("texture precision: the renderer's bilinear and trilinear weights, measured") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const MeasuredTexturePrecision measured = measure_texture_precision();
    REQUIRE_MESSAGE(measured.error.empty(), measured.error);
    std::printf("texture precision on %s: sub-texel weight off by up to %.2e, mip level weight by up to %.2e; "
                "the upper level's weight at t, %s\n",
                context->renderer().c_str(), measured.sub_texel, measured.level_fraction, measured.level_curve.c_str());
    // Vulkan's least precision (4 bits) is within 1/16 of the exact weight; a "trilinear" fetch that read
    // the nearest level alone would be a half off
    CHECK_MESSAGE(measured.sub_texel <= 1.0 / 16.0, "sub-texel weight off by ", measured.sub_texel);
    CHECK_MESSAGE(measured.level_fraction < 0.25, "mip level weight off by ", measured.level_fraction, ": ",
                  measured.level_curve);
    // the probe reads what it means to: the blend is near the exact one at the middle of each range
    CHECK(measured.level_curve.find("0.500 → 0.5") != std::string::npos);
    // llvmpipe: 8-bit weights, truncated, and RGBA8 fetches filtered in 8 bits (a result rounded to 1/255)
    if (context->renderer().find("llvmpipe") != std::string::npos) {
        CHECK(measured.sub_texel <= 1.0 / 128.0);
        CHECK(measured.level_fraction <= 1.0 / 128.0);
    }
}
