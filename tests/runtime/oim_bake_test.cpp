// tests/runtime/oim_bake_test.cpp — occlusion interval maps without GL: the sun's path, unique
// texture coordinates, the Embree bake against Embree's visibility of the same linear light, and
// the disk cache.
#include <doctest/doctest.h>

#include "bake/oim_bake.hpp"
#include "bake/oim_cache.hpp"
#include "reference/ground_truth.hpp"
#include "scenes/charts.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/obj_loader.hpp"
#include "scenes/scenes.hpp"
#include "scenes/uv_coverage.hpp"
#include "temp_dir.hpp"

#include <penumbra/sun_path.hpp>

#include <algorithm>
#include <cmath>

using namespace penumbra::playground;

namespace {

std::string first_message(const penumbra::SunPath& path) {
    const auto errors = penumbra::validate(path);
    return errors.empty() ? std::string() : errors.front().message;
}

Scene charted(const char* name, int resolution) {
    Scene scene = *make_scene(name);
    REQUIRE(generate_charts(scene.mesh, resolution) == "");
    return scene;
}

} // namespace

TEST_CASE("oim: the sun's path is validated with messages naming the problem") {
    CHECK(first_message(penumbra::SunPath{}) == "");
    CHECK(first_message(penumbra::SunPath{{}}).starts_with("sun_path: 0 point(s) is too short; allowed: two or more"));
    CHECK(first_message(penumbra::SunPath{{{180, 40}}}).starts_with("sun_path: 1 point(s) is too short"));
    CHECK(first_message(penumbra::SunPath{{{90, 30}, {90, 30}}}).find("has zero length") != std::string::npos);
    CHECK(first_message(penumbra::SunPath{{{90, -5}, {180, -10}, {270, 0}}}).find("never rise above the horizon") !=
          std::string::npos);
    CHECK(first_message(penumbra::SunPath{{{90, 30}, {180, 95}}}) ==
          "sun_path[1].elevation: 95 is out of range; allowed: -90 to 90 degrees");
    CHECK(first_message(penumbra::SunPath{{{90, 0}, {270, 0}}}).find("opposite directions") != std::string::npos);
}

TEST_CASE("oim: path directions, speed and the window of the sun's disk") {
    const penumbra::SunPath path; // three points, two segments
    const glm::dvec3 noon = penumbra::sun_direction(path, 0.5);
    CHECK(noon.y == doctest::Approx(std::sin(glm::radians(50.0))).epsilon(1e-12));
    CHECK(noon.z == doctest::Approx(std::cos(glm::radians(50.0))).epsilon(1e-12)); // south is +z
    const glm::dvec3 morning = penumbra::sun_direction(path, 0.0);
    CHECK(morning.x > 0.9); // east is +x
    // Constant angular speed along a segment: the angle covered over dt is speed·dt.
    const double speed = penumbra::sun_speed(path, 0.2);
    const double angle = std::acos(glm::dot(penumbra::sun_direction(path, 0.1), penumbra::sun_direction(path, 0.3)));
    CHECK(angle == doctest::Approx(0.2 * speed).epsilon(1e-9));
    const penumbra::SunWindow w = penumbra::sun_window(path, 0.25, 0.05);
    CHECK((w.end - w.start) * speed == doctest::Approx(0.05));
    CHECK(w.inverse_width == doctest::Approx(1.0 / (w.end - w.start)));
    const penumbra::SunWindow hard = penumbra::sun_window(path, 0.25, 0.0);
    CHECK(hard.end - hard.start == doctest::Approx(penumbra::min_window_width));
}

TEST_CASE("oim: every procedural scene gets non-overlapping charts") {
    for (std::string_view name : scene_names()) {
        CAPTURE(name);
        Scene scene = *make_scene(name);
        const int resolution = name == "crowd" ? 1024 : 256;
        REQUIRE(generate_charts(scene.mesh, resolution) == "");
        CHECK(validate_mesh(scene.mesh) == "");
        CHECK(check_unique_uvs(scene.mesh, resolution) == "");
        // Conservative texels: the texel under every triangle's centroid stands for a point near it.
        const std::vector<TexelSample> texels = texel_samples(scene.mesh, resolution);
        std::size_t far = 0;
        for (std::size_t t = 0; t < scene.mesh.triangle_count(); ++t) {
            const std::uint32_t* v = &scene.mesh.indices[3 * t];
            const glm::vec2 uv = (scene.mesh.uvs[v[0]] + scene.mesh.uvs[v[1]] + scene.mesh.uvs[v[2]]) / 3.0f;
            const glm::vec3 p = (scene.mesh.positions[v[0]] + scene.mesh.positions[v[1]] + scene.mesh.positions[v[2]]) / 3.0f;
            const glm::ivec2 texel = glm::clamp(glm::ivec2(uv * static_cast<float>(resolution)), 0, resolution - 1);
            const TexelSample& s = texels[static_cast<std::size_t>(texel.y * resolution + texel.x)];
            REQUIRE(s.triangle >= 0);
            // within a texel's world size plus the triangle's own extent
            const float extent = glm::length(scene.mesh.positions[v[1]] - scene.mesh.positions[v[0]]) +
                                 glm::length(scene.mesh.positions[v[2]] - scene.mesh.positions[v[0]]);
            far += glm::length(s.position - p) > extent + 0.2f;
        }
        CHECK(far == 0);
    }
    Scene crowd = *make_scene("crowd");
    CHECK(generate_charts(crowd.mesh, 64).find("charts do not fit in 64x64 texels") != std::string::npos);
}

