// Occlusion interval maps on real OpenGL (llvmpipe on CI), label "gl": the emitted shader against
// the bake it reads and against Embree's visibility of the same linear light; the zero-width window
// is the hard shadow; every scene renders with a sane shadowed fraction.
#include "../temp_dir.hpp"
#include "app/headless_job.hpp"
#include "bake/oim_scene.hpp"
#include "reference/ground_truth.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scenes.hpp"
#include "scenes/uv_coverage.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

using namespace penumbra::playground;

namespace {

penumbra::Config oim_config(int resolution) {
    penumbra::Config config{.technique = penumbra::Technique::oim};
    config.oim.resolution = resolution;
    config.oim.intervals = 8;
    config.oim.samples = 256;
    return config;
}

struct Rendered {
    Scene scene;
    OimSetup setup;
    HeadlessResult result;
};

Rendered render_oim(const char* name, const penumbra::Config& config, double t, double angular_diameter, int size,
                    const std::filesystem::path& cache) {
    Rendered r{*make_scene(name), {}, {}};
    r.scene.sun.angular_diameter = angular_diameter;
    std::string error;
    std::optional<OimSetup> setup = prepare_oim(r.scene, config, penumbra::SunPath{}, t, cache, &error);
    REQUIRE_MESSAGE(setup, error);
    r.setup = std::move(*setup);
    RenderOptions options;
    options.bake_textures = r.setup.textures;
    options.time_window = r.setup.time_window;
    REQUIRE_MESSAGE(render_headless(r.scene, config, size, size, r.result, &error, options), error);
    return r;
}

// The texel a fragment reads (nearest filtering), or -1 when uv·R lies too close to a texel edge to say.
long texel_of(glm::vec2 uv, int R) {
    const glm::vec2 p = uv * static_cast<float>(R);
    const glm::vec2 f = p - glm::floor(p);
    if (f.x < 1e-3f || f.x > 1.0f - 1e-3f || f.y < 1e-3f || f.y > 1.0f - 1e-3f) return -1;
    const glm::ivec2 texel = glm::clamp(glm::ivec2(glm::floor(p)), 0, R - 1);
    return static_cast<long>(texel.y) * R + texel.x;
}

} // namespace

TEST_CASE("oim: the shader evaluates the bake exactly, and both follow Embree's linear light") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    testing::TempDir dir;
    const penumbra::Config config = oim_config(128);
    const double t = 0.4;
    const Rendered r = render_oim("planes", config, t, 0.0093 * 5.0, 128, dir.file("cache"));
    const OimBake& bake = r.setup.cached.bake;
    const glm::vec4 w = r.setup.time_window;
    const std::vector<TexelSample> texels = texel_samples(r.scene.mesh, config.oim.resolution);

    // Shader = the chapter's formula on the CPU over the same texel.
    std::size_t compared = 0, mismatched = 0, soft = 0;
    std::vector<glm::vec3> points, normals;
    std::vector<float> shaded;
    for (std::size_t i = 0; i < r.result.visibility.size(); ++i) {
        if (!r.result.geometry[i]) continue;
        const long texel = texel_of(r.result.tex_coords[i], config.oim.resolution);
        if (texel < 0) continue;
        REQUIRE(texels[static_cast<std::size_t>(texel)].triangle >= 0);
        const float expected = bake.visibility(static_cast<std::size_t>(texel), w.x, w.y);
        ++compared;
        mismatched += std::abs(r.result.visibility[i] - expected) > 2e-3f;
        soft += expected > 0.02f && expected < 0.98f;
        points.push_back(texels[static_cast<std::size_t>(texel)].position);
        normals.push_back(texels[static_cast<std::size_t>(texel)].normal);
        shaded.push_back(r.result.visibility[i]);
    }
    CHECK(compared > 3000);
    CHECK(mismatched == 0);
    CHECK(soft > 8); // penumbra pixels are among them

    // Shader = Embree's visibility of the linear light (64 instants of the window) at the texels'
    // points, within what 256 bake instants can resolve.
    const GroundTruth truth(r.scene.mesh);
    std::vector<glm::vec3> window;
    for (int m = 0; m < 64; ++m)
        window.push_back(glm::vec3(penumbra::sun_direction(penumbra::SunPath{}, w.x + (m + 0.5) / 64.0 * (w.y - w.x))));
    const std::vector<float> expected = truth.visibility(points, normals, window);
    double total = 0.0;
    std::size_t far = 0;
    const double step_error = 0.5 / bake.samples * w.z + 1.0 / 64.0; // one edge: half a bake step, half a truth step
    for (std::size_t k = 0; k < shaded.size(); ++k) {
        const double e = std::abs(shaded[k] - expected[k]);
        total += e;
        far += e > 2.0 * step_error + 1e-3;
    }
    std::printf("oim planes: shader vs Embree linear light at %zu pixels: MAE %.4f, %zu beyond two edges' error %.3f\n",
                shaded.size(), total / static_cast<double>(shaded.size()), far, 2.0 * step_error);
    CHECK(total / static_cast<double>(shaded.size()) < 0.01);
    CHECK(far == 0);
}

