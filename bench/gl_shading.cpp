// What specialization buys: GPU time of the specialized deferred shading pass (unrolled, constants
// baked in) against the generic one (penumbra/generic.hpp: uniform loops, no baked constants), on
// the same G-buffer and the same textures.
//
//   penumbra-bench-shading [--size N] [--resolution R] [--runs K] [--scene NAME] [--scene-camera]
//                          [--light-size W[,H]] [--light-center X,Y,Z] [--light-normal X,Y,Z] [--light-up
//                          X,Y,Z]
//                          [--camera-position X,Y,Z] [--camera-target X,Y,Z]
// (the light and camera flags as penumbra-playground's, set on the scene once made; a camera flag
// implies --scene-camera)
//
// Defaults: 512x512 G-buffer of the "boxes" scene seen from straight above (every pixel a
// surface; --scene-camera uses the scene's camera instead), occlusion textures 512x512, 7 timed
// runs of each pass after one warm-up run. Medians of GL_TIME_ELAPSED and of wall-clock time to
// glFinish. On llvmpipe the absolute times mean little; the ratios are what to read. The last
// column checks that both passes gave the same image.
#include "app/scene_overrides.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/gpu_scene.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/generic_shading.hpp>
#include <penumbra/gl/runtime.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::playground;

namespace {

struct Options {
    int size = 512;
    int resolution = 512;
    int runs = 7;
    std::string scene = "boxes";
    bool scene_camera = false; // false: top-down view, every pixel a surface
    SceneOverrides overrides;  // --light-*, --camera-*
};

bool parse(int argc, char** argv, Options& o) {
    for (int i = 1; i < argc; ++i) {
        const std::string flag = argv[i];
        if (flag == "--help") return false;
        if (flag == "--scene-camera") {
            o.scene_camera = true;
            continue;
        }
        if (i + 1 >= argc) {
            std::fprintf(stderr, "error: %s needs a value\n", flag.c_str());
            return false;
        }
        const std::string value = argv[++i];
        if (is_scene_override_flag(flag)) {
            if (const std::string e = parse_scene_override(flag, value, o.overrides); !e.empty()) {
                std::fprintf(stderr, "error: %s\n", e.c_str());
                return false;
            }
            o.scene_camera |= o.overrides.moves_camera();
            continue;
        }
        if (flag == "--size") o.size = std::atoi(value.c_str());
        else if (flag == "--resolution") o.resolution = std::atoi(value.c_str());
        else if (flag == "--runs") o.runs = std::atoi(value.c_str());
        else if (flag == "--scene") o.scene = value;
        else {
            std::fprintf(stderr,
                         "error: unknown flag %s; allowed: --size, --resolution, --runs, --scene, "
                         "--scene-camera, %s\n",
                         flag.c_str(), scene_override_flag_list);
            return false;
        }
    }
    if (const std::string e = check_scene_overrides(o.overrides); !e.empty()) {
        std::fprintf(stderr, "error: %s\n", e.c_str());
        return false;
    }
    if (o.size < 1 || o.size > 4096 || o.runs < 1) {
        std::fprintf(stderr, "error: --size must be 1 to 4096 and --runs at least 1\n");
        return false;
    }
    return true;
}

double median(std::vector<double> samples) {
    std::nth_element(samples.begin(), samples.begin() + samples.size() / 2, samples.end());
    return samples[samples.size() / 2];
}

struct Timing {
    double gpu_ms = 0.0;  // GL_TIME_ELAPSED
    double wall_ms = 0.0; // from the call to the end of glFinish
};

// Medians over `runs` runs of `pass`, after one warm-up run. Two clocks that must agree: on
// llvmpipe GL_TIME_ELAPSED under-reports back-to-back draws into an unchanged framebuffer (see
// GenericVisibilityPass::shade), and the wall clock catches that kind of mistake.
Timing median_times(int runs, const std::function<void()>& pass) {
    pass(); // llvmpipe compiles the shader variant on first use
    glFinish();
    std::vector<double> gpu, wall;
    GLuint query = 0;
    glGenQueries(1, &query);
    for (int i = 0; i < runs; ++i) {
        const auto start = std::chrono::steady_clock::now();
        glBeginQuery(GL_TIME_ELAPSED, query);
        pass();
        glEndQuery(GL_TIME_ELAPSED);
        glFinish();
        wall.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
        GLuint64 ns = 0;
        glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
        gpu.push_back(ns * 1e-6);
    }
    glDeleteQueries(1, &query);
    return {median(gpu), median(wall)};
}

} // namespace

