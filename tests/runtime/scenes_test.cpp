// tests/runtime/scenes_test.cpp — every procedural scene is well formed and deterministic.
#include <doctest/doctest.h>

#include "scenes/mesh_builder.hpp"
#include "scenes/scenes.hpp"

#include <cmath>
#include <cstring>
#include <set>
#include <string>

using namespace penumbra::playground;

namespace {

template <class T>
bool bitwise_equal(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

} // namespace

TEST_CASE("scene_names lists the procedural scenes of docs/model.md §5 and the cut-out scene") {
    const auto names = scene_names();
    const std::set<std::string_view> got(names.begin(), names.end());
    CHECK(got == std::set<std::string_view>{"planes", "boxes", "tree", "butterfly", "terrain", "crowd", "box", "cutout"});
    CHECK(names.size() == got.size());
    CHECK_FALSE(make_scene("no-such-scene").has_value());
    CHECK_FALSE(make_scene("").has_value());
}

TEST_CASE("every procedural scene is well formed and deterministic") {
    for (std::string_view name : scene_names()) {
        CAPTURE(name);
        const std::optional<Scene> a = make_scene(name);
        const std::optional<Scene> b = make_scene(name);
        REQUIRE(a.has_value());
        REQUIRE(b.has_value());
        const Scene& s = *a;
        CHECK(s.name == name);

        // Determinism: two builds are bit-identical.
        CHECK(bitwise_equal(s.mesh.positions, b->mesh.positions));
        CHECK(bitwise_equal(s.mesh.normals, b->mesh.normals));
        CHECK(bitwise_equal(s.mesh.indices, b->mesh.indices));

        // Structure.
        CHECK(validate_mesh(s.mesh).empty());
        REQUIRE(s.mesh.normals.size() == s.mesh.positions.size());
        REQUIRE(s.mesh.indices.size() % 3 == 0);
        CHECK(s.mesh.triangle_count() > 0);
        CHECK(s.mesh.triangle_count() < 200000);
        std::size_t bad_index = 0, bad_normal = 0, bad_winding = 0, outside = 0;
        for (std::uint32_t i : s.mesh.indices) bad_index += i >= s.mesh.positions.size();
        for (const glm::vec3& n : s.mesh.normals) bad_normal += std::abs(glm::length(n) - 1.0f) > 1e-4f;
        for (const glm::vec3& p : s.mesh.positions)
            outside += glm::any(glm::lessThan(p, s.bounds_min)) || glm::any(glm::greaterThan(p, s.bounds_max));
        // Winding and normals agree: the triangle's geometric normal points to the side its
        // vertex normals point to (renderers rely on either).
        for (std::size_t t = 0; t < s.mesh.indices.size(); t += 3) {
            const auto ia = s.mesh.indices[t], ib = s.mesh.indices[t + 1], ic = s.mesh.indices[t + 2];
            const glm::vec3 g = glm::cross(s.mesh.positions[ib] - s.mesh.positions[ia],
                                           s.mesh.positions[ic] - s.mesh.positions[ia]);
            if (glm::length(g) < 1e-9f) continue;
            bad_winding += glm::dot(g, s.mesh.normals[ia] + s.mesh.normals[ib] + s.mesh.normals[ic]) <= 0.0f;
        }
        CHECK(bad_index == 0);
        CHECK(bad_normal == 0);
        CHECK(bad_winding == 0);
        CHECK(outside == 0);

        // Bounds are tight (they are the mesh's bounds, not a guess).
        const auto [lo, hi] = compute_bounds(s.mesh);
        CHECK(lo == s.bounds_min);
        CHECK(hi == s.bounds_max);

        // Common frame: ~10×10 ground around the origin at y ≈ 0, objects ≤ ~3 tall.
        CHECK(s.bounds_max.x - s.bounds_min.x == doctest::Approx(10.0f).epsilon(0.05));
        CHECK(s.bounds_max.z - s.bounds_min.z == doctest::Approx(10.0f).epsilon(0.05));
        CHECK(s.bounds_min.y > -0.5f);
        CHECK(s.bounds_max.y < 3.6f);

        // Lights: a 2×2-ish area light facing down above everything, a sun from above.
        CHECK(s.light.center.y > s.bounds_max.y + 1.0);
        CHECK(s.light.center.y >= 5.5);
        CHECK(s.light.center.y <= 8.5);
        CHECK(s.light.normal().y == doctest::Approx(-1.0));
        CHECK(s.light.width == doctest::Approx(2.0).epsilon(0.1));
        CHECK(s.light.height == doctest::Approx(2.0).epsilon(0.1));
        CHECK(glm::length(s.sun.direction) == doctest::Approx(1.0));
        CHECK(s.sun.direction.y < -0.9);
        CHECK(s.sun.direction.y > -0.9999); // tilted, not straight down
        CHECK(s.sun.angular_diameter == doctest::Approx(0.0093 * 5));

        // Camera: above the ground, outside the bounds, looking at the centre.
        const glm::vec3 eye = s.camera.eye_position();
        CHECK(eye.y > s.bounds_max.y);
        CHECK(glm::length(eye - s.camera.target) == doctest::Approx(s.camera.distance));
        const glm::vec4 centre_clip = s.camera.projection_matrix(1.0f) * s.camera.view_matrix() *
                                      glm::vec4(0.5f * (s.bounds_min + s.bounds_max), 1.0f);
        CHECK(std::abs(centre_clip.x / centre_clip.w) < 1e-3f);
        CHECK(std::abs(centre_clip.y / centre_clip.w) < 1e-3f);
        CHECK(std::abs(centre_clip.z / centre_clip.w) < 1.0f); // between near and far
    }
}

TEST_CASE("planes: occluders lie exactly on their advertised heights") {
    const Scene s = *make_scene("planes");
    std::set<float> heights;
    for (const glm::vec3& p : s.mesh.positions) heights.insert(p.y);
    std::set<float> expected{0.0f};
    for (float h : planes_occluder_heights) expected.insert(h);
    CHECK(heights == expected);
    for (const glm::vec3& n : s.mesh.normals) CHECK(n == glm::vec3(0, 1, 0)); // parallel to the light
}

TEST_CASE("scene sizes are in the intended ranges") {
    CHECK(make_scene("tree")->mesh.triangle_count() >= 2 * 300);    // several hundred leaf quads
    CHECK(make_scene("crowd")->mesh.triangle_count() >= 10000);      // many instances
    CHECK(make_scene("boxes")->mesh.triangle_count() >= 2 + 12 * 5); // ground + several boxes
}
