// playground/src/scenes/mesh_builder.cpp
#include "scenes/mesh_builder.hpp"

#include <glm/gtc/matrix_inverse.hpp>

#include <cmath>
#include <limits>
#include <sstream>

namespace penumbra::playground {

namespace {

glm::vec3 safe_normalize(glm::vec3 v, glm::vec3 fallback) {
    const float len = glm::length(v);
    return len > 0.0f && std::isfinite(len) ? v / len : fallback;
}

std::uint32_t push_vertex(Mesh& mesh, glm::vec3 p, glm::vec3 n) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(n);
    return static_cast<std::uint32_t>(mesh.positions.size() - 1);
}

} // namespace

void add_triangle(Mesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 n = safe_normalize(glm::cross(b - a, c - a), glm::vec3(0, 1, 0));
    const std::uint32_t i0 = push_vertex(mesh, a, n);
    const std::uint32_t i1 = push_vertex(mesh, b, n);
    const std::uint32_t i2 = push_vertex(mesh, c, n);
    mesh.indices.insert(mesh.indices.end(), {i0, i1, i2});
}

void add_quad(Mesh& mesh, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3) {
    // Newell's normal: robust for slightly non-planar quads.
    const glm::vec3 n = safe_normalize(glm::cross(p2 - p0, p3 - p1), glm::vec3(0, 1, 0));
    const std::uint32_t i0 = push_vertex(mesh, p0, n);
    const std::uint32_t i1 = push_vertex(mesh, p1, n);
    const std::uint32_t i2 = push_vertex(mesh, p2, n);
    const std::uint32_t i3 = push_vertex(mesh, p3, n);
    mesh.indices.insert(mesh.indices.end(), {i0, i1, i2, i0, i2, i3});
}

void complete_cut_materials(Mesh& mesh) {
    if (!mesh.cuts()) return;
    mesh.material_uvs.resize(mesh.positions.size(), glm::vec2(0.0f));
    mesh.triangle_materials.resize(mesh.triangle_count(), -1);
}

Mesh without_cuts(Mesh mesh) {
    mesh.cut_materials.clear();
    mesh.material_uvs.clear();
    mesh.triangle_materials.clear();
    return mesh;
}

void add_cut_quad(Mesh& mesh, glm::vec3 p0, glm::vec3 p1, glm::vec3 p2, glm::vec3 p3, int material, glm::vec2 uv0,
                  glm::vec2 uv1, glm::vec2 uv2, glm::vec2 uv3) {
    complete_cut_materials(mesh);
    add_quad(mesh, p0, p1, p2, p3);
    mesh.material_uvs.insert(mesh.material_uvs.end(), {uv0, uv1, uv2, uv3});
    mesh.triangle_materials.insert(mesh.triangle_materials.end(), {material, material});
}

void add_horizontal_rect(Mesh& mesh, float cx, float y, float cz, float size_x, float size_z) {
    const float hx = 0.5f * size_x;
    const float hz = 0.5f * size_z;
    // Counter-clockwise seen from +y: (−x,+z) → (+x,+z) → (+x,−z) → (−x,−z).
    add_quad(mesh, {cx - hx, y, cz + hz}, {cx + hx, y, cz + hz}, {cx + hx, y, cz - hz},
             {cx - hx, y, cz - hz});
}

void add_box(Mesh& mesh, const glm::mat4& model) {
    Mesh unit;
    const float h = 0.5f;
    // Each face counter-clockwise seen from outside.
    add_quad(unit, {h, -h, h}, {h, -h, -h}, {h, h, -h}, {h, h, h});     // +x
    add_quad(unit, {-h, -h, -h}, {-h, -h, h}, {-h, h, h}, {-h, h, -h}); // −x
    add_quad(unit, {-h, h, h}, {h, h, h}, {h, h, -h}, {-h, h, -h});     // +y
    add_quad(unit, {-h, -h, -h}, {h, -h, -h}, {h, -h, h}, {-h, -h, h}); // −y
    add_quad(unit, {-h, -h, h}, {h, -h, h}, {h, h, h}, {-h, h, h});     // +z
    add_quad(unit, {h, -h, -h}, {-h, -h, -h}, {-h, h, -h}, {h, h, -h}); // −z
    append_mesh(mesh, unit, model);
}

void append_mesh(Mesh& dst, const Mesh& src, const glm::mat4& model) {
    const glm::mat3 normal_matrix = glm::inverseTranspose(glm::mat3(model));
    // A mirroring transform flips the winding; swap two indices to keep faces front-facing.
    const bool mirrored = glm::determinant(glm::mat3(model)) < 0.0f;
    const auto base = static_cast<std::uint32_t>(dst.positions.size());
    for (std::size_t i = 0; i < src.positions.size(); ++i) {
        dst.positions.push_back(glm::vec3(model * glm::vec4(src.positions[i], 1.0f)));
        dst.normals.push_back(safe_normalize(normal_matrix * src.normals[i], glm::vec3(0, 1, 0)));
    }
    for (std::size_t t = 0; t + 2 < src.indices.size(); t += 3) {
        const std::uint32_t a = base + src.indices[t];
        const std::uint32_t b = base + src.indices[t + 1];
        const std::uint32_t c = base + src.indices[t + 2];
        if (mirrored)
            dst.indices.insert(dst.indices.end(), {a, c, b});
        else
            dst.indices.insert(dst.indices.end(), {a, b, c});
    }
}

