// playground/src/scenes/mesh_builder.hpp — small helpers to assemble procedural meshes and check them.
#pragma once

#include "scenes/scene.hpp"

#include <glm/glm.hpp>

#include <string>
#include <utility>

namespace penumbra::playground {

// One flat-shaded triangle (its own three vertices, normal from the winding: counter-clockwise
// seen from the side the normal points to).
void add_triangle(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c);

// A flat quad p0 p1 p2 p3 (counter-clockwise seen from the normal's side), as two triangles.
void add_quad(Mesh& mesh, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3);

// A quad like add_quad whose triangles are cut by mesh.cut_materials[material], with the material's
// texture coordinates uv0 … uv3 at its corners (the arrays of the mesh's other vertices and
// triangles are completed first: solid).
void add_cut_quad(Mesh& mesh, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, int material, glm::vec2 uv0,
                  glm::vec2 uv1, glm::vec2 uv2, glm::vec2 uv3);

// When a material cuts: material_uvs and triangle_materials extended to every vertex and triangle,
// those added since solid (texture coordinates (0, 0), material -1). Nothing when none cuts.
void complete_cut_materials(Mesh& mesh);

// `mesh` with every material solid (no cut materials): what casts with the alpha test off.
Mesh without_cuts(Mesh mesh);

// A horizontal rectangle at height y, facing +y, centred at (cx, cz), sizes along x and z.
void add_horizontal_rect(Mesh& mesh, float cx, float y, float cz, float size_x, float size_z);

// The unit cube [-0.5, 0.5]^3 transformed by `model`: 6 flat faces, 12 triangles, outward normals
// (normals use the inverse transpose, so non-uniform scales are fine).
void add_box(Mesh& mesh, const glm::mat4& model);

// Appends `src` transformed by `model` (instancing by copy).
void append_mesh(Mesh& dst, const Mesh& src, const glm::mat4& model);

// Replaces mesh.normals with angle-weighted averages of the adjacent face normals. Vertices that
// touch only degenerate triangles get +y so that every normal stays unit length.
void compute_vertex_normals(Mesh& mesh);

// Axis-aligned bounds of the positions ({0,0} for an empty mesh).
std::pair<glm::vec3, glm::vec3> compute_bounds(const Mesh& mesh);

// Empty string if the cut materials are well formed (none, or one texture coordinate per vertex,
// one material per triangle within range, textures of width × height texels, cutoffs 0 to 1).
std::string validate_cut_materials(const Mesh& mesh);

// Empty string if the mesh is well formed (index count a multiple of 3, every index in range,
// one finite normal per vertex, finite positions, texture coordinates absent or one finite pair
// per vertex); otherwise a one-line description of the
// first problem found.
std::string validate_mesh(const Mesh& mesh);

} // namespace penumbra::playground
