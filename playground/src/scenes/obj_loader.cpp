// playground/src/scenes/obj_loader.cpp
// The parser's implementation comes from Debian's libtinyobjloader (linked), not compiled here.
#include <tiny_obj_loader.h>

#include "scenes/obj_loader.hpp"

#include "scenes/material_textures.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/scene_defaults.hpp"

#include <penumbra_tools/bounded_read.hpp>
#include <penumbra_tools/printable.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace penumbra::playground {

namespace {

LoadResult failure(const std::string& path, const std::string& problem) {
    return {std::nullopt, "cannot load OBJ file '" + penumbra_gen::printable(path, 200) + "': " + problem, {}};
}

// tinyobjloader's messages end in newlines and may hold several lines; keep the first line.
std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '.'))
        line.pop_back();
    return line;
}

// Coordinates beyond this make the scene's bounds, light and camera overflow single precision.
constexpr double coordinate_limit = 1e9;

std::string_view next_word(std::string_view& rest) {
    const std::size_t start = rest.find_first_not_of(" \t\r\f\v");
    if (start == std::string_view::npos) {
        rest = {};
        return {};
    }
    rest.remove_prefix(start);
    const std::size_t end = std::min(rest.find_first_of(" \t\r\f\v"), rest.size());
    const std::string_view word = rest.substr(0, end);
    rest.remove_prefix(end);
    return word;
}

// 'text', escaped (built with append: GCC 12 warns wrongly on "'" + std::string, bug 105329).
std::string quoted(std::string_view text) {
    std::string out(1, '\'');
    out += penumbra_gen::printable(text);
    out += '\'';
    return out;
}

// The 'v', 'vn' and 'f' lines checked before tinyobjloader reads them, which turns text that is
// not a number into 0 and lets overflowing indices wrap: every coordinate a finite number within
// ±coordinate_limit, every index an integer that names an existing vertex or normal. Empty, or
// "line N: …".
std::string check_obj_text(std::string_view text) {
    // Totals first: a positive index may name a vertex defined further down.
    long long vertices_total = 0, normals_total = 0;
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t end = std::min(text.find('\n', at), text.size());
        std::string_view rest = text.substr(at, end - at);
        const std::string_view word = next_word(rest);
        vertices_total += word == "v";
        normals_total += word == "vn";
        at = end + 1;
    }
    long long vertices = 0, normals = 0;
    std::size_t number = 0;
    for (std::size_t at = 0; at < text.size(); at = std::min(text.find('\n', at), text.size()) + 1) {
        ++number;
        std::string_view rest = text.substr(at, std::min(text.find('\n', at), text.size()) - at);
        const std::string where = "line " + std::to_string(number) + ": ";
        const std::string_view verb = next_word(rest);
        if (verb == "v" || verb == "vn") {
            for (int axis = 0; axis < 3; ++axis) {
                std::string_view word = next_word(rest);
                const std::string name = std::string(1, "xyz"[axis]) + (verb == "v" ? " coordinate" : " of the normal");
                if (word.empty()) return where + "'" + std::string(verb) + "' needs 3 numbers, the " + name + " is missing";
                if (word.front() == '+') word.remove_prefix(1);
                double value = 0.0;
                const auto [ptr, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
                const std::string shown = quoted(word);
                if (ec == std::errc::invalid_argument || ptr != word.data() + word.size() || word.empty())
                    return where + name + " " + shown + " is not a number; allowed: finite numbers within ±1e9";
                if (ec == std::errc::result_out_of_range || !std::isfinite(value) || std::abs(value) > coordinate_limit)
                    return where + name + " " + shown + " is out of range; allowed: finite numbers within ±1e9";
            }
            (verb == "v" ? vertices : normals) += 1;
        } else if (verb == "f") {
            for (std::string_view corner = next_word(rest); !corner.empty(); corner = next_word(rest)) {
                // v, v/vt, v//vn or v/vt/vn: the texture index is not used and only has to be an integer.
                for (int part = 0; part < 3 && !corner.empty(); ++part) {
                    const std::size_t slash = std::min(corner.find('/'), corner.size());
                    const std::string_view index = corner.substr(0, slash);
                    corner.remove_prefix(std::min(slash + 1, corner.size()));
                    if (index.empty() && part > 0) continue; // "v//vn"
                    const char* what = part == 0 ? "vertex" : part == 1 ? "texture" : "normal";
                    const long long defined = part == 0 ? vertices : normals;
                    const long long total = part == 0 ? vertices_total : normals_total;
                    long long value = 0;
                    const auto [ptr, ec] = std::from_chars(index.data(), index.data() + index.size(), value);
                    const std::string shown = quoted(index);
                    if (index.empty() || ec == std::errc::invalid_argument || ptr != index.data() + index.size())
                        return where + std::string(what) + " index " + shown + " is not an integer";
                    if (part == 1) continue;
                    const std::string allowed = "; allowed: 1 to " + std::to_string(total) + ", or -1 to -" +
                                                std::to_string(defined) + " counting back from this line";
                    if (ec != std::errc() || value == 0)
                        return where + std::string(what) + " index " + shown + " is out of range" + allowed;
                    if (value > total)
                        return where + "the face refers to " + what + " " + std::to_string(value) + " but the file has " +
                               std::to_string(total) + " " + (part == 0 ? "vertices" : "normals") + allowed;
                    if (-value > defined)
                        return where + "the face has a relative " + what + " index " + std::to_string(value) +
                               " that points before the first " + what + allowed;
                }
            }
        }
    }
    return {};
}