TEST_CASE("oim: a time window of zero width gives the hard shadow") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    testing::TempDir dir;
    const penumbra::Config config = oim_config(128);
    const int i = 102;
    const double t = (i + 0.5) / 256.0; // a bake instant: the same rays as the bake
    const Rendered r = render_oim("boxes", config, t, 0.0, 96, dir.file("cache"));
    const glm::vec3 towards_sun(penumbra::sun_direction(penumbra::SunPath{}, t));
    const GroundTruth truth(r.scene.mesh);
    const std::vector<TexelSample> texels = texel_samples(r.scene.mesh, config.oim.resolution);
    std::vector<glm::vec3> points, normals;
    std::vector<float> shaded;
    std::size_t binary = 0, geometry = 0;
    for (std::size_t p = 0; p < r.result.visibility.size(); ++p) {
        if (!r.result.geometry[p]) continue;
        ++geometry;
        const float v = r.result.visibility[p];
        binary += v < 1e-4f || v > 1.0f - 1e-4f;
        const long texel = texel_of(r.result.tex_coords[p], config.oim.resolution);
        if (texel < 0) continue;
        points.push_back(texels[static_cast<std::size_t>(texel)].position);
        normals.push_back(texels[static_cast<std::size_t>(texel)].normal);
        shaded.push_back(v);
    }
    CHECK(binary == geometry);
    const std::vector<std::uint8_t> open = truth.unoccluded(points, normals, {&towards_sun, 1});
    std::size_t wrong = 0, lit = 0;
    for (std::size_t k = 0; k < shaded.size(); ++k) {
        wrong += std::abs(shaded[k] - static_cast<float>(open[k])) > 1e-4f;
        lit += open[k];
    }
    CHECK(wrong == 0);
    CHECK(lit > shaded.size() / 3);
    CHECK(lit < shaded.size());
}

TEST_CASE("oim: every scene renders without a GL error and shadows like the sun's disk") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    testing::TempDir dir;
    for (std::string_view name : scene_names()) {
        CAPTURE(name);
        const penumbra::Config config = oim_config(name == "crowd" ? 256 : 128);
        const Rendered r = render_oim(std::string(name).c_str(), config, 0.5, 0.0093 * 5.0, 64, dir.file("cache"));
        CHECK(glGetError() == GL_NO_ERROR);
        HeadlessResult reference = r.result;
        reference.visibility = reference_visibility(r.scene, r.result, 4, penumbra::Light::sun);
        const double shadowed = shadowed_fraction(r.result), expected = shadowed_fraction(reference);
        std::printf("oim %-10s shadowed %.3f (truth %.3f), bake %.0f ms\n", std::string(name).c_str(), shadowed, expected,
                    r.setup.cached.bake.bake_ms);
        // Some shadow where the truth has some (the one-box scene casts only a small one at noon).
        CHECK(expected > 0.0);
        CHECK(shadowed > 0.5 * expected);
        CHECK(std::abs(shadowed - expected) < 0.1);
    }
}
