// The irradiance window (Config::irradiance_window, docs/model.md §1.7.5) on "boxes" under a light 16 times
// its default: the GPU's visibility equals the oracle's within its bound, the window changes it, and against
// the Embree irradiance truth the estimate is closer with the window than without, under the default light
// and the large one; with the window's quadrants (Config::irradiance_quadrants, §1.7.6) the same agreement
// with the oracle, and closer to the truth than the two windows. Label "gl".
#include "oracle_agreement.hpp"
#include "reference/oracle.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <utility>
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

// The penumbra MAE against the Embree irradiance truth of `config` on `scene`, 64², 8×8 rays.
double irradiance_mae(const Scene& scene, const Config& config) {
    std::string error;
    HeadlessResult result;
    REQUIRE_MESSAGE(render_headless(scene, config, 64, 64, result, &error), error);
    const References truth = reference_all(scene, result, 8);
    return compare_quality(result, truth).irradiance.penumbra.mae;
}

} // namespace

TEST_CASE("irradiance window: the GPU's visibility equals the oracle's within its bound, and differs from the whole light's") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const Scene scene = boxes_under_light(16.0);
    const std::vector<Config> configs{
        {.slices = 16, .resolution = 256, .irradiance_window = true}, // the default, windowed
        {.slices = 8,
         .resolution = 128,
         .filter = Filter::mipmap,
         .packing = Packing::array,
         .irradiance_window = true},
        {.slices = 16, .resolution = 128, .fusion = Fusion::clustered, .irradiance_window = true},
        {.slices = 16,
         .resolution = 256,
         .irradiance_window = true,
         .irradiance_quadrants = true}, // profile large
    };
    for (const Config& config : configs) {
        const std::string name =
            std::string(to_string(config.filter)) + " " + std::string(to_string(config.fusion)) + " " +
            std::string(to_string(config.packing)) + " S=" + std::to_string(config.slices) +
            " R=" + std::to_string(config.resolution) + (config.irradiance_quadrants ? " quadrants" : "");
        GpuRun run;
        REQUIRE_MESSAGE(render_for_oracle(scene, config, 64, run, &error), name, ": ", error);
        Config whole = run.config;
        whole.irradiance_window = false; // and with it the quadrants
        const Oracle oracle = oracle_of(run), whole_light(whole, run.frame, run.slices);
        const Agreement a = agreement(oracle, run.result, config.fusion, name);
        std::size_t changed = 0;
        for (std::size_t i = 0; i < run.result.visibility.size(); ++i)
            if (run.result.geometry[i])
                changed += std::abs(oracle.visibility(run.result.positions[i], run.result.normals[i], config.fusion).visibility -
                                    whole_light.visibility(run.result.positions[i], run.result.normals[i], config.fusion).visibility) >
                           0.05;
        std::printf("irradiance window oracle %-34s max |GPU - oracle| %.2e, beyond the bound %zu of %zu, penumbra %zu, "
                    "changed by the window %zu\n",
                    name.c_str(), a.max_difference, a.beyond_bound, a.pixels, a.penumbra_pixels, changed);
        CHECK_MESSAGE(a.beyond_bound == 0, name, ": ", a.beyond_bound, " pixels beyond the bound, max |diff| ", a.max_difference,
                      "; the worst, ", a.worst);
        CHECK_MESSAGE(a.penumbra_pixels > 100, name, ": too few penumbra pixels for a meaningful comparison");
        CHECK_MESSAGE(changed > a.pixels / 20, name, ": the window changed only ", changed, " of ", a.pixels, " pixels");
    }
}

namespace {

// On boxes under its light scaled by each `scale`, the penumbra MAE against the irradiance truth with
// `with` is below `ratio` times the one with `without`.
void check_closer(const char* what, std::initializer_list<std::pair<double, double>> scales_and_ratios,
                  const Config& without, const Config& with) {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    for (const auto& [scale, ratio] : scales_and_ratios) {
        const Scene scene = boxes_under_light(scale);
        const double before = irradiance_mae(scene, without), after = irradiance_mae(scene, with);
        std::printf("%s on boxes x%g: irradiance penumbra MAE %.4f without, %.4f with (%.2f times)\n", what, scale,
                    before, after, after / before);
        CAPTURE(scale);
        CHECK(after < ratio * before);
    }
}

} // namespace

TEST_CASE("irradiance window: closer to the irradiance truth under the default light and a large one") {
    check_closer("irradiance window", {{1.0, 0.97}, {16.0, 0.7}},
                 {.slices = 16, .resolution = 256, .irradiance_window = false},
                 {.slices = 16, .resolution = 256, .irradiance_window = true});
}

TEST_CASE("irradiance quadrants: closer to the irradiance truth than the two windows, under the default "
          "light and a larger one") {
    // measured: 0.86 times at x1, 0.56 at x4
    check_closer("irradiance quadrants", {{1.0, 0.95}, {4.0, 0.8}},
                 {.slices = 16, .resolution = 256, .irradiance_window = true},
                 {.slices = 16, .resolution = 256, .irradiance_window = true, .irradiance_quadrants = true});
}
