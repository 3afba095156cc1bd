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

// Empty string if the mesh is well formed (index count a multiple of 3, every index in range,
// one finite normal per vertex, finite positions, texture coordinates absent or one finite pair
// per vertex); otherwise a one-line description of the
// first problem found.
std::string validate_mesh(const Mesh& mesh);

} // namespace penumbra::playground
