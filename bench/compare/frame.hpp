// bench/compare/frame.hpp — one frame of a technique as the GL benchmarks measure it: the scene's
// G-buffer (rendered once, shared by every technique) and its read-back, a frame of every pass of
// the layout then the deferred screen pass with GL_TIME_ELAPSED per pass and the wall clock to
// glFinish, and the sums and medians the tables use. Needs a current GL 4.5 context.
#pragma once

#include "rendering/gpu_scene.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scene.hpp"

#include <penumbra/gl/runtime.hpp>

#include <algorithm>
#include <chrono>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::bench {

using playground::GBuffer;
using playground::HeadlessResult;
using playground::MeshBuffers;
using playground::Scene;

inline double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

inline double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The scene's pixels, shared by every technique: the G-buffer on the GPU and its read-back.
struct Pixels {
    std::unique_ptr<GBuffer> gbuffer;
    HeadlessResult frame; // size, positions, normals and geometry mask, top row first (no visibility)
};

inline std::optional<Pixels> render_pixels(const Scene& scene, const MeshBuffers& mesh, int width, int height,
                                           std::string* error) {
    Pixels p;
    p.gbuffer = GBuffer::create(width, height, error);
    if (!p.gbuffer) return std::nullopt;
    p.gbuffer->render(mesh, scene.camera.projection_matrix(static_cast<float>(width) / height) * scene.camera.view_matrix());
    const std::size_t n = static_cast<std::size_t>(width) * height;
    std::vector<glm::vec4> pos(n), nrm(n);
    glGetTextureImage(p.gbuffer->positions(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(n * sizeof(glm::vec4)), pos.data());
    glGetTextureImage(p.gbuffer->normals(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(n * sizeof(glm::vec4)), nrm.data());
    p.frame.width = width;
    p.frame.height = height;
    p.frame.positions.assign(n, glm::vec3(std::numeric_limits<float>::quiet_NaN()));
    p.frame.normals.assign(n, glm::vec3(0.0f));
    p.frame.geometry.assign(n, 0);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t src = static_cast<std::size_t>(y) * width + x;
            const std::size_t dst = static_cast<std::size_t>(height - 1 - y) * width + x;
            if (pos[src].w < 0.5f) continue;
            p.frame.geometry[dst] = 1;
            p.frame.positions[dst] = glm::vec3(pos[src]);
            p.frame.normals[dst] = glm::vec3(nrm[src]);
        }
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        if (error) *error = "GL error " + std::to_string(e) + " while reading the G-buffer";
        return std::nullopt;
    }
    return p;
}

// One frame of a technique: every pass of its layout, then the deferred screen passes.
struct FrameTimes {
    std::vector<gl::PassTiming> passes; // GL_TIME_ELAPSED of each pass, shading last
    double wall_build_ms = 0, wall_shading_ms = 0;
};

inline bool run_frame(gl::Runtime& runtime, const MeshBuffers& mesh, const Pixels& pixels, FrameTimes& out,
               std::string* error) {
    out.passes.clear();
    const auto start = std::chrono::steady_clock::now();
    if (std::string d = runtime.build(
            [&](GLuint program) { // each material's casters with its alpha texture and cutoff (alpha_test), closed
                                  // parts first and flagged (solid_casters)
                mesh.draw_materials(
                    [&](GLuint alpha, float cutoff, bool closed) {
                        runtime.bind_caster_material(program, alpha, 0, cutoff);
                        runtime.bind_caster_closed(program, closed);
                    },
                    true);
            },
            &out.passes); !d.empty()) {
        if (error) *error = d;
        return false;
    }
    glFinish();
    out.wall_build_ms = milliseconds_since(start);
    const auto shading_start = std::chrono::steady_clock::now();
    // Every G-buffer texture the layouts know (as playground::render_headless gives them): each
    // technique's screen passes read the ones they declare (occlusion interval maps: the texture
    // coordinates of their bake; erosion: several passes at the output size).
    const gl::Runtime::TextureMap gbuffer_textures{{"penumbra_worldPositions", pixels.gbuffer->positions()},
                                                   {"penumbra_worldNormals", pixels.gbuffer->normals()},
                                                   {"penumbra_texCoords", pixels.gbuffer->tex_coords()}};
    std::vector<gl::PassTiming> screen;
    if (std::string d = runtime.run_screen(gbuffer_textures, pixels.gbuffer->width(), pixels.gbuffer->height(), &screen);
        !d.empty()) {
        if (error) *error = d;
        return false;
    }
    gl::PassTiming shading; // the screen passes as one: the tables' "screen pass"
    for (const gl::PassTiming& t : screen) {
        shading.name += (shading.name.empty() ? "" : "+") + t.name;
        shading.milliseconds += t.milliseconds;
    }
    glFinish();
    out.wall_shading_ms = milliseconds_since(shading_start);
    out.passes.push_back(shading);
    return true;
}

// The visibility of the last frame, top row first, 1 on background.
inline std::vector<float> read_visibility(const gl::Runtime& runtime, const Pixels& pixels) {
    const std::vector<float> bottom_up = runtime.read_visibility();
    const int w = pixels.gbuffer->width(), h = pixels.gbuffer->height();
    std::vector<float> out(bottom_up.size(), 1.0f);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t dst = static_cast<std::size_t>(y) * w + x;
            if (pixels.frame.geometry[dst]) out[dst] = bottom_up[static_cast<std::size_t>(h - 1 - y) * w + x];
        }
    return out;
}

// Pass names in order, instances of one pass (N-buffer levels, SAT steps) summed.
inline std::vector<std::pair<std::string, double>> pass_totals(const std::vector<gl::PassTiming>& timings,
                                                        std::vector<int>* instances = nullptr) {
    std::vector<std::pair<std::string, double>> totals;
    if (instances) instances->clear();
    for (const gl::PassTiming& t : timings) {
        if (totals.empty() || totals.back().first != t.name) {
            totals.push_back({t.name, 0.0});
            if (instances) instances->push_back(0);
        }
        totals.back().second += t.milliseconds;
        if (instances) ++instances->back();
    }
    return totals;
}

} // namespace penumbra::bench
