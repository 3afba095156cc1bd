#include "rendering/headless_render.hpp"

#include "rendering/gpu_scene.hpp"
#include "reference/ground_truth.hpp"
#include "rendering/light_term.hpp"

#include <penumbra/gl/runtime.hpp>
#include <penumbra/texture_memory.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::playground {

Light shading_light(const Config& config) {
    return config.technique == Technique::oim ? Light::sun : config.light;
}

bool render_headless(const Scene& scene, const Config& config, int width, int height, HeadlessResult& out,
                     std::string* error, const RenderOptions& options) {
    // Created lit, so its programs are linked once, with the levels this light reaches.
    const glm::dvec3 bounds_min(scene.bounds_min), bounds_max(scene.bounds_max);
    auto runtime = shading_light(config) == Light::sun
                       ? penumbra::gl::Runtime::create(config, scene.sun, bounds_min, bounds_max, error)
                       : penumbra::gl::Runtime::create(config, scene.light, bounds_min, bounds_max, error);
    if (!runtime) return false;
    std::unique_ptr<GBuffer> gbuffer = GBuffer::create(width, height, error);
    if (!gbuffer) return false;
    MeshBuffers mesh(scene.mesh);
    // The casters, each material's triangles with its alpha texture and cutoff (alpha_test), the closed
    // parts first and flagged (solid_casters); a program without the parameters ignores them.
    const penumbra::gl::Runtime& rt = *runtime;
    const auto draw_casters = [&](GLuint program) {
        mesh.draw_materials([&](GLuint alpha, float cutoff, bool closed) {
            rt.bind_caster_material(program, alpha, 0, cutoff);
            rt.bind_caster_closed(program, closed);
        }, true);
    };
    gbuffer->render(mesh, scene.camera.projection_matrix(static_cast<float>(width) / height) * scene.camera.view_matrix());

    // Penumbra passes.
    for (const auto& [name, texels] : options.bake_textures)
        if (std::string d = runtime->supply_texture(name, texels); !d.empty()) {
            if (error) *error = d;
            return false;
        }
    if (options.time_window) runtime->set_time_window(*options.time_window);
    // Every G-buffer texture the layouts know; each technique's screen pass reads the ones it declares.
    const penumbra::gl::Runtime::TextureMap gbuffer_textures{{"penumbra_worldPositions", gbuffer->positions()},
                                                             {"penumbra_worldNormals", gbuffer->normals()},
                                                             {"penumbra_texCoords", gbuffer->tex_coords()}};
    if (options.warm_up) {
        if (std::string d = runtime->build(draw_casters); !d.empty()) {
            if (error) *error = d;
            return false;
        }
        if (std::string d = runtime->run_screen(gbuffer_textures, width, height); !d.empty()) {
            if (error) *error = d;
            return false;
        }
        glFinish();
    }
    out.warm = options.warm_up;
    out.texture_bytes = penumbra::texture_bytes(runtime->layout(), width, height);
    out.timings.clear();
    if (std::string d = runtime->build(draw_casters, &out.timings); !d.empty()) {
        if (error) *error = d;
        return false;
    }
    std::vector<penumbra::gl::PassTiming> screen_timings;
    if (std::string d = runtime->run_screen(gbuffer_textures, width, height, &screen_timings); !d.empty()) {
        if (error) *error = d;
        return false;
    }
    penumbra::gl::PassTiming shading_timing;
    for (const penumbra::gl::PassTiming& t : screen_timings) {
        shading_timing.name += (shading_timing.name.empty() ? "" : "+") + t.name;
        shading_timing.milliseconds += t.milliseconds;
    }
    out.timings.push_back(shading_timing);
    if (options.inspect) options.inspect(*runtime);
    const std::vector<float> vis = runtime->read_visibility();
    std::vector<glm::vec4> pos(static_cast<std::size_t>(width) * height), nrm(pos.size()), uv(pos.size());
    glGetTextureImage(gbuffer->positions(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pos.size() * sizeof(glm::vec4)), pos.data());
    glGetTextureImage(gbuffer->normals(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(nrm.size() * sizeof(glm::vec4)), nrm.data());
    glGetTextureImage(gbuffer->tex_coords(), 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(uv.size() * sizeof(glm::vec4)), uv.data());
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        if (error) *error = "GL error " + std::to_string(e) + " in the headless pipeline";
        return false;
    }

    // Flip to top row first; the example shading on the CPU (rendering/light_term.hpp).
    out.width = width;
    out.height = height;
    const std::size_t n = pos.size();
    out.visibility.assign(n, 1.0f);
    out.positions.assign(n, glm::vec3(std::numeric_limits<float>::quiet_NaN()));
    out.normals.assign(n, glm::vec3(0.0f));
    out.tex_coords.assign(n, glm::vec2(0.0f));
    out.geometry.assign(n, 0);
    out.light_term.assign(n, 0.0f);
    const glm::vec3 eye = scene.camera.eye_position();
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t src = static_cast<std::size_t>(y) * width + x;
            const std::size_t dst = static_cast<std::size_t>(height - 1 - y) * width + x;
            if (pos[src].w < 0.5f) continue;
            out.geometry[dst] = 1;
            out.positions[dst] = glm::vec3(pos[src]);
            out.normals[dst] = glm::vec3(nrm[src]);
            out.tex_coords[dst] = glm::vec2(uv[src]);
            out.visibility[dst] = vis[src];
            out.light_term[dst] =
                shading_light(config) == Light::sun
                    ? sun_light_term(glm::vec3(pos[src]), glm::vec3(nrm[src]), eye, scene.sun)
                    : rect_light_term(glm::vec3(pos[src]), glm::vec3(nrm[src]), eye, scene.light);
        }
    out.rgb = example_shading(out, out.visibility);
    return true;
}

