#include "rendering/gpu_scene.hpp"

#include <penumbra/gl/link_program.hpp>

#include <cstdint>
#include <memory>
#include <utility>

namespace penumbra::playground {

namespace {

constexpr const char* gbuffer_vertex = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 uv;
layout(location = 3) in vec2 materialUV;
uniform mat4 clipFromWorld;
out vec3 worldPos;
out vec3 worldNormal;
out vec2 texCoord;
out vec2 materialTexCoord;
void main() {
    worldPos = position;
    worldNormal = normal;
    texCoord = uv;
    materialTexCoord = materialUV;
    gl_Position = clipFromWorld * vec4(position, 1.0);
}
)";

constexpr const char* gbuffer_fragment = R"(#version 450 core
in vec3 worldPos;
in vec3 worldNormal;
in vec2 texCoord;
in vec2 materialTexCoord;
uniform sampler2D alphaTexture; // the draw's cut material (a 1x1 opaque texture for solid ones)
uniform float alphaCutoff;
layout(location = 0) out vec4 outPosition;
layout(location = 1) out vec4 outNormal;
layout(location = 2) out vec4 outTexCoord;
void main() {
    // cut-out pixels are not surfaces (the same test as the casters' alpha test)
    if (texture(alphaTexture, materialTexCoord).a < alphaCutoff) discard;
    outPosition = vec4(worldPos, 1.0);
    // The normal of the side the camera sees (two-sided surfaces, back faces of sheets). Which side that is
    // comes from the surface's own plane, whose screen-space cross product faces the camera, and not
    // from gl_FrontFacing: a mesh wound clockwise with outward normals (OBJ files often are) would get
    // its lit faces' normals turned inwards, and no light.
    vec3 seen = cross(dFdx(worldPos), dFdy(worldPos));
    vec3 n = normalize(worldNormal);
    outNormal = vec4(dot(n, seen) < 0.0 ? -n : n, 0.0);
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

namespace {

// An RGBA8 texture whose alpha is `alpha` (rgb white), nearest filtering, repeat wrapping: what the
// CPU's AlphaTexture::at reads.
GLuint alpha_texture(int width, int height, const std::uint8_t* alpha) {
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4, 255);
    for (std::size_t i = 0; i < rgba.size() / 4; ++i) rgba[4 * i + 3] = alpha[i];
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, GL_RGBA8, width, height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(t, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data()); // row 0 at v = 0
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_REPEAT);
    return t;
}

} // namespace

