// playground/src/scenes/gltf_compression.cpp — KHR_draco_mesh_compression and EXT_meshopt_compression
// decoded by their libraries (Debian's libdraco and libmeshoptimizer); this file only checks what
// the file claims against what the decoders are allowed to be asked, and moves the results into
// the model as plain buffers.
#include <tiny_gltf.h>

#include "scenes/gltf_compression.hpp"

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <memory>
#include <optional>

namespace penumbra::playground::gltf_compression {

namespace {

constexpr const char* meshopt_name = "EXT_meshopt_compression";
constexpr const char* draco_name = "KHR_draco_mesh_compression";

// A member of a JSON object read as an unsigned integer: nullopt when absent, `problem` set when
// present but not an unsigned integer.
std::optional<std::uint64_t> unsigned_member(const nlohmann::json& object, const char* key,
                                             const std::string& what, std::string* problem) {
    if (!object.contains(key)) return std::nullopt;
    const nlohmann::json& v = object[key];
    if (!v.is_number_unsigned()) {
        if (problem->empty()) *problem = what + "'s " + key + " is not an unsigned integer";
        return std::nullopt;
    }
    return v.get<std::uint64_t>();
}

// The extension object `name` of `owner`, when there is one; `problem` set when it is not an object.
const nlohmann::json* extension(const nlohmann::json& owner, const char* name, const std::string& what,
                                std::string* problem) {
    if (!owner.is_object() || !owner.contains("extensions") || !owner["extensions"].is_object())
        return nullptr;
    const nlohmann::json& extensions = owner["extensions"];
    if (!extensions.contains(name)) return nullptr;
    if (!extensions[name].is_object()) {
        if (problem->empty()) *problem = what + "'s " + name + " is not a JSON object";
        return nullptr;
    }
    return &extensions[name];
}

std::string read_meshopt_view(const nlohmann::json& ext, const std::string& what, MeshoptView* out) {
    std::string problem;
    struct Field {
        const char* key;
        std::uint64_t* value;
        bool required;
    };
    for (const Field& f : {Field{"buffer", &out->buffer, true}, Field{"byteOffset", &out->byte_offset, false},
                           Field{"byteLength", &out->byte_length, true},
                           Field{"byteStride", &out->byte_stride, true}, Field{"count", &out->count, true}}) {
        const std::optional<std::uint64_t> v = unsigned_member(ext, f.key, what, &problem);
        if (!problem.empty()) return problem;
        if (!v && f.required) return what + " has no " + f.key + "; the extension requires it";
        if (v) *f.value = *v;
    }
    for (auto [key, value] : {std::pair{"mode", &out->mode}, std::pair{"filter", &out->filter}}) {
        if (!ext.contains(key)) continue;
        if (!ext[key].is_string()) return what + "'s " + key + " is not a string";
        *value = ext[key].get<std::string>();
    }
    if (out->mode.empty())
        return what + " has no mode; the extension requires one of ATTRIBUTES, TRIANGLES, INDICES";
    return {};
}

std::string read_draco_primitive(const nlohmann::json& ext, const std::string& what, DracoPrimitive* out) {
    std::string problem;
    const std::optional<std::uint64_t> view = unsigned_member(ext, "bufferView", what, &problem);
    if (!problem.empty()) return problem;
    if (!view) return what + " has no bufferView; the extension requires it";
    out->buffer_view = *view;
    if (!ext.contains("attributes") || !ext["attributes"].is_object())
        return what + " has no attributes object; the extension requires one";
    for (const auto& [name, id] : ext["attributes"].items()) {
        if (!id.is_number_unsigned())
            return what + "'s attribute id for " + name.substr(0, 60) + " is not an unsigned integer";
        out->attributes[name] = id.get<std::uint64_t>();
    }
    return {};
}

// The data of meshopt fallback buffers is never read; tinygltf refuses a buffer without a uri, so
// it gets four bytes of its own (a view that reads it then fails the loader's bounds checks).
constexpr const char* empty_buffer_uri = "data:application/octet-stream;base64,AAAAAA==";

std::string element_text(std::uint64_t count, std::uint64_t stride) {
    return std::to_string(count) + " elements of " + std::to_string(stride) + " bytes";
}

// What decode() adds to the model, with the decoded-size budget.
struct Output {
    tinygltf::Model& model;
    std::uint64_t decoded_bytes = 0;

