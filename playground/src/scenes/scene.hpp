// playground/src/scenes/scene.hpp — what a test scene is: triangles, one area light, one sun, a camera.
//
// Scenes are plain data so that every consumer (the GL renderer, the Embree ground truth, the
// CPU oracle, the metrics) sees exactly the same triangles and lights.
#pragma once

#include <penumbra/light.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::playground {

// An indexed triangle mesh with one normal per vertex. Faces that must look flat (boxes, quads)
// get their own vertices so that their normals are not averaged across edges.
struct Mesh {
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;      // same size as positions, unit length
    std::vector<std::uint32_t> indices;  // three per triangle, each < positions.size()
    std::vector<glm::vec2> uvs;          // texture coordinates in [0,1]², same size as positions; empty
                                         // when the mesh has none (scenes/charts.hpp makes unique ones)

    std::size_t triangle_count() const { return indices.size() / 3; }
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
};

} // namespace penumbra::playground
