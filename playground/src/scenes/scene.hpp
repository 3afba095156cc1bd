// playground/src/scenes/scene.hpp — what a test scene is: triangles, one area light, one sun, a camera.
//
// Scenes are plain data so that every consumer (the GL renderer, the Embree ground truth, the
// CPU oracle, the metrics) sees exactly the same triangles and lights.
#pragma once

#include <penumbra/light.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::playground {

// The alpha of a cut-out material's texture (alpha test), one byte per texel, row-major, the first
// row at texture coordinate v = 0 (glTF's convention: v = 0 is the image's top row). Read with
// nearest filtering and repeat wrapping, on the GPU (GL_NEAREST, GL_REPEAT) and on the CPU alike.
struct AlphaTexture {
    int width = 0, height = 0;
    std::vector<std::uint8_t> alpha; // width * height; the material's alpha factor already applied

    // The texel under texture coordinate `uv` (nearest, repeat), 0 to 255.
    std::uint8_t at(glm::vec2 uv) const {
        const float fu = uv.x - std::floor(uv.x), fv = uv.y - std::floor(uv.y);
        const int x = std::min(width - 1, static_cast<int>(fu * static_cast<float>(width)));
        const int y = std::min(height - 1, static_cast<int>(fv * static_cast<float>(height)));
        return alpha[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)];
    }
};

// A material that cuts its triangles: where its texture's alpha is below the cutoff there is no
// surface (glTF alphaMode MASK, a BLEND material cast as a cut-out, OBJ map_d).
struct CutMaterial {
    std::string name;
    AlphaTexture texture;
    float cutoff = 0.5f; // alpha / 255 below this is cut; 0 to 1

    // True where the material has a surface at texture coordinate `uv`.
    bool solid_at(glm::vec2 uv) const { return static_cast<float>(texture.at(uv)) >= cutoff * 255.0f; }
};

// An indexed triangle mesh with one normal per vertex. Faces that must look flat (boxes, quads)
// get their own vertices so that their normals are not averaged across edges.
struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;      // same size as positions, unit length
    std::vector<std::uint32_t> indices;  // three per triangle, each < positions.size()
    std::vector<glm::vec2> uvs;          // texture coordinates in [0,1]², same size as positions; empty
                                         // when the mesh has none (scenes/charts.hpp makes unique ones)
    // Cut-out materials (alpha test). Empty when nothing cuts; otherwise material_uvs has one texture
    // coordinate per vertex (the materials' own, not the unique charts of `uvs`) and
    // triangle_materials one entry per triangle: an index into cut_materials, or -1 for a solid one.
    std::vector<CutMaterial> cut_materials;
    std::vector<glm::vec2> material_uvs;
    std::vector<std::int32_t> triangle_materials;
    // One entry per triangle: 1 where it belongs to a closed part (scenes/closed_parts.hpp), whose slices
    // between its surfaces solid_casters fills. Set by finish_scene.
    std::vector<std::uint8_t> triangle_closed;

    std::size_t triangle_count() const { return indices.size() / 3; }
    bool closed(std::size_t t) const { return t < triangle_closed.size() && triangle_closed[t] != 0; }
    bool cuts() const { return !cut_materials.empty(); }
    // The cut material of triangle `t`, or nullptr when it is solid.
    const CutMaterial* material_of(std::size_t t) const {
        if (triangle_materials.empty() || triangle_materials[t] < 0) return nullptr;
        return &cut_materials[static_cast<std::size_t>(triangle_materials[t])];
    }
    // True where triangle `t` has a surface at barycentric (u, v) (Embree's: weight u on its second
    // corner, v on its third).
    bool solid_at(std::size_t t, float u, float v) const {
        const CutMaterial* m = material_of(t);
        if (!m) return true;
        const glm::vec2 uv = (1.0f - u - v) * material_uvs[indices[3 * t]] + u * material_uvs[indices[3 * t + 1]] +
                             v * material_uvs[indices[3 * t + 2]];
        return m->solid_at(uv);
    }
};

// A camera orbiting `target`: right-handed, +y up, GL clip depth −1..1 (GLM's defaults).
// yaw rotates about +y (0 looks along −z from the +z side), pitch lifts the eye above the target.
struct OrbitCamera {
    glm::vec3 target{0.0f};
    float distance = 10.0f;
    float yaw_radians = 0.0f;
    float pitch_radians = 0.0f;
    float fov_y_radians = 0.785398f; // 45°
    float z_near = 0.05f;
    float z_far = 100.0f;

    glm::vec3 eye_position() const {
        const float c = std::cos(pitch_radians);
        return target + distance * glm::vec3(c * std::sin(yaw_radians), std::sin(pitch_radians),
                                             c * std::cos(yaw_radians));
    }
    glm::mat4 view_matrix() const {
        return glm::lookAt(eye_position(), target, glm::vec3(0.0f, 1.0f, 0.0f));
    }
    glm::mat4 projection_matrix(float aspect) const {
        return glm::perspective(fov_y_radians, aspect, z_near, z_far);
    }
};

struct Scene {
    std::string name;
    Mesh mesh;
    penumbra::RectLight light;
    penumbra::SunLight sun;
    OrbitCamera camera;
    glm::vec3 bounds_min{0.0f}; // axis-aligned bounds of mesh.positions
    glm::vec3 bounds_max{0.0f};
    // True for the procedural scenes: their texture coordinates may be generated (one chart per
    // connected planar piece, scenes/charts.hpp). A loaded file keeps its own or has none.
    bool generated_charts = false;
    // True when a floor was added under a loaded mesh (scenes/ground_plane.hpp).
    bool ground = false;
    // The lights a loaded file brings (a glTF file's EXT_lights_area rectangle, its KHR_lights_punctual
    // directional light's direction; scenes/gltf_loader.hpp): finish_scene puts them in place of the
    // defaults it computes, so they survive the floor (add_ground_plane). Unset: the defaults.
    std::optional<penumbra::RectLight> file_light;
    std::optional<glm::dvec3> file_sun_direction; // unit; the sun keeps the default angular diameter
};

} // namespace penumbra::playground
