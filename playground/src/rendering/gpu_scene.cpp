#include "rendering/gpu_scene.hpp"

#include <penumbra/gl/link_program.hpp>

#include <memory>
#include <utility>

namespace penumbra::playground {

namespace {

constexpr const char* gbuffer_vertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 uv;
uniform mat4 clipFromWorld;
out vec3 worldPos;
out vec3 worldNormal;
out vec2 texCoord;
void main() {
    worldPos = position;
    worldNormal = normal;
    texCoord = uv;
    gl_Position = clipFromWorld * vec4(position, 1.0);
}
)";

constexpr const char* gbuffer_fragment = R"(#version 450 core
in vec3 worldPos;
in vec3 worldNormal;
in vec2 texCoord;
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outTexCoord;
void main() {
    outPosition = vec4(worldPos, 1.0);
    // the normal of the side the camera sees (two-sided surfaces, back faces of sheets)
    outNormal = vec4(normalize(gl_FrontFacing ? worldNormal : -worldNormal), 0.0);
    outTexCoord = vec4(texCoord, 0.0, 1.0);
}
)";

} // namespace

GLuint build_program(const std::string& name, std::string vertex, std::string fragment, std::string* error) {
    const Program program{name, {{name + ".vert", Stage::vertex, std::move(vertex)},
                                 {name + ".frag", Stage::fragment, std::move(fragment)}}};
    std::string log;
    const GLuint id = penumbra::gl::link_program(program, &log);
    if (!id && error) *error = log;
    return id;
}

MeshBuffers::MeshBuffers(const Mesh& mesh) {
    glCreateVertexArrays(1, &vao_);
    glCreateBuffers(1, &positions_);
    glCreateBuffers(1, &normals_);
    glCreateBuffers(1, &indices_);
    glCreateBuffers(1, &uvs_);
    glNamedBufferStorage(positions_, static_cast<GLsizeiptr>(mesh.positions.size() * sizeof(glm::vec3)), mesh.positions.data(), 0);
    glNamedBufferStorage(normals_, static_cast<GLsizeiptr>(mesh.normals.size() * sizeof(glm::vec3)), mesh.normals.data(), 0);
    glNamedBufferStorage(indices_, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)), mesh.indices.data(), 0);
    glVertexArrayVertexBuffer(vao_, 0, positions_, 0, sizeof(glm::vec3));
    glVertexArrayVertexBuffer(vao_, 1, normals_, 0, sizeof(glm::vec3));
    for (GLuint a : {0u, 1u}) {
        glEnableVertexArrayAttrib(vao_, a);
        glVertexArrayAttribFormat(vao_, a, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao_, a, a);
    }
    if (!mesh.uvs.empty()) {
        glNamedBufferStorage(uvs_, static_cast<GLsizeiptr>(mesh.uvs.size() * sizeof(glm::vec2)), mesh.uvs.data(), 0);
        glVertexArrayVertexBuffer(vao_, 2, uvs_, 0, sizeof(glm::vec2));
        glEnableVertexArrayAttrib(vao_, 2);
        glVertexArrayAttribFormat(vao_, 2, 2, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao_, 2, 2);
    }
    glVertexArrayElementBuffer(vao_, indices_);
    count_ = static_cast<GLsizei>(mesh.indices.size());
}

MeshBuffers::~MeshBuffers() {
    glDeleteVertexArrays(1, &vao_);
    const GLuint buffers[4] = {positions_, normals_, indices_, uvs_};
    glDeleteBuffers(4, buffers);
}

void MeshBuffers::draw() const {
    glBindVertexArray(vao_);
    glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
}

std::unique_ptr<GBuffer> GBuffer::create(int width, int height, std::string* error) {
    std::unique_ptr<GBuffer> g(new GBuffer());
    g->width_ = width;
    g->height_ = height;
    g->program_ = build_program("gbuffer", gbuffer_vertex, gbuffer_fragment, error);
    if (!g->program_) return nullptr;
    glCreateTextures(GL_TEXTURE_2D, 3, g->textures_);
    for (GLuint t : g->textures_) {
        glTextureStorage2D(t, 1, GL_RGBA32F, width, height);
        glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    }
    glCreateRenderbuffers(1, &g->depth_);
    glNamedRenderbufferStorage(g->depth_, GL_DEPTH_COMPONENT32F, width, height);
    glCreateFramebuffers(1, &g->fbo_);
    glNamedFramebufferTexture(g->fbo_, GL_COLOR_ATTACHMENT0, g->textures_[0], 0);
    glNamedFramebufferTexture(g->fbo_, GL_COLOR_ATTACHMENT1, g->textures_[1], 0);
    glNamedFramebufferTexture(g->fbo_, GL_COLOR_ATTACHMENT2, g->textures_[2], 0);
    glNamedFramebufferRenderbuffer(g->fbo_, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, g->depth_);
    const GLenum buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(g->fbo_, 3, buffers);
    if (glCheckNamedFramebufferStatus(g->fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        if (error) *error = "G-buffer framebuffer incomplete";
        return nullptr;
    }
    return g;
}

GBuffer::~GBuffer() {
    if (fbo_) glDeleteFramebuffers(1, &fbo_);
    if (depth_) glDeleteRenderbuffers(1, &depth_);
    if (textures_[0]) glDeleteTextures(3, textures_);
    if (program_) glDeleteProgram(program_);
}

void GBuffer::render(const MeshBuffers& mesh, const glm::mat4& clip_from_world) {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glViewport(0, 0, width_, height_);
    const float zero[4] = {0, 0, 0, 0};
    const float one = 1.0f;
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_COLOR, 1, zero);
    glClearBufferfv(GL_COLOR, 2, zero);
    glClearBufferfv(GL_DEPTH, 0, &one);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glUseProgram(program_);
    glUniformMatrix4fv(glGetUniformLocation(program_, "clipFromWorld"), 1, GL_FALSE, &clip_from_world[0][0]);
    mesh.draw();
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace penumbra::playground
