// tests/runtime/gl/debug_views_test.cpp — the playground's debug views rendered into an FBO under
// EGL and read back: slice textures of every packing and filter, the slice/level view against a
// CPU computation from the same G-buffer, the error heatmap, the scalar view, bad input.
#include "rendering/debug_views.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/gpu_scene.hpp"
#include "app/image_io.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

using namespace penumbra::playground;

namespace {

// An RGBA8 render target; pixels() reads it back bottom row first (as GL stores it).
class Target {
public:
    Target(int width, int height) : width_(width), height_(height) {
        glCreateTextures(GL_TEXTURE_2D, 1, &color_);
        glTextureStorage2D(color_, 1, GL_RGBA8, width, height);
        glCreateFramebuffers(1, &fbo_);
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, color_, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glViewport(0, 0, width, height);
        glClearColor(0.2f, 0.4f, 0.6f, 1.0f); // a colour no view produces on its own
        glClear(GL_COLOR_BUFFER_BIT);
    }
    ~Target() {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glDeleteFramebuffers(1, &fbo_);
        glDeleteTextures(1, &color_);
    }
    std::vector<std::array<unsigned char, 4>> pixels() const {
        std::vector<std::array<unsigned char, 4>> out(static_cast<std::size_t>(width_) * height_);
        glGetTextureImage(color_, 0, GL_RGBA, GL_UNSIGNED_BYTE, static_cast<GLsizei>(out.size() * 4),
                          out.data());
        return out;
    }
    // Grey level of each pixel (red channel / 255).
    std::vector<float> grey() const {
        std::vector<float> out;
        for (const auto& p : pixels()) out.push_back(p[0] / 255.0f);
        return out;
    }

private:
    int width_, height_;
    GLuint color_ = 0, fbo_ = 0;
};

bool near_color(const std::array<unsigned char, 4>& pixel, glm::vec3 expected, int tolerance) {
    for (int c = 0; c < 3; ++c)
        if (std::abs(int(pixel[static_cast<std::size_t>(c)]) - int(std::lround(expected[c] * 255.0f))) >
            tolerance)
            return false;
    return true;
}

GLuint r32f_texture(int width, int height, const std::vector<float>& values) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, GL_R32F, width, height);
    glTextureSubImage2D(texture, 0, 0, 0, width, height, GL_RED, GL_FLOAT, values.data());
    return texture;
}

// A runtime with its passes run over the planes scene.
struct Built {
    Scene scene = *make_scene("planes");
    std::unique_ptr<MeshBuffers> mesh;
    std::unique_ptr<penumbra::gl::Runtime> runtime;
};

std::unique_ptr<Built> build(const penumbra::Config& config, std::string* error) {
    auto b = std::make_unique<Built>();
    b->mesh = std::make_unique<MeshBuffers>(b->scene.mesh);
    // the views show every filter level, not only those the light reaches (RuntimeOptions::fit_level_bound)
    b->runtime = penumbra::gl::Runtime::create(config, error, {.fit_level_bound = false});
    if (!b->runtime) return nullptr;
    // A sun straight overhead: the planes stay parallel to the slices, one plane per slice, so
    // the expected coverage is known (the scene's tilted sun spreads each plane over several).
    b->scene.sun.direction = {0.0, -1.0, 0.0};
    const glm::dvec3 lo(b->scene.bounds_min), hi(b->scene.bounds_max);
    if (config.light == penumbra::Light::sun)
        b->runtime->set_light(b->scene.sun, lo, hi);
    else
        b->runtime->set_light(b->scene.light, lo, hi);
    if (std::string d = b->runtime->build([&](GLuint) { b->mesh->draw(); }); !d.empty()) {
        *error = d;
        return nullptr;
    }
    return b;
}

// The slice holding light-frame depth z (docs/model.md §1.3: slice k holds (z_k, z_k+1]).
int slice_of(const penumbra::SliceFrame& frame, float z, int slices) {
    return std::clamp(static_cast<int>(std::ceil((z - frame.slice_depths.x) / frame.slice_depths.y)) - 1, 0,
                      slices - 1);
}