TEST_CASE("oim: an OBJ keeps its texture coordinates when unique, and is refused when they overlap") {
    testing::TempDir dir;
    const std::string quads = "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nv 0 1 0\nv 1 1 0\nv 1 1 -1\nv 0 1 -1\n";
    const std::string unique = dir.write("unique.obj", quads +
        "vt 0.05 0.05\nvt 0.45 0.05\nvt 0.45 0.45\nvt 0.05 0.45\nvt 0.55 0.55\nvt 0.95 0.55\nvt 0.95 0.95\nvt 0.55 0.95\n"
        "f 1/1 2/2 3/3 4/4\nf 5/5 6/6 7/7 8/8\n");
    const std::string tiled = dir.write("tiled.obj", quads + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                                             "f 1/1 2/2 3/3 4/4\nf 5/1 6/2 7/3 8/4\n");
    const std::string bare = dir.write("bare.obj", quads + "f 1 2 3 4\nf 5 6 7 8\n");
    LoadResult a = load_obj_scene(unique), b = load_obj_scene(tiled), c = load_obj_scene(bare);
    REQUIRE(a.scene);
    REQUIRE(b.scene);
    REQUIRE(c.scene);
    CHECK(a.scene->mesh.uvs.size() == a.scene->mesh.positions.size());
    CHECK(check_unique_uvs(a.scene->mesh, 64) == "");
    CHECK(check_unique_uvs(b.scene->mesh, 64).starts_with("texture coordinates overlap: triangles 0 and 2"));
    CHECK(check_unique_uvs(c.scene->mesh, 64).starts_with("has no texture coordinates"));
    CHECK_FALSE(a.scene->generated_charts);
}

TEST_CASE("oim: visibility runs keep up to the capacity, merging what changes least") {
    bool merged = false;
    //                     0  1  2  3  4  5  6  7  8  9
    std::vector<std::uint8_t> v{0, 1, 1, 0, 1, 0, 0, 0, 1, 1};
    CHECK(visibility_runs(v, 4, &merged) == std::vector<std::pair<int, int>>{{1, 3}, {4, 5}, {8, 10}});
    CHECK_FALSE(merged);
    // Two runs allowed: the one-sample gap 3 is filled (cheaper than dropping a run).
    CHECK(visibility_runs(v, 2, &merged) == std::vector<std::pair<int, int>>{{1, 5}, {8, 10}});
    CHECK(merged);
    CHECK(visibility_runs(std::vector<std::uint8_t>(5, 0), 4, &merged).empty());
}

