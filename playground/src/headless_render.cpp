#include "headless_render.hpp"

#include "ground_truth.hpp"

#include <penumbra/gl/runtime.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::playground {

namespace {

constexpr const char* gbuffer_vertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 clipFromWorld;
out vec3 worldPos;
out vec3 worldNormal;
void main() {
    worldPos = position;
    worldNormal = normal;
    gl_Position = clipFromWorld * vec4(position, 1.0);
}
)";

constexpr const char* gbuffer_fragment = R"(#version 450 core
in vec3 worldPos;
in vec3 worldNormal;
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
void main() {
    outPosition = vec4(worldPos, 1.0);
    outNormal = vec4(normalize(worldNormal), 0.0);
}
)";

GLuint compile_gbuffer_program(std::string* error) {
    const GLuint program = glCreateProgram();
    bool ok = true;
    for (auto [kind, text] : {std::pair{GL_VERTEX_SHADER, gbuffer_vertex}, std::pair{GL_FRAGMENT_SHADER, gbuffer_fragment}}) {
        const GLuint s = glCreateShader(kind);
        glShaderSource(s, 1, &text, nullptr);
        glCompileShader(s);
        GLint status = 0;
        glGetShaderiv(s, GL_COMPILE_STATUS, &status);
        if (!status) {
            char log[2048] = {};
            glGetShaderInfoLog(s, sizeof log, nullptr, log);
            if (error) *error = std::string("G-buffer shader: ") + log;
            ok = false;
        }
        glAttachShader(program, s);
        glDeleteShader(s);
    }
    if (ok) {
        glLinkProgram(program);
        GLint status = 0;
        glGetProgramiv(program, GL_LINK_STATUS, &status);
        if (!status) {
            if (error) *error = "G-buffer program failed to link";
            ok = false;
        }
    }
    if (!ok) {
        glDeleteProgram(program);
        return 0;
    }
    return program;
}

struct MeshBuffers {
    GLuint vao = 0, positions = 0, normals = 0, indices = 0;
    GLsizei count = 0;
    explicit MeshBuffers(const Mesh& mesh) {
        glCreateVertexArrays(1, &vao);
        glCreateBuffers(1, &positions);
        glCreateBuffers(1, &normals);
        glCreateBuffers(1, &indices);
        glNamedBufferStorage(positions, static_cast<GLsizeiptr>(mesh.positions.size() * sizeof(glm::vec3)), mesh.positions.data(), 0);
        glNamedBufferStorage(normals, static_cast<GLsizeiptr>(mesh.normals.size() * sizeof(glm::vec3)), mesh.normals.data(), 0);
        glNamedBufferStorage(indices, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)), mesh.indices.data(), 0);
        glVertexArrayVertexBuffer(vao, 0, positions, 0, sizeof(glm::vec3));
        glVertexArrayVertexBuffer(vao, 1, normals, 0, sizeof(glm::vec3));
        for (GLuint a : {0u, 1u}) {
            glEnableVertexArrayAttrib(vao, a);
            glVertexArrayAttribFormat(vao, a, 3, GL_FLOAT, GL_FALSE, 0);
            glVertexArrayAttribBinding(vao, a, a);
        }
        glVertexArrayElementBuffer(vao, indices);
        count = static_cast<GLsizei>(mesh.indices.size());
    }
    ~MeshBuffers() {
        glDeleteVertexArrays(1, &vao);
        GLuint b[3] = {positions, normals, indices};
        glDeleteBuffers(3, b);
    }
    void draw() const {
        glBindVertexArray(vao);
        glDrawElements(GL_TRIANGLES, count, GL_UNSIGNED_INT, nullptr);
        glBindVertexArray(0);
    }
};

ErrorStats stats(std::vector<double> errors) {
    ErrorStats s;
    s.count = errors.size();
    if (errors.empty()) return s;
    double sum = 0, sq = 0;
    for (double e : errors) {
        sum += e;
        sq += e * e;
    }
    s.mae = sum / errors.size();
    s.rmse = std::sqrt(sq / errors.size());
    const std::size_t k = std::min(errors.size() - 1, static_cast<std::size_t>(std::ceil(0.95 * errors.size())) - 1);
    std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(k), errors.end());
    s.p95 = errors[k];
    return s;
}

} // namespace

bool render_headless(const Scene& scene, const Config& config, int width, int height, HeadlessResult& out,
                     std::string* error) {
    auto runtime = penumbra::gl::Runtime::create(config, error);
    if (!runtime) return false;
    const GLuint gbuffer_program = compile_gbuffer_program(error);
    if (!gbuffer_program) return false;
    MeshBuffers mesh(scene.mesh);

    // G-buffer: world positions (w = 1 on geometry, 0 elsewhere), normals, depth.
    GLuint textures[2], depth = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 2, textures);
    for (GLuint t : textures) {
        glTextureStorage2D(t, 1, GL_RGBA32F, width, height);
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glCreateRenderbuffers(1, &depth);
    glNamedRenderbufferStorage(depth, GL_DEPTH_COMPONENT32F, width, height);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, textures[0], 0);
    glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT1, textures[1], 0);
    glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
    const GLenum buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(fbo, 2, buffers);
    auto cleanup = [&] {
        glDeleteFramebuffers(1, &fbo);
        glDeleteRenderbuffers(1, &depth);
        glDeleteTextures(2, textures);
        glDeleteProgram(gbuffer_program);
    };
    if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        if (error) *error = "G-buffer framebuffer incomplete";
        cleanup();
        return false;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, width, height);
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_COLOR, 1, zero);
    glClearBufferfv(GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    const glm::mat4 clip = scene.camera.projection_matrix(static_cast<float>(width) / height) * scene.camera.view_matrix();
    glUseProgram(gbuffer_program);
    glUniformMatrix4fv(glGetUniformLocation(gbuffer_program, "clipFromWorld"), 1, GL_FALSE, &clip[0][0]);
    mesh.draw();
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);

    // Penumbra passes.
    runtime->set_light(scene.light, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
    if (config.light == Light::sun) runtime->set_light(scene.sun, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
    if (std::string d = runtime->build([&](GLuint) { mesh.draw(); }); !d.empty()) {
        if (error) *error = d;
        cleanup();
        return false;
    }
    if (!runtime->shade_deferred(textures[0], width, height, error)) {
        cleanup();
        return false;
    }
    const std::vector<float> vis = runtime->read_visibility();
    std::vector<glm::vec4> pos(static_cast<std::size_t>(width) * height), nrm(pos.size());
    glGetTextureImage(textures[0], 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(pos.size() * sizeof(glm::vec4)), pos.data());
    glGetTextureImage(textures[1], 0, GL_RGBA, GL_FLOAT, static_cast<GLsizei>(nrm.size() * sizeof(glm::vec4)), nrm.data());
    cleanup();
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
    std::vector<double> all, pen;
    for (std::size_t i = 0; i < result.visibility.size(); ++i) {
        if (!result.geometry[i]) continue;
        const double e = std::abs(static_cast<double>(result.visibility[i]) - reference[i]);
        all.push_back(e);
        if (reference[i] < 0.98f || result.visibility[i] < 0.98f) pen.push_back(e);
    }
    return {stats(std::move(all)), stats(std::move(pen))};
}

} // namespace penumbra::playground