// The material libraries (mtllib) of an OBJ file, next to it, read through the bounded reader. One
// that cannot be read leaves its materials out (tinyobjloader warns; nothing cuts then).
class BoundedMaterialReader : public tinyobj::MaterialReader {
public:
    explicit BoundedMaterialReader(std::filesystem::path dir) : dir_(std::move(dir)) {}
    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* map, std::string* warn, std::string* err) override {
        const penumbra_gen::BoundedRead file = penumbra_gen::read_bounded_file((dir_ / name).string(), penumbra_gen::obj_file_limit);
        if (!file.text) return false;
        std::istringstream stream(*file.text);
        tinyobj::LoadMtl(map, materials, &stream, warn, err);
        return true;
    }

private:
    std::filesystem::path dir_;
};

// The cut material of each OBJ material (alpha test), appended to `out`: its slot there, or -1
// when it does not cut. map_d cuts at 0.5 by its image's alpha (or grey level); map_Kd cuts by its
// alpha channel when its image has one (only the header is read to know). Only those images are
// decoded; one that cannot be read is a warning and the material stays solid.
std::vector<int> cut_slots(const std::vector<tinyobj::material_t>& materials, const std::filesystem::path& dir,
                           std::vector<CutMaterial>& out, std::vector<std::string>& warnings) {
    std::vector<int> slots(materials.size(), -1);
    for (std::size_t i = 0; i < materials.size(); ++i) {
        const tinyobj::material_t& m = materials[i];
        const bool dissolve = !m.alpha_texname.empty();
        const std::string& texture = dissolve ? m.alpha_texname : m.diffuse_texname;
        if (texture.empty()) continue;
        const std::string what = "material '" + penumbra_gen::printable(m.name, 60) + "' " +
                                 (dissolve ? "map_d" : "map_Kd") + " '" + penumbra_gen::printable(texture, 100) + "'";
        const penumbra_gen::BoundedRead file = penumbra_gen::read_bounded_file((dir / texture).string(), penumbra_gen::obj_file_limit);
        if (!file.text) {
            if (dissolve) warnings.push_back(what + " not read (" + file.problem + "); it does not cut");
            continue;
        }
        const auto* bytes = reinterpret_cast<const unsigned char*>(file.text->data());
        if (!dissolve && !image_has_alpha(bytes, file.text->size())) continue; // an opaque diffuse texture
        std::string error;
        std::optional<AlphaTexture> alpha = decode_alpha_texture(
            bytes, file.text->size(), dissolve ? AlphaChannel::alpha_or_grey : AlphaChannel::alpha, 1.0, &error);
        if (!alpha) {
            warnings.push_back(what + ": " + error + "; it does not cut");
            continue;
        }
        out.push_back({"material '" + penumbra_gen::printable(m.name, 60) + "'", std::move(*alpha), 0.5f});
        slots[i] = static_cast<int>(out.size()) - 1;
    }
    return slots;
}

