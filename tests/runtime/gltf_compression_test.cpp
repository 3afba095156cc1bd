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
#include <meshoptimizer.h>
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

// gltfpack 0.18 writes no EXPONENTIAL filter, no INDICES mode and no 4-byte indices: a .glb
// written here with libmeshoptimizer's encoder has all three (float positions through
// meshopt_encodeFilterExp, 15-bit mantissas), and a fallback buffer without data.
TEST_CASE("glTF compression: EXPONENTIAL-filtered positions and INDICES-mode 32-bit indices decode") {
    std::vector<float> positions;
    std::vector<unsigned int> indices;
    const int n = 12;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) // magnitudes from 1e-3 to 1e3, so the exponents differ
            positions.insert(
                positions.end(),
                {float(i - 5) * 100.0f, std::sin(float(i * j)) * 1e-3f + float(j) * 0.01f, float(j) * 37.5f});
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const unsigned int a = unsigned(i * n + j), b = a + 1, c = a + unsigned(n), d = c + 1;
            indices.insert(indices.end(), {a, c, b, b, c, d});
        }
    const std::size_t count = positions.size() / 3;
    std::vector<unsigned char> filtered(count * 12);
    meshopt_encodeFilterExp(filtered.data(), count, 12, 15, positions.data());
    std::string vertex_stream(meshopt_encodeVertexBufferBound(count, 12), '\0');
    vertex_stream.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(vertex_stream.data()),
                                                    vertex_stream.size(), filtered.data(), count, 12));
    std::string index_stream(meshopt_encodeIndexSequenceBound(indices.size(), count), '\0');
    index_stream.resize(meshopt_encodeIndexSequence(reinterpret_cast<unsigned char*>(index_stream.data()),
                                                    index_stream.size(), indices.data(), indices.size()));
    while (vertex_stream.size() % 4) vertex_stream += '\0';
    std::string bin = vertex_stream + index_stream;
    while (bin.size() % 4) bin += '\0';
    using J = nlohmann::json;
    auto meshopt = [](std::size_t offset, std::size_t length, std::size_t stride, std::size_t n_,
                      const char* mode) {
        J e = {{"buffer", 0},          {"byteOffset", offset}, {"byteLength", length},
               {"byteStride", stride}, {"count", n_},          {"mode", mode}};
        return e;
    };
    J vertex_ext = meshopt(0, vertex_stream.size(), 12, count, "ATTRIBUTES");
    vertex_ext["filter"] = "EXPONENTIAL";
    const J json = {
        {"asset", {{"version", "2.0"}}},
        {"extensionsUsed", {"EXT_meshopt_compression"}},
        {"extensionsRequired", {"EXT_meshopt_compression"}},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", count}, {"type", "VEC3"}},
          {{"bufferView", 1}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}}}},
        {"bufferViews",
         {{{"buffer", 1},
           {"byteOffset", 0},
           {"byteLength", count * 12},
           {"byteStride", 12},
           {"extensions", {{"EXT_meshopt_compression", vertex_ext}}}},
          {{"buffer", 1},
           {"byteOffset", count * 12},
           {"byteLength", indices.size() * 4},
           {"extensions",
            {{"EXT_meshopt_compression",
              meshopt(vertex_stream.size(), index_stream.size(), 4, indices.size(), "INDICES")}}}}}},
        {"buffers",
         {{{"byteLength", bin.size()}},
          {{"byteLength", count * 12 + indices.size() * 4},
           {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}}};
    TempDir dir;
    const std::string path = dir.write("exp.glb", t::make_glb(json.dump(), bin));
    const LoadResult r = load_gltf_scene(path);
    REQUIRE_MESSAGE(r.scene, r.error);
    const Mesh& mesh = r.scene->mesh;
    REQUIRE(mesh.positions.size() == count);
    CHECK(mesh.indices == std::vector<std::uint32_t>(indices.begin(), indices.end()));
    // 15-bit mantissas under one exponent per vector (libmeshoptimizer 0.18): errors relative to
    // the vector's largest component.
    double worst = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const glm::dvec3 want(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
        const double scale = std::max({std::abs(want.x), std::abs(want.y), std::abs(want.z)});
        for (int c = 0; c < 3; ++c)
            worst = std::max(worst, std::abs(double(mesh.positions[i][c]) - want[c]) / scale);
    }
    MESSAGE("EXPONENTIAL (15-bit mantissa): largest relative position error " << worst);
    CHECK(worst < 1.0 / (1 << 13));
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
