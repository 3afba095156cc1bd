// The model against Embree ground truth on real OpenGL (llvmpipe on CI), label "gl":
//   - a single planar occluder on a slice's bottom plane, where slicing adds no error (docs/model.md §4);
//   - the paper's fusion claim on `boxes` (§3.3): probabilistic beats maximum and additive;
//   - every scene with every filter and packing renders without a GL error and casts a shadow.
#include "rendering/egl_context.hpp"
#include "app/headless_job.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/scene_defaults.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/light_frame.hpp>
#include <penumbra/validate.hpp>

#include <doctest/doctest.h>

#include <array>
#include <cstdio>
#include <string>

using namespace penumbra::playground;

namespace {

void print_metrics(const char* label, const Metrics& m) {
    std::printf("%s\n  all:      MAE %.4f RMSE %.4f p95 %.4f (%zu px)\n  penumbra: MAE %.4f RMSE %.4f p95 %.4f (%zu px)\n",
                label, m.all.mae, m.all.rmse, m.all.p95, m.all.count, m.penumbra.mae, m.penumbra.rmse, m.penumbra.p95,
                m.penumbra.count);
}

// A 6×6 receiver at y = 0 and a 1.2×1.2 occluder parallel to a 2×2 light at y = 6. The bounds
// are chosen, not measured: their top (y = 3.5) sets z0 and Δ, and the occluder is then put on
// the bottom plane ζ_k = z_{k+1} of slice k, where the slice's projection moves it by nothing.
struct SingleOccluder {
    Scene scene;
    double plane_depth = 0; // ζ_k, along the light normal from the light's centre
    double occluder_depth = 0;
};

// `lift`: how far above the plane, in slices, the occluder is put (0 = on the plane).
SingleOccluder single_occluder_scene(int slices, int slice, double lift) {
    SingleOccluder out;
    Scene& scene = out.scene;
    scene.name = "single-occluder";
    scene.light.center = {0.0, 6.0, 0.0}; // u = +x, v = +z: facing down, 2×2 (RectLight's defaults)
    scene.bounds_min = {-3.0f, 0.0f, -3.0f};
    scene.bounds_max = {3.0f, 3.5f, 3.0f};
    const penumbra::SliceFrame frame =
        penumbra::slice_frame(scene.light, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max), slices);
    const double z0 = frame.slice_depths.x, thickness = frame.slice_depths.y;
    out.plane_depth = z0 + (slice + 1) * thickness;
    out.occluder_depth = out.plane_depth - lift * thickness;
    const float occluder_y = static_cast<float>(scene.light.center.y - out.occluder_depth);
    add_horizontal_rect(scene.mesh, 0.0f, 0.0f, 0.0f, 6.0f, 6.0f);
    add_horizontal_rect(scene.mesh, 0.0f, occluder_y, 0.0f, 1.2f, 1.2f);
    scene.sun = default_sun_light();
    scene.camera.target = {0.0f, 0.0f, 0.0f};
    scene.camera.distance = 8.5f;
    scene.camera.pitch_radians = glm::radians(75.0f);
    scene.camera.yaw_radians = glm::radians(20.0f);
    scene.camera.z_near = 0.1f;
    scene.camera.z_far = 30.0f;
    return out;
}

// Renders the single occluder with sat 512², 16 slices, no leak fix (or `config`); Embree with 32×32 rays.
Metrics single_occluder_metrics(double lift,
                                const penumbra::Config& config = {.slices = 16, .resolution = 512,
                                                                  .filter = penumbra::Filter::sat, .leak_fix = false}) {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const SingleOccluder setup = single_occluder_scene(config.slices, 1, lift);
    const int size = 192;
    HeadlessResult result;
    REQUIRE_MESSAGE(render_headless(setup.scene, config, size, size, result, &error), error);
    const std::vector<float> truth = reference_visibility(setup.scene, result, 32);
    const Metrics m = compare(result, truth);
    std::printf("occluder at depth %.4f, slice plane %.4f\n", setup.occluder_depth, setup.plane_depth);
    print_metrics("single occluder, sat 512², 16 slices, Embree 32×32", m);
    // Enough penumbra to measure: a ring around the shadow, a sizeable part of the image.
    CHECK(m.penumbra.count > static_cast<std::size_t>(size * size / 20));
    return m;
}

} // namespace

TEST_CASE("scenes: a single occluder on a slice's bottom plane matches the ground truth (sat, 512², no leak fix)") {
    // A thousandth of a slice towards the light, so that float rounding of the interpolated depth
    // cannot push the occluder into slice k + 1; its kernel changes by ~1e-4 of its size.
    CHECK(single_occluder_metrics(1e-3).penumbra.mae <= 0.01);
}

TEST_CASE("scenes: the single occluder stays exact with chained fusion and the tangent clip") {
    // The receiver faces the whole light and the occluder is one slice: neither option may move it.
    CHECK(single_occluder_metrics(1e-3, {.slices = 16, .resolution = 512, .filter = penumbra::Filter::sat,
                                         .fusion = penumbra::Fusion::chained, .leak_fix = false, .tangent_clip = true})
              .penumbra.mae <= 0.01);
}

