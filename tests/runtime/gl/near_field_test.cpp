// The near field (Config::near_field, docs/model.md §1.7.7) on `room`, whose bookshelf's boards, sides and
// back panel are occluders within a slice or two of their receivers: the GPU's visibility equals the oracle's
// within its bound (the oracle marches the same rays over the nearest depths the GPU's slicing pass kept),
// the near field darkens the contacts and nothing else (a receiver never gets lighter; not so with the
// window's quadrants, docs/model.md §1.7.7), and against the Embree irradiance truth the estimate is closer
// with it than without; on `box`, where nothing lies within two slices of a receiver, it changes nothing.
// Label "gl".
#include "oracle_agreement.hpp"
#include "reference/oracle.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::playground;

namespace {

Scene scene_named(const char* name) {
    std::optional<Scene> scene = make_scene(name);
    REQUIRE(scene);
    return *scene;
}

// The penumbra error against the Embree irradiance truth of `config` on `scene`, 64², 8×8 rays.
QualityMetrics quality(const Scene& scene, const Config& config) {
    std::string error;
    HeadlessResult result;
    REQUIRE_MESSAGE(render_headless(scene, config, 64, 64, result, &error), error);
    return compare_quality(result, reference_all(scene, result, 8));
}

} // namespace

TEST_CASE("near field: the GPU's visibility equals the oracle's within its bound, and only darkens") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const Scene room = scene_named("room");
    for (const Config& config : {Config{.resolution = 256, .near_field = true},
                                 Config{.slices = 8,
                                 .resolution = 128,
                                 .fusion = Fusion::chained,
                                 .irradiance_window = false,
                                 .near_field = true},
                                 Config{.resolution = 128, .tangent_clip = false, .near_field = true}}) {
        const std::string name = "S=" + std::to_string(config.slices) +
                                 " R=" + std::to_string(config.resolution) +
                                 (config.tangent_clip ? "" : " no clip");
        GpuRun run;
        REQUIRE_MESSAGE(render_for_oracle(room, config, 64, run, &error), name, ": ", error);
        REQUIRE(run.slices.near_depth.size() == run.slices.coverage.size());
        const Oracle oracle = oracle_of(run);
        const Agreement a = agreement(oracle, run.result, config.fusion, name);
        INFO(name, ": ", a.beyond_bound, " of ", a.pixels, " pixels beyond the bound, max |GPU - oracle| ",
             a.max_difference, "; worst ", a.worst);
        CHECK(a.beyond_bound <= a.pixels / 200); // as the other oracle tests: rasterisation at texel edges
        // the same slices without the near field: the rays can only lower the visibility, and they do here
        Config without = run.config;
        without.near_field = false;
        SliceTextures slices = run.slices;
        slices.near_depth.clear();
        const Oracle fused(without, run.frame, slices, run.boundaries);
        std::size_t lighter = 0, darker = 0;
        for (std::size_t i = 0; i < run.result.visibility.size(); ++i) {
            if (!run.result.geometry[i]) continue;
            const double near =
                oracle.visibility(run.result.positions[i], run.result.normals[i], config.fusion).visibility;
            const double far =
                fused.visibility(run.result.positions[i], run.result.normals[i], config.fusion).visibility;
            lighter += near > far + 1e-9;
            darker += near < far - 0.05;
        }
        CHECK(lighter == 0);
        CHECK(darker > 20); // the shelves, the chair and the table's legs
        // and the GPU marched them: without its rays the oracle misses those pixels
        const Agreement unmarched =
            agreement(fused, run.result, config.fusion, name + " without the near field");
        CHECK(unmarched.beyond_bound > a.beyond_bound + 20);
    }
}

TEST_CASE(
    "near field: closer to the irradiance truth where occluders touch their receivers, the same elsewhere") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const Config without{.resolution = 256}, with{.resolution = 256, .near_field = true};
    const Scene room = scene_named("room");
    const QualityMetrics room_without = quality(room, without), room_with = quality(room, with);
    INFO("room: shaded penumbra MAE ", room_without.shaded.penumbra.mae, " without, ",
         room_with.shaded.penumbra.mae, " with; false light ", room_without.false_light.fraction(), " and ",
         room_with.false_light.fraction());
    CHECK(room_with.shaded.penumbra.mae < 0.85 * room_without.shaded.penumbra.mae);
    CHECK(room_with.irradiance.penumbra.mae < 0.85 * room_without.irradiance.penumbra.mae);
    CHECK(room_with.false_light.wrong < room_without.false_light.wrong);
    const Scene box = scene_named("box");
    const QualityMetrics box_without = quality(box, without), box_with = quality(box, with);
    CHECK(std::abs(box_with.irradiance.penumbra.mae - box_without.irradiance.penumbra.mae) < 0.002);
}
