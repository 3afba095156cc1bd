// Cut-out casters (Config::alpha_test) on the "cutout" scene: grilles, a fence and leaf cards whose
// materials cut. The slicing pass's output is the CPU's cut coverage (reference/slice_coverage.hpp);
// the GPU's visibility equals the oracle's within its bound; the G-buffer has no surface where the
// receivers are cut; and against the Embree truth, which honours the cut, each technique is
// measurably closer with alpha_test on than with the casters solid. Label "gl".
#include "oracle_agreement.hpp"
#include "reference/ground_truth.hpp"
#include "reference/oracle.hpp"
#include "reference/slice_coverage.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/mesh_builder.hpp"
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

std::string name_of(const Config& c) {
    std::string name = std::string(to_string(c.technique)) + " " + std::string(to_string(c.light));
    if (c.technique == Technique::occlusion)
        name += " " + std::string(to_string(c.filter)) + " " + std::string(to_string(c.packing)) +
                " S=" + std::to_string(c.slices) + " R=" + std::to_string(c.resolution);
    return name + (c.alpha_test ? " alpha test" : " solid");
}

} // namespace

TEST_CASE("cut-out casters: the slicing pass covers only where the materials' alpha reaches the cutoff") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const std::optional<Scene> scene = make_scene("cutout");
    REQUIRE(scene);
    for (const Light light : all_values<Light>())
        for (const bool alpha_test : {true, false}) {
            const Config config{.slices = 8, .resolution = 128, .light = light, .alpha_test = alpha_test};
            const std::string name = name_of(config);
            SliceTextures gpu;
            SliceFrame frame;
            bool read = false;
            RenderOptions options{.inspect = [&](const gl::Runtime& runtime) {
                read = read_slice_textures(runtime, gpu, &error);
                frame = runtime.frame();
            }};
            HeadlessResult result;
            REQUIRE_MESSAGE(render_headless(*scene, config, 16, 16, result, &error, options), name, ": ",
                            error);
            REQUIRE_MESSAGE(read, name, ": ", error);
            const int reach = leak_fix_reach(config);
            const SliceCoverage expected = cpu_slice_coverage(scene->mesh, config, frame, reach, alpha_test);
            const SliceCoverage other = cpu_slice_coverage(scene->mesh, config, frame, reach, !alpha_test);
            const int R = config.resolution;
            std::size_t wrong = 0, covered = 0, cut_texels = 0, cut_followed = 0;
            for (int s = 0; s < config.slices; ++s)
                for (int y = 0; y < R; ++y)
                    for (int x = 0; x < R; ++x) {
                        const float g = gpu.at(s, x, y);
                        const Coverage e = expected.at(s, x, y), o = other.at(s, x, y);
                        covered += e == Coverage::covered;
                        wrong += (e == Coverage::covered && g != 1.0f) || (e == Coverage::empty && g != 0.0f);
                        if ((e == Coverage::covered && o == Coverage::empty) ||
                            (e == Coverage::empty && o == Coverage::covered)) {
                            ++cut_texels;
                            cut_followed += (e == Coverage::covered) == (g == 1.0f);
                        }
                    }
            std::printf("cutout slicing %-40s covered %zu, wrong %zu, texels the cut decides %zu (as "
                        "configured %zu)\n",
                        name.c_str(), covered, wrong, cut_texels, cut_followed);
            CHECK_MESSAGE(wrong == 0, name, ": ", wrong,
                          " texels disagree with the CPU's coverage away from edges");
            CHECK_MESSAGE(cut_texels > 500, name, ": the cut should decide many texels");
            CHECK_MESSAGE(cut_followed == cut_texels, name, ": the slicing does not follow alpha_test");
        }
}

