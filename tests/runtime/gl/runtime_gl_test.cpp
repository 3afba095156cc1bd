// penumbra/gl/runtime.hpp end to end on llvmpipe (or a GPU): the planes scene, default config,
// compared with Embree ground truth. Label "gl".
#include "egl_context.hpp"
#include "headless_render.hpp"
#include "scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>

using namespace penumbra::playground;

TEST_CASE("gl runtime: every program of the default configuration compiles and links") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto runtime = penumbra::gl::Runtime::create(penumbra::Config{}, &error);
    CHECK_MESSAGE(runtime, error);
}

TEST_CASE("gl runtime: invalid configuration gives a diagnostic, not a crash") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto runtime = penumbra::gl::Runtime::create(penumbra::Config{.slices = 0}, &error);
    CHECK(!runtime);
    CHECK(!error.empty());
}

TEST_CASE("gl runtime: planes, default config, 128x128, against Embree 16x16") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const std::optional<Scene> scene = make_scene("planes");
    REQUIRE(scene);
    HeadlessResult result;
    REQUIRE_MESSAGE(render_headless(*scene, penumbra::Config{}, 128, 128, result, &error), error);
    int shadowed = 0, lit = 0, geometry = 0;
    for (std::size_t i = 0; i < result.visibility.size(); ++i) {
        if (!result.geometry[i]) continue;
        ++geometry;
        shadowed += result.visibility[i] < 0.5f;
        lit += result.visibility[i] > 0.95f;
    }
    const std::vector<float> truth = reference_visibility(*scene, result, 16);
    const Metrics m = compare(result, truth);
    std::printf("planes 128x128 default config (%s): geometry %d, shadowed %d, lit %d\n"
                "  all:      MAE %.4f RMSE %.4f p95 %.4f (%zu px)\n  penumbra: MAE %.4f RMSE %.4f p95 %.4f (%zu px)\n",
                context->renderer().c_str(), geometry, shadowed, lit, m.all.mae, m.all.rmse, m.all.p95, m.all.count,
                m.penumbra.mae, m.penumbra.rmse, m.penumbra.p95, m.penumbra.count);
    CHECK(shadowed > 0);
    CHECK(lit > 0);
    CHECK(m.all.mae < 0.05);
}