// Texel of the slice textures under a world point.
glm::ivec2 texel_of(const penumbra::SliceFrame& frame, glm::vec3 world, int resolution) {
    const glm::vec4 clip = frame.slice_clip_from_world * glm::vec4(world, 1.0f);
    const glm::vec2 uv = 0.5f + 0.5f * glm::vec2(clip) / clip.w;
    return glm::ivec2(glm::floor(uv * float(resolution)));
}

struct Occluder {
    glm::vec3 centre;
    glm::vec3 outside; // same plane, off the occluder
};

// The planes scene's occluders (scenes.cpp: build_planes).
const Occluder planes_occluders[] = {
    {{-1.5f, 1.0f, 0.5f}, {1.5f, 1.0f, 0.5f}},
    {{1.0f, 2.0f, -0.5f}, {3.0f, 2.0f, -0.5f}},
    {{0.0f, 3.0f, 1.5f}, {1.5f, 3.0f, 1.5f}},
};

float mean(const std::vector<float>& v) {
    double sum = 0;
    for (float x : v) sum += x;
    return static_cast<float>(sum / v.size());
}

} // namespace

TEST_CASE("debug views: slice textures of every packing and filter show the occluders where they are") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto views = DebugViews::create(&error);
    REQUIRE_MESSAGE(views, error);

    using penumbra::Filter, penumbra::Packing, penumbra::Light;
    struct Case {
        Filter filter;
        Packing packing;
        Light light;
    };
    const Case cases[] = {
        {Filter::mipmap, Packing::atlas, Light::rect},   {Filter::mipmap, Packing::array, Light::rect},
        {Filter::nbuffer, Packing::atlas, Light::rect},  {Filter::nbuffer, Packing::array, Light::rect},
        {Filter::nbuffer, Packing::volume, Light::rect}, {Filter::sat, Packing::atlas, Light::rect},
        {Filter::sat, Packing::array, Light::rect},      {Filter::gaussian, Packing::atlas, Light::sun},
        {Filter::gaussian, Packing::array, Light::sun},  {Filter::gaussian, Packing::volume, Light::sun},
    };
    constexpr int R = 64, S = 8;
    for (const Case& c : cases) {
        const penumbra::Config config{
            .slices = S, .resolution = R, .filter = c.filter, .packing = c.packing, .light = c.light};
        CAPTURE(penumbra::to_string(c.filter));
        CAPTURE(penumbra::to_string(c.packing));
        auto built = build(config, &error);
        REQUIRE_MESSAGE(built, error);
        const penumbra::SliceFrame& frame = built->runtime->frame();

        // Which slices hold geometry (leak fix: slice k also marks k + 1); the rest must be empty.
        std::set<int> occupied;
        for (const glm::vec3& v : built->scene.mesh.positions) {
            const int k = slice_of(frame, (frame.light_from_world * glm::vec4(v, 1.0f)).z, S);
            occupied.insert(k);
            occupied.insert(std::min(k + 1, S - 1));
        }
        REQUIRE(occupied.size() < S); // the test needs an empty slice
        for (int k = 0; k < S; ++k) {
            Target target(R, R);
            REQUIRE(views->draw_slice_texture(*built->runtime, {.slice = k, .level = 0}) == "");
            const std::vector<float> coverage = target.grey();
            const float max_value = *std::max_element(coverage.begin(), coverage.end());
            CAPTURE(k);
            if (!occupied.count(k))
                CHECK(max_value == 0.0f);
            else
                CHECK(max_value == 1.0f);
        }
        for (const Occluder& o : planes_occluders) {
            const int k = slice_of(frame, (frame.light_from_world * glm::vec4(o.centre, 1.0f)).z, S);
            CAPTURE(k);
            Target level0(R, R);
            REQUIRE(views->draw_slice_texture(*built->runtime, {.slice = k, .level = 0}) == "");
            const std::vector<float> sharp = level0.grey();
            const glm::ivec2 inside = texel_of(frame, o.centre, R), outside = texel_of(frame, o.outside, R);
            REQUIRE(inside.x >= 0);
            REQUIRE(inside.x < R);
            REQUIRE(outside.x >= 0);
            REQUIRE(outside.x < R);
            CHECK(sharp[std::size_t(inside.y * R + inside.x)] == 1.0f);
            CHECK(sharp[std::size_t(outside.y * R + outside.x)] == 0.0f);
            const int partial0 = static_cast<int>(
                std::count_if(sharp.begin(), sharp.end(), [](float v) { return v > 0.1f && v < 0.9f; }));
            if (c.filter != Filter::gaussian) CHECK(partial0 == 0); // level 0 is the binary coverage

            // Filter level 2: 4-texel windows. Still covered at the centre, soft edges, same mass.
            Target level2(R, R);
            REQUIRE(views->draw_slice_texture(*built->runtime, {.slice = k, .level = 2}) == "");
            const std::vector<float> soft = level2.grey();
            CHECK(soft[std::size_t(inside.y * R + inside.x)] > 0.9f);
            const int partial2 = static_cast<int>(
                std::count_if(soft.begin(), soft.end(), [](float v) { return v > 0.1f && v < 0.9f; }));
            CHECK(partial2 > 8);
            CHECK(std::abs(mean(soft) - mean(sharp)) <= 0.1f * mean(sharp) + 0.002f);
        }
    }
}

