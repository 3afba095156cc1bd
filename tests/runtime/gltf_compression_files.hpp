// tests/runtime/gltf_compression_files.hpp — compressed glTF files for the tests, made from files
// nobody here wrote or by Debian's tools: a torus OBJ packed by gltfpack -cc (EXT_meshopt_compression
// with KHR_mesh_quantization), assimp-testmodels' Draco 2CylinderEngine (KHR_draco_mesh_compression),
// small seeds of both for the fuzz driver (tests/hostile/fuzz_test.cpp), and broken variants with
// the words each must be refused with (gltf_compression_test.cpp in-process, tests/hostile through
// penumbra-playground).
#pragma once

#include "gltf_test_file.hpp" // make_glb

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace penumbra::playground::testing {

inline std::string read_binary(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

inline void write_binary(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

inline constexpr float torus_major = 1.0f;  // ring radius
inline constexpr float torus_minor = 0.35f; // tube radius

// A torus around +y with analytic normals, `rings` × `sides` quads, as OBJ text (no materials).
inline std::string torus_obj(int rings = 48, int sides = 24) {
    std::ostringstream obj;
    obj << "# torus written by the penumbra tests\n";
    const double tau = 6.283185307179586;
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < sides; ++j) {
            const double u = tau * i / rings, v = tau * j / sides;
            const double nx = std::cos(v) * std::cos(u), ny = std::sin(v), nz = std::cos(v) * std::sin(u);
            obj << "v " << torus_major * std::cos(u) + torus_minor * nx << " " << torus_minor * ny << " "
                << torus_major * std::sin(u) + torus_minor * nz << "\n";
            obj << "vn " << nx << " " << ny << " " << nz << "\n";
        }
    auto at = [&](int i, int j) { return (i % rings) * sides + (j % sides) + 1; };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < sides; ++j) {
            const int a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            obj << "f " << a << "//" << a << " " << d << "//" << d << " " << c << "//" << c << "\n";
            obj << "f " << a << "//" << a << " " << c << "//" << c << " " << b << "//" << b << "\n";
        }
    return obj.str();
}

inline bool have_gltfpack() { return std::system("command -v gltfpack >/dev/null 2>&1") == 0; }

// gltfpack -cc: meshopt compression at its higher ratio, positions as 14-bit integers.
inline bool run_gltfpack(const std::string& in, const std::string& out) {
    return std::system(("gltfpack -i '" + in + "' -o '" + out + "' -cc >/dev/null 2>&1").c_str()) == 0;
}

inline const std::string draco_engine = "/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf";

// The JSON of a .glb.
inline std::string glb_json(const std::string& glb) {
    std::uint32_t length = 0;
    std::memcpy(&length, glb.data() + 12, 4);
    return glb.substr(20, length);
}
// The BIN chunk of a .glb (empty when there is none).
inline std::string glb_bin(const std::string& glb) {
    std::uint32_t json_length = 0, bin_length = 0;
    std::memcpy(&json_length, glb.data() + 12, 4);
    if (glb.size() < 28 + std::size_t(json_length)) return {};
    std::memcpy(&bin_length, glb.data() + 20 + json_length, 4);
    return glb.substr(28 + json_length, bin_length);
}

// A small Draco seed: the first mesh of 2CylinderEngine (one primitive, 2,750 triangles) alone,
// its stream moved to the start of a buffer of its own. Returns {json, bin}; json's buffer has
// `buffer_uri` (empty for a .glb).
inline std::pair<nlohmann::json, std::string> draco_seed(const std::string& buffer_uri) {
    nlohmann::json j = nlohmann::json::parse(read_binary(draco_engine));
    const std::string all = read_binary(
        (std::filesystem::path(draco_engine).parent_path() / j["buffers"][0]["uri"].get<std::string>())
            .string());
    nlohmann::json primitive = j["meshes"][0]["primitives"][0];
    primitive.erase("material");
    const nlohmann::json view =
        j["bufferViews"][primitive["extensions"]["KHR_draco_mesh_compression"]["bufferView"].get<int>()];
    std::string bin = all.substr(view.value("byteOffset", 0), view["byteLength"].get<std::size_t>());
    while (bin.size() % 4) bin += '\0';
    primitive["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 0;
    nlohmann::json out = {
        {"asset", j["asset"]},
        {"extensionsUsed", {"KHR_draco_mesh_compression"}},
        {"extensionsRequired", {"KHR_draco_mesh_compression"}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes", {{{"primitives", {primitive}}}}},
        {"accessors", j["accessors"]},
        {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", view["byteLength"]}}}},
        {"buffers", {{{"byteLength", bin.size()}}}}};
    if (!buffer_uri.empty()) out["buffers"][0]["uri"] = buffer_uri;
    return {out, bin};
}

// A broken compressed file and a part of the one line it must be refused with.
struct BrokenCompressedFile {
    std::string name;
    std::string path;
    std::string expected;
};

// Writes the broken files into `dir` (which must exist); empty when gltfpack or assimp-testmodels
// is missing.
inline std::vector<BrokenCompressedFile> broken_compressed_files(const std::string& dir) {
    namespace fs = std::filesystem;
    std::vector<BrokenCompressedFile> out;
    if (!have_gltfpack() || !fs::is_regular_file(draco_engine)) return out;
    const fs::path d(dir);

    // Draco: the engine's JSON changed, its .bin beside it.
    const nlohmann::json engine = nlohmann::json::parse(read_binary(draco_engine));
    const std::string engine_bin_name = engine["buffers"][0]["uri"].get<std::string>();
    fs::copy_file(fs::path(draco_engine).parent_path() / engine_bin_name, d / engine_bin_name,
                  fs::copy_options::overwrite_existing);
    auto draco_case = [&](const std::string& name, const std::string& expected, auto&& change) {
        nlohmann::json j = engine;
        change(j);
        const std::string path = (d / (name + ".gltf")).string();
        write_binary(path, j.dump());
        out.push_back({name, path, expected});
    };
    draco_case(
        "draco-cut-short",
        "mesh 0 primitive 0's Draco stream (KHR_draco_mesh_compression, buffer view 0) does not decode",
        [](nlohmann::json& j) { j["bufferViews"][0]["byteLength"] = 1000; });
    draco_case("draco-wrong-attribute-id",
               "'s POSITION is Draco attribute id 7, which the stream does not have (its ids: 1, 0)",
               [](nlohmann::json& j) {
                   j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]
                    ["POSITION"] = 7;
               });
    draco_case("draco-no-such-buffer-view", "buffer view 4000): the file has", [](nlohmann::json& j) {
        j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 4000;
    });
    const int engine_points = engine["accessors"][2]["count"].get<int>(); // mesh 0's POSITION
    draco_case("draco-count-lies",
               "POSITION decodes " + std::to_string(engine_points) + " elements but its accessor 2 says " +
                   std::to_string(engine_points + 1) + "; they must be equal",
               [&](nlohmann::json& j) { j["accessors"][2]["count"] = engine_points + 1; });
    draco_case("draco-malformed", "mesh 0 primitive 0's KHR_draco_mesh_compression has no bufferView",
               [](nlohmann::json& j) {
                   j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"].erase(
                       "bufferView");
               });

    // meshopt: gltfpack -cc of the torus as .gltf + .bin; buffer view 0 holds the positions
    // (ATTRIBUTES, stride 8), the index view is found by its mode.
    const std::string obj = (d / "torus.obj").string();
    write_binary(obj, torus_obj(16, 8));
    if (!run_gltfpack(obj, (d / "torus.gltf").string())) return {};
    const nlohmann::json torus = nlohmann::json::parse(read_binary((d / "torus.gltf").string()));
    auto meshopt_case = [&](const std::string& name, const std::string& expected, auto&& change) {
        nlohmann::json j = torus;
        std::size_t positions = 0, indices = 0;
        for (std::size_t i = 0; i < j["bufferViews"].size(); ++i) {
            const auto& ext = j["bufferViews"][i]["extensions"]["EXT_meshopt_compression"];
            if (ext["mode"] == "TRIANGLES") indices = i;
            if (ext["mode"] == "ATTRIBUTES" && ext["byteStride"] == 8 && !ext.contains("filter"))
                positions = i;
        }
        change(j, j["bufferViews"][positions], j["bufferViews"][indices]);
        const std::string path = (d / (name + ".gltf")).string();
        write_binary(path, j.dump());
        out.push_back({name, path, expected});
    };
    using J = nlohmann::json;
    const std::string does_not_decode = "does not decode (meshopt_decode";
    meshopt_case("meshopt-count-lies", "but its buffer view has", [](J&, J& p, J&) {
        p["extensions"]["EXT_meshopt_compression"]["count"] =
            p["extensions"]["EXT_meshopt_compression"]["count"].get<int>() + 1;
    });
    meshopt_case("meshopt-count-lies-consistently", does_not_decode, [](J&, J& p, J&) {
        J& e = p["extensions"]["EXT_meshopt_compression"];
        e["count"] = e["count"].get<int>() + 16;
        p["byteLength"] = e["count"].get<int>() * 8;
    });
    meshopt_case("meshopt-stride-lies", does_not_decode, [](J&, J& p, J&) {
        J& e = p["extensions"]["EXT_meshopt_compression"];
        e["byteStride"] = 12;
        p["byteStride"] = 12;
        p["byteLength"] = e["count"].get<int>() * 12;
    });
    meshopt_case("meshopt-stride-not-allowed",
                 "byteStride is 6; allowed for ATTRIBUTES: a multiple of 4 from 4 to 256", [](J&, J& p, J&) {
                     p["extensions"]["EXT_meshopt_compression"]["byteStride"] =
                         6; // (tinygltf checks the view's)
                 });
    meshopt_case("meshopt-index-count-lies", does_not_decode, [](J&, J&, J& i) {
        J& e = i["extensions"]["EXT_meshopt_compression"];
        e["count"] = e["count"].get<int>() - 3;
        i["byteLength"] = e["count"].get<int>() * e["byteStride"].get<int>();
    });
    meshopt_case("meshopt-cut-short", does_not_decode, [](J&, J& p, J&) {
        J& e = p["extensions"]["EXT_meshopt_compression"];
        e["byteLength"] = e["byteLength"].get<int>() / 2;
    });
    meshopt_case("meshopt-past-the-vertex-limit", "decodes 67108865 vertices; allowed: up to 67108864",
                 [](J&, J& p, J&) {
                     J& e = p["extensions"]["EXT_meshopt_compression"];
                     e["count"] = 67108865;
                     p["byteLength"] = 67108865ull * 8;
                 });
    meshopt_case("meshopt-claims-too-much", "a meshopt stream decodes to at most 64 times its size",
                 [](J&, J& p, J&) {
                     J& e = p["extensions"]["EXT_meshopt_compression"];
                     e["count"] = 60000000;
                     p["byteLength"] = 480000000ull;
                 });
    meshopt_case("meshopt-unknown-filter", "filter 'SPIRAL' is not known",
                 [](J&, J& p, J&) { p["extensions"]["EXT_meshopt_compression"]["filter"] = "SPIRAL"; });
    meshopt_case("meshopt-khr-required", "KHR_meshopt_compression, which is not supported",
                 [](J& j, J&, J&) { j["extensionsRequired"].push_back("KHR_meshopt_compression"); });
    return out;
}

} // namespace penumbra::playground::testing
