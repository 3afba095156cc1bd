// tests/runtime/scenes_test.cpp — every procedural scene is well formed and deterministic.
#include <doctest/doctest.h>

#include "scenes/mesh_builder.hpp"
#include "scenes/scenes.hpp"

#include <algorithm>
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

// The nearest triangle that the ray from `origin` along `direction` hits (Möller–Trumbore, both sides),
// or -1; `distance` is set to the hit's distance along the (unit) direction.
long nearest_hit(const Mesh& mesh, glm::dvec3 origin, glm::dvec3 direction, double& distance) {
    long nearest = -1;
    distance = 1e30;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]), b(mesh.positions[mesh.indices[3 * t + 1]]),
            c(mesh.positions[mesh.indices[3 * t + 2]]);
        const glm::dvec3 e1 = b - a, e2 = c - a, p = glm::cross(direction, e2);
        const double det = glm::dot(e1, p);
        if (std::abs(det) < 1e-14) continue;
        const glm::dvec3 s = origin - a;
        const double u = glm::dot(s, p) / det;
        const glm::dvec3 q = glm::cross(s, e1);
        const double v = glm::dot(direction, q) / det;
        const double d = glm::dot(e2, q) / det;
        if (u < 0 || v < 0 || u + v > 1 || d <= 0 || d >= distance) continue;
        distance = d;
        nearest = static_cast<long>(t);
    }
    return nearest;
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

