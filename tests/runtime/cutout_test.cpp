// tests/runtime/cutout_test.cpp — cut-out casters without a GPU: the cut materials of a mesh, the
// Embree truth's occlusion filter (a ray passes where a cut material's alpha is below its cutoff)
// and the CPU's slicing with and without the cut (reference/slice_coverage.hpp).
#include <doctest/doctest.h>

#include "temp_dir.hpp"

#include "bake/oim_bake.hpp"
#include "bake/oim_cache.hpp"
#include "reference/ground_truth.hpp"
#include "reference/slice_coverage.hpp"
#include "scenes/charts.hpp"
#include "scenes/gltf_loader.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/obj_loader.hpp"
#include "scenes/scenes.hpp"

#include <stb/stb_image_write.h> // implemented in the playground's image_io.cpp

#include <penumbra/light_frame.hpp>

#include <algorithm>
#include <vector>

using namespace penumbra;
using namespace penumbra::playground;
using penumbra::playground::testing::TempDir;

namespace {

// A PNG of `width` x `height` texels with `channels` channels (1 grey … 4 RGBA), as bytes.
std::string png(int width, int height, int channels, const std::vector<std::uint8_t>& texels) {
    std::string out;
    stbi_write_png_to_func(
        [](void* context, void* data, int size) {
            static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                                       static_cast<std::size_t>(size));
        },
        &out, width, height, channels, texels.data(), width * channels);
    return out;
}

// A unit quad in the xz plane (two triangles, TEXCOORD_0 (0,0) … (1,1)) drawn by three primitives
// with materials MASK (cutoff 0.4, texture: a 2 x 1 PNG, alpha 255 then 51, factor 0.5), BLEND (no
// texture, factor 0.3) and OPAQUE.
std::string masked_gltf(const std::string& image_uri) {
    return R"({
  "asset": {"version": "2.0"},
  "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0}],
  "meshes": [{"primitives": [
    {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 0},
    {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 1},
    {"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2, "material": 2}
  ]}],
  "materials": [
    {"name": "leaf", "alphaMode": "MASK", "alphaCutoff": 0.4,
     "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.5], "baseColorTexture": {"index": 0}}},
    {"name": "glass", "alphaMode": "BLEND", "pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.3]}},
    {"name": "stone"}
  ],
  "textures": [{"source": 0}],
  "images": [{"uri": ")" +
           image_uri + R"("}],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [0, 0, 0], "max": [1, 0, 1]},
    {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
    {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"}
  ],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 48},
    {"buffer": 0, "byteOffset": 48, "byteLength": 32},
    {"buffer": 0, "byteOffset": 80, "byteLength": 12}
  ],
  "buffers": [{"uri": "quad.bin", "byteLength": 92}]
})";
}

std::string quad_buffer() {
    std::string bin;
    auto put = [&](std::initializer_list<float> values) {
        for (float v : values) bin.append(reinterpret_cast<const char*>(&v), 4);
    };
    put({0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1});
    put({0, 0, 1, 0, 1, 1, 0, 1});
    const std::uint16_t indices[6] = {0, 2, 1, 0, 3, 2};
    bin.append(reinterpret_cast<const char*>(indices), sizeof indices);
    return bin;
}

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
    CHECK_FALSE(m.solid_at({0.75f, 0.25f}));     // 100 / 255 < 0.5
    CHECK(m.solid_at({0.25f, 0.75f}));           // 200 / 255 >= 0.5
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
    const SliceFrame frame = slice_frame(scene->light, glm::dvec3(scene->bounds_min),
                                         glm::dvec3(scene->bounds_max), config.slices);
    const SliceCoverage with = cpu_slice_coverage(mesh, config, frame, 1, true);
    const SliceCoverage without = cpu_slice_coverage(mesh, config, frame, 1, false);
    std::size_t covered_with = 0, covered_without = 0, gained = 0, removed = 0;
    for (std::size_t i = 0; i < with.texels.size(); ++i) {
        covered_with += with.texels[i] == Coverage::covered;
        covered_without += without.texels[i] == Coverage::covered;
        gained += with.texels[i] == Coverage::covered && without.texels[i] == Coverage::empty;
        removed += with.texels[i] == Coverage::empty && without.texels[i] == Coverage::covered;
    }
    MESSAGE("covered texels: ", covered_with, " with the cut, ", covered_without, " without (", removed,
            " cut away)");
    CHECK(gained == 0);   // the cut only removes coverage
    CHECK(removed > 300); // the holes of the grilles, between the pickets and around the leaves
}