TEST_CASE("scenes: on box, chained fusion with the tangent clip is close to the fair truth; the paper's model is not") {
    // One box on the ground (fair reference: the light above each surface's tangent plane).
    // The paper's model darkens the walls with the box's own slices and counts the box once per
    // slice on the ground (measured 0.55 at 256² with 32×32 rays); restricted kernels, the normal
    // offset and neighbours fused by maximum give 0.04.
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const std::optional<Scene> scene = make_scene("box");
    REQUIRE(scene);
    std::optional<References> truth;
    double mae[2] = {0, 0};
    const penumbra::Config configs[2] = {{.fusion = penumbra::Fusion::probabilistic, .tangent_clip = false},
                                         {.fusion = penumbra::Fusion::chained, .tangent_clip = true}};
    for (int i = 0; i < 2; ++i) {
        HeadlessResult result;
        REQUIRE_MESSAGE(render_headless(*scene, configs[i], 256, 256, result, &error), error);
        if (!truth) truth = reference_all(*scene, result, 16);
        const QualityMetrics q = compare_quality(result, *truth);
        print_metrics(i ? "box, chained + tangent clip (the default), fair (oriented)" : "box, the paper's model, fair (oriented)",
                      q.oriented);
        mae[i] = q.oriented.penumbra.mae;
        CHECK(q.oriented.penumbra.count > 300);
    }
    CHECK(mae[0] > 0.3);
    CHECK(mae[1] <= 0.05);
}

TEST_CASE("scenes: the same occluder in the middle of its slice is measurably off (the check above can fail)") {
    // Projected half a slice down onto ζ_k, its shadow is too small: the slicing error the test
    // above avoids (0.016 measured on llvmpipe, against 0.002 on the plane).
    CHECK(single_occluder_metrics(0.5).penumbra.mae > 0.01);
}

namespace {

// Penumbra MAE of each fusion rule (probabilistic, maximum, additive) on a built-in scene:
// the paper's whole-light kernels and the leak fix off, since the leak fix draws every surface into two
// slices and so darkens every rule that sums (paper §3.4.1: "umbrae are a little overestimated").
// 128², one Embree reference (16×16 rays) for the three.
std::array<double, 3> fusion_penumbra_mae(std::string_view scene_name) {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const std::optional<Scene> scene = make_scene(scene_name);
    REQUIRE(scene);
    const penumbra::Fusion fusions[3] = {penumbra::Fusion::probabilistic, penumbra::Fusion::maximum,
                                         penumbra::Fusion::additive};
    std::array<double, 3> mae{};
    std::vector<float> truth; // the G-buffer does not depend on the fusion rule: one reference
    for (int i = 0; i < 3; ++i) {
        HeadlessResult result;
        const penumbra::Config config{.fusion = fusions[i], .leak_fix = false, .tangent_clip = false};
        REQUIRE_MESSAGE(render_headless(*scene, config, 128, 128, result, &error), error);
        if (truth.empty()) truth = reference_visibility(*scene, result, 16);
        const Metrics m = compare(result, truth);
        print_metrics((std::string(scene_name) + ", fusion " + std::string(penumbra::to_string(fusions[i]))).c_str(), m);
        mae[i] = m.penumbra.mae;
    }
    return mae;
}

} // namespace

TEST_CASE("scenes: probabilistic fusion is closer to the ground truth than maximum and additive on tree") {
    // Paper §3.3, eq. (5): the product assumes the slices block independent parts of the light,
    // which holds for foliage (measured on llvmpipe: 0.076 against 0.258 and 0.142).
    const std::array<double, 3> mae = fusion_penumbra_mae("tree");
    CHECK(mae[0] < mae[1]);
    CHECK(mae[0] < mae[2]);
}

TEST_CASE("scenes: fusion rules on boxes, measured (the paper's ordering does not hold there)") {
    // A solid box is drawn in every slice it spans (its walls as bands, its top in one slice), so
    // the slices' occlusions are strongly correlated and the product counts the same body several
    // times; the maximum, which takes one slice, comes out closer (0.086 against 0.100; with the
    // leak fix 0.078 against 0.138). Printed, not asserted; additive stays the worst.
    const std::array<double, 3> mae = fusion_penumbra_mae("boxes");
    CHECK(mae[0] < mae[2]);
}

TEST_CASE("scenes: every scene renders with every filter and packing and casts a shadow") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    for (std::string_view name : scene_names()) {
        const std::optional<Scene> scene = make_scene(name);
        REQUIRE(scene);
        for (penumbra::Light light : penumbra::all_values<penumbra::Light>())
            for (penumbra::Filter filter : penumbra::all_values<penumbra::Filter>())
                for (penumbra::Packing packing : penumbra::all_values<penumbra::Packing>()) {
                    const penumbra::Config config{
                        .slices = 8, .resolution = 128, .filter = filter, .packing = packing, .light = light};
                    if (!penumbra::validate(config).empty()) continue; // e.g. gaussian needs the sun
                    const std::string label = std::string(name) + " " + std::string(penumbra::to_string(light)) + " " +
                                              std::string(penumbra::to_string(filter)) + " " +
                                              std::string(penumbra::to_string(packing));
                    CAPTURE(label);
                    HeadlessResult result;
                    REQUIRE_MESSAGE(render_headless(*scene, config, 64, 64, result, &error), error);
                    CHECK(glGetError() == GL_NO_ERROR);
                    const double shadowed = shadowed_fraction(result);
                    std::printf("%-36s shadowed %.3f\n", label.c_str(), shadowed);
                    // box at 64²: 0.8 % of the image (its walls are lit: the tangent clip)
                    CHECK(shadowed > 0.005);
                    CHECK(shadowed < 0.8);
                }
    }
}