int main(int argc, char** argv) {
    Options options;
    if (!parse(argc, argv, options)) {
        std::fprintf(
            stderr,
            "usage: penumbra-bench-shading [--size N] [--resolution R] [--runs K] [--scene NAME] "
            "[--scene-camera]\n"
            "           [--light-size W[,H]] [--light-center X,Y,Z] [--light-normal X,Y,Z] [--light-up "
            "X,Y,Z]\n"
            "           [--camera-position X,Y,Z] [--camera-target X,Y,Z]  (as penumbra-playground's; a\n"
            "           camera flag implies --scene-camera)\n");
        std::fprintf(stderr, "  NAME: %s (default boxes)\n", allowed_scene_names().c_str());
        return 2;
    }
    std::string error;
    auto context = HeadlessContext::create(&error);
    if (!context) {
        std::fprintf(stderr, "error: no OpenGL context: %s\n", error.c_str());
        return 1;
    }
    std::optional<Scene> scene = make_scene(options.scene);
    if (!scene) {
        std::fprintf(stderr, "error: --scene: unknown scene '%s'; allowed: %s\n", options.scene.c_str(),
                     allowed_scene_names().c_str());
        return 2;
    }
    if (const std::string e = apply_scene_overrides(options.overrides, *scene, Light::rect); !e.empty()) {
        std::fprintf(stderr, "error: %s\n", e.c_str());
        return 2;
    }
    MeshBuffers mesh(scene->mesh);
    auto gbuffer = GBuffer::create(options.size, options.size, &error);
    if (!gbuffer) {
        std::fprintf(stderr, "error: %s\n", error.c_str());
        return 1;
    }
    // Straight down at the ground, orthographic: every pixel is a surface. From the scene's own
    // camera most pixels are sky, which a program whose visibility call stays a real branch (the
    // generic loops, the atlas level walk) skips block by block while the straight-line
    // specialized code gets flattened and computes for every pixel.
    const glm::mat4 top_down = glm::ortho(-4.5f, 4.5f, -4.5f, 4.5f, 0.1f, 40.0f) *
                               glm::lookAt(glm::vec3(0.0f, 20.0f, 0.0f), glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    gbuffer->render(mesh, options.scene_camera ? scene->camera.projection_matrix(1.0f) * scene->camera.view_matrix()
                                               : top_down);

    std::printf("specialized vs generic deferred shading pass, %s, scene %s, %dx%d pixels, occlusion %d, median of %d\n",
                context->renderer().c_str(), options.scene.c_str(), options.size, options.size, options.resolution,
                options.runs);
    std::printf("%-8s %-8s %6s | %-26s | %-26s | %s\n", "", "", "", "GL_TIME_ELAPSED ms", "wall clock to glFinish ms", "");
    std::printf("%-8s %-8s %6s | %8s %8s %8s | %8s %8s %8s | %s\n", "filter", "packing", "slices", "special", "generic",
                "gen/spe", "special", "generic", "gen/spe", "max |diff|");
    const std::pair<Filter, Packing> storages[] = {
        {Filter::mipmap, Packing::atlas}, {Filter::mipmap, Packing::array},  {Filter::nbuffer, Packing::atlas},
        {Filter::nbuffer, Packing::array}, {Filter::nbuffer, Packing::volume}, {Filter::sat, Packing::atlas},
        {Filter::sat, Packing::array},
    };
    for (const auto& [filter, packing] : storages) {
        const Config storage{.resolution = options.resolution, .filter = filter, .packing = packing};
        auto generic = gl::GenericVisibilityPass::create(storage, &error);
        if (!generic) {
            std::fprintf(stderr, "error: %s\n", error.c_str());
            return 1;
        }
        for (int slices : {4, 16, 32}) {
            Config config = storage;
            config.slices = slices;
            auto runtime = gl::Runtime::create(config, &error);
            if (!runtime) {
                std::fprintf(stderr, "error: %s\n", error.c_str());
                return 1;
            }
            runtime->set_light(scene->light, glm::dvec3(scene->bounds_min), glm::dvec3(scene->bounds_max));
            if (std::string d = runtime->build([&](GLuint program) {
                    mesh.draw_materials(
                        [&](GLuint alpha, float cutoff, bool closed) {
                            runtime->bind_caster_material(program, alpha, 0, cutoff);
                            runtime->bind_caster_closed(program, closed);
                        },
                        true);
                }); !d.empty()) {
                std::fprintf(stderr, "error: %s\n", d.c_str());
                return 1;
            }
            const Timing specialized = median_times(options.runs, [&] {
                if (!runtime->shade_deferred(gbuffer->positions(), options.size, options.size, &error, nullptr,
                                             gbuffer->normals()))
                    std::fprintf(stderr, "error: %s\n", error.c_str());
            });
            const Timing generic_time = median_times(options.runs, [&] {
                if (std::string d =
                        generic->shade(*runtime, gbuffer->positions(), options.size, options.size, gbuffer->normals());
                    !d.empty())
                    std::fprintf(stderr, "error: %s\n", d.c_str());
            });
            const std::vector<float> a = runtime->read_visibility(), b = generic->read_visibility();
            double max_diff = 0.0;
            for (std::size_t i = 0; i < a.size() && i < b.size(); ++i)
                max_diff = std::max(max_diff, std::abs(double(a[i]) - b[i]));
            std::printf("%-8s %-8s %6d | %8.2f %8.2f %8.2f | %8.2f %8.2f %8.2f | %.2g\n",
                        std::string(to_string(filter)).c_str(), std::string(to_string(packing)).c_str(), slices,
                        specialized.gpu_ms, generic_time.gpu_ms, generic_time.gpu_ms / specialized.gpu_ms,
                        specialized.wall_ms, generic_time.wall_ms, generic_time.wall_ms / specialized.wall_ms, max_diff);
            std::fflush(stdout);
        }
    }
    return 0;
}