TEST_CASE("glTF: MASK and BLEND materials cut (factor x texture alpha, cutoff), OPAQUE ones do not") {
    TempDir dir;
    dir.write("quad.bin", quad_buffer());
    dir.write("leaf.png", png(2, 1, 4, {0, 0, 0, 255, 0, 0, 0, 51}));
    const LoadResult r = load_gltf_scene(dir.write("quad.gltf", masked_gltf("leaf.png")));
    REQUIRE_MESSAGE(r.scene.has_value(), r.error);
    const Mesh& mesh = r.scene->mesh;
    CHECK(validate_mesh(mesh).empty());
    REQUIRE(mesh.cut_materials.size() == 2);
    const CutMaterial& leaf = mesh.cut_materials[0];
    CHECK(leaf.name == "material 0 'leaf'");
    CHECK(leaf.cutoff == doctest::Approx(0.4f));
    REQUIRE(leaf.texture.width == 2);
    CHECK(leaf.texture.alpha == std::vector<std::uint8_t>{128, 26}); // 255 x 0.5, 51 x 0.5
    const CutMaterial& glass = mesh.cut_materials[1];
    CHECK(glass.cutoff == 0.5f); // BLEND: a cut-out at 0.5
    CHECK(glass.texture.alpha == std::vector<std::uint8_t>{77});
    CHECK_FALSE(glass.solid_at({0.5f, 0.5f}));
    // the triangles: two per primitive, in order; the floor added under a mesh is not part of the file
    REQUIRE(mesh.triangle_materials.size() >= 6);
    CHECK(std::vector<std::int32_t>(mesh.triangle_materials.begin(), mesh.triangle_materials.begin() + 6) ==
          std::vector<std::int32_t>{0, 0, 1, 1, -1, -1});
    CHECK(mesh.material_uvs[2] == glm::vec2(1, 1));
    CHECK(mesh.solid_at(0, 0.1f, 0.1f));       // texture coordinate (0.2, 0.1): texel 0, 128 / 255 >= 0.4
    CHECK_FALSE(mesh.solid_at(0, 0.5f, 0.4f)); // (0.9, 0.5): texel 1, 26 / 255 < 0.4
    CHECK(r.warnings.empty());

    // An image that does not decode: a warning, the factor alone cuts (0.5 >= 0.4: solid)
    dir.write("broken.png", "not a png");
    const LoadResult broken = load_gltf_scene(dir.write("broken.gltf", masked_gltf("broken.png")));
    REQUIRE_MESSAGE(broken.scene.has_value(), broken.error);
    REQUIRE(broken.scene->mesh.cut_materials.size() == 2);
    CHECK(broken.scene->mesh.cut_materials[0].texture.alpha == std::vector<std::uint8_t>{128});
    REQUIRE(broken.warnings.size() == 1);
    CHECK(broken.warnings[0].find("material 0 'leaf' (alphaMode MASK): image 0") != std::string::npos);
    CHECK(broken.warnings[0].find("its alpha factor alone cuts") != std::string::npos);
}

TEST_CASE("OBJ: map_d and map_Kd with alpha cut at 0.5, an opaque map_Kd does not; v is flipped") {
    TempDir dir;
    dir.write("dissolve.png", png(1, 2, 1, {255, 0}));     // grey: top row solid, bottom cut
    dir.write("leaf.png", png(1, 1, 4, {10, 200, 10, 0})); // RGBA, alpha 0
    dir.write("bark.png", png(1, 1, 3, {90, 60, 30}));     // RGB: no alpha, never decoded
    dir.write("quad.mtl", "newmtl fence\nmap_d dissolve.png\nnewmtl leaf\nmap_Kd leaf.png\n"
                          "newmtl bark\nmap_Kd bark.png\nnewmtl plain\nKd 1 1 1\n");
    const std::string obj =
        "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "usemtl fence\nf 1/1 2/2 3/3\nusemtl leaf\nf 1/1 3/3 4/4\nusemtl bark\nf 1/1 2/2 3/3\n"
        "usemtl plain\nf 1/1 3/3 4/4\n";
    const LoadResult r = load_obj_scene(dir.write("quad.obj", obj));
    REQUIRE_MESSAGE(r.scene.has_value(), r.error);
    const Mesh& mesh = r.scene->mesh;
    CHECK(validate_mesh(mesh).empty());
    REQUIRE(mesh.cut_materials.size() == 2);
    CHECK(mesh.cut_materials[0].name == "material 'fence'");
    CHECK(mesh.cut_materials[0].texture.alpha == std::vector<std::uint8_t>{255, 0});
    CHECK(mesh.cut_materials[1].texture.alpha == std::vector<std::uint8_t>{0});
    REQUIRE(mesh.triangle_materials.size() >= 4);
    CHECK(std::vector<std::int32_t>(mesh.triangle_materials.begin(), mesh.triangle_materials.begin() + 4) ==
          std::vector<std::int32_t>{0, 1, -1, -1});
    // vt (0, 0) is the image's bottom row: material v = 1, the dissolve map's cut second row
    CHECK(mesh.material_uvs[mesh.indices[0]] == glm::vec2(0, 1));
    CHECK_FALSE(mesh.cut_materials[0].solid_at(mesh.material_uvs[mesh.indices[0]] * 0.999f));
    CHECK(mesh.cut_materials[0].solid_at({0.5f, 0.25f}));
    CHECK(r.warnings.empty());
}

TEST_CASE("oim: the bake casts through the cut with alpha_test on (its cache key says so)") {
    Scene scene = *make_scene("cutout");
    const int R = 64;
    REQUIRE(generate_charts(scene.mesh, R) == ""); // the charts keep the cut materials
    CHECK(validate_mesh(scene.mesh).empty());
    CHECK(scene.mesh.cuts());
    OimBakeSettings settings;
    settings.resolution = R;
    settings.samples = 256;
    settings.intervals = 16;
    const OimBake cut = bake_occlusion_intervals(scene.mesh, settings);
    const Mesh solid_mesh = without_cuts(scene.mesh);
    const OimBake solid = bake_occlusion_intervals(solid_mesh, settings);
    CHECK(oim_cache_key(scene.mesh, settings) != oim_cache_key(solid_mesh, settings));
    // over the day, texels see the sun longer through the cut than under solid casters (never shorter,
    // but where the intervals beyond 16 are merged)
    std::size_t longer = 0, shorter = 0;
    for (std::size_t texel = 0; texel < cut.covered.size(); ++texel) {
        if (!cut.covered[texel]) continue;
        const float a = cut.visibility(texel, 0.0, 1.0), b = solid.visibility(texel, 0.0, 1.0);
        longer += a > b + 1e-6f;
        shorter += a < b - 1e-6f;
    }
    MESSAGE("oim bake of cutout at 64x64: ", longer, " texels see the sun longer through the cut, ", shorter,
            " shorter");
    CHECK(longer > 50);
    CHECK(shorter * 10 < longer);
}
