// Lights inside the scene (docs/model.md §1.2b), label "gl": what lies behind a rectangular light's plane
// casts no shadow, in every technique's light passes, on real OpenGL.
//   - The "planes" scene with its light lowered between two occluders and a ceiling above it: the
//     visibility of every receiver in front of the light is that of the same scene without the ceiling and
//     the occluder behind the light (the bounds kept, so both get the same light frame). Before the clip,
//     the ceiling landed in the first slice (in the shadow map, at its near plane) and darkened everything.
//   - A wall crossing the light's plane beside the light: the GPU's slices hold its part in front of the
//     plane only, as the CPU's slicing clips it (reference/slice_coverage.hpp).
#include "reference/oracle.hpp"
#include "reference/slice_coverage.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace penumbra;
using namespace penumbra::playground;

namespace {

constexpr float light_height = 2.5f; // between the occluders at 2 and 3 (planes_occluder_heights)

// "planes" lit from below its top occluder, under a ceiling, seen from below the ceiling.
Scene lowered_light_scene() {
    Scene scene = *make_scene("planes");
    add_horizontal_rect(scene.mesh, 0.0f, 2.8f, 0.0f, 12.0f, 12.0f); // a ceiling over everything
    scene.bounds_min = glm::min(scene.bounds_min, glm::vec3(-6.0f, 0.0f, -6.0f));
    scene.bounds_max = glm::max(scene.bounds_max, glm::vec3(6.0f, 3.0f, 6.0f));
    scene.light.center = {0.0, light_height, 0.0};
    scene.camera.target = {0.0f, 0.5f, 0.0f};
    scene.camera.distance = 8.0f;
    scene.camera.pitch_radians = 0.2f; // the eye at y = 2.09, under the light and the ceiling
    return scene;
}

// The same scene without the triangles that lie wholly behind the light's plane.
Scene without_what_is_behind(const Scene& scene) {
    Scene kept = scene;
    kept.mesh.indices.clear();
    const glm::dvec3 n = scene.light.normal();
    for (std::size_t t = 0; t < scene.mesh.triangle_count(); ++t) {
        bool behind = true;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 p(scene.mesh.positions[scene.mesh.indices[3 * t + k]]);
            behind = behind && glm::dot(p - scene.light.center, n) <= 0.0;
        }
        if (behind) continue;
        for (int k = 0; k < 3; ++k) kept.mesh.indices.push_back(scene.mesh.indices[3 * t + k]);
    }
    kept.mesh.triangle_closed.assign(kept.mesh.triangle_count(), 0);
    return kept;
}

} // namespace

TEST_CASE("lights inside the scene: nothing behind the light's plane casts a shadow, in every technique") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const Scene scene = lowered_light_scene();
    const Scene kept = without_what_is_behind(scene);
    REQUIRE(kept.mesh.triangle_count() + 4 ==
            scene.mesh.triangle_count()); // the ceiling and the top occluder
    const Config configs[] = {
        {},
        {.slices = 8, .resolution = 128, .filter = Filter::mipmap, .packing = Packing::array},
        {.slices = 16, .resolution = 128, .slice_placement = SlicePlacement::adaptive},
        {.technique = Technique::shadowmap},
        {.technique = Technique::pcf},
        {.technique = Technique::pcss},
        {.technique = Technique::evsm},
        {.technique = Technique::smrt},
    };
    for (const Config& config : configs) {
        const std::string label = std::string(to_string(config.technique)) + " " +
                                  std::string(to_string(config.filter)) + " " +
                                  std::string(to_string(config.slice_placement));
        CAPTURE(label);
        HeadlessResult with, without;
        REQUIRE_MESSAGE(render_headless(scene, config, 96, 96, with, &error), error);
        REQUIRE_MESSAGE(render_headless(kept, config, 96, 96, without, &error), error);
        std::size_t compared = 0, differ = 0;
        double lit = 0.0;
        for (std::size_t i = 0; i < with.visibility.size(); ++i) {
            if (!with.geometry[i] || !without.geometry[i]) continue;
            if (glm::length(with.positions[i] - without.positions[i]) > 1e-4f) continue; // the ceiling, seen
            if (with.positions[i].y > light_height - 0.01f) continue;
            ++compared;
            lit += with.visibility[i];
            differ += std::abs(with.visibility[i] - without.visibility[i]) > 0.02f;
        }
        std::printf("light plane %-32s compared %zu pixels, %zu differ, mean visibility %.3f\n",
                    label.c_str(), compared, differ, compared ? lit / static_cast<double>(compared) : 0.0);
        REQUIRE(compared > 2000);
        CHECK(differ <= compared / 500); // a few pixels where rounding moves an edge
        CHECK(lit / static_cast<double>(compared) >
              0.3); // lit, not darkened by the ceiling (faces turned away: 0)
    }
}

TEST_CASE("lights inside the scene: a wall crossing the light's plane is sliced in front of it only") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    Scene scene = lowered_light_scene();
    add_quad(scene.mesh, {2.0f, 0.0f, -2.0f}, {2.0f, 0.0f, 2.0f}, {2.0f, 2.9f, 2.0f}, {2.0f, 2.9f, -2.0f});
    scene.mesh.triangle_closed.assign(scene.mesh.triangle_count(), 0);
    const Config config{.slices = 16, .resolution = 256, .packing = Packing::array};
    SliceTextures gpu;
    SliceFrame frame;
    bool read = false;
    RenderOptions options{.inspect = [&](const gl::Runtime& runtime) {
        read = read_slice_textures(runtime, gpu, &error);
        frame = runtime.frame();
    }};
    HeadlessResult result;
    REQUIRE_MESSAGE(render_headless(scene, config, 32, 32, result, &error, options), error);
    REQUIRE_MESSAGE(read, error);
    CHECK_FALSE(frame.contained);
    const SliceCoverage expected =
        cpu_slice_coverage(scene.mesh, config, frame, leak_fix_reach(config), false);
    const int R = config.resolution;
    std::size_t wrong = 0, covered_first = 0;
    for (int s = 0; s < config.slices; ++s)
        for (int y = 0; y < R; ++y)
            for (int x = 0; x < R; ++x) {
                const Coverage e = expected.at(s, x, y);
                const float g = gpu.at(s, x, y);
                wrong += (e == Coverage::covered && g != 1.0f) || (e == Coverage::empty && g != 0.0f);
                covered_first += s == 0 && g == 1.0f;
            }
    std::printf("light plane: crossing wall, %zu texels differ from the CPU's clipped slicing, slice 0 "
                "covers %zu of %d\n",
                wrong, covered_first, R * R);
    CHECK(wrong == 0);
    CHECK(covered_first <
          static_cast<std::size_t>(R * R / 10)); // neither the ceiling nor the wall's top fill it
}