TEST_CASE("the rooms are named apart from scene_names and each is closed around its light") {
    const auto rooms = room_scene_names();
    CHECK(std::vector<std::string_view>(rooms.begin(), rooms.end()) ==
          std::vector<std::string_view>{"room", "window", "cornell"});
    const auto names = scene_names();
    for (std::string_view room : rooms) CHECK(std::find(names.begin(), names.end(), room) == names.end());
    CHECK(allowed_scene_names() ==
          "planes, boxes, tree, butterfly, terrain, crowd, box, cutout, room, window, cornell");

    for (std::string_view name : rooms) {
        CAPTURE(name);
        const std::optional<Scene> a = make_scene(name);
        const std::optional<Scene> b = make_scene(name);
        REQUIRE(a.has_value());
        REQUIRE(b.has_value());
        const Scene& s = *a;
        CHECK(s.name == name);
        CHECK(bitwise_equal(s.mesh.positions, b->mesh.positions));
        CHECK(bitwise_equal(s.mesh.normals, b->mesh.normals));
        CHECK(bitwise_equal(s.mesh.indices, b->mesh.indices));
        CHECK(validate_mesh(s.mesh).empty());
        const auto [lo, hi] = compute_bounds(s.mesh);
        CHECK(lo == s.bounds_min);
        CHECK(hi == s.bounds_max);

        // Flat faces: every normal unit length, the winding agreeing with it, the three corners' alike.
        std::size_t bad_normal = 0, bad_winding = 0, smooth = 0;
        for (const glm::vec3& n : s.mesh.normals) bad_normal += std::abs(glm::length(n) - 1.0f) > 1e-4f;
        for (std::size_t t = 0; t < s.mesh.indices.size(); t += 3) {
            const auto ia = s.mesh.indices[t], ib = s.mesh.indices[t + 1], ic = s.mesh.indices[t + 2];
            const glm::vec3 g = glm::cross(s.mesh.positions[ib] - s.mesh.positions[ia],
                                           s.mesh.positions[ic] - s.mesh.positions[ia]);
            bad_winding += glm::dot(g, s.mesh.normals[ia]) <= 0.0f;
            smooth += s.mesh.normals[ia] != s.mesh.normals[ib] || s.mesh.normals[ia] != s.mesh.normals[ic];
        }
        CHECK(bad_normal == 0);
        CHECK(bad_winding == 0);
        CHECK(smooth == 0);

        // The light: an orthonormal frame, its centre inside the room's bounds.
        const penumbra::RectLight& light = s.light;
        CHECK(glm::length(light.u_axis) == doctest::Approx(1.0));
        CHECK(glm::length(light.v_axis) == doctest::Approx(1.0));
        CHECK(glm::dot(light.u_axis, light.v_axis) == doctest::Approx(0.0));
        CHECK(light.width > 0.0);
        CHECK(light.height > 0.0);
        const glm::dvec3 centre = light.center, normal = light.normal();
        CHECK(glm::all(glm::greaterThan(centre, glm::dvec3(s.bounds_min))));
        CHECK(glm::all(glm::lessThan(centre, glm::dvec3(s.bounds_max))));

        // Geometry behind the light's plane (the ceiling, or the wall the window is set in)...
        std::size_t behind = 0;
        for (const glm::vec3& p : s.mesh.positions) behind += glm::dot(glm::dvec3(p) - centre, normal) < 0.0;
        CHECK(behind >= 3);
        // ... right behind the light: a surface backs it, facing it, a few centimetres away at most.
        double backing = 0;
        const long back = nearest_hit(s.mesh, centre, -normal, backing);
        REQUIRE(back >= 0);
        CHECK(backing < 0.03);
        const glm::dvec3 back_normal(s.mesh.normals[s.mesh.indices[3 * static_cast<std::size_t>(back)]]);
        CHECK(glm::dot(back_normal, normal) > 0.99); // facing the light: along the light's own normal

        // Closed: a ray from the light's centre in each of the 26 directions towards the faces, edges and
        // corners of a cube meets a surface that faces the light (the room's inside, or furniture), except
        // through the Cornell box's open front (−z).
        std::size_t rays = 0, missed = 0, facing_away = 0;
        for (int x = -1; x <= 1; ++x)
            for (int y = -1; y <= 1; ++y)
                for (int z = -1; z <= 1; ++z) {
                    if (x == 0 && y == 0 && z == 0) continue;
                    if (name == "cornell" && z < 0) continue;
                    const glm::dvec3 direction = glm::normalize(glm::dvec3(x, y, z));
                    double distance = 0;
                    const long hit = nearest_hit(s.mesh, centre, direction, distance);
                    ++rays;
                    if (hit < 0) {
                        ++missed;
                        continue;
                    }
                    const glm::dvec3 n(s.mesh.normals[s.mesh.indices[3 * static_cast<std::size_t>(hit)]]);
                    facing_away += glm::dot(n, direction) >= 0.0;
                }
        CHECK(rays >= 17);
        CHECK(missed == 0);
        CHECK(facing_away == 0);

        // The camera: inside the room (room, window), or in front of the Cornell box's opening,
        // looking at something inside; near and far planes for a scene of a few metres.
        const glm::vec3 eye = s.camera.eye_position();
        CAPTURE(eye);
        CHECK(glm::all(glm::greaterThan(s.camera.target, s.bounds_min)));
        CHECK(glm::all(glm::lessThan(s.camera.target, s.bounds_max)));
        if (name == "cornell") {
            CHECK(eye.x == doctest::Approx(0.278f));
            CHECK(eye.y == doctest::Approx(0.273f));
            CHECK(eye.z == doctest::Approx(-0.8f));
            CHECK(glm::degrees(s.camera.fov_y_radians) == doctest::Approx(39.31f).epsilon(0.001));
            const glm::vec3 forward = glm::normalize(s.camera.target - eye);
            CHECK(forward.z == doctest::Approx(1.0f));
        } else {
            CHECK(glm::all(glm::greaterThan(eye, s.bounds_min)));
            CHECK(glm::all(glm::lessThan(eye, s.bounds_max)));
        }
        CHECK(s.camera.z_near > 0.0f);
        CHECK(s.camera.z_near < 0.05f);
        CHECK(s.camera.z_far > glm::length(s.bounds_max - s.bounds_min) + glm::length(eye - s.camera.target));
        CHECK(s.camera.z_far < 50.0f);
        CHECK(glm::length(s.sun.direction) == doctest::Approx(1.0));
        CHECK(s.sun.direction.y < 0.0);
    }
}

TEST_CASE("cornell: the published measurements in metres") {
    const Scene s = *make_scene("cornell");
    CHECK(s.bounds_min.x == 0.0f);
    CHECK(s.bounds_min.y == 0.0f);
    CHECK(s.bounds_min.z == 0.0f);
    CHECK(s.bounds_max.x == doctest::Approx(0.556f));
    CHECK(s.bounds_max.y == doctest::Approx(0.5488f));
    CHECK(s.bounds_max.z == doctest::Approx(0.5592f));
    CHECK(s.light.width == doctest::Approx(0.130));
    CHECK(s.light.height == doctest::Approx(0.105));
    CHECK(s.light.center.x == doctest::Approx(0.278));
    CHECK(s.light.center.y == doctest::Approx(0.5487));
    CHECK(s.light.center.z == doctest::Approx(0.2795));
    CHECK(s.light.normal().y == doctest::Approx(-1.0));
    // Five walls of two triangles each, two blocks of six faces (their bottoms added), no front wall.
    CHECK(s.mesh.triangle_count() == 2 * 5 + 2 * 2 * 6);
    // The blocks are closed parts (solid_casters), the walls are not (the front is open).
    std::size_t closed = 0;
    for (std::size_t t = 0; t < s.mesh.triangle_count(); ++t) closed += s.mesh.closed(t);
    CHECK(closed == 2 * 2 * 6);
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
