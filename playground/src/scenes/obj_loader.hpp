// playground/src/scenes/obj_loader.hpp — any Wavefront OBJ file as a Scene.
#pragma once

#include "scenes/scene.hpp"

#include <optional>
#include <string>
#include <vector>

namespace penumbra::playground {

struct LoadResult {
    std::optional<Scene> scene; // set on success
    std::string error;          // on failure: one line naming the file and the problem
    std::vector<std::string> warnings; // on success: parts of the file that were skipped, one line each
};

// Loads every polygon of every object/group into one mesh (polygons are fan-triangulated; lines and
// points are ignored). Materials (mtllib, next to the file) matter only when they cut (alpha test):
// map_d (its image's alpha, or grey level) and map_Kd with an alpha channel cut at 0.5, read at the
// faces' texture coordinates (mesh.cut_materials); their images are decoded with stb_image, no other. Normals from the file are used when every corner of every
// face has one; otherwise smooth normals are computed. Texture coordinates (`vt`) are kept in
// mesh.uvs when every corner has one (vertices split at texture seams). The scene gets the default light above its
// bounds and a camera framing it (scene_defaults.hpp), and is named after the file's stem.
// Never throws on bad input: missing files, unparsable lines, face indices out of range, faces
// with fewer than three corners and files without triangles are reported in `error`.
LoadResult load_obj_scene(const std::string& path);

} // namespace penumbra::playground
