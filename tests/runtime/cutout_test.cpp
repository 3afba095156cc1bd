// tests/runtime/cutout_test.cpp — cut-out casters without a GPU: the cut materials of a mesh, the
// Embree truth's occlusion filter (a ray passes where a cut material's alpha is below its cutoff)
// and the CPU's slicing with and without the cut (reference/slice_coverage.hpp).
#include <doctest/doctest.h>

#include "reference/ground_truth.hpp"
#include "reference/slice_coverage.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/light_frame.hpp>

#include <algorithm>
#include <vector>

using namespace penumbra;
using namespace penumbra::playground;

namespace {

// A 2 x 2 quad at height 1 over x, z in [-1, 1] whose texture is solid on its left half (x < 0) and
// cut on its right half: two texels, u = 0 at x = -1. `alpha_right`: the right texel's alpha.
Mesh half_cut_quad(std::uint8_t alpha_right, float cutoff) {
    Mesh mesh;
    mesh.cut_materials = {{"half", {2, 1, {255, alpha_right}}, cutoff}};
    add_cut_quad(mesh, {-1, 1, 1}, {1, 1, 1}, {1, 1, -1}, {-1, 1, -1}, 0, {0, 0}, {1, 0}, {1, 1}, {0, 1});
    return mesh;
}

} // namespace

TEST_CASE("cut materials: the alpha texture is read nearest with repeat, and the cutoff decides") {
    const CutMaterial m{"m", {2, 2, {0, 100, 200, 255}}, 0.5f};
    CHECK(m.texture.at({0.25f, 0.25f}) == 0);
    CHECK(m.texture.at({0.75f, 0.25f}) == 100);
    CHECK(m.texture.at({0.25f, 0.75f}) == 200);
    CHECK(m.texture.at({1.75f, -0.25f}) == 255); // repeat: (0.75, 0.75)
    CHECK_FALSE(m.solid_at({0.75f, 0.25f}));      // 100 / 255 < 0.5
    CHECK(m.solid_at({0.25f, 0.75f}));            // 200 / 255 >= 0.5
    Mesh bad = half_cut_quad(0, 0.5f);
    CHECK(validate_mesh(bad).empty());
    bad.triangle_materials[1] = 3;
    CHECK(validate_mesh(bad).find("triangle 1 has material 3") != std::string::npos);
    bad = half_cut_quad(0, 1.5f);
    CHECK(validate_mesh(bad).find("alpha cutoff") != std::string::npos);
}

TEST_CASE("ground truth: rays pass where a cut material's alpha is below its cutoff (occlusion filter)") {
    SunLight sun; // straight down, a small disk
    const std::vector<glm::vec3> points{{-0.5f, 0, 0}, {0.5f, 0, 0}};
    const std::vector<glm::vec3> normals(points.size(), glm::vec3(0, 1, 0));
    {
        const GroundTruth truth(half_cut_quad(0, 0.5f));
        const std::vector<float> v = truth.visibility(points, normals, sun, 8);
        CHECK(v[0] == 0.0f); // under the solid half
        CHECK(v[1] == 1.0f); // under the cut half
    }
    {
        const GroundTruth truth(half_cut_quad(200, 0.5f)); // 200 / 255 is above the cutoff: solid
        CHECK(truth.visibility(points, normals, sun, 8)[1] == 0.0f);
    }
    {
        const GroundTruth truth(half_cut_quad(200, 0.9f)); // a higher cutoff cuts it
        CHECK(truth.visibility(points, normals, sun, 8)[1] == 1.0f);
    }
    {
        const GroundTruth solid(without_cuts(half_cut_quad(0, 0.5f))); // the casters solid
        CHECK(solid.visibility(points, normals, sun, 8)[1] == 0.0f);
    }
}

TEST_CASE("the cutout scene: cut materials well formed, deterministic, and the cut removes slice coverage") {
    const std::optional<Scene> scene = make_scene("cutout");
    REQUIRE(scene);
    const Mesh& mesh = scene->mesh;
    CHECK(validate_mesh(mesh).empty());
    REQUIRE(mesh.cut_materials.size() == 3);
    CHECK(mesh.material_uvs.size() == mesh.positions.size());
    CHECK(mesh.triangle_materials.size() == mesh.triangle_count());
    const auto cut = std::count_if(mesh.triangle_materials.begin(), mesh.triangle_materials.end(),
                                   [](std::int32_t m) { return m >= 0; });
    CHECK(cut > 200); // leaf cards, grilles, the fence
    CHECK(make_scene("cutout")->mesh.material_uvs == mesh.material_uvs);
    for (const CutMaterial& m : mesh.cut_materials) {
        const auto holes = std::count_if(m.texture.alpha.begin(), m.texture.alpha.end(),
                                         [&](std::uint8_t a) { return a < m.cutoff * 255.0f; });
        CAPTURE(m.name);
        CHECK(holes > 0);
        CHECK(holes < static_cast<long>(m.texture.alpha.size()));
    }
    const Config config{.slices = 8, .resolution = 128};
    const SliceFrame frame = slice_frame(scene->light, glm::dvec3(scene->bounds_min), glm::dvec3(scene->bounds_max),
                                         config.slices);
    const SliceCoverage with = cpu_slice_coverage(mesh, config, frame, 1, true);
    const SliceCoverage without = cpu_slice_coverage(mesh, config, frame, 1, false);
    std::size_t covered_with = 0, covered_without = 0, gained = 0;
    for (std::size_t i = 0; i < with.texels.size(); ++i) {
        covered_with += with.texels[i] == Coverage::covered;
        covered_without += without.texels[i] == Coverage::covered;
        gained += with.texels[i] == Coverage::covered && without.texels[i] == Coverage::empty;
    }
    MESSAGE("covered texels: ", covered_with, " with the cut, ", covered_without, " without");
    CHECK(gained == 0);                              // the cut only removes coverage
    CHECK(covered_with < covered_without * 9 / 10); // and removes a good part of it
}
