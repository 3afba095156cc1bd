// playground/src/scenes/obj_loader.cpp
// The parser's implementation comes from Debian's libtinyobjloader (linked), not compiled here.
#include <tiny_obj_loader.h>

#include "scenes/obj_loader.hpp"

#include "scenes/mesh_builder.hpp"
#include "scenes/scene_defaults.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace penumbra::playground {

namespace {

LoadResult failure(const std::string& path, const std::string& problem) {
    return {std::nullopt, "cannot load OBJ file '" + path + "': " + problem};
}

// tinyobjloader's messages end in newlines and may hold several lines; keep the first line.
std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '.'))
        line.pop_back();
    return line;
}

} // namespace

LoadResult load_obj_scene(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return failure(path, "file does not exist");
    if (!std::filesystem::is_regular_file(path, ec)) return failure(path, "not a regular file");
    std::ifstream stream(path);
    if (!stream) return failure(path, "file cannot be opened for reading");

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    // No material reader (materials are irrelevant to visibility) and triangulate = false: the
    // library's own quad triangulation reads vertex positions through unchecked face indices, so
    // we validate the indices first and fan-triangulate ourselves.
    bool ok = false;
    try {
        ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &stream,
                              /*readMatFn=*/nullptr, /*triangulate=*/false);
    } catch (const std::exception& e) {
        return failure(path, std::string("parser failed: ") + e.what());
    }
    if (!ok) return failure(path, err.empty() ? "parse error" : first_line(err));
    if (warn.find("Degenerated face") != std::string::npos)
        return failure(path, "a face has fewer than 3 vertices (truncated 'f' line?)");
    if (attrib.vertices.size() % 3 != 0) return failure(path, "vertex data is incomplete");

    const std::size_t vertex_count = attrib.vertices.size() / 3;
    const std::size_t normal_count = attrib.normals.size() / 3;
    const std::size_t texcoord_count = attrib.texcoords.size() / 2;

    // Validate every corner of every polygon, then fan-triangulate (fine for the convex
    // polygons OBJ exporters write). `corners` holds three validated corners per triangle.
    std::vector<tinyobj::index_t> corners;
    bool all_corners_have_normals = true;
    bool all_corners_have_texcoords = texcoord_count > 0;
    std::size_t face_number = 0;
    for (const tinyobj::shape_t& shape : shapes) {
        std::size_t offset = 0;
        for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f, ++face_number) {
            const std::size_t count = shape.mesh.num_face_vertices[f];
            if (offset + count > shape.mesh.indices.size())
                return failure(path, "face table is inconsistent (file truncated?)");
            if (count < 3) {
                std::ostringstream msg;
                msg << "face " << face_number + 1 << " has " << count << " vertices, need at least 3";
                return failure(path, msg.str());
            }
            for (std::size_t c = 0; c < count; ++c) {
                const tinyobj::index_t idx = shape.mesh.indices[offset + c];
                // tinyobjloader has already turned 1-based and negative (relative) indices into
                // 0-based ones, without range checks: anything outside [0, count) is bad input.
                if (idx.vertex_index < 0 || static_cast<std::size_t>(idx.vertex_index) >= vertex_count) {
                    std::ostringstream msg;
                    if (idx.vertex_index < 0)
                        msg << "face " << face_number + 1 << " has a relative (negative) vertex index that "
                            << "points before the first vertex";
                    else
                        msg << "face " << face_number + 1 << " refers to vertex " << idx.vertex_index + 1
                            << " but the file has " << vertex_count << " vertices";
                    return failure(path, msg.str());
                }
                if (idx.normal_index >= 0 && static_cast<std::size_t>(idx.normal_index) >= normal_count) {
                    std::ostringstream msg;
                    msg << "face " << face_number + 1 << " refers to normal " << idx.normal_index + 1
                        << " but the file has " << normal_count << " normals";
                    return failure(path, msg.str());
                }
                if (idx.normal_index < 0) all_corners_have_normals = false;
                if (idx.texcoord_index >= 0 && static_cast<std::size_t>(idx.texcoord_index) >= texcoord_count) {
                    std::ostringstream msg;
                    msg << "face " << face_number + 1 << " refers to texture coordinate " << idx.texcoord_index + 1
                        << " but the file has " << texcoord_count << " texture coordinates";
                    return failure(path, msg.str());
                }
                if (idx.texcoord_index < 0) all_corners_have_texcoords = false;
            }
            for (std::size_t c = 1; c + 1 < count; ++c)
                corners.insert(corners.end(), {shape.mesh.indices[offset], shape.mesh.indices[offset + c],
                                               shape.mesh.indices[offset + c + 1]});
            offset += count;
        }
    }
    if (corners.empty()) return failure(path, "no triangles (no face with 3 or more vertices)");

    auto file_position = [&](int i) {
        const std::size_t v = static_cast<std::size_t>(i) * 3;
        return glm::vec3(attrib.vertices[v], attrib.vertices[v + 1], attrib.vertices[v + 2]);
    };
    auto file_texcoord = [&](int i) {
        const std::size_t t = static_cast<std::size_t>(i) * 2;
        return glm::vec2(attrib.texcoords[t], attrib.texcoords[t + 1]);
    };
    auto file_normal = [&](int i) {
        const std::size_t n = static_cast<std::size_t>(i) * 3;
        return glm::vec3(attrib.normals[n], attrib.normals[n + 1], attrib.normals[n + 2]);
    };
    // File normals are used only if every corner has a usable one; otherwise all normals are
    // recomputed rather than mixing two conventions.
    if (all_corners_have_normals) {
        for (const tinyobj::index_t& idx : corners) {
            const float len = glm::length(file_normal(idx.normal_index));
            if (!(len > 1e-12f) || !std::isfinite(len)) {
                all_corners_have_normals = false;
                break;
            }
        }
    }

    Mesh mesh;
    if (all_corners_have_normals) {
        // One output vertex per corner: a position may carry different normals on different faces.
        for (const tinyobj::index_t& idx : corners) {
            mesh.indices.push_back(static_cast<std::uint32_t>(mesh.positions.size()));
            mesh.positions.push_back(file_position(idx.vertex_index));
            mesh.normals.push_back(glm::normalize(file_normal(idx.normal_index)));
            if (all_corners_have_texcoords) mesh.uvs.push_back(file_texcoord(idx.texcoord_index));
        }
    } else {
        // Share the file's vertices so the computed normals are smooth across faces.
        for (std::size_t i = 0; i < vertex_count; ++i) mesh.positions.push_back(file_position(static_cast<int>(i)));
        for (const tinyobj::index_t& idx : corners) mesh.indices.push_back(static_cast<std::uint32_t>(idx.vertex_index));
        compute_vertex_normals(mesh);
        if (all_corners_have_texcoords) {
            // Texture seams: one vertex per distinct (position, texture coordinate) pair, normals kept smooth.
            Mesh split;
            std::map<std::pair<int, int>, std::uint32_t> vertex_of;
            for (const tinyobj::index_t& idx : corners) {
                auto [it, added] = vertex_of.try_emplace({idx.vertex_index, idx.texcoord_index},
                                                         static_cast<std::uint32_t>(split.positions.size()));
                if (added) {
                    split.positions.push_back(mesh.positions[static_cast<std::size_t>(idx.vertex_index)]);
                    split.normals.push_back(mesh.normals[static_cast<std::size_t>(idx.vertex_index)]);
                    split.uvs.push_back(file_texcoord(idx.texcoord_index));
                }
                split.indices.push_back(it->second);
            }
            mesh = std::move(split);
        }
    }

    for (const glm::vec3& p : mesh.positions)
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            return failure(path, "a vertex position is not a finite number");

    Scene scene;
    scene.name = std::filesystem::path(path).stem().string();
    scene.mesh = std::move(mesh);
    finish_scene(scene);
    if (const std::string problem = validate_mesh(scene.mesh); !problem.empty()) return failure(path, problem);
    return {std::move(scene), {}};
}

} // namespace penumbra::playground