    std::string charge(std::uint64_t bytes, const std::string& what) {
        if (bytes > decoded_byte_limit - decoded_bytes)
            return what + " would take the file's decoded data past " +
                   std::to_string(decoded_byte_limit >> 20) + " MiB; allowed: up to that much";
        decoded_bytes += bytes;
        return {};
    }
    int add_buffer(std::vector<unsigned char> data) {
        tinygltf::Buffer b;
        b.data = std::move(data);
        model.buffers.push_back(std::move(b));
        return static_cast<int>(model.buffers.size() - 1);
    }
    // A tightly packed accessor over a new buffer.
    int add_accessor(std::vector<unsigned char> data, int component_type, int type, std::size_t count) {
        tinygltf::BufferView view;
        view.byteLength = data.size();
        view.buffer = add_buffer(std::move(data));
        model.bufferViews.push_back(view);
        tinygltf::Accessor a;
        a.bufferView = static_cast<int>(model.bufferViews.size() - 1);
        a.componentType = component_type;
        a.type = type;
        a.count = count;
        model.accessors.push_back(a);
        return static_cast<int>(model.accessors.size() - 1);
    }
};

// The bytes [offset, offset + length) of buffer `buffer`, or a problem.
std::string buffer_bytes(const tinygltf::Model& model, std::uint64_t buffer, std::uint64_t offset,
                         std::uint64_t length, const std::string& what, const unsigned char** out) {
    if (buffer >= model.buffers.size())
        return what + " refers to buffer " + std::to_string(buffer) + " but the file has " +
               std::to_string(model.buffers.size());
    const std::vector<unsigned char>& data = model.buffers[buffer].data;
    if (offset > data.size() || length > data.size() - offset)
        return what + " (bytes " + std::to_string(offset) + " + " + std::to_string(length) +
               ") goes past the end of buffer " + std::to_string(buffer) + " (" +
               std::to_string(data.size()) + " bytes)";
    *out = data.data() + offset;
    return {};
}

// EXT_meshopt_compression §Decoding: the allowed strides per mode and filter, checked before the
// decoder (which asserts them) is called.
std::string check_meshopt_view(const MeshoptView& m, const tinygltf::BufferView& view,
                               const std::string& what) {
    const std::uint64_t stride = m.byte_stride, count = m.count;
    if (m.mode == "ATTRIBUTES") {
        if (stride == 0 || stride > 256 || stride % 4 != 0)
            return what + "'s byteStride is " + std::to_string(stride) +
                   "; allowed for ATTRIBUTES: a multiple of 4 from 4 to 256";
        if (count > decoded_vertex_limit)
            return what + " decodes " + std::to_string(count) + " vertices; allowed: up to " +
                   std::to_string(decoded_vertex_limit);
        if (view.byteStride != 0 && view.byteStride != stride)
            return what + "'s byteStride " + std::to_string(stride) +
                   " is not its buffer view's byteStride " + std::to_string(view.byteStride) +
                   "; they must be equal";
    } else if (m.mode == "TRIANGLES" || m.mode == "INDICES") {
        if (stride != 2 && stride != 4)
            return what + "'s byteStride is " + std::to_string(stride) + "; allowed for " + m.mode +
                   ": 2 or 4";
        if (count > 3 * decoded_vertex_limit)
            return what + " decodes " + std::to_string(count) + " indices; allowed: up to " +
                   std::to_string(3 * decoded_vertex_limit);
        if (m.mode == "TRIANGLES" && count % 3 != 0)
            return what + "'s count " + std::to_string(count) + " is not a multiple of 3 (TRIANGLES)";
    } else {
        return what + "'s mode '" + m.mode.substr(0, 40) +
               "' is not known; allowed: ATTRIBUTES, TRIANGLES, INDICES";
    }
    if (m.filter != "NONE") {
        if (m.mode != "ATTRIBUTES")
            return what + " has filter " + m.filter.substr(0, 40) + " in mode " + m.mode +
                   "; filters need ATTRIBUTES";
        if (m.filter == "OCTAHEDRAL" && stride != 4 && stride != 8)
            return what + "'s byteStride is " + std::to_string(stride) + "; allowed with OCTAHEDRAL: 4 or 8";
        if (m.filter == "QUATERNION" && stride != 8)
            return what + "'s byteStride is " + std::to_string(stride) + "; allowed with QUATERNION: 8";
        if (m.filter != "OCTAHEDRAL" && m.filter != "QUATERNION" && m.filter != "EXPONENTIAL")
            return what + "'s filter '" + m.filter.substr(0, 40) +
                   "' is not known; allowed: NONE, OCTAHEDRAL, QUATERNION, EXPONENTIAL";
    }
    if (count * stride != view.byteLength)
        return what + " decodes " + element_text(count, stride) + " (" + std::to_string(count * stride) +
               " bytes) but its buffer view has " + std::to_string(view.byteLength) + "; they must be equal";
    // The densest meshopt code (the vertex codec) spends at least 2 bits per 16 bytes of output:
    // a stream that claims more is lying about its count before anything is allocated.
    if (count * stride / 64 > m.byte_length)
        return what + " claims " + element_text(count, stride) + " from a stream of only " +
               std::to_string(m.byte_length) +
               " bytes; a meshopt stream decodes to at most 64 times its size";
    return {};
}

std::string decode_meshopt(Output& out, const Prepared& prepared, const std::map<int, std::string>& missing) {
    tinygltf::Model& model = out.model;
    for (const auto& [index, m] : prepared.meshopt_views) {
        if (static_cast<std::size_t>(index) >= model.bufferViews.size())
            continue; // tinygltf read fewer: it refused
        const std::string what =
            "buffer view " + std::to_string(index) + "'s meshopt stream (" + meshopt_name + ")";
        tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(index)];
        if (prepared.fallback_buffers.count(static_cast<int>(m.buffer)))
            return what + " is in buffer " + std::to_string(m.buffer) +
                   ", a fallback buffer that holds no data";
        if (m.buffer < model.buffers.size() && missing.count(static_cast<int>(m.buffer))) {
            view.buffer =
                static_cast<int>(m.buffer); // the loader skips what reads it, naming the missing file
            continue;
        }
        const unsigned char* stream = nullptr;
        if (std::string p = buffer_bytes(model, m.buffer, m.byte_offset, m.byte_length, what, &stream);
            !p.empty())
            return p;
        if (std::string p = check_meshopt_view(m, view, what); !p.empty()) return p;
        const std::size_t count = static_cast<std::size_t>(m.count),
                          stride = static_cast<std::size_t>(m.byte_stride);
        if (std::string p = out.charge(count * stride, what); !p.empty()) return p;
        std::vector<unsigned char> decoded(count * stride);
        const std::size_t size = static_cast<std::size_t>(m.byte_length);
        int rc = 0;
        const char* decoder = "meshopt_decodeVertexBuffer";
        if (m.mode == "ATTRIBUTES") {
            rc = meshopt_decodeVertexBuffer(decoded.data(), count, stride, stream, size);
        } else if (m.mode == "TRIANGLES") {
            decoder = "meshopt_decodeIndexBuffer";
            rc = meshopt_decodeIndexBuffer(decoded.data(), count, stride, stream, size);
        } else {
            decoder = "meshopt_decodeIndexSequence";
            rc = meshopt_decodeIndexSequence(decoded.data(), count, stride, stream, size);
        }
        if (rc != 0)
            return what + " does not decode (" + decoder + " returned " + std::to_string(rc) +
                   "): the stream is cut short or corrupt, or its count or byteStride is not what it was "
                   "encoded with";
        if (m.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(decoded.data(), count, stride);
        if (m.filter == "QUATERNION") meshopt_decodeFilterQuat(decoded.data(), count, stride);
        if (m.filter == "EXPONENTIAL") meshopt_decodeFilterExp(decoded.data(), count, stride);
        view.buffer = out.add_buffer(std::move(decoded)); // `stream` is not read past this point
        view.byteOffset = 0;
        view.extensions.erase(meshopt_name);
    }
    return {};
}

std::string attribute_ids(const draco::Mesh& mesh) {
    std::string ids;
    for (int i = 0; i < mesh.num_attributes() && i < 16; ++i)
        ids += (ids.empty() ? "" : ", ") + std::to_string(mesh.attribute(i)->unique_id());
    return ids.empty() ? "none" : ids;
}

std::string decode_draco(Output& out, const Prepared& prepared, const std::map<int, std::string>& missing) {
    tinygltf::Model& model = out.model;
    std::map<std::uint64_t, std::unique_ptr<draco::Mesh>> decoded; // by buffer view: primitives may share one
    for (const DracoPrimitive& d : prepared.draco_primitives) {
        if (static_cast<std::size_t>(d.mesh) >= model.meshes.size() ||
            static_cast<std::size_t>(d.primitive) >=
                model.meshes[static_cast<std::size_t>(d.mesh)].primitives.size())
            continue;
        tinygltf::Primitive& p =
            model.meshes[static_cast<std::size_t>(d.mesh)].primitives[static_cast<std::size_t>(d.primitive)];
        const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN)
            continue; // the loader skips points and lines
        const std::string what = "mesh " + std::to_string(d.mesh) + " primitive " +
                                 std::to_string(d.primitive) + "'s Draco stream (" + draco_name +
                                 ", buffer view " + std::to_string(d.buffer_view) + ")";
        if (d.buffer_view >= model.bufferViews.size())
            return what + ": the file has " + std::to_string(model.bufferViews.size()) + " buffer views";
        const tinygltf::BufferView& view = model.bufferViews[d.buffer_view];
        if (view.buffer >= 0 && missing.count(view.buffer)) continue; // left for the loader to skip
        if (view.buffer >= 0 && prepared.fallback_buffers.count(view.buffer))
            return what + " is in buffer " + std::to_string(view.buffer) +
                   ", a fallback buffer that holds no data";
        std::unique_ptr<draco::Mesh>& mesh = decoded[d.buffer_view];
        if (!mesh) {
            const unsigned char* stream = nullptr;
            if (view.buffer < 0) return what + ": its buffer view names no buffer";
            if (std::string problem = buffer_bytes(model, static_cast<std::uint64_t>(view.buffer),
                                                   view.byteOffset, view.byteLength, what, &stream);
                !problem.empty())
                return problem;
            draco::DecoderBuffer buffer;
            buffer.Init(reinterpret_cast<const char*>(stream), view.byteLength);
            draco::Decoder decoder;
            draco::StatusOr<std::unique_ptr<draco::Mesh>> result = decoder.DecodeMeshFromBuffer(&buffer);
            if (!result.ok() || !result.value())
                return what + " does not decode (Draco: " +
                       (result.ok() ? std::string("no mesh")
                                    : result.status().error_msg_string().substr(0, 120)) +
                       "): the stream is cut short or corrupt";
            mesh = std::move(result).value();
        }
        const std::uint64_t points = mesh->num_points(), faces = mesh->num_faces();
        if (points > decoded_vertex_limit || faces > decoded_vertex_limit)
            return what + " decodes " + std::to_string(points) + " vertices and " + std::to_string(faces) +
                   " triangles; allowed: up to " + std::to_string(decoded_vertex_limit) + " of each";
        if (points == 0 || faces == 0) return what + " decodes to no triangles";

        // The attributes the extension maps, each as a float accessor of the type the file declares.
        for (const auto& [name, id] : d.attributes) {
            const auto at = p.attributes.find(name);
            if (at == p.attributes.end()) continue; // mapped but unused by the primitive
            const std::string attribute = what + "'s " + name.substr(0, 60);
            const draco::PointAttribute* source =
                id > 0xffffffffu ? nullptr : mesh->GetAttributeByUniqueId(static_cast<std::uint32_t>(id));
            if (!source)
                return attribute + " is Draco attribute id " + std::to_string(id) +
                       ", which the stream does not have (its ids: " + attribute_ids(*mesh) + ")";
            if (at->second < 0 || static_cast<std::size_t>(at->second) >= model.accessors.size())
                continue; // the loader names the bad accessor index
            const tinygltf::Accessor accessor = model.accessors[static_cast<std::size_t>(at->second)];
            const int components =
                tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(accessor.type));
            if (components < 1 || components > 4) continue; // the loader names the bad type
            if (accessor.count != points)
                return attribute + " decodes " + std::to_string(points) + " elements but its accessor " +
                       std::to_string(at->second) + " says " + std::to_string(accessor.count) +
                       "; they must be equal";
            const std::size_t bytes = static_cast<std::size_t>(points) * components * sizeof(float);
            if (std::string problem = out.charge(bytes, attribute); !problem.empty()) return problem;
            std::vector<unsigned char> data(bytes);
            float* values = reinterpret_cast<float*>(data.data());
            for (draco::PointIndex i(0); i < mesh->num_points(); ++i)
                if (!source->ConvertValue<float>(source->mapped_index(i),
                                                 static_cast<std::int8_t>(components),
                                                 values + std::size_t(i.value()) * components))
                    return attribute + "'s value " + std::to_string(i.value()) +
                           " cannot be read from the Draco data";
            at->second =
                out.add_accessor(std::move(data), TINYGLTF_COMPONENT_TYPE_FLOAT, accessor.type, points);
        }

