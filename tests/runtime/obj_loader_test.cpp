// tests/runtime/obj_loader_test.cpp — OBJ files load, and bad ones give one clear line.
#include <doctest/doctest.h>

#include "scenes/mesh_builder.hpp"
#include "scenes/obj_loader.hpp"
#include "temp_dir.hpp"

#include <cmath>

using namespace penumbra::playground;
using penumbra::playground::testing::TempDir;

namespace {

const char* const cube_obj = R"(# unit cube, quads, no normals
o cube
v -1 -1 -1
v  1 -1 -1
v  1  1 -1
v -1  1 -1
v -1 -1  1
v  1 -1  1
v  1  1  1
v -1  1  1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 4 8 7 3
f 1 5 8 4
f 2 3 7 6
)";

// The error is one line that names the file.
void check_error(const LoadResult& r, const std::string& path, const std::string& needle) {
    CAPTURE(r.error);
    CHECK_FALSE(r.scene.has_value());
    CHECK(r.error.find(path) != std::string::npos);
    CHECK(r.error.find(needle) != std::string::npos);
    CHECK(r.error.find('\n') == std::string::npos);
}

} // namespace

TEST_CASE("OBJ: a quad cube without normals loads with computed smooth normals") {
    TempDir dir;
    const std::string path = dir.write("cube.obj", cube_obj);
    const LoadResult r = load_obj_scene(path);
    REQUIRE_MESSAGE(r.scene.has_value(), r.error);
    CHECK(r.error.empty());
    const Scene& s = *r.scene;
    CHECK(s.name == "cube");
    CHECK(s.mesh.triangle_count() == 12);
    CHECK(validate_mesh(s.mesh).empty());
    CHECK(s.bounds_min == glm::vec3(-1.0f));
    CHECK(s.bounds_max == glm::vec3(1.0f));
    for (std::size_t i = 0; i < s.mesh.positions.size(); ++i) {
        // Smooth normals of a cube corner point along the diagonal, outwards.
        CHECK(glm::length(s.mesh.normals[i]) == doctest::Approx(1.0f));
        CHECK(glm::dot(s.mesh.normals[i], glm::normalize(s.mesh.positions[i])) == doctest::Approx(1.0f).epsilon(1e-4));
    }
    // Default light above the bounds, facing down; camera looks at the centre.
    CHECK(s.light.center.y > s.bounds_max.y);
    CHECK(s.light.normal().y == doctest::Approx(-1.0));
    CHECK(s.camera.target == glm::vec3(0.0f));
    CHECK(glm::length(s.camera.eye_position()) > glm::length(glm::vec3(1.0f)));
}

TEST_CASE("OBJ: file normals are used; negative (relative) indices work") {
    TempDir dir;
    const std::string path = dir.write("tri.obj",
                                       "v 0 0 0\nv 1 0 0\nv 0 0 -1\nvn 0 2 0\n"
                                       "f -3//1 -2//1 -1//1\n");
    const LoadResult r = load_obj_scene(path);
    REQUIRE_MESSAGE(r.scene.has_value(), r.error);
    REQUIRE(r.scene->mesh.triangle_count() == 1);
    for (const glm::vec3& n : r.scene->mesh.normals) CHECK(n == glm::vec3(0, 1, 0)); // normalised
}

TEST_CASE("OBJ: errors are reported, never crash") {
    TempDir dir;

    SUBCASE("missing file") {
        const std::string path = dir.file("does-not-exist.obj");
        check_error(load_obj_scene(path), path, "does not exist");
    }
    SUBCASE("truncated face line") {
        const std::string path = dir.write("truncated.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2");
        check_error(load_obj_scene(path), path, "fewer than 3 vertices");
    }
    SUBCASE("vertex index out of range") {
        const std::string path = dir.write("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
        check_error(load_obj_scene(path), path, "vertex 7 but the file has 3 vertices");
    }
    SUBCASE("quad with an index out of range (tinyobjloader's own triangulation would read it)") {
        const std::string path = dir.write("quad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3 1000000\n");
        check_error(load_obj_scene(path), path, "vertex 1000000");
    }
    SUBCASE("relative index before the first vertex") {
        const std::string path = dir.write("relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -5 1 2\n");
        check_error(load_obj_scene(path), path, "relative");
    }
    SUBCASE("normal index out of range") {
        const std::string path = dir.write("normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 1 0\nf 1//1 2//1 3//4\n");
        check_error(load_obj_scene(path), path, "normal 4");
    }
    SUBCASE("zero index") {
        const std::string path = dir.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
        check_error(load_obj_scene(path), path, "line 4");
    }
    SUBCASE("no triangles") {
        const std::string path = dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nl 1 2\n");
        check_error(load_obj_scene(path), path, "no triangles");
    }
    SUBCASE("empty file") {
        const std::string path = dir.write("empty.obj", "");
        check_error(load_obj_scene(path), path, "no triangles");
    }
    SUBCASE("garbage") {
        const std::string path = dir.write("garbage.obj", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16));
        check_error(load_obj_scene(path), path, "no triangles");
    }
    SUBCASE("a directory") {
        check_error(load_obj_scene(dir.file("")), dir.file(""), "not a regular file");
    }
}