// The cut materials onto the finished mesh: `slots` per OBJ material, `triangle_material` the OBJ
// material of each triangle (-1: none); the materials' texture coordinates are the file's, v
// flipped (OBJ's v = 0 is the image's bottom row).
void attach_cuts(Mesh& mesh, std::vector<CutMaterial> cuts, const std::vector<int>& slots,
                 const std::vector<int>& triangle_material, std::vector<std::string>& warnings) {
    if (cuts.empty()) return;
    mesh.cut_materials = std::move(cuts);
    if (mesh.uvs.empty()) warnings.push_back("faces without texture coordinates (vt): cut materials read their texture at (0, 0)");
    mesh.material_uvs.assign(mesh.positions.size(), glm::vec2(0.0f));
    for (std::size_t i = 0; i < mesh.uvs.size(); ++i) mesh.material_uvs[i] = {mesh.uvs[i].x, 1.0f - mesh.uvs[i].y};
    mesh.triangle_materials.assign(mesh.triangle_count(), -1);
    for (std::size_t t = 0; t < mesh.triangle_count() && t < triangle_material.size(); ++t) {
        const int m = triangle_material[t];
        if (m >= 0 && static_cast<std::size_t>(m) < slots.size()) mesh.triangle_materials[t] = slots[static_cast<std::size_t>(m)];
    }
}

} // namespace

LoadResult load_obj_scene(const std::string& path) {
    const penumbra_gen::BoundedRead file = penumbra_gen::read_bounded_file(path, penumbra_gen::obj_file_limit);
    if (!file.text) return failure(path, file.problem == "no such file" ? "file does not exist" : file.problem);
    if (std::string problem = check_obj_text(*file.text); !problem.empty()) return failure(path, problem);
    std::istringstream stream(*file.text);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    // Materials are read for the ones that cut (alpha test: map_d, map_Kd with alpha). triangulate =
    // false: the library's own quad triangulation reads vertex positions through unchecked face
    // indices, so we validate the indices first and fan-triangulate ourselves.
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    BoundedMaterialReader material_reader(dir);
    bool ok = false;
    try {
        ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &stream, &material_reader,
                              /*triangulate=*/false);
    } catch (const std::exception& e) {
        return failure(path, std::string("parser failed: ") + e.what());
    }
    if (!ok) return failure(path, err.empty() ? "parse error" : penumbra_gen::printable(first_line(err), 200));
    if (warn.find("Degenerated face") != std::string::npos)
        return failure(path, "a face has fewer than 3 vertices (truncated 'f' line?)");
    if (attrib.vertices.size() % 3 != 0) return failure(path, "vertex data is incomplete");

    const std::size_t vertex_count = attrib.vertices.size() / 3;
    const std::size_t normal_count = attrib.normals.size() / 3;
    const std::size_t texcoord_count = attrib.texcoords.size() / 2;

    // Validate every corner of every polygon, then fan-triangulate (fine for the convex
    // polygons OBJ exporters write). `corners` holds three validated corners per triangle.
    std::vector<tinyobj::index_t> corners;
    std::vector<int> triangle_material; // the OBJ material of each triangle, -1 for none
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
            for (std::size_t c = 1; c + 1 < count; ++c) {
                corners.insert(corners.end(), {shape.mesh.indices[offset], shape.mesh.indices[offset + c],
                                               shape.mesh.indices[offset + c + 1]});
                triangle_material.push_back(f < shape.mesh.material_ids.size() ? shape.mesh.material_ids[f] : -1);
            }
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

    std::vector<std::string> warnings;
    std::vector<CutMaterial> cuts;
    const std::vector<int> slots = cut_slots(materials, dir, cuts, warnings);
    attach_cuts(mesh, std::move(cuts), slots, triangle_material, warnings);

    Scene scene;
    scene.name = std::filesystem::path(path).stem().string();
    scene.mesh = std::move(mesh);
    finish_scene(scene);
    if (const std::string problem = validate_mesh(scene.mesh); !problem.empty()) return failure(path, problem);
    for (std::string& w : warnings) w = penumbra_gen::printable(path, 200) + ": " + w;
    return {std::move(scene), {}, std::move(warnings)};
}

} // namespace penumbra::playground
