// The erosion technique (Klein et al.) on real OpenGL (llvmpipe on CI), label "gl":
//   - on `planes`, the edge buffer follows from the hard shadow: read back both textures and
//     compare with a CPU Laplacian of the hard shadow; level 1 of the min-max chain is the max of
//     level 0's 3x3 windows;
//   - every built-in scene renders without a GL error, shadowing about as much as the Embree truth.
#include "rendering/egl_context.hpp"
#include "app/headless_job.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scenes.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

using namespace penumbra::playground;

namespace {

// Level `level` of an RGBA texture as floats, bottom row first.
std::vector<float> read_rgba(GLuint texture, int width, int height) {
    std::vector<float> texels(static_cast<std::size_t>(width) * height * 4);
    glGetTextureImage(texture, 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(float)), texels.data());
    return texels;
}

std::vector<float> read_rgba_level(GLuint texture, int level, int width, int height) {
    std::vector<float> texels(static_cast<std::size_t>(width) * height * 4);
    glGetTextureImage(texture, level, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(texels.size() * sizeof(float)),
                      texels.data());
    return texels;
}

} // namespace

TEST_CASE("erosion: on planes the edge buffer is the Laplacian of the hard shadow, level 1 its 3x3 max") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const std::optional<Scene> scene = make_scene("planes");
    REQUIRE(scene);
    const penumbra::Config config{.technique = penumbra::Technique::erosion, .shadow_map = {.resolution = 512}};
    const int n = 128;
    std::vector<float> hard, edges, level1;
    RenderOptions options;
    options.inspect = [&](const penumbra::gl::Runtime& runtime) {
        hard = read_rgba(runtime.texture("penumbra_erosionHard"), n, n);
        edges = read_rgba(runtime.texture("penumbra_erosionEdges"), n, n);
        level1 = read_rgba_level(runtime.texture("penumbra_erosionEdges"), 1, n / 2, n / 2);
    };
    HeadlessResult result;
    REQUIRE_MESSAGE(render_headless(*scene, config, n, n, result, &error, options), error);
    REQUIRE(glGetError() == GL_NO_ERROR);
    auto at = [&](const std::vector<float>& t, int x, int y, int c, int w) {
        x = std::clamp(x, 0, w - 1);
        y = std::clamp(y, 0, w - 1);
        return t[(static_cast<std::size_t>(y) * w + x) * 4 + c];
    };
    int edge_pixels = 0, shadowed = 0, mismatches = 0;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const float centre = at(hard, x, y, 0, n);
            const bool geometry = at(hard, x, y, 3, n) > 0.5f;
            float laplacian = 0.0f;
            for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
                laplacian += (at(hard, x + dx, y + dy, 3, n) > 0.5f ? at(hard, x + dx, y + dy, 0, n) : centre) - centre;
            const bool expected = geometry && std::abs(laplacian) > config.erosion.edge_threshold;
            const bool got = at(edges, x, y, 0, n) > 0.5f;
            mismatches += expected != got;
            edge_pixels += expected;
            shadowed += geometry && centre < 0.5f;
            CHECK(at(edges, x, y, 2, n) == centre); // b and a: min and max of the hard shadow
        }
    std::printf("erosion planes %dx%d: %d shadowed, %d edge pixels, %d mismatches\n", n, n, shadowed, edge_pixels,
                mismatches);
    CHECK(shadowed > n * n / 50);
    CHECK(edge_pixels > n / 2);
    CHECK(mismatches == 0);
    int chain_mismatches = 0;
    for (int y = 0; y < n / 2; ++y)
        for (int x = 0; x < n / 2; ++x) {
            float edge = 0.0f, lo = 1.0f;
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 3; ++i) {
                    edge = std::max(edge, at(edges, 2 * x + i, 2 * y + j, 0, n));
                    lo = std::min(lo, at(edges, 2 * x + i, 2 * y + j, 2, n));
                }
            chain_mismatches += at(level1, x, y, 0, n / 2) != edge || at(level1, x, y, 2, n / 2) != lo;
        }
    CHECK(chain_mismatches == 0);
}

TEST_CASE("erosion renders every scene without a GL error and shadows like the truth") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    for (std::string_view name : scene_names()) {
        const std::optional<Scene> scene = make_scene(name);
        REQUIRE(scene);
        const penumbra::Config config{.technique = penumbra::Technique::erosion, .shadow_map = {.resolution = 512}};
        CAPTURE(name);
        HeadlessResult result;
        REQUIRE_MESSAGE(render_headless(*scene, config, 64, 64, result, &error), error);
        CHECK(glGetError() == GL_NO_ERROR);
        HeadlessResult reference = result;
        reference.visibility = reference_visibility(*scene, result, 4);
        const double shadowed = shadowed_fraction(result), expected = shadowed_fraction(reference);
        std::printf("%-12s erosion shadowed %.3f (truth %.3f)\n", std::string(name).c_str(), shadowed, expected);
        CHECK(shadowed > 0.01);
        CHECK(std::abs(shadowed - expected) < 0.1);
    }
}
