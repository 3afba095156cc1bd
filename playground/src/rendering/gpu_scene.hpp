// playground/src/rendering/gpu_scene.hpp — the scene on the GPU: mesh buffers and a G-buffer of world
// positions and normals. Shared by the headless renderer and the window, so both shade exactly
// the same positions. Needs a current GL 4.5 core context.
#pragma once

#include "scenes/scene.hpp"

#include <penumbra/program.hpp>

#include <epoxy/gl.h>

#include <functional>
#include <memory>
#include <string>

namespace penumbra::playground {

// One triangle that covers the viewport: vertices (−1,−1), (3,−1), (−1,3); draw 3 vertices with
// any (empty) vertex array bound.
inline constexpr const char* fullscreen_triangle_vertex = R"(#version 450 core
void main() {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Compiles and links a vertex + fragment program of the playground's own (views, compose,
// G-buffer); 0 with "name.vert:line: message" diagnostics in *error.
GLuint build_program(const std::string& name, std::string vertex, std::string fragment, std::string* error);

// Vertex buffers of a Mesh: attribute 0 = position, 1 = normal (what the slicing pass expects),
// 2 = texture coordinates when the mesh has them (otherwise the attribute stays disabled: (0, 0)),
// 3 = the cut materials' texture coordinates when a material cuts. The triangles are stored grouped
// by material (solid first), one draw range per material, each with its alpha texture (RGBA8, the
// alpha in .a; nearest, repeat) and cutoff; solid ranges use a 1x1 opaque texture and cutoff 0.
class MeshBuffers {
public:
    explicit MeshBuffers(const Mesh& mesh);
    ~MeshBuffers();
    MeshBuffers(const MeshBuffers&) = delete;
    MeshBuffers& operator=(const MeshBuffers&) = delete;
    // Every triangle in one draw (attributes 0 to 3).
    void draw() const;
    // Each material's triangles in a draw of its own, `material(alpha_texture, cutoff, closed)` called
    // before each; the triangles of closed parts (Mesh::triangle_closed) come first, in a draw of their
    // own (solid_casters: closed meshes before open casters). `caster`: the layout's caster convention,
    // the material texture coordinates as attribute 2 (penumbra_uv; detail/alpha_test.hpp) instead of
    // the unique ones.
    void draw_materials(const std::function<void(GLuint alpha_texture, float cutoff, bool closed)>& material,
                        bool caster) const;

private:
    struct Range {
        GLsizei first = 0, count = 0; // indices
        GLuint texture = 0;
        float cutoff = 0.0f;
        bool closed = false;
    };
    GLuint vao_ = 0, caster_vao_ = 0, positions_ = 0, normals_ = 0, indices_ = 0, uvs_ = 0, material_uvs_ = 0;
    GLsizei count_ = 0;
    std::vector<Range> ranges_;
    std::vector<GLuint> textures_; // [0]: the 1x1 opaque texture, then one per cut material
};

// World positions (RGBA32F, w = 1 on geometry, 0 on background), unit normals (RGBA32F) and
// texture coordinates (RGBA32F: xy, w = 1 on geometry) of what a camera sees, plus a depth buffer.
class GBuffer {
public:
    // nullptr with *error set when the program does not build or the framebuffer is incomplete.
    static std::unique_ptr<GBuffer> create(int width, int height, std::string* error);
    ~GBuffer();
    GBuffer(const GBuffer&) = delete;
    GBuffer& operator=(const GBuffer&) = delete;

    // Clears and rasterises `mesh` with clip_from_world; restores framebuffer 0 afterwards. Cut-out
    // pixels (a cut material's alpha below its cutoff) are not surfaces: background (w = 0).
    void render(const MeshBuffers& mesh, const glm::mat4& clip_from_world);

    int width() const { return width_; }
    int height() const { return height_; }
    GLuint positions() const { return textures_[0]; }
    GLuint normals() const { return textures_[1]; }
    GLuint tex_coords() const { return textures_[2]; }
    GLuint framebuffer() const { return fbo_; }

private:
    GBuffer() = default;
    int width_ = 0, height_ = 0;
    GLuint program_ = 0, textures_[3] = {0, 0, 0}, depth_ = 0, fbo_ = 0;
};

} // namespace penumbra::playground