        // The faces: a triangle list whatever the primitive's mode said (Draco stores triangles).
        if (mode == TINYGLTF_MODE_TRIANGLES && d.indices >= 0 &&
            static_cast<std::size_t>(d.indices) < model.accessors.size() &&
            model.accessors[static_cast<std::size_t>(d.indices)].count != 3 * faces)
            return what + " decodes " + std::to_string(faces) + " triangles but its index accessor " +
                   std::to_string(d.indices) + " has " +
                   std::to_string(model.accessors[static_cast<std::size_t>(d.indices)].count) +
                   " indices; allowed: 3 per triangle";
        const std::size_t bytes = static_cast<std::size_t>(faces) * 3 * sizeof(std::uint32_t);
        if (std::string problem = out.charge(bytes, what + "'s indices"); !problem.empty()) return problem;
        std::vector<unsigned char> data(bytes);
        std::uint32_t* indices = reinterpret_cast<std::uint32_t*>(data.data());
        for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
            for (int c = 0; c < 3; ++c)
                indices[std::size_t(f.value()) * 3 + std::size_t(c)] = mesh->face(f)[c].value();
        p.indices = out.add_accessor(std::move(data), TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                                     TINYGLTF_TYPE_SCALAR, static_cast<std::size_t>(faces) * 3);
        p.mode = TINYGLTF_MODE_TRIANGLES;
        p.extensions.erase(draco_name);
    }
    return {};
}

} // namespace