TEST_CASE("cut-out casters: the GPU's visibility equals the oracle's within its bound") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    // a 20-degree sun, whose penumbrae reach the upper filter levels (as in oracle_test.cpp)
    std::optional<Scene> scene = make_scene("cutout");
    REQUIRE(scene);
    scene->sun.angular_diameter = 0.35;
    const std::vector<Config> configs{
        {.slices = 16, .resolution = 256, .alpha_test = true}, // the default, cut
        {.slices = 8,
         .resolution = 128,
         .filter = Filter::sat,
         .packing = Packing::array,
         .light = Light::sun,
         .alpha_test = true},
        {.slices = 16,
         .resolution = 128,
         .filter = Filter::mipmap,
         .fusion = Fusion::probabilistic,
         .packing = Packing::array,
         .tangent_clip = false,
         .alpha_test = true},
        {.slices = 16,
         .resolution = 128,
         .filter = Filter::gaussian,
         .packing = Packing::volume,
         .light = Light::sun,
         .alpha_test = true},
    };
    for (const Config& config : configs) {
        const std::string name = name_of(config);
        GpuRun run;
        REQUIRE_MESSAGE(render_for_oracle(*scene, config, 64, run, &error), name, ": ", error);
        const Agreement a = agreement(oracle_of(run), run.result, config.fusion, name);
        std::printf("cutout oracle %-40s max |GPU - oracle| %.2e, beyond the bound %zu of %zu, penumbra %zu\n",
                    name.c_str(), a.max_difference, a.beyond_bound, a.pixels, a.penumbra_pixels);
        CHECK_MESSAGE(a.beyond_bound == 0, name, ": ", a.beyond_bound, " pixels beyond the bound, max |diff| ",
                      a.max_difference, "; the worst, ", a.worst);
        CHECK_MESSAGE(a.penumbra_pixels > 100, name, ": too few penumbra pixels for a meaningful comparison");
    }
}

TEST_CASE("cut-out receivers: the G-buffer has no surface where a material is cut") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    // The grille seen from straight above, filling the view: its holes show the ground 1.4 below.
    std::optional<Scene> scene = make_scene("cutout");
    REQUIRE(scene);
    scene->camera.target = glm::vec3(-1.5f, 1.4f, 0.6f);
    scene->camera.distance = 1.2f;
    scene->camera.pitch_radians = 1.5707f;
    HeadlessResult result;
    REQUIRE_MESSAGE(render_headless(*scene, Config{}, 64, 64, result, &error), error);
    std::size_t grille = 0, below = 0;
    for (std::size_t i = 0; i < result.positions.size(); ++i) {
        if (!result.geometry[i]) continue;
        (result.positions[i].y > 1.0f ? grille : below) += 1;
    }
    std::printf("cutout receivers: %zu grille pixels, %zu pixels of what lies below it\n", grille, below);
    // the grille's texture is 6/32 bars on each side of a cell: about 61 % of it is solid
    CHECK(grille > 64 * 64 / 3);
    CHECK(below > 64 * 64 / 5);
}

// The technique's error against the truth with the cut, with alpha_test on and off (solid casters):
// the G-buffer is the same (receivers are cut either way), so one truth serves both.
TEST_CASE("cut-out casters: every technique is closer to the truth with the cut than with solid casters") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const std::optional<Scene> scene = make_scene("cutout");
    REQUIRE(scene);
    constexpr int size = 96;
    // (the configuration, the largest share of the solid casters' error that the cut may leave): erosion
    // works on the screen-space hard shadow and its own errors dominate (measured on llvmpipe: 0.116
    // cut, 0.124 solid); the others lose about two thirds of the error (0.020 against 0.057)
    const std::vector<std::pair<Config, double>> configs{
        {{.technique = Technique::occlusion}, 0.5},
        {{.technique = Technique::pcss, .pcss = {.blocker_samples = 16, .filter_samples = 16}}, 0.5},
        {{.technique = Technique::pcf}, 0.8},
        {{.technique = Technique::erosion}, 0.97},
    };
    References truth;
    for (const auto& [base, share] : configs) {
        double mae[2] = {0, 0};
        for (const bool alpha_test : {true, false}) {
            Config config = base;
            config.alpha_test = alpha_test;
            HeadlessResult result;
            REQUIRE_MESSAGE(render_headless(*scene, config, size, size, result, &error), name_of(config),
                            ": ", error);
            if (truth.oriented.empty()) truth = reference_all(*scene, result, 8);
            const QualityMetrics m = compare_quality(result, truth);
            mae[alpha_test ? 0 : 1] = m.oriented.all.mae;
            std::printf(
                "cutout %-32s MAE %.4f (penumbra %.4f over %zu pixels) against the fair truth with the cut\n",
                name_of(config).c_str(), m.oriented.all.mae, m.oriented.penumbra.mae,
                m.oriented.penumbra.count);
        }
        CHECK_MESSAGE(mae[0] < share * mae[1], name_of(base), ": with the cut ", mae[0], ", solid casters ",
                      mae[1]);
    }
}