std::vector<float> example_shading(const HeadlessResult& result, const std::vector<float>& visibility) {
    const float sky[3] = {0.55f, 0.65f, 0.8f};
    std::vector<float> rgb(3 * result.geometry.size());
    for (std::size_t i = 0; i < result.geometry.size(); ++i) {
        // NaN visibility (a truth where the pixel sees none of the light) has a light term of 0 there
        const float v = std::isnan(visibility[i]) ? 0.0f : visibility[i];
        const float shade = 0.9f * (0.15f + 0.85f * result.light_term[i] * v);
        for (int c = 0; c < 3; ++c) rgb[3 * i + c] = result.geometry[i] ? shade : sky[c];
    }
    return rgb;
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

References reference_all(const Scene& scene, const HeadlessResult& result, int samples_per_axis, Light light) {
    GroundTruth truth(scene.mesh);
    const glm::vec3 eye = scene.camera.eye_position();
    std::vector<glm::vec3> facing(result.normals.size(), glm::vec3(0.0f));
    for (std::size_t i = 0; i < facing.size(); ++i)
        if (result.geometry[i])
            facing[i] = glm::dot(result.normals[i], eye - result.positions[i]) < 0.0f ? -result.normals[i] : result.normals[i];
    References out;
    GroundTruth::Oriented fair;
    if (light == Light::sun) {
        out.visibility = truth.visibility(result.positions, facing, scene.sun, samples_per_axis);
        fair = truth.oriented(result.positions, facing, scene.sun, samples_per_axis);
    } else {
        out.visibility = truth.visibility(result.positions, facing, scene.light, samples_per_axis);
        fair = truth.oriented(result.positions, facing, scene.light, samples_per_axis);
    }
    out.oriented = std::move(fair.oriented);
    out.irradiance = std::move(fair.irradiance);
    out.unoccluded = std::move(fair.unoccluded);
    return out;
}

QualityMetrics compare_quality(const HeadlessResult& result, const References& references) {
    return compare_quality(result.visibility, result.geometry, references.visibility, references.oriented,
                           references.irradiance, references.unoccluded);
}

} // namespace penumbra::playground
