// playground/src/scenes/gltf_compression.hpp — compressed glTF geometry, decoded into plain buffers
// before the loader (gltf_loader.cpp) reads any accessor:
//   KHR_draco_mesh_compression  by Debian's libdraco (draco::Decoder)
//   EXT_meshopt_compression     by Debian's libmeshoptimizer (meshopt_decodeVertexBuffer,
//                               meshopt_decodeIndexBuffer, meshopt_decodeIndexSequence and the
//                               OCTAHEDRAL, QUATERNION and EXPONENTIAL filters)
// KHR_mesh_quantization's integer attributes need nothing here: the loader reads them.
//
// Two steps around tinygltf's parse:
//   prepare()  reads the extensions' JSON (exact 64-bit numbers) and rewrites what tinygltf
//              would refuse: the index accessor of a Draco primitive has no buffer view, and a
//              meshopt fallback buffer has no data (no uri).
//   decode()   runs the decoders on the parsed model and points the primitives (Draco) and buffer
//              views (meshopt) at new buffers holding the decoded data, which the loader then
//              validates like any other.
// Every failure is a value: one line naming the buffer view or primitive and what is allowed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace tinygltf {
class Model;
}

namespace penumbra::playground::gltf_compression {

// The loader's limits, which decoded data must also keep to: vertices per file (and triangles),
// and all decoded bytes of one file together (64 Mi vertices × 32 bytes: position, normal, uv).
inline constexpr std::uint64_t decoded_vertex_limit = std::uint64_t(64) << 20;
inline constexpr std::uint64_t decoded_byte_limit = std::uint64_t(2) << 30;

// One buffer view's EXT_meshopt_compression object.
struct MeshoptView {
    std::uint64_t buffer = 0;      // where the compressed stream is
    std::uint64_t byte_offset = 0; // into that buffer
    std::uint64_t byte_length = 0; // of the stream
    std::uint64_t byte_stride = 0; // of one decoded element
    std::uint64_t count = 0;       // decoded elements
    std::string mode;              // ATTRIBUTES, TRIANGLES or INDICES
    std::string filter = "NONE";   // NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL
};

// One primitive's KHR_draco_mesh_compression object.
struct DracoPrimitive {
    int mesh = 0;
    int primitive = 0;
    std::uint64_t buffer_view = 0;                   // the Draco stream
    std::map<std::string, std::uint64_t> attributes; // glTF attribute name → Draco unique id
    std::int64_t indices = -1;                       // the index accessor the file names (-1: none)
};

struct Prepared {
    std::string json;     // what tinygltf should parse: the file's JSON, or the rewritten copy
    bool changed = false; // json differs from the file's
    std::string problem;  // a malformed extension object: the file is refused with this line
    std::map<int, MeshoptView> meshopt_views; // by buffer view
    std::vector<DracoPrimitive> draco_primitives;
    std::map<int, std::uint64_t> fallback_buffers; // meshopt fallback buffers without data: their byteLength
};

// Reads the compression extensions from the file's JSON. A JSON that does not parse is returned
// unchanged (tinygltf then reports it).
Prepared prepare(const std::string& json);

// Decodes every compressed buffer view and Draco primitive of `model` (parsed from prepared.json).
// `missing_buffers`: buffers whose external file does not exist; what is compressed in them stays
// undecoded, for the loader to skip with a warning. Returns "" or the one-line problem.
std::string decode(tinygltf::Model& model, const Prepared& prepared,
                   const std::map<int, std::string>& missing_buffers);

// The .glb `bytes` (already checked) with its JSON chunk replaced by `json`.
std::string rewrap_glb(const std::string& bytes, const std::string& json);

} // namespace penumbra::playground::gltf_compression