MeshBuffers::MeshBuffers(const Mesh& mesh) {
    glCreateVertexArrays(1, &vao_);
    glCreateVertexArrays(1, &caster_vao_);
    glCreateBuffers(1, &positions_);
    glCreateBuffers(1, &normals_);
    glCreateBuffers(1, &indices_);
    glCreateBuffers(1, &uvs_);
    glCreateBuffers(1, &material_uvs_);
    // The triangles grouped by material, the closed parts' first (never cut), then the other solid ones
    // (-1), then one range per cut material.
    std::vector<std::vector<std::uint32_t>> groups(mesh.cut_materials.size() + 2); // material m in groups[m + 2]
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const int m = mesh.closed(t) ? -2 : mesh.triangle_materials.empty() ? -1 : mesh.triangle_materials[t];
        std::vector<std::uint32_t>& group = groups[static_cast<std::size_t>(m + 2)];
        group.insert(group.end(), mesh.indices.begin() + static_cast<std::ptrdiff_t>(3 * t),
                     mesh.indices.begin() + static_cast<std::ptrdiff_t>(3 * t + 3));
    }
    std::vector<std::uint32_t> indices;
    indices.reserve(mesh.indices.size());
    const std::uint8_t opaque = 255;
    textures_.push_back(alpha_texture(1, 1, &opaque));
    for (int m = -2; m < static_cast<int>(mesh.cut_materials.size()); ++m) {
        Range range{static_cast<GLsizei>(indices.size()), 0, textures_.front(), 0.0f, m == -2};
        if (m >= 0) {
            const CutMaterial& material = mesh.cut_materials[static_cast<std::size_t>(m)];
            textures_.push_back(alpha_texture(material.texture.width, material.texture.height, material.texture.alpha.data()));
            range.texture = textures_.back();
            range.cutoff = material.cutoff;
        }
        const std::vector<std::uint32_t>& group = groups[static_cast<std::size_t>(m + 2)];
        indices.insert(indices.end(), group.begin(), group.end());
        range.count = static_cast<GLsizei>(group.size());
        if (range.count > 0) ranges_.push_back(range);
    }
    glNamedBufferStorage(positions_, static_cast<GLsizeiptr>(mesh.positions.size() * sizeof(glm::vec3)), mesh.positions.data(), 0);
    glNamedBufferStorage(normals_, static_cast<GLsizeiptr>(mesh.normals.size() * sizeof(glm::vec3)), mesh.normals.data(), 0);
    glNamedBufferStorage(indices_, static_cast<GLsizeiptr>(indices.size() * sizeof(std::uint32_t)), indices.data(), 0);
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
    // The casters' vertex array: position, and the material texture coordinates as penumbra_uv (2).
    glVertexArrayVertexBuffer(caster_vao_, 0, positions_, 0, sizeof(glm::vec3));
    glEnableVertexArrayAttrib(caster_vao_, 0);
    glVertexArrayAttribFormat(caster_vao_, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(caster_vao_, 0, 0);
    if (mesh.cuts()) {
        glNamedBufferStorage(material_uvs_, static_cast<GLsizeiptr>(mesh.material_uvs.size() * sizeof(glm::vec2)),
                             mesh.material_uvs.data(), 0);
        for (const auto& [vao, attribute] : {std::pair{vao_, 3u}, std::pair{caster_vao_, 2u}}) {
            glVertexArrayVertexBuffer(vao, attribute, material_uvs_, 0, sizeof(glm::vec2));
            glEnableVertexArrayAttrib(vao, attribute);
            glVertexArrayAttribFormat(vao, attribute, 2, GL_FLOAT, GL_FALSE, 0);
            glVertexArrayAttribBinding(vao, attribute, attribute);
        }
    }
    glVertexArrayElementBuffer(vao_, indices_);
    glVertexArrayElementBuffer(caster_vao_, indices_);
    count_ = static_cast<GLsizei>(indices.size());
}

MeshBuffers::~MeshBuffers() {
    glDeleteVertexArrays(1, &vao_);
    glDeleteVertexArrays(1, &caster_vao_);
    const GLuint buffers[5] = {positions_, normals_, indices_, uvs_, material_uvs_};
    glDeleteBuffers(5, buffers);
    glDeleteTextures(static_cast<GLsizei>(textures_.size()), textures_.data());
}

void MeshBuffers::draw() const {
    glBindVertexArray(vao_);
    glDrawElements(GL_TRIANGLES, count_, GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
}

void MeshBuffers::draw_materials(const std::function<void(GLuint alpha_texture, float cutoff, bool closed)>& material,
                                 bool caster) const {
    glBindVertexArray(caster ? caster_vao_ : vao_);
    for (const Range& r : ranges_) {
        material(r.texture, r.cutoff, r.closed);
        glDrawElements(GL_TRIANGLES, r.count, GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(static_cast<std::uintptr_t>(r.first) * sizeof(std::uint32_t)));
    }
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
    glUniform1i(glGetUniformLocation(program_, "alphaTexture"), 0);
    const GLint cutoff_location = glGetUniformLocation(program_, "alphaCutoff");
    mesh.draw_materials([&](GLuint alpha, float cutoff, bool) {
        glBindTextureUnit(0, alpha);
        glBindSampler(0, 0);
        glUniform1f(cutoff_location, cutoff);
    }, false);
    glBindTextureUnit(0, 0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

} // namespace penumbra::playground