namespace {

void prepare_json(Prepared& out) {
    nlohmann::json j = nlohmann::json::parse(out.json, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object()) return;
    std::string problem;

    if (j.contains("bufferViews") && j["bufferViews"].is_array())
        for (std::size_t i = 0; i < j["bufferViews"].size(); ++i) {
            const std::string what = "buffer view " + std::to_string(i) + "'s " + meshopt_name;
            const nlohmann::json* ext = extension(j["bufferViews"][i], meshopt_name, what, &problem);
            if (!problem.empty()) return void(out.problem = problem);
            if (!ext) continue;
            MeshoptView m;
            if (std::string p = read_meshopt_view(*ext, what, &m); !p.empty()) return void(out.problem = p);
            out.meshopt_views[static_cast<int>(i)] = m;
        }

    if (j.contains("buffers") && j["buffers"].is_array())
        for (std::size_t i = 0; i < j["buffers"].size(); ++i) {
            nlohmann::json& b = j["buffers"][i];
            const nlohmann::json* ext = extension(b, meshopt_name, "buffer " + std::to_string(i), &problem);
            if (!problem.empty()) return void(out.problem = problem);
            if (!ext || !ext->contains("fallback") || (*ext)["fallback"] != true || b.contains("uri"))
                continue;
            out.fallback_buffers[static_cast<int>(i)] =
                b.contains("byteLength") && b["byteLength"].is_number_unsigned()
                    ? b["byteLength"].get<std::uint64_t>()
                    : 0;
            b["uri"] = empty_buffer_uri;
            b["byteLength"] = 4;
            out.changed = true;
        }

    if (j.contains("meshes") && j["meshes"].is_array())
        for (std::size_t m = 0; m < j["meshes"].size(); ++m) {
            nlohmann::json& mesh = j["meshes"][m];
            if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
            for (std::size_t p = 0; p < mesh["primitives"].size(); ++p) {
                nlohmann::json& primitive = mesh["primitives"][p];
                const std::string what =
                    "mesh " + std::to_string(m) + " primitive " + std::to_string(p) + "'s " + draco_name;
                const nlohmann::json* ext = extension(primitive, draco_name, what, &problem);
                if (!problem.empty()) return void(out.problem = problem);
                if (!ext) continue;
                DracoPrimitive d;
                d.mesh = static_cast<int>(m);
                d.primitive = static_cast<int>(p);
                if (std::string e = read_draco_primitive(*ext, what, &d); !e.empty())
                    return void(out.problem = e);
                // The decoded faces replace the index accessor, which has no buffer view (tinygltf
                // refuses that for indices).
                if (primitive.contains("indices")) {
                    if (primitive["indices"].is_number_unsigned() &&
                        primitive["indices"].get<std::uint64_t>() < (1ull << 31))
                        d.indices = primitive["indices"].get<std::int64_t>();
                    primitive.erase("indices");
                    out.changed = true;
                }
                out.draco_primitives.push_back(d);
            }
        }
    if (out.changed) out.json = j.dump();
}

} // namespace