TEST_CASE("debug views: the filter levels widen monotonically (N-buffers, atlas)") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto views = DebugViews::create(&error);
    REQUIRE_MESSAGE(views, error);
    constexpr int R = 64;
    auto built = build({.slices = 8, .resolution = R}, &error);
    REQUIRE_MESSAGE(built, error);
    // Slice 2 holds the occluder at height 2: the number of partly covered texels grows with l.
    int previous = -1;
    for (int level = 0; level <= 4; ++level) {
        Target target(R, R);
        REQUIRE(views->draw_slice_texture(*built->runtime, {.slice = 2, .level = level}) == "");
        const std::vector<float> g = target.grey();
        const int partial = static_cast<int>(
            std::count_if(g.begin(), g.end(), [](float v) { return v > 0.02f && v < 0.98f; }));
        CAPTURE(level);
        CHECK(partial > previous);
        previous = partial;
    }
}

TEST_CASE("debug views: slice and level of each pixel match a CPU computation from the G-buffer") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto views = DebugViews::create(&error);
    REQUIRE_MESSAGE(views, error);
    constexpr int W = 96, H = 72, S = 8, R = 128;
    for (const char* name : {"planes", "boxes"}) {
        CAPTURE(name);
        const Scene scene = *make_scene(name);
        MeshBuffers mesh(scene.mesh);
        auto gbuffer = GBuffer::create(W, H, &error);
        REQUIRE_MESSAGE(gbuffer, error);
        gbuffer->render(mesh, scene.camera.projection_matrix(float(W) / H) * scene.camera.view_matrix());
        const penumbra::Config config{.slices = S, .resolution = R};
        auto runtime = penumbra::gl::Runtime::create(config, scene.light, glm::dvec3(scene.bounds_min),
                                                     glm::dvec3(scene.bounds_max), &error);
        REQUIRE_MESSAGE(runtime, error);
        const penumbra::SliceFrame& frame = runtime->frame();

        std::vector<glm::vec4> positions(std::size_t(W) * H);
        glGetTextureImage(gbuffer->positions(), 0, GL_RGBA, GL_FLOAT,
                          GLsizei(positions.size() * sizeof(glm::vec4)), positions.data());

        Target slices(W, H);
        REQUIRE(views->draw_slice_level(*runtime, gbuffer->positions(), {.mode = SliceLevelMode::slice}) ==
                "");
        Target levels(W, H);
        REQUIRE(views->draw_slice_level(*runtime, gbuffer->positions(), {.mode = SliceLevelMode::level}) ==
                "");
        const auto slice_pixels = slices.pixels(), level_pixels = levels.pixels();

        int geometry = 0, slice_match = 0, level_match = 0, background_match = 0;
        std::set<std::array<unsigned char, 4>> slice_colors, level_colors;
        for (std::size_t i = 0; i < positions.size(); ++i) {
            if (positions[i].w < 0.5f) {
                background_match += near_color(slice_pixels[i], background_color, 0) &&
                                    near_color(level_pixels[i], background_color, 0);
                continue;
            }
            ++geometry;
            slice_colors.insert(slice_pixels[i]);
            level_colors.insert(level_pixels[i]);
            const glm::vec3 p(frame.light_from_world * glm::vec4(glm::vec3(positions[i]), 1.0f));
            const int s = slice_of(frame, p.z, S);
            slice_match += near_color(slice_pixels[i], slice_color(s), 1);
            // The level the shading reads for the nearest slice above (docs/model.md §1).
            glm::vec3 expected = no_slice_color;
            if (s > 0) {
                const float zeta = frame.slice_depths.x + float(s) * frame.slice_depths.y;
                const float side =
                    std::max(p.z - zeta, 0.0f) * frame.cop_distance / (p.z * (frame.cop_distance + zeta));
                const float level =
                    std::clamp(std::log2(std::max(side * R, 1.0f)), 0.0f, float(penumbra::max_level(config)));
                expected = level_color(level);
            }
            level_match += near_color(level_pixels[i], expected, 3);
        }
        const int background = int(positions.size()) - geometry;
        std::printf(
            "slice/level view %s %dx%d: %d geometry px, slice match %d, level match %d, %zu slice colours, "
            "%zu level colours\n",
            name, W, H, geometry, slice_match, level_match, slice_colors.size(), level_colors.size());
        CHECK(geometry > W * H / 8);
        CHECK(background_match == background);
        CHECK(slice_match >= 0.99 * geometry); // points on a slice boundary may round either way
        CHECK(level_match >= 0.97 * geometry);
        CHECK(slice_colors.size() > 2);
        CHECK(level_colors.size() > 2);
    }
}