void compute_vertex_normals(Mesh& mesh) {
    // Angle-weighted face normals (Thürmer & Wüthrich): unlike area weighting, the result does
    // not depend on how a polygon was split into triangles (a quad cube gets exact diagonals).
    std::vector<glm::vec3> sum(mesh.positions.size(), glm::vec3(0.0f));
    auto angle = [](glm::vec3 a, glm::vec3 b) {
        const float la = glm::length(a), lb = glm::length(b);
        if (!(la > 0.0f) || !(lb > 0.0f)) return 0.0f;
        return std::acos(glm::clamp(glm::dot(a, b) / (la * lb), -1.0f, 1.0f));
    };
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const std::uint32_t ids[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
        const glm::vec3 p[3] = {mesh.positions[ids[0]], mesh.positions[ids[1]], mesh.positions[ids[2]]};
        const glm::vec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
        const float len = glm::length(face);
        if (!(len > 0.0f)) continue; // degenerate: no direction to contribute
        for (int k = 0; k < 3; ++k)
            sum[ids[k]] += angle(p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]) * (face / len);
    }
    mesh.normals.resize(mesh.positions.size());
    for (std::size_t i = 0; i < sum.size(); ++i)
        mesh.normals[i] = safe_normalize(sum[i], glm::vec3(0, 1, 0));
}

std::pair<glm::vec3, glm::vec3> compute_bounds(const Mesh& mesh) {
    if (mesh.positions.empty()) return {glm::vec3(0.0f), glm::vec3(0.0f)};
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(-std::numeric_limits<float>::max());
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    return {lo, hi};
}

std::string validate_cut_materials(const Mesh& mesh) {
    if (!mesh.cuts()) {
        if (!mesh.material_uvs.empty() || !mesh.triangle_materials.empty())
            return "material texture coordinates or triangle materials without a cut material";
        return {};
    }
    std::ostringstream out;
    if (mesh.material_uvs.size() != mesh.positions.size()) {
        out << mesh.material_uvs.size() << " material texture coordinates for " << mesh.positions.size() << " vertices";
        return out.str();
    }
    if (mesh.triangle_materials.size() != mesh.triangle_count()) {
        out << mesh.triangle_materials.size() << " triangle materials for " << mesh.triangle_count() << " triangles";
        return out.str();
    }
    for (std::size_t i = 0; i < mesh.material_uvs.size(); ++i)
        if (!std::isfinite(mesh.material_uvs[i].x) || !std::isfinite(mesh.material_uvs[i].y)) {
            out << "vertex " << i << " has non-finite material texture coordinates";
            return out.str();
        }
    for (std::size_t t = 0; t < mesh.triangle_materials.size(); ++t)
        if (mesh.triangle_materials[t] < -1 ||
            mesh.triangle_materials[t] >= static_cast<std::int32_t>(mesh.cut_materials.size())) {
            out << "triangle " << t << " has material " << mesh.triangle_materials[t] << "; allowed: -1 to "
                << mesh.cut_materials.size() - 1;
            return out.str();
        }
    for (const CutMaterial& m : mesh.cut_materials) {
        const std::size_t texels = static_cast<std::size_t>(std::max(m.texture.width, 0)) *
                                   static_cast<std::size_t>(std::max(m.texture.height, 0));
        if (m.texture.width < 1 || m.texture.height < 1 || m.texture.alpha.size() != texels) {
            out << "cut material '" << m.name << "' has a " << m.texture.width << "x" << m.texture.height
                << " texture with " << m.texture.alpha.size() << " texels";
            return out.str();
        }
        if (!(m.cutoff >= 0.0f && m.cutoff <= 1.0f)) {
            out << "cut material '" << m.name << "' has alpha cutoff " << m.cutoff << "; allowed: 0 to 1";
            return out.str();
        }
    }
    return {};
}

std::string validate_mesh(const Mesh& mesh) {
    std::ostringstream out;
    if (mesh.indices.size() % 3 != 0) {
        out << "index count " << mesh.indices.size() << " is not a multiple of 3";
        return out.str();
    }
    if (mesh.normals.size() != mesh.positions.size()) {
        out << mesh.normals.size() << " normals for " << mesh.positions.size() << " vertices";
        return out.str();
    }
    if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) {
        out << mesh.uvs.size() << " texture coordinates for " << mesh.positions.size() << " vertices";
        return out.str();
    }
    for (std::size_t i = 0; i < mesh.uvs.size(); ++i)
        if (!std::isfinite(mesh.uvs[i].x) || !std::isfinite(mesh.uvs[i].y)) {
            out << "vertex " << i << " has non-finite texture coordinates";
            return out.str();
        }
    if (const std::string problem = validate_cut_materials(mesh); !problem.empty()) return problem;
    for (std::size_t i = 0; i < mesh.indices.size(); ++i) {
        if (mesh.indices[i] >= mesh.positions.size()) {
            out << "index " << mesh.indices[i] << " (triangle " << i / 3 << ") is out of range ("
                << mesh.positions.size() << " vertices)";
            return out.str();
        }
    }
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
        const glm::vec3 p = mesh.positions[i];
        const glm::vec3 n = mesh.normals[i];
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
            out << "vertex " << i << " has a non-finite position";
            return out.str();
        }
        if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) {
            out << "vertex " << i << " has a non-finite normal";
            return out.str();
        }
    }
    return {};
}

} // namespace penumbra::playground