Prepared prepare(const std::string& json) {
    Prepared out;
    out.json = json;
    try {
        prepare_json(out);
    } catch (const std::exception& e) { // std::bad_alloc
        out.problem =
            std::string("out of memory or internal error while reading the compression extensions: ") +
            e.what();
    }
    return out;
}

std::string decode(tinygltf::Model& model, const Prepared& prepared,
                   const std::map<int, std::string>& missing_buffers) {
    Output out{model};
    if (std::string problem = decode_meshopt(out, prepared, missing_buffers); !problem.empty())
        return problem;
    return decode_draco(out, prepared, missing_buffers);
}

std::string rewrap_glb(const std::string& bytes, const std::string& json) {
    std::uint32_t json_length = 0;
    std::memcpy(&json_length, bytes.data() + 12, 4);
    const std::string rest = bytes.substr(20 + std::size_t(json_length)); // the BIN chunk, header and all
    std::string padded = json;
    while (padded.size() % 4 != 0) padded += ' ';
    auto u32 = [](std::size_t v) {
        const std::uint32_t x = static_cast<std::uint32_t>(v);
        return std::string(reinterpret_cast<const char*>(&x), 4);
    };
    return std::string("glTF") + u32(2) + u32(12 + 8 + padded.size() + rest.size()) + u32(padded.size()) +
           std::string("JSON", 4) + padded + rest;
}

} // namespace penumbra::playground::gltf_compression