TEST_CASE("debug views: error heatmap, scalar view, sub-viewports") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto views = DebugViews::create(&error);
    REQUIRE_MESSAGE(views, error);
    constexpr int W = 32, H = 16;
    std::vector<float> ramp(W * H), shifted(W * H);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            ramp[std::size_t(y * W + x)] = float(x) / (W - 1);
            shifted[std::size_t(y * W + x)] = float(x) / (W - 1) + (x >= W / 2 ? 0.25f : 0.0f);
        }
    const GLuint a = r32f_texture(W, H, ramp), b = r32f_texture(W, H, shifted);
    const glm::vec3 zero_color(magnitude_colors(std::vector<float>{0.0f}, 1.0f)[0],
                               magnitude_colors(std::vector<float>{0.0f}, 1.0f)[1],
                               magnitude_colors(std::vector<float>{0.0f}, 1.0f)[2]);
    const std::vector<float> full = magnitude_colors(std::vector<float>{1.0f}, 1.0f);

    SUBCASE("identical inputs give the zero colour everywhere") {
        Target target(W, H);
        REQUIRE(views->draw_error(a, a) == "");
        for (const auto& p : target.pixels()) CHECK(near_color(p, zero_color, 1));
    }
    SUBCASE("an error of max_error saturates; no error stays at zero") {
        Target target(W, H);
        REQUIRE(views->draw_error(a, b, {.max_error = 0.25f}) == "");
        const auto pixels = target.pixels();
        for (int x = 0; x < W; ++x) {
            CAPTURE(x);
            const glm::vec3 expected = x >= W / 2 ? glm::vec3(full[0], full[1], full[2]) : zero_color;
            CHECK(near_color(pixels[std::size_t(x)], expected, 2));
        }
    }
    SUBCASE("NaN (not computed yet) shows green in the heatmap and the scalar view") {
        std::vector<float> holes = ramp;
        holes[5] = std::numeric_limits<float>::quiet_NaN();
        const GLuint c = r32f_texture(W, H, holes);
        Target heat(W, H);
        REQUIRE(views->draw_error(a, c) == "");
        CHECK(near_color(heat.pixels()[5], not_computed_color, 0));
        Target grey(W, H);
        REQUIRE(views->draw_scalar(c) == "");
        CHECK(near_color(grey.pixels()[5], not_computed_color, 0));
        glDeleteTextures(1, &c);
    }
    SUBCASE("the scalar view maps [min, max] to black..white") {
        Target target(W, H);
        REQUIRE(views->draw_scalar(a) == "");
        const auto pixels = target.pixels();
        for (int x = 0; x < W; ++x)
            CHECK(std::abs(int(pixels[std::size_t(x)][0]) - int(std::lround(255.0f * x / (W - 1)))) <= 1);
        Target stretched(W, H);
        REQUIRE(views->draw_scalar(a, {.min_value = 0.5f, .max_value = 1.0f}) == "");
        const auto s = stretched.pixels();
        CHECK(s[0][0] == 0);
        CHECK(s[W - 1][0] == 255);
    }
    SUBCASE("a view fills only the current viewport and restores the state it changes") {
        Target target(W, H);
        glViewport(W / 2, 0, W / 2, H);
        glEnable(GL_DEPTH_TEST);
        REQUIRE(views->draw_scalar(a) == "");
        CHECK(glIsEnabled(GL_DEPTH_TEST));
        glDisable(GL_DEPTH_TEST);
        GLint program = -1;
        glGetIntegerv(GL_CURRENT_PROGRAM, &program);
        CHECK(program == 0);
        const auto pixels = target.pixels();
        CHECK(near_color(pixels[0], glm::vec3(0.2f, 0.4f, 0.6f), 1)); // left half: untouched clear colour
        // Right half: the whole ramp squeezed, pixel i shows texel 2i + 1 (the one under its centre).
        for (int i = 0; i < W / 2; ++i)
            CHECK(std::abs(int(pixels[std::size_t(W / 2 + i)][0]) -
                           int(std::lround(255.0f * (2 * i + 1) / (W - 1)))) <= 1);
    }
    glDeleteTextures(1, &a);
    glDeleteTextures(1, &b);
    CHECK(glGetError() == GL_NO_ERROR);
}

