#include "rendering/headless_render.hpp"

#include "rendering/gpu_scene.hpp"
#include "reference/ground_truth.hpp"

#include <penumbra/gl/runtime.hpp>
#include <penumbra/texture_memory.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::playground {

bool render_headless(const Scene& scene, const Config& config, int width, int height, HeadlessResult& out,
                     std::string* error, const RenderOptions& options) {
    auto runtime = penumbra::gl::Runtime::create(config, error);
    if (!runtime) return false;
    std::unique_ptr<GBuffer> gbuffer = GBuffer::create(width, height, error);
    if (!gbuffer) return false;
    MeshBuffers mesh(scene.mesh);
    gbuffer->render(mesh, scene.camera.projection_matrix(static_cast<float>(width) / height) * scene.camera.view_matrix());

    // Penumbra passes.
    if (config.light == Light::sun) runtime->set_light(scene.sun, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
    else runtime->set_light(scene.light, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
    if (options.warm_up) {
        if (std::string d = runtime->build([&](GLuint) { mesh.draw(); }); !d.empty()) {
            if (error) *error = d;
            return false;
        }
        if (!runtime->shade_deferred(gbuffer->positions(), width, height, error)) return false;
        glFinish();
    }
    out.warm = options.warm_up;
    out.texture_bytes = penumbra::texture_bytes(runtime->layout(), width, height);
    out.timings.clear();
    if (std::string d = runtime->build([&](GLuint) { mesh.draw(); }, &out.timings); !d.empty()) {
        if (error) *error = d;
        return false;
    }
    penumbra::gl::PassTiming shading_timing;
    if (!runtime->shade_deferred(gbuffer->positions(), width, height, error, &shading_timing)) return false;
    out.timings.push_back(shading_timing);
    if (options.inspect) options.inspect(*runtime);
    const std::vector<float> vis = runtime->read_visibility();
    std::vector<glm::vec4> pos(static_cast<std::size_t>(width) * height), nrm(pos.size());
    glGetTextureImage(gbuffer->positions(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pos.size() * sizeof(glm::vec4)), pos.data());
    glGetTextureImage(gbuffer->normals(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(nrm.size() * sizeof(glm::vec4)), nrm.data());
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        if (error) *error = "GL error " + std::to_string(e) + " in the headless pipeline";
        return false;
    }

    // Flip to top row first; Lambert shading on the CPU.
    out.width = width;
    out.height = height;
    const std::size_t n = pos.size();
    out.visibility.assign(n, 1.0f);
    out.positions.assign(n, glm::vec3(std::numeric_limits<float>::quiet_NaN()));
    out.normals.assign(n, glm::vec3(0.0f));
    out.geometry.assign(n, 0);
    out.rgb.assign(3 * n, 0.0f);
    const glm::vec3 light_centre(scene.light.center);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t src = static_cast<std::size_t>(y) * width + x;
            const std::size_t dst = static_cast<std::size_t>(height - 1 - y) * width + x;
            if (pos[src].w < 0.5f) {
                const float sky[3] = {0.55f, 0.65f, 0.8f};
                for (int c = 0; c < 3; ++c) out.rgb[3 * dst + c] = sky[c];
                continue;
            }
            out.geometry[dst] = 1;
            out.positions[dst] = glm::vec3(pos[src]);
            out.normals[dst] = glm::vec3(nrm[src]);
            out.visibility[dst] = vis[src];
            const glm::vec3 to_light = config.light == Light::sun ? -glm::vec3(glm::normalize(scene.sun.direction))
                                                                  : glm::normalize(light_centre - glm::vec3(pos[src]));
            const float lambert = std::abs(glm::dot(glm::vec3(nrm[src]), to_light));
            const float shade = 0.15f + 0.85f * lambert * vis[src];
            for (int c = 0; c < 3; ++c) out.rgb[3 * dst + c] = shade * 0.9f;
        }
    return true;
}

std::vector<float> reference_visibility(const Scene& scene, const HeadlessResult& result, int samples_per_axis,
                                       Light light) {
    GroundTruth truth(scene.mesh);
    if (light == Light::sun) return truth.visibility(result.positions, result.normals, scene.sun, samples_per_axis);
    return truth.visibility(result.positions, result.normals, scene.light, samples_per_axis);
}

Metrics compare(const HeadlessResult& result, const std::vector<float>& reference) {
    return compare(result.visibility, result.geometry, reference);
}

} // namespace penumbra::playground