TEST_CASE("oim: the bake equals Embree's visibility of the same linear light along the path") {
    const int R = 64, S = 256;
    const Scene scene = charted("planes", R);
    OimBakeSettings settings;
    settings.resolution = R;
    settings.samples = S;
    const OimBake bake = bake_occlusion_intervals(scene.mesh, settings);
    MESSAGE("planes bake " << R << "x" << R << ", " << S << " samples: " << bake.bake_ms << " ms, " << bake.rays
                           << " rays");
    CHECK(bake.merged_texels == 0);
    const std::vector<TexelSample> texels = texel_samples(scene.mesh, R);
    std::vector<glm::vec3> positions, normals;
    std::vector<std::size_t> ids;
    for (std::size_t i = 0; i < texels.size(); ++i)
        if (texels[i].triangle >= 0) {
            positions.push_back(texels[i].position);
            normals.push_back(texels[i].normal);
            ids.push_back(i);
        }
    REQUIRE(ids.size() > 1000);
    const GroundTruth truth(scene.mesh);

    SUBCASE("a zero-width window is the hard shadow: the same rays at a sample instant") {
        const std::vector<glm::vec3> directions = sample_directions(settings.path, S);
        for (int i : {40, 128, 200}) {
            const double t = (i + 0.5) / S;
            const penumbra::SunWindow w = penumbra::sun_window(settings.path, t, 0.0);
            const std::vector<std::uint8_t> open = truth.unoccluded(positions, normals, {&directions[i], 1});
            std::size_t wrong = 0, lit = 0;
            for (std::size_t k = 0; k < ids.size(); ++k) {
                const float v = bake.visibility(ids[k], w.start, w.end);
                wrong += std::abs(v - static_cast<float>(open[k])) > 1e-4f;
                lit += open[k];
            }
            CAPTURE(i);
            CHECK(wrong == 0);
            CHECK(lit > ids.size() / 4);
            CHECK(lit < ids.size()); // the occluders shadow the ground
        }
    }
    SUBCASE("soft: the window of a sun five times the real one, against 64 instants inside it") {
        const double diameter = 0.0093 * 5.0;
        for (double t : {0.3, 0.5, 0.71}) {
            const penumbra::SunWindow w = penumbra::sun_window(settings.path, t, diameter);
            std::vector<glm::vec3> window;
            const int M = 64;
            for (int m = 0; m < M; ++m)
                window.push_back(glm::vec3(penumbra::sun_direction(settings.path, w.start + (m + 0.5) / M * (w.end - w.start))));
            const std::vector<float> expected = truth.visibility(positions, normals, window);
            double total = 0.0;
            std::size_t beyond = 0, soft = 0;
            for (std::size_t k = 0; k < ids.size(); ++k) {
                const double v = bake.visibility(ids[k], w.start, w.end);
                // Bound: every edge near the window moves by at most half a bake step, and the
                // 64-instant truth misplaces each edge by at most half of its own step.
                int edges = 0;
                for (int e = 0; e < bake.intervals; ++e) {
                    const std::size_t at = ids[k] * static_cast<std::size_t>(bake.intervals) + static_cast<std::size_t>(e);
                    if (bake.rise[at] == bake.fall[at]) continue;
                    for (std::uint16_t edge : {bake.rise[at], bake.fall[at]}) {
                        const double te = static_cast<double>(edge) / S;
                        edges += te > w.start - 1.0 / S && te < w.end + 1.0 / S;
                    }
                }
                const double bound = edges * (0.5 / S * w.inverse_width + 1.0 / M) + 1e-4;
                const double error = std::abs(v - expected[k]);
                total += error;
                beyond += error > bound;
                soft += expected[k] > 0.02f && expected[k] < 0.98f;
            }
            CAPTURE(t);
            CHECK(beyond == 0);
            CHECK(total / static_cast<double>(ids.size()) < 0.01);
            CHECK(soft > 10); // there is a penumbra to get right
        }
    }
}

TEST_CASE("oim: the bake cache is keyed by scene, path and resolution and written atomically") {
    testing::TempDir dir;
    const Scene scene = charted("planes", 32);
    OimBakeSettings settings;
    settings.resolution = 32;
    settings.intervals = 4;
    const std::string key = oim_cache_key(scene.mesh, settings);
    CHECK(key.size() == 32);
    OimBakeSettings other_path = settings;
    other_path.path.points[1].elevation_degrees = 55.0;
    OimBakeSettings other_resolution = settings;
    other_resolution.resolution = 64;
    Scene moved = scene;
    moved.mesh.positions[5].y += 0.01f;
    CHECK(oim_cache_key(scene.mesh, other_path) != key);
    CHECK(oim_cache_key(scene.mesh, other_resolution) != key);
    CHECK(oim_cache_key(moved.mesh, settings) != key);

    const std::filesystem::path folder = std::filesystem::path(dir.file("cache")) / "oim";
    const CachedBake first = bake_with_cache(scene.mesh, settings, folder);
    CHECK_FALSE(first.from_cache);
    CHECK(first.warning == "");
    CHECK(first.file_bytes > 32u * 32u * 4u * 4u);
    const CachedBake second = bake_with_cache(scene.mesh, settings, folder);
    CHECK(second.from_cache);
    CHECK(second.bake.rise == first.bake.rise);
    CHECK(second.bake.fall == first.bake.fall);
    CHECK(second.bake.bake_ms == first.bake.bake_ms);
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::directory_iterator(folder)) {
        ++files;
        CHECK(entry.path().extension() == ".bin"); // no temporary left behind
    }
    CHECK(files == 1);
    // A truncated file is not used.
    std::filesystem::resize_file(first.file, first.file_bytes - 10);
    CHECK_FALSE(read_cached_bake(folder, key, settings));
    CHECK_FALSE(bake_with_cache(scene.mesh, settings, folder).from_cache);
}