TEST_CASE("debug views: bad input gets a message naming what is allowed") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto views = DebugViews::create(&error);
    REQUIRE_MESSAGE(views, error);
    auto built = build({.slices = 8, .resolution = 64}, &error);
    REQUIRE_MESSAGE(built, error);
    Target target(8, 8);
    CHECK(views->draw_slice_texture(*built->runtime, {.slice = 8}) ==
          "slice view: slice 8 is out of range: the configuration has 8 slices (0 to 7)");
    CHECK(views->draw_slice_texture(*built->runtime, {.slice = 0, .level = 7}) ==
          "slice view: level 7 is out of range: resolution 64 has filter levels 0 to 6");
    CHECK(views->draw_slice_level(*built->runtime, 0) ==
          "slice/level view: the world positions is not a texture (name 0)");
    const GLuint small = r32f_texture(4, 4, std::vector<float>(16, 0.0f)),
                 big = r32f_texture(8, 4, std::vector<float>(32, 0.0f));
    CHECK(views->draw_error(small, big) ==
          "error view: texture a is 4x4 but b is 8x4; give two textures of the same size");
    CHECK(views->draw_error(small, small, {.max_error = 0.0f}) == "error view: max_error must be > 0, got 0");
    CHECK(views->draw_scalar(small, {.min_value = 1.0f, .max_value = 1.0f}) ==
          "scalar view: max_value (1) must be greater than min_value (1)");
    glDeleteTextures(1, &small);
    glDeleteTextures(1, &big);
    CHECK(glGetError() == GL_NO_ERROR);

    const std::vector<float> estimate{0.5f, 1.0f, 0.2f, 0.0f}, reference{0.5f, 0.0f, std::nanf(""), 1.0f};
    const std::vector<unsigned char> geometry{1, 0, 1, 1};
    const std::optional<Metrics> m = visibility_error(estimate, reference, geometry, &error);
    REQUIRE(m);
    CHECK(m->all.count == 2); // background and not-yet-computed pixels are left out
    CHECK(m->all.mae == doctest::Approx(0.5));
    CHECK(!visibility_error(estimate, reference, std::vector<unsigned char>{1}, &error));
    CHECK(error == "visibility error: sizes differ (estimate 4, reference 4, geometry 1)");
}
