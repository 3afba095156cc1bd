// The irradiance window (Config::irradiance_window, docs/model.md §1.7.5) on "boxes" under a light 16 times
// its default: the GPU's visibility equals the oracle's within its bound, the window changes it, and against the
// Embree irradiance truth the estimate is closer with the window than without, under the default light and
// the large one. Label "gl".
#include "reference/oracle.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::playground;

namespace {

// boxes under its default rectangle scaled `scale` times (both sides), as penumbra-bench-quality's --light-scales
Scene boxes_under_light(double scale) {
    std::optional<Scene> scene = make_scene("boxes");
    REQUIRE(scene);
    scene->light.width *= static_cast<float>(scale);
    scene->light.height *= static_cast<float>(scale);
    return *scene;
}

} // namespace

TEST_CASE("irradiance window: the GPU's visibility equals the oracle's within its bound, and differs from the whole light's") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const Scene scene = boxes_under_light(16.0);
    const std::vector<Config> configs{
        {.slices = 16, .resolution = 256, .irradiance_window = true}, // the default, windowed
        {.slices = 8, .resolution = 128, .filter = Filter::mipmap, .packing = Packing::array, .irradiance_window = true},
        {.slices = 16, .resolution = 128, .fusion = Fusion::clustered, .irradiance_window = true},
    };
    for (const Config& config : configs) {
        const std::string name = std::string(to_string(config.filter)) + " " + std::string(to_string(config.fusion)) + " " +
                                 std::string(to_string(config.packing)) + " S=" + std::to_string(config.slices) +
                                 " R=" + std::to_string(config.resolution);
        SliceTextures slices;
        SliceFrame frame;
        Config ran;
        bool read = false;
        RenderOptions options{.inspect = [&](const gl::Runtime& runtime) {
            read = read_slice_textures(runtime, slices, &error);
            frame = runtime.frame();
            ran = runtime.config();
        }};
        HeadlessResult result;
        REQUIRE_MESSAGE(render_headless(scene, config, 64, 64, result, &error, options), name, ": ", error);
        REQUIRE_MESSAGE(read, name, ": ", error);
        Config whole = ran;
        whole.irradiance_window = false;
        const Oracle oracle(ran, frame, slices), whole_light(whole, frame, slices);
        std::size_t pixels = 0, beyond = 0, penumbra = 0, changed = 0;
        double max_difference = 0;
        for (std::size_t i = 0; i < result.visibility.size(); ++i) {
            if (!result.geometry[i]) continue;
            const OracleValue expected = oracle.visibility(result.positions[i], result.normals[i], config.fusion);
            const double difference = std::abs(result.visibility[i] - expected.visibility);
            ++pixels;
            beyond += difference > expected.bound;
            max_difference = std::max(max_difference, difference);
            penumbra += expected.visibility > 0.02 && expected.visibility < 0.98;
            changed += std::abs(expected.visibility -
                                whole_light.visibility(result.positions[i], result.normals[i], config.fusion).visibility) > 0.05;
        }
        std::printf("irradiance window oracle %-34s max |GPU - oracle| %.2e, beyond the bound %zu of %zu, penumbra %zu, "
                    "changed by the window %zu\n",
                    name.c_str(), max_difference, beyond, pixels, penumbra, changed);
        CHECK_MESSAGE(beyond == 0, name, ": ", beyond, " pixels beyond the bound, max |diff| ", max_difference);
        CHECK_MESSAGE(penumbra > 100, name, ": too few penumbra pixels for a meaningful comparison");
        CHECK_MESSAGE(changed > pixels / 20, name, ": the window changed only ", changed, " of ", pixels, " pixels");
    }
}

TEST_CASE("irradiance window: closer to the irradiance truth under the default light and a large one") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    for (double scale : {1.0, 16.0}) {
        const Scene scene = boxes_under_light(scale);
        double mae[2] = {0, 0};
        for (bool window : {false, true}) {
            const Config config{.slices = 16, .resolution = 256, .irradiance_window = window};
            HeadlessResult result;
            REQUIRE_MESSAGE(render_headless(scene, config, 64, 64, result, &error), error);
            const References truth = reference_all(scene, result, 8);
            mae[window] = compare_quality(result, truth).irradiance.penumbra.mae;
        }
        std::printf("irradiance window on boxes x%g: irradiance penumbra MAE %.4f without, %.4f with\n", scale, mae[0],
                    mae[1]);
        CAPTURE(scale);
        CHECK(mae[1] < (scale == 1.0 ? 0.97 : 0.7) * mae[0]);
    }
}
