// tests/runtime/gltf_compression_test.cpp — compressed glTF (playground/src/scenes/gltf_compression.hpp):
// Debian's Draco 2CylinderEngine matches the uncompressed .glb within the quantization its streams
// declare; files that Debian's gltfpack compresses with meshopt (-cc) match their source within
// the quantization their node scale declares; broken streams are one error line each.
#include <doctest/doctest.h>

#include "gltf_compression_files.hpp"
#include "scenes/gltf_loader.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/obj_loader.hpp"
#include "temp_dir.hpp"

#include <draco/attributes/attribute_quantization_transform.h>
#include <draco/compression/decode.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unordered_map>

using namespace penumbra::playground;
using penumbra::playground::testing::TempDir;
namespace fs = std::filesystem;
namespace t = penumbra::playground::testing;

namespace {

// For every point of `from`, the distance to the nearest point of `to` (a hash grid of cell
// `cell`, searched one cell around; a point farther than `cell` counts as `cell`·10).
double farthest_nearest(const std::vector<glm::vec3>& from, const std::vector<glm::vec3>& to, double cell) {
    auto key = [&](glm::dvec3 p) {
        const glm::dvec3 c = glm::floor(p / cell);
        return (std::uint64_t(std::int64_t(c.x) & 0x1fffff) << 42) |
               (std::uint64_t(std::int64_t(c.y) & 0x1fffff) << 21) |
               std::uint64_t(std::int64_t(c.z) & 0x1fffff);
    };
    std::unordered_map<std::uint64_t, std::vector<glm::vec3>> grid;
    for (const glm::vec3& p : to) grid[key(glm::dvec3(p))].push_back(p);
    double worst = 0;
    for (const glm::vec3& p : from) {
        double best = cell * 10;
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = grid.find(key(glm::dvec3(p) + glm::dvec3(dx, dy, dz) * cell));
                    if (it == grid.end()) continue;
                    for (const glm::vec3& q : it->second)
                        best = std::min(best, glm::length(glm::dvec3(p) - glm::dvec3(q)));
                }
        worst = std::max(worst, best);
    }
    return worst;
}

// Triangles whose three corners are distinct points (what a Draco encoder keeps).
std::size_t proper_triangles(const Mesh& mesh, std::vector<glm::vec3>* corners) {
    std::size_t n = 0;
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const glm::vec3 a = mesh.positions[mesh.indices[i]], b = mesh.positions[mesh.indices[i + 1]],
                        c = mesh.positions[mesh.indices[i + 2]];
        if (a == b || b == c || a == c) continue;
        ++n;
        if (corners) corners->insert(corners->end(), {a, b, c});
    }
    return n;
}

// The largest position quantization step of the file's Draco streams (range / (2^bits − 1)).
double draco_position_step(const fs::path& gltf) {
    const nlohmann::json j = nlohmann::json::parse(t::read_binary(gltf.string()));
    const std::string bin =
        t::read_binary((gltf.parent_path() / j["buffers"][0]["uri"].get<std::string>()).string());
    double step = 0;
    for (const auto& mesh : j["meshes"])
        for (const auto& p : mesh["primitives"]) {
            const auto& ext = p["extensions"]["KHR_draco_mesh_compression"];
            const auto& view = j["bufferViews"][ext["bufferView"].get<std::size_t>()];
            draco::DecoderBuffer buffer;
            buffer.Init(bin.data() + view.value("byteOffset", 0), view["byteLength"].get<std::size_t>());
            draco::Decoder decoder;
            decoder.SetSkipAttributeTransform(
                draco::GeometryAttribute::POSITION); // keeps the quantization data
            auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
            REQUIRE(decoded.ok());
            const draco::PointAttribute* position =
                decoded.value()->GetAttributeByUniqueId(ext["attributes"]["POSITION"].get<std::uint32_t>());
            REQUIRE(position != nullptr);
            draco::AttributeQuantizationTransform q;
            REQUIRE(q.InitFromAttribute(*position)); // the stream declares its quantization
            step = std::max(step, double(q.range()) / double((1 << q.quantization_bits()) - 1));
        }
    return step;
}

} // namespace

