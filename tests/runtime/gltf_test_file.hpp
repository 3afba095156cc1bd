// tests/runtime/gltf_test_file.hpp — a small glTF 2.0 asset built by the tests themselves, as a
// .gltf with its .bin or as one .glb (also the fuzz driver's seed, tests/hostile/fuzz_test.cpp).
//
// One triangle (0,0,0) (1,0,0) (0,0,−1), counter-clockwise seen from +y, read through three index
// types and without indices; node 0 places it by translation × rotation × scale, node 1 by a
// mirroring matrix, node 2 (a child of node 3) carries a copy with file normals under a
// non-uniform scale. expected_* below are worked out by hand in the comments.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace penumbra::playground::testing {

// The binary buffer: 3 positions, 3 normals, the indices as uint8, uint16 and uint32 (padded to 4).
inline std::string gltf_test_buffer() {
    std::string bin;
    auto put_floats = [&](std::initializer_list<float> values) {
        for (float v : values) bin.append(reinterpret_cast<const char*>(&v), 4);
    };
    put_floats({0, 0, 0, 1, 0, 0, 0, 0, -1});                                     // 0: positions, 36 bytes
    const float d = 0.70710678f;
    put_floats({d, d, 0, d, d, 0, d, d, 0});                                       // 36: normals (1,1,0)/√2
    bin += std::string("\x00\x01\x02\x00", 4);                                     // 72: uint8 indices + pad
    bin += std::string("\x00\x00\x01\x00\x02\x00\x00\x00", 8);                     // 76: uint16 + pad
    bin += std::string("\x00\x00\x00\x00\x01\x00\x00\x00\x02\x00\x00\x00", 12);    // 84: uint32
    return bin;                                                                    // 96 bytes
}

// The JSON; `buffer_uri` empty for a .glb (the BIN chunk).
inline std::string gltf_test_json(const std::string& buffer_uri) {
    const std::string uri = buffer_uri.empty() ? "" : "\"uri\": \"" + buffer_uri + "\", ";
    return R"({
  "asset": {"version": "2.0", "generator": "penumbra tests"},
  "scene": 0,
  "scenes": [{"nodes": [0, 1, 3]}],
  "nodes": [
    {"mesh": 0, "translation": [10, 0, 0], "rotation": [0, 0, 0.70710678, 0.70710678], "scale": [2, 2, 2]},
    {"mesh": 0, "matrix": [-1,0,0,0, 0,1,0,0, 0,0,1,0, 0,5,0,1]},
    {"mesh": 1, "scale": [2, 1, 1]},
    {"children": [2], "translation": [0, 0, 7]}
  ],
  "meshes": [
    {"primitives": [
      {"attributes": {"POSITION": 0}, "indices": 2},
      {"attributes": {"POSITION": 0}, "indices": 3},
      {"attributes": {"POSITION": 0}, "indices": 4, "mode": 4},
      {"attributes": {"POSITION": 0}}
    ]},
    {"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}}]}
  ],
  "accessors": [
    {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, -1], "max": [1, 0, 0]},
    {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC3"},
    {"bufferView": 2, "componentType": 5121, "count": 3, "type": "SCALAR"},
    {"bufferView": 3, "componentType": 5123, "count": 3, "type": "SCALAR"},
    {"bufferView": 4, "componentType": 5125, "count": 3, "type": "SCALAR"}
  ],
  "bufferViews": [
    {"buffer": 0, "byteOffset": 0, "byteLength": 36},
    {"buffer": 0, "byteOffset": 36, "byteLength": 36},
    {"buffer": 0, "byteOffset": 72, "byteLength": 3},
    {"buffer": 0, "byteOffset": 76, "byteLength": 6},
    {"buffer": 0, "byteOffset": 84, "byteLength": 12}
  ],
  "buffers": [{)" + uri + R"("byteLength": 96}]
})";
}

// The asset above with top-level `extensions` (a JSON object's members, e.g. the lights of
// EXT_lights_area and KHR_lights_punctual) and `extra_nodes` (JSON objects) appended as nodes 4, 5, …
// whose indices `extra_roots` (e.g. "4, 6") adds to scene 0's roots.
inline std::string gltf_test_json_with(const std::string& buffer_uri, const std::string& extensions,
                                       const std::string& extra_nodes, const std::string& extra_roots) {
    std::string json = gltf_test_json(buffer_uri);
    auto replace = [&](const std::string& from, const std::string& to) {
        const std::size_t at = json.find(from);
        if (at != std::string::npos) json.replace(at, from.size(), to);
    };
    replace(R"("scene": 0,)", R"("scene": 0, "extensions": {)" + extensions + "},");
    if (!extra_roots.empty())
        replace(R"("nodes": [0, 1, 3]})", R"("nodes": [0, 1, 3, )" + extra_roots + "]}");
    if (!extra_nodes.empty())
        replace(R"({"children": [2], "translation": [0, 0, 7]})",
                R"({"children": [2], "translation": [0, 0, 7]}, )" + extra_nodes);
    return json;
}

// A .glb container: 12-byte header, the JSON chunk padded with spaces, the BIN chunk with zeros.
inline std::string make_glb(std::string json, std::string bin) {
    while (json.size() % 4) json += ' ';
    while (bin.size() % 4) bin += '\0';
    std::string out;
    auto u32 = [&](std::uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); };
    out += "glTF";
    u32(2);
    u32(static_cast<std::uint32_t>(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
    u32(static_cast<std::uint32_t>(json.size()));
    u32(0x4E4F534Au); // "JSON"
    out += json;
    if (!bin.empty()) {
        u32(static_cast<std::uint32_t>(bin.size()));
        u32(0x004E4942u); // "BIN\0"
        out += bin;
    }
    return out;
}

} // namespace penumbra::playground::testing
