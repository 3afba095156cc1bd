// Which triangles belong to a closed part (scenes/closed_parts.hpp): the parts solid_casters fills
// between their surfaces. Closed means every edge is used an even number of times within the part.
#include "scenes/closed_parts.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/scenes.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>

using namespace penumbra::playground;

namespace {

std::size_t closed_count(const Mesh& mesh) {
    const std::vector<std::uint8_t> closed = closed_triangles(mesh);
    REQUIRE(closed.size() == mesh.triangle_count());
    return static_cast<std::size_t>(std::count(closed.begin(), closed.end(), std::uint8_t{1}));
}

} // namespace

TEST_CASE("closed parts: a box is closed, a ground quad is open, each part on its own") {
    Mesh mesh;
    add_horizontal_rect(mesh, 0.0f, 0.0f, 0.0f, 10.0f, 10.0f); // 2 triangles, open
    add_box(mesh, glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 1.0f, 0.0f)));   // 12, closed
    add_box(mesh, glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 1.0f, 0.0f)));   // 12, closed
    const std::vector<std::uint8_t> closed = closed_triangles(mesh);
    CHECK(closed[0] == 0);
    CHECK(closed[1] == 0);
    CHECK(closed_count(mesh) == 24);
}

TEST_CASE("closed parts: a box missing a face is open, so is one with a face twice; four faces on an edge pair up") {
    Mesh box;
    add_box(box, glm::mat4(1.0f));
    Mesh missing = box;
    missing.indices.resize(missing.indices.size() - 3); // one triangle less: three edges used once
    CHECK(closed_count(missing) == 0);
    Mesh doubled = box; // a face twice cancels out of the XOR: a hole
    doubled.indices.insert(doubled.indices.end(), box.indices.begin(), box.indices.begin() + 3);
    CHECK(closed_count(doubled) == 0);
    Mesh touching = box; // two boxes sharing one vertical edge: one part, four triangles on that edge
    add_box(touching, glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 1.0f)));
    CHECK(closed_count(touching) == 24);
}

TEST_CASE("closed parts: the procedural scenes, as finish_scene marks them") {
    // crowd: every figure's boxes closed, the ground open; tree: the leaf cards open, trunk and branches closed;
    // planes: open sheets only
    const std::optional<Scene> crowd = make_scene("crowd");
    REQUIRE(crowd);
    CHECK(crowd->mesh.triangle_closed.size() == crowd->mesh.triangle_count());
    CHECK(closed_count(crowd->mesh) == crowd->mesh.triangle_count() - 2);
    const std::optional<Scene> tree = make_scene("tree");
    REQUIRE(tree);
    CHECK(closed_count(tree->mesh) == 12 * 7); // the trunk and six branches
    const std::optional<Scene> planes = make_scene("planes");
    REQUIRE(planes);
    CHECK(closed_count(planes->mesh) == 0);
    // cut-out cards are never closed, whatever their edges
    const std::optional<Scene> cutout = make_scene("cutout");
    REQUIRE(cutout);
    for (std::size_t t = 0; t < cutout->mesh.triangle_count(); ++t)
        if (cutout->mesh.material_of(t)) CHECK(!cutout->mesh.closed(t));
}