TEST_CASE("glTF compression: Draco 2CylinderEngine of assimp-testmodels matches the uncompressed .glb") {
    const fs::path root = "/usr/share/assimp/models/glTF2";
    if (!fs::is_regular_file(root / "draco/2CylinderEngine.gltf")) {
        MESSAGE("assimp-testmodels is not installed (scripts/setup.sh installs it): skipped");
        return;
    }
    const LoadResult draco = load_gltf_scene((root / "draco/2CylinderEngine.gltf").string());
    const LoadResult plain =
        load_gltf_scene((root / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb").string());
    REQUIRE_MESSAGE(draco.scene, draco.error);
    REQUIRE_MESSAGE(plain.scene, plain.error);
    CHECK(draco.warnings.empty());
    // The Draco encoder dropped the .glb's 11,160 degenerate triangles (11,154 repeat an index,
    // 6 repeat a position); every other triangle is there.
    std::vector<glm::vec3> plain_corners;
    const std::size_t plain_proper = proper_triangles(plain.scene->mesh, &plain_corners);
    CHECK(plain.scene->mesh.triangle_count() == 121496);
    CHECK(plain_proper == 110336);
    CHECK(draco.scene->mesh.triangle_count() == plain_proper);
    CHECK(validate_mesh(draco.scene->mesh).empty());

    // Positions: within half a quantization step per axis of the .glb's (the node matrices of this
    // file are rotations and translations, so the step is the same in world space), both ways.
    const double step = draco_position_step(root / "draco/2CylinderEngine.gltf");
    const double tolerance = step * std::sqrt(3.0) / 2 + 1e-4; // + float rounding of the world transform
    const double draco_to_plain = farthest_nearest(draco.scene->mesh.positions, plain_corners, 1.0);
    const double plain_to_draco = farthest_nearest(plain_corners, draco.scene->mesh.positions, 1.0);
    MESSAGE("2CylinderEngine Draco: " << draco.scene->mesh.triangle_count()
                                      << " triangles; largest position step " << step << "; farthest vertex "
                                      << draco_to_plain << " / " << plain_to_draco);
    CHECK(step > 0);
    CHECK(step < 0.5); // the engine is 743 units long: at least 11 bits
    CHECK(draco_to_plain <= tolerance);
    CHECK(plain_to_draco <= tolerance);
}

TEST_CASE("glTF compression: gltfpack -cc (meshopt, quantized) files match their source OBJ") {
    if (!t::have_gltfpack()) {
        MESSAGE("gltfpack is not installed (scripts/setup.sh installs it): skipped");
        return;
    }
    TempDir dir;
    const std::string obj = dir.write("torus.obj", t::torus_obj());
    const LoadResult source = load_obj_scene(obj);
    REQUIRE_MESSAGE(source.scene, source.error);
    for (const std::string name : {"torus.glb", "torus.gltf"}) {
        CAPTURE(name);
        REQUIRE(t::run_gltfpack(obj, dir.file(name)));
        // What the file declares: meshopt streams, and positions as 14-bit integers scaled by the node.
        std::string json = t::read_binary(dir.file(name));
        if (json.starts_with("glTF"))
            json = json.substr(20, *reinterpret_cast<const std::uint32_t*>(json.data() + 12));
        const nlohmann::json j = nlohmann::json::parse(json);
        CHECK(j["extensionsRequired"].dump().find("EXT_meshopt_compression") != std::string::npos);
        CHECK(j["extensionsRequired"].dump().find("KHR_mesh_quantization") != std::string::npos);
        const double step = j["nodes"][0]["scale"][0].get<double>();
        CHECK(step > 0);

        const LoadResult packed = load_gltf_scene(dir.file(name));
        REQUIRE_MESSAGE(packed.scene, packed.error);
        CHECK(packed.warnings.empty());
        const Mesh& a = source.scene->mesh;
        const Mesh& b = packed.scene->mesh;
        CHECK(b.triangle_count() == a.triangle_count());
        const double tolerance = step * std::sqrt(3.0) / 2 * 1.001;
        const double ab = farthest_nearest(a.positions, b.positions, 0.1);
        const double ba = farthest_nearest(b.positions, a.positions, 0.1);
        MESSAGE(name << ": " << b.triangle_count() << " triangles; step " << step << "; farthest vertex "
                     << ab << " / " << ba);
        CHECK(ab <= tolerance);
        CHECK(ba <= tolerance);
        // Normals: 8-bit octahedral (the OCTAHEDRAL filter); each within a few degrees of the
        // analytic torus normal at its position.
        double worst_cos = 1;
        for (std::size_t i = 0; i < b.positions.size(); ++i) {
            const glm::vec3 p = b.positions[i];
            const glm::vec3 ring = glm::normalize(glm::vec3(p.x, 0, p.z)) * t::torus_major;
            worst_cos = std::min(worst_cos, double(glm::dot(b.normals[i], glm::normalize(p - ring))));
        }
        MESSAGE(name << ": largest normal error " << std::acos(std::min(1.0, worst_cos)) * 180 / M_PI
                     << " degrees");
        CHECK(worst_cos > std::cos(3.0 * M_PI / 180));
    }
}

TEST_CASE("glTF compression: animation rotations (QUATERNION filter) decode; the mesh loads as before") {
    const fs::path source = "/usr/share/assimp/models/glTF2/simple_skin/simple_skin.gltf";
    if (!t::have_gltfpack() || !fs::is_regular_file(source)) {
        MESSAGE("gltfpack or assimp-testmodels is not installed (scripts/setup.sh installs them): skipped");
        return;
    }
    TempDir dir;
    REQUIRE(t::run_gltfpack(source.string(), dir.file("skin.gltf")));
    CHECK(t::read_binary(dir.file("skin.gltf")).find("\"QUATERNION\"") != std::string::npos);
    const LoadResult packed = load_gltf_scene(dir.file("skin.gltf"));
    const LoadResult plain = load_gltf_scene(source.string());
    REQUIRE_MESSAGE(packed.scene, packed.error);
    REQUIRE_MESSAGE(plain.scene, plain.error);
    CHECK(packed.scene->mesh.triangle_count() == plain.scene->mesh.triangle_count());
}

// Broken streams, each one line naming the stream and what is wrong (the same files go through
// penumbra-playground in tests/hostile/hostile_cases_test.cpp).
TEST_CASE("glTF compression: broken Draco and meshopt streams are one error line") {
    TempDir dir;
    const std::vector<t::BrokenCompressedFile> cases = t::broken_compressed_files(dir.file(""));
    if (cases.empty()) {
        MESSAGE("gltfpack or assimp-testmodels is not installed (scripts/setup.sh installs them): skipped");
        return;
    }
    CHECK(cases.size() >= 8);
    for (const t::BrokenCompressedFile& c : cases) {
        CAPTURE(c.name);
        const LoadResult r = load_gltf_scene(c.path);
        CAPTURE(r.error);
        CHECK_FALSE(r.scene.has_value());
        CHECK(r.error.find('\n') == std::string::npos);
        CHECK(r.error.find(c.path) != std::string::npos);
        CHECK(r.error.find(c.expected) != std::string::npos);
    }
}
