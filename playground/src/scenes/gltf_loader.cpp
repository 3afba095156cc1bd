// playground/src/scenes/gltf_loader.cpp
// The parser is Debian's libtinygltf (linked, built there with its own JSON and image code); this
// file checks what it leaves unchecked and turns the node tree's triangle primitives into one mesh.
#include <tiny_gltf.h>

#include "scenes/gltf_loader.hpp"

#include "scenes/gltf_compression.hpp"
#include "scenes/material_textures.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/scene_defaults.hpp"

#include <penumbra_tools/bounded_read.hpp>
#include <penumbra_tools/printable.hpp>

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

namespace penumbra::playground {

namespace {

// Coordinates beyond this make the scene's bounds, light and camera overflow single precision
// (the OBJ loader's limit).
constexpr double coordinate_limit = 1e9;
// A node may be reached along several paths (instancing); this bounds what a small file can expand to.
constexpr std::size_t vertex_budget = std::size_t(64) << 20;
constexpr std::size_t node_visit_budget = std::size_t(1) << 20;
static_assert(gltf_compression::decoded_vertex_limit == vertex_budget, "decoded data keeps to the same limit");

// A failure inside the loader: the problem, without the file name.
struct Problem {
    std::string text;
};

std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '.')) line.pop_back();
    return penumbra_gen::printable(line, 200);
}

std::uint32_t read_u32(const std::string& bytes, std::size_t at) {
    std::uint32_t v = 0;
    std::memcpy(&v, bytes.data() + at, 4); // glTF is little-endian, as is every target we build for
    return v;
}

// The .glb container (glTF 2.0 §4.4) checked before tinygltf reads it: tinygltf accepts a file
// longer than its header says and chunks that are not where the header puts them.
std::string check_glb(const std::string& bytes) {
    const std::size_t size = bytes.size();
    if (size < 12) return "a .glb file starts with a 12-byte header; the file has " + std::to_string(size) + " bytes";
    if (bytes.compare(0, 4, "glTF") != 0) return "not a binary glTF file: it does not start with 'glTF'";
    const std::uint32_t version = read_u32(bytes, 4), length = read_u32(bytes, 8);
    if (version != 2) return "binary glTF version " + std::to_string(version) + " is not supported; allowed: 2";
    if (length != size)
        return "the header says the file has " + std::to_string(length) + " bytes but it has " + std::to_string(size) +
               " (truncated or padded?)";
    std::size_t at = 12;
    for (int chunk = 0; at < size; ++chunk) {
        if (size - at < 8) return "chunk " + std::to_string(chunk) + "'s 8-byte header is cut off at the end of the file";
        const std::uint64_t chunk_length = read_u32(bytes, at), type = read_u32(bytes, at + 4);
        if (chunk_length > size - at - 8)
            return "chunk " + std::to_string(chunk) + " says it has " + std::to_string(chunk_length) +
                   " bytes but only " + std::to_string(size - at - 8) + " follow";
        if (chunk_length % 4 != 0)
            return "chunk " + std::to_string(chunk) + "'s length " + std::to_string(chunk_length) +
                   " is not a multiple of 4";
        if (chunk == 0 && type != 0x4E4F534Au) return "the first chunk is not JSON";
        if (chunk == 0 && chunk_length == 0) return "the JSON chunk is empty";
        if (chunk == 1 && type != 0x004E4942u) return "the second chunk is not BIN";
        at += 8 + chunk_length;
    }
    return {};
}

// A buffer whose external file does not exist. tinygltf refuses the whole file then; instead it
// reads zeros of the declared length, and the primitives that use the buffer are skipped.
struct MissingBuffer {
    int buffer;
    std::string uri;
    std::size_t bytes;
};

// What tinygltf reads through: regular files only, each at most the scene limit, no path expansion
// (its default expands `~` and `$VARS` with wordexp); missing buffer files stand in as zeros.
struct FileAccess {
    std::map<std::string, MissingBuffer> missing_buffers; // by the path tinygltf will ask for
    std::vector<std::string> missing;                     // other files asked for that do not exist
};

// tinygltf's own decoding of a buffer's uri into a file name (dlib::urldecode) and joining
// (JoinPath), so that the paths it asks for are recognised.
std::string decoded_uri(const std::string& uri) {
    std::string out;
    auto hex = [](char c) {
        return c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10 : c >= 'A' && c <= 'F' ? c - 'A' + 10 : 0;
    };
    for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+') out += ' ';
        else if (uri[i] == '%' && uri.size() > i + 2) {
            out += static_cast<char>((hex(uri[i + 1]) << 4) | hex(uri[i + 2]));
            i += 2;
        } else out += uri[i];
    }
    return out;
}

std::string joined(const std::string& dir, const std::string& name) {
    if (dir.empty()) return name;
    return dir.back() == '/' ? dir + name : dir + "/" + name;
}

// The buffers of the JSON whose external file is missing (a JSON tinygltf will refuse anyway: none).
std::map<std::string, MissingBuffer> missing_buffer_files(const std::string& json, const std::string& base_dir) {
    std::map<std::string, MissingBuffer> out;
    const nlohmann::json j = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
    if (!j.is_object() || !j.contains("buffers") || !j["buffers"].is_array()) return out;
    for (std::size_t i = 0; i < j["buffers"].size(); ++i) {
        const nlohmann::json& b = j["buffers"][i];
        if (!b.is_object() || !b.contains("uri") || !b["uri"].is_string() || !b.contains("byteLength") ||
            !b["byteLength"].is_number_unsigned())
            continue;
        const std::string uri = b["uri"].get<std::string>();
        if (uri.empty() || uri.starts_with("data:")) continue;
        const std::string path = joined(base_dir, decoded_uri(uri));
        std::error_code ec;
        const std::uint64_t bytes = b["byteLength"].get<std::uint64_t>();
        if (!std::filesystem::exists(path, ec) && bytes > 0 && bytes <= penumbra_gen::obj_file_limit)
            out[path] = {static_cast<int>(i), uri, static_cast<std::size_t>(bytes)};
    }
    return out;
}

bool file_exists(const std::string& path, void* user) {
    FileAccess& access = *static_cast<FileAccess*>(user);
    if (access.missing_buffers.count(path)) return true;
    std::error_code ec;
    const bool exists = std::filesystem::exists(path, ec);
    if (!exists) access.missing.push_back(path);
    return exists;
}

std::string expand_nothing(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    const FileAccess& access = *static_cast<const FileAccess*>(user);
    if (const auto it = access.missing_buffers.find(path); it != access.missing_buffers.end()) {
        out->assign(it->second.bytes, 0);
        return true;
    }
    const penumbra_gen::BoundedRead file = penumbra_gen::read_bounded_file(path, penumbra_gen::obj_file_limit);
    if (!file.text) {
        if (err) *err += file.problem;
        return false;
    }
    out->assign(file.text->begin(), file.text->end());
    return true;
}

bool write_nothing(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is not supported";
    return false;
}

// Images only matter for the materials that cut (alpha test): their encoded bytes are kept, by image
// index, and decoded later for those materials only; none is required.
using EncodedImages = std::map<int, std::vector<unsigned char>>;
bool keep_encoded_image(tinygltf::Image*, const int index, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void* user) {
    if (bytes && size > 0) static_cast<EncodedImages*>(user)->insert_or_assign(index, std::vector<unsigned char>(bytes, bytes + size));
    return true;
}

std::string component_name(int type) {
    switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "byte";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "unsigned byte";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "short";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "unsigned short";
    case TINYGLTF_COMPONENT_TYPE_INT: return "int";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "unsigned int";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "float";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "double";
    default: return "component type " + std::to_string(type);
    }
}

std::string mode_name(int mode) {
    switch (mode) {
    case TINYGLTF_MODE_POINTS: return "points";
    case TINYGLTF_MODE_LINE: return "lines";
    case TINYGLTF_MODE_LINE_LOOP: return "a line loop";
    case TINYGLTF_MODE_LINE_STRIP: return "a line strip";
    default: return "mode " + std::to_string(mode);
    }
}

// One accessor, validated: where its elements are and how to read one component as a number.
struct View {
    const unsigned char* data = nullptr; // first element
    std::size_t stride = 0;
    std::size_t count = 0;
    int components = 0;
    int component_type = 0;
    bool normalized = false;

    double component(std::size_t element, int c) const {
        const unsigned char* p = data + element * stride;
        switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            std::int8_t v;
            std::memcpy(&v, p + c, 1);
            return normalized ? std::max(v / 127.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
            std::uint8_t v;
            std::memcpy(&v, p + c, 1);
            return normalized ? v / 255.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t v;
            std::memcpy(&v, p + 2 * c, 2);
            return normalized ? std::max(v / 32767.0, -1.0) : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t v;
            std::memcpy(&v, p + 2 * c, 2);
            return normalized ? v / 65535.0 : v;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            std::uint32_t v;
            std::memcpy(&v, p + 4 * c, 4);
            return v;
        }
        default: {
            float v;
            std::memcpy(&v, p + 4 * c, 4);
            return v;
        }
        }
    }
    glm::dvec3 vec3(std::size_t i) const { return {component(i, 0), component(i, 1), component(i, 2)}; }
};

// Why a primitive cannot be read although the file is valid (it is skipped), or empty.
struct ViewResult {
    View view;
    std::string skip;
};

// Checks accessor `index` for the attribute `what`: its type (`components`), its component type
// (one of `allowed`), its buffer view and buffer, and that every element lies inside them.
// Throws Problem for an invalid file; returns `skip` for valid data this loader does not read.
ViewResult accessor_view(const tinygltf::Model& model, const std::map<int, std::string>& missing, int index,
                         const std::string& what, int type, std::initializer_list<int> allowed,
                         const std::string& allowed_text) {
    const int components = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(type));
    if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size())
        throw Problem{what + " refers to accessor " + std::to_string(index) + " but the file has " +
                      std::to_string(model.accessors.size())};
    const tinygltf::Accessor& a = model.accessors[static_cast<std::size_t>(index)];
    const std::string name = what + " (accessor " + std::to_string(index) + ")";
    auto type_name = [](int t) {
        switch (t) {
        case TINYGLTF_TYPE_SCALAR: return std::string("SCALAR");
        case TINYGLTF_TYPE_VEC2: return std::string("VEC2");
        case TINYGLTF_TYPE_VEC3: return std::string("VEC3");
        case TINYGLTF_TYPE_VEC4: return std::string("VEC4");
        case TINYGLTF_TYPE_MAT2: return std::string("MAT2");
        case TINYGLTF_TYPE_MAT3: return std::string("MAT3");
        case TINYGLTF_TYPE_MAT4: return std::string("MAT4");
        default: return "type " + std::to_string(t);
        }
    };
    if (a.type != type) throw Problem{name + " is " + type_name(a.type) + "; allowed: " + type_name(type)};
    bool type_ok = false;
    for (int t : allowed) type_ok = type_ok || a.componentType == t;
    if (!type_ok) throw Problem{name + " has " + component_name(a.componentType) + " components; allowed: " + allowed_text};
    if (a.sparse.isSparse) return {{}, name + " is a sparse accessor"};
    if (a.count == 0) return {{}, name + " is empty"};
    if (a.bufferView < 0) return {{}, name + " has no buffer view (no data)"};
    if (static_cast<std::size_t>(a.bufferView) >= model.bufferViews.size())
        throw Problem{name + " refers to buffer view " + std::to_string(a.bufferView) + " but the file has " +
                      std::to_string(model.bufferViews.size())};
    const tinygltf::BufferView& bv = model.bufferViews[static_cast<std::size_t>(a.bufferView)];
    const std::string view_name = "buffer view " + std::to_string(a.bufferView);
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= model.buffers.size())
        throw Problem{view_name + " refers to buffer " + std::to_string(bv.buffer) + " but the file has " +
                      std::to_string(model.buffers.size())};
    if (const auto it = missing.find(bv.buffer); it != missing.end())
        return {{}, name + " is in buffer " + std::to_string(bv.buffer) + ", whose file '" + it->second +
                        "' does not exist"};
    const std::vector<unsigned char>& buffer = model.buffers[static_cast<std::size_t>(bv.buffer)].data;
    if (bv.byteOffset > buffer.size() || bv.byteLength > buffer.size() - bv.byteOffset)
        throw Problem{view_name + " (bytes " + std::to_string(bv.byteOffset) + " + " + std::to_string(bv.byteLength) +
                      ") goes past the end of buffer " + std::to_string(bv.buffer) + " (" +
                      std::to_string(buffer.size()) + " bytes)"};
    const std::size_t component_size = static_cast<std::size_t>(tinygltf::GetComponentSizeInBytes(
        static_cast<std::uint32_t>(a.componentType)));
    const std::size_t element = component_size * static_cast<std::size_t>(components);
    const std::size_t stride = bv.byteStride ? bv.byteStride : element;
    if (stride < element || stride % component_size != 0)
        throw Problem{view_name + "'s byte stride " + std::to_string(bv.byteStride) + " does not fit " + name +
                      "'s " + std::to_string(element) + "-byte elements"};
    if (a.byteOffset % component_size != 0)
        throw Problem{name + "'s byte offset " + std::to_string(a.byteOffset) + " is not a multiple of its " +
                      std::to_string(component_size) + "-byte components"};
    // a.byteOffset + stride·(count − 1) + element ≤ byteLength, without overflow.
    const std::size_t length = bv.byteLength;
    if (a.byteOffset > length || element > length - a.byteOffset ||
        (a.count - 1) > (length - a.byteOffset - element) / stride)
        throw Problem{name + " (" + std::to_string(a.count) + " elements of " + std::to_string(element) +
                      " bytes from byte " + std::to_string(a.byteOffset) + ", stride " + std::to_string(stride) +
                      ") goes past the end of " + view_name + " (" + std::to_string(length) + " bytes)"};
    View v;
    v.data = buffer.data() + bv.byteOffset + a.byteOffset;
    v.stride = stride;
    v.count = a.count;
    v.components = components;
    v.component_type = a.componentType;
    v.normalized = a.normalized;
    return {v, {}};
}

// The node's local transform: its matrix, or translation × rotation × scale.
glm::dmat4 local_transform(const tinygltf::Node& node, int index) {
    const std::string name = "node " + std::to_string(index);
    auto finite = [&](const std::vector<double>& values, const char* what) {
        for (double v : values)
            if (!std::isfinite(v)) throw Problem{name + "'s " + what + " has a value that is not a finite number"};
    };
    if (!node.matrix.empty()) {
        if (node.matrix.size() != 16)
            throw Problem{name + "'s matrix has " + std::to_string(node.matrix.size()) + " numbers; allowed: 16"};
        finite(node.matrix, "matrix");
        return glm::make_mat4(node.matrix.data()); // column-major, as glTF stores it
    }
    glm::dmat4 m(1.0);
    if (!node.translation.empty()) {
        if (node.translation.size() != 3)
            throw Problem{name + "'s translation has " + std::to_string(node.translation.size()) + " numbers; allowed: 3"};
        finite(node.translation, "translation");
        m = glm::translate(m, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (!node.rotation.empty()) {
        if (node.rotation.size() != 4)
            throw Problem{name + "'s rotation has " + std::to_string(node.rotation.size()) + " numbers; allowed: 4"};
        finite(node.rotation, "rotation");
        glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]); // stored x, y, z, w
        const double len = glm::length(q);
        if (!(len > 1e-12)) throw Problem{name + "'s rotation is not a unit quaternion (its length is 0)"};
        m = m * glm::mat4_cast(q / len);
    }
    if (!node.scale.empty()) {
        if (node.scale.size() != 3)
            throw Problem{name + "'s scale has " + std::to_string(node.scale.size()) + " numbers; allowed: 3"};
        finite(node.scale, "scale");
        m = glm::scale(m, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    return m;
}

// Lights. EXT_lights_area (a vendor extension; Babylon.js's glTF loader reads it): top-level
// extensions.EXT_lights_area.lights[] with "type" ("rect" or "disk"), "size" (a rectangle's height, a
// disk's diameter; 1 when absent), "rect": {"aspect"} (width over height; 1 when absent), colour and
// intensity (not read); a node names one with extensions.EXT_lights_area.light. KHR_lights_punctual:
// extensions.KHR_lights_punctual.lights[] with "type", a node's extensions.KHR_lights_punctual.light;
// only a directional light is read (as the sun). Read from the JSON itself, whatever tinygltf keeps.
struct AreaLightDefinition {
    std::string label; // "EXT_lights_area light 0 'panel'"
    bool disk = false;
    double size = 1.0;   // the rectangle's height, the disk's diameter
    double aspect = 1.0; // width over height (a rectangle)
};

struct FileLights {
    std::vector<AreaLightDefinition> area;
    std::vector<std::string> punctual_types, punctual_labels;
    std::map<int, int> area_of_node, punctual_of_node; // node → the light it carries
};

std::string number_text(double v) {
    std::ostringstream text;
    text << v;
    return text.str();
}

std::string light_label(const char* extension, std::size_t index, const nlohmann::json& light) {
    std::string label = std::string(extension) + " light " + std::to_string(index);
    if (light.is_object() && light.contains("name") && light["name"].is_string())
        label += " '" + penumbra_gen::printable(light["name"].get<std::string>(), 60) + "'";
    return label;
}

// A size or an aspect: absent → `fallback`; a number that is not finite or not above 0 is an error.
double positive_field(const nlohmann::json& object, const char* key, const std::string& label,
                      const std::string& field, const std::string& meaning, double fallback) {
    if (!object.contains(key)) return fallback;
    const nlohmann::json& value = object[key];
    const std::string allowed = "; allowed: a finite number greater than 0 (" + meaning + ")";
    if (!value.is_number()) throw Problem{label + ": " + field + " is not a number" + allowed};
    const double v = value.get<double>();
    if (!std::isfinite(v) || !(v > 0.0))
        throw Problem{label + ": " + field + " is " + number_text(v) + allowed};
    return v;
}

// The lights of the file's JSON and which node carries which; Problem for a light or a reference that
// is not valid (checked for every light in the lists, used or not).
FileLights read_file_lights(const nlohmann::json& j) {
    FileLights out;
    if (!j.is_object()) return out;
    auto list = [&](const char* extension) -> const nlohmann::json* {
        if (!j.contains("extensions") || !j["extensions"].is_object() || !j["extensions"].contains(extension))
            return nullptr;
        const nlohmann::json& e = j["extensions"][extension];
        if (!e.is_object() || (e.contains("lights") && !e["lights"].is_array()))
            throw Problem{std::string("extensions.") + extension +
                          " is not an object with a \"lights\" array"};
        return e.contains("lights") ? &e["lights"] : nullptr;
    };
    if (const nlohmann::json* lights = list("EXT_lights_area"))
        for (std::size_t i = 0; i < lights->size(); ++i) {
            const nlohmann::json& l = (*lights)[i];
            AreaLightDefinition d;
            d.label = light_label("EXT_lights_area", i, l);
            if (!l.is_object()) throw Problem{d.label + " is not an object"};
            const std::string type =
                l.contains("type") && l["type"].is_string() ? l["type"].get<std::string>() : "";
            if (type != "rect" && type != "disk")
                throw Problem{d.label +
                              (l.contains("type") ? ": type is '" + penumbra_gen::printable(type, 30) + "'"
                                                  : ": no type") +
                              "; allowed: rect, disk"};
            d.disk = type == "disk";
            d.size = positive_field(
                l, "size", d.label, "size",
                d.disk ? "the disk's diameter in scene units" : "the rectangle's height in scene units", 1.0);
            if (!d.disk && l.contains("rect")) {
                if (!l["rect"].is_object())
                    throw Problem{d.label +
                                  ": rect is not an object; allowed: {\"aspect\": width over height}"};
                d.aspect = positive_field(l["rect"], "aspect", d.label, "rect.aspect",
                                          "the rectangle's width over its height", 1.0);
            }
            out.area.push_back(std::move(d));
        }
    if (const nlohmann::json* lights = list("KHR_lights_punctual"))
        for (std::size_t i = 0; i < lights->size(); ++i) {
            const nlohmann::json& l = (*lights)[i];
            out.punctual_labels.push_back(light_label("KHR_lights_punctual", i, l));
            out.punctual_types.push_back(l.is_object() && l.contains("type") && l["type"].is_string()
                                             ? penumbra_gen::printable(l["type"].get<std::string>(), 30)
                                             : "");
        }
    if (!j.contains("nodes") || !j["nodes"].is_array()) return out;
    for (std::size_t n = 0; n < j["nodes"].size(); ++n) {
        const nlohmann::json& node = j["nodes"][n];
        if (!node.is_object() || !node.contains("extensions") || !node["extensions"].is_object()) continue;
        for (const auto& [extension, count, of_node] :
             {std::tuple{"EXT_lights_area", out.area.size(), &out.area_of_node},
              std::tuple{"KHR_lights_punctual", out.punctual_types.size(), &out.punctual_of_node}}) {
            if (!node["extensions"].contains(extension)) continue;
            const nlohmann::json& ref = node["extensions"][extension];
            const std::string name = "node " + std::to_string(n) + "'s " + extension + " light";
            if (!ref.is_object() || !ref.contains("light") || !ref["light"].is_number_integer())
                throw Problem{name + " is not an index; allowed: {\"light\": an index into extensions." +
                              extension + ".lights}"};
            const std::int64_t index = ref["light"].get<std::int64_t>();
            if (index < 0 || static_cast<std::uint64_t>(index) >= count)
                throw Problem{name + " is " + std::to_string(index) + " but the file has " +
                              std::to_string(count) + " in extensions." + extension + ".lights"};
            (*of_node)[static_cast<int>(n)] = static_cast<int>(index);
        }
    }
    return out;
}

// A light carried by a node the scene reaches, with the node's world transform.
struct LightUse {
    int node = -1;
    int light = -1;
    glm::dmat4 world{1.0};
};

// The rectangle of area light `d` on `node` placed by `world`, as glTF places lights (and Babylon.js
// builds its RectAreaLight): it faces the node's local −z; its width (size × aspect) lies along the
// node's x axis, its height (size) along its y axis, both scaled by the node's transform (Babylon.js
// transforms its width and height vectors by the node's world matrix). u = the node's −x, v = its +y,
// so that u × v is the node's −z (Babylon.js too turns its light half a turn about y). A transform
// that shears x against y keeps the height along y and gives the rectangle the parallelogram's area.
// A disk becomes the square of the same area (side √π/2 × the diameter), as Babylon.js does.
penumbra::RectLight place_area_light(const AreaLightDefinition& d, const glm::dmat4& world, int node) {
    const std::string name = d.label + " on node " + std::to_string(node);
    const double side = d.disk ? d.size * std::sqrt(std::acos(-1.0)) / 2.0 : d.size;
    const double width = d.disk ? side : d.size * d.aspect, height = side;
    const glm::dmat3 linear(world);
    const glm::dvec3 x = linear[0], y = linear[1], xy = glm::cross(x, y);
    const double y_length = glm::length(y), xy_length = glm::length(xy);
    if (!(y_length > 1e-12) || !(xy_length > 1e-12 * std::max(1.0, y_length * glm::length(x))))
        throw Problem{name +
                      ": its node's transform flattens the light (a zero scale along x or y); allowed: a "
                      "transform that keeps the light's x and y axes apart"};
    penumbra::RectLight light;
    light.center = glm::dvec3(world[3]);
    // The node's −z seen through the transform: −(x × y), turned over by a mirroring transform.
    const glm::dvec3 normal = (glm::determinant(linear) < 0.0 ? 1.0 : -1.0) * xy / xy_length;
    light.v_axis = y / y_length;
    light.u_axis = glm::normalize(glm::cross(light.v_axis, normal)); // the node's −x when not sheared
    light.width = width * xy_length / y_length;
    light.height = height * y_length;
    for (int axis = 0; axis < 3; ++axis)
        if (!std::isfinite(light.center[axis]) || std::abs(light.center[axis]) > coordinate_limit)
            throw Problem{name + ": its centre is out of range after its node's transform; allowed: finite "
                                 "coordinates within ±1e9"};
    for (const auto& [value, what] : {std::pair{light.width, "width"}, std::pair{light.height, "height"}})
        if (!std::isfinite(value) || value > coordinate_limit)
            throw Problem{name + ": its " + what + " after its node's transform is " + number_text(value) +
                          "; allowed: a finite number up to 1e9"};
    return light;
}

struct Loader {
    const tinygltf::Model& model;
    std::map<int, std::string> missing; // buffers whose file does not exist: their uri
    Mesh mesh;
    std::vector<std::string> warnings;
    bool all_have_uvs = true;
    std::size_t triangles_skipped_primitives = 0;
    const EncodedImages* images = nullptr;
    std::map<int, int> material_slots; // glTF material → its index in mesh.cut_materials, -1: it does not cut
    const FileLights* lights = nullptr;
    // The first area light (EXT_lights_area) and directional light (KHR_lights_punctual) met walking
    // the scene's nodes (depth first, in order), and how many of each and of other punctual lights.
    std::optional<LightUse> first_area{}, first_directional{};
    std::size_t area_uses = 0, directional_uses = 0, other_punctual_uses = 0;

    // The slot in mesh.cut_materials of glTF material `index` when it cuts (alpha test), else -1:
    // alphaMode MASK (baseColorFactor.a × baseColorTexture.a below alphaCutoff), or BLEND, cast as a
    // cut-out at 0.5. Its texture is decoded on first use; one that cannot be read leaves the factor
    // alone to cut, with a warning.
    int cut_slot(int index) {
        if (index < 0 || static_cast<std::size_t>(index) >= model.materials.size()) return -1;
        if (const auto it = material_slots.find(index); it != material_slots.end()) return it->second;
        material_slots[index] = -1;
        const tinygltf::Material& m = model.materials[static_cast<std::size_t>(index)];
        const bool mask = m.alphaMode == "MASK";
        if (!mask && m.alphaMode != "BLEND") return -1;
        const std::vector<double>& color = m.pbrMetallicRoughness.baseColorFactor;
        const double factor = color.size() == 4 && std::isfinite(color[3]) ? color[3] : 1.0;
        const double cutoff = mask && std::isfinite(m.alphaCutoff) ? std::clamp(m.alphaCutoff, 0.0, 1.0) : 0.5;
        CutMaterial cut{"material " + std::to_string(index) +
                            (m.name.empty() ? "" : " '" + penumbra_gen::printable(m.name, 60) + "'"),
                        uniform_alpha_texture(factor), static_cast<float>(cutoff)};
        if (const std::string problem = read_base_color_alpha(m.pbrMetallicRoughness.baseColorTexture, factor, cut.texture);
            !problem.empty())
            warnings.push_back(cut.name + " (alphaMode " + m.alphaMode + "): " + problem + "; its alpha factor alone cuts");
        mesh.cut_materials.push_back(std::move(cut));
        return material_slots[index] = static_cast<int>(mesh.cut_materials.size()) - 1;
    }

    // The base colour texture's alpha times `factor` into `out`; "" when there is none or it was read,
    // else why it could not be.
    std::string read_base_color_alpha(const tinygltf::TextureInfo& info, double factor, AlphaTexture& out) const {
        if (info.index < 0) return {};
        if (info.texCoord != 0)
            return "its base colour texture uses TEXCOORD_" + std::to_string(info.texCoord) + " (only TEXCOORD_0 is read)";
        if (static_cast<std::size_t>(info.index) >= model.textures.size())
            return "its base colour texture " + std::to_string(info.index) + " does not exist";
        const int source = model.textures[static_cast<std::size_t>(info.index)].source;
        const auto bytes = images ? images->find(source) : EncodedImages::const_iterator{};
        if (!images || bytes == images->end()) return "image " + std::to_string(source) + " has no data";
        std::string error;
        std::optional<AlphaTexture> decoded =
            decode_alpha_texture(bytes->second.data(), bytes->second.size(), AlphaChannel::alpha, factor, &error);
        if (!decoded) return "image " + std::to_string(source) + ": " + error;
        out = std::move(*decoded);
        return {};
    }

    // After a part's vertices and triangles were appended: its material texture coordinates (its
    // TEXCOORD_0) and its triangles' cut material `slot`, when anything in the mesh cuts. Call
    // complete_cut_materials(mesh) before appending the part.
    void append_cuts(int slot, const Mesh& part, const std::string& where) {
        if (!mesh.cuts()) return;
        if (slot >= 0 && part.uvs.empty())
            warnings.push_back(where + ": no TEXCOORD_0, so its material's texture is read at (0, 0)");
        if (part.uvs.empty()) mesh.material_uvs.resize(mesh.material_uvs.size() + part.positions.size(), glm::vec2(0.0f));
        else mesh.material_uvs.insert(mesh.material_uvs.end(), part.uvs.begin(), part.uvs.end());
        mesh.triangle_materials.resize(mesh.triangle_materials.size() + part.triangle_count(), slot);
    }

    void skip(const std::string& where, const std::string& why) {
        warnings.push_back(where + " skipped: " + why);
        ++triangles_skipped_primitives;
    }

    // Triangle list corners from the primitive's indices (or 0..n−1), strips and fans unrolled.
    std::vector<std::uint32_t> corners(const tinygltf::Primitive& p, const std::string& where, std::size_t vertices,
                                       std::string* skipped) {
        std::vector<std::uint32_t> order;
        if (p.indices >= 0) {
            const ViewResult r = accessor_view(model, missing, p.indices, where + "'s indices", TINYGLTF_TYPE_SCALAR,
                                               {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                                               "unsigned byte, unsigned short, unsigned int");
            if (!r.skip.empty()) {
                *skipped = r.skip;
                return {};
            }
            order.resize(r.view.count);
            for (std::size_t i = 0; i < r.view.count; ++i) {
                const double value = r.view.component(i, 0);
                if (value >= static_cast<double>(vertices))
                    throw Problem{where + "'s index " + std::to_string(i) + " is " +
                                  std::to_string(static_cast<unsigned long long>(value)) + " but it has " +
                                  std::to_string(vertices) + " vertices; allowed: 0 to " + std::to_string(vertices - 1)};
                order[i] = static_cast<std::uint32_t>(value);
            }
        } else {
            order.resize(vertices);
            for (std::size_t i = 0; i < vertices; ++i) order[i] = static_cast<std::uint32_t>(i);
        }
        const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        std::vector<std::uint32_t> list;
        if (mode == TINYGLTF_MODE_TRIANGLES) {
            if (order.size() % 3 != 0)
                throw Problem{where + " has " + std::to_string(order.size()) + " " +
                              (p.indices >= 0 ? "indices" : "vertices") + ", not a multiple of 3 (triangles)"};
            return order;
        }
        if (order.size() < 3) {
            *skipped = "a triangle " + std::string(mode == TINYGLTF_MODE_TRIANGLE_STRIP ? "strip" : "fan") +
                       " with fewer than 3 vertices";
            return {};
        }
        for (std::size_t i = 2; i < order.size(); ++i) {
            if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                if (i % 2 == 0) list.insert(list.end(), {order[i - 2], order[i - 1], order[i]});
                else list.insert(list.end(), {order[i - 1], order[i - 2], order[i]}); // keep the winding
            } else {
                list.insert(list.end(), {order[0], order[i - 1], order[i]});
            }
        }
        return list;
    }

    void add_primitive(const tinygltf::Primitive& p, const std::string& where, const glm::dmat4& world) {
        const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
        if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            mode != TINYGLTF_MODE_TRIANGLE_FAN)
            return skip(where, mode_name(mode) + ", not triangles");
        if (p.extensions.count("KHR_draco_mesh_compression")) // decoded unless its buffer's file is missing
            return skip(where, "its Draco data (KHR_draco_mesh_compression) is in a buffer whose file does not exist");
        const auto position_at = p.attributes.find("POSITION");
        if (position_at == p.attributes.end()) return skip(where, "no POSITION attribute");
        const ViewResult positions = accessor_view(model, missing, position_at->second, where + "'s POSITION", TINYGLTF_TYPE_VEC3,
                                                   {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_SHORT,
                                                    TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                                                   "float, or (KHR_mesh_quantization) byte and short types");
        if (!positions.skip.empty()) return skip(where, positions.skip);
        const std::size_t count = positions.view.count;
        std::optional<View> normals, uvs;
        if (const auto at = p.attributes.find("NORMAL"); at != p.attributes.end()) {
            const ViewResult r = accessor_view(model, missing, at->second, where + "'s NORMAL", TINYGLTF_TYPE_VEC3,
                                               {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                TINYGLTF_COMPONENT_TYPE_SHORT},
                                               "float, or (KHR_mesh_quantization) normalized byte and short");
            if (r.skip.empty()) normals = r.view;
        }
        if (const auto at = p.attributes.find("TEXCOORD_0"); at != p.attributes.end()) {
            const ViewResult r = accessor_view(model, missing, at->second, where + "'s TEXCOORD_0", TINYGLTF_TYPE_VEC2,
                                               {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                                TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_COMPONENT_TYPE_BYTE,
                                                TINYGLTF_COMPONENT_TYPE_SHORT},
                                               "float, unsigned byte or unsigned short (normalized)");
            if (r.skip.empty()) uvs = r.view;
        }
        for (const auto& [view, name] : {std::pair{&normals, "NORMAL"}, std::pair{&uvs, "TEXCOORD_0"}})
            if (*view && (*view)->count != count)
                throw Problem{where + "'s " + name + " has " + std::to_string((*view)->count) +
                              " elements but POSITION has " + std::to_string(count) + "; they must be equal"};

        std::string skipped;
        std::vector<std::uint32_t> list = corners(p, where, count, &skipped);
        if (!skipped.empty()) return skip(where, skipped);
        if (mesh.positions.size() + count > vertex_budget || mesh.indices.size() + list.size() > 3 * vertex_budget)
            throw Problem{"more than " + std::to_string(vertex_budget) +
                          " vertices or triangles after placing every node's mesh; allowed: up to that many"};

        // Positions in world space, checked; a mirroring transform flips the winding (glTF §3.7.4).
        Mesh part;
        part.positions.resize(count);
        for (std::size_t i = 0; i < count; ++i) {
            const glm::dvec3 local = positions.view.vec3(i);
            const glm::dvec3 w = glm::dvec3(world * glm::dvec4(local, 1.0));
            const bool file_finite = std::isfinite(local.x) && std::isfinite(local.y) && std::isfinite(local.z);
            for (int axis = 0; axis < 3; ++axis)
                if (!file_finite || !std::isfinite(w[axis]) || std::abs(w[axis]) > coordinate_limit)
                    throw Problem{where + "'s position " + std::to_string(i) + " is " +
                                  (file_finite ? "out of range after its node's transform" : "not a finite number") +
                                  "; allowed: finite coordinates within ±1e9"};
            part.positions[i] = glm::vec3(w);
        }
        const glm::dmat3 linear(world);
        const double det = glm::determinant(linear);
        if (det < 0.0)
            for (std::size_t t = 0; t + 2 < list.size(); t += 3) std::swap(list[t + 1], list[t + 2]);
        part.indices = std::move(list);

        // Normals: the file's, through the inverse transpose, when all are usable; else computed.
        bool usable = normals.has_value() && std::abs(det) > 1e-30;
        if (usable) {
            const glm::dmat3 normal_matrix = glm::inverseTranspose(linear);
            part.normals.resize(count);
            for (std::size_t i = 0; i < count && usable; ++i) {
                const glm::dvec3 n = normal_matrix * normals->vec3(i);
                const double len = glm::length(n);
                usable = std::isfinite(len) && len > 1e-12;
                if (usable) part.normals[i] = glm::vec3(n / len);
            }
            if (!usable) warnings.push_back(where + ": a normal is zero or not a finite number; normals computed instead");
        }
        if (!usable) compute_vertex_normals(part);
        if (uvs) {
            part.uvs.resize(count);
            for (std::size_t i = 0; i < count; ++i) {
                const glm::dvec2 t(uvs->component(i, 0), uvs->component(i, 1));
                if (!std::isfinite(t.x) || !std::isfinite(t.y))
                    throw Problem{where + "'s TEXCOORD_0 " + std::to_string(i) + " is not a finite number"};
                part.uvs[i] = glm::vec2(t);
            }
        } else {
            all_have_uvs = false;
        }
        // Append.
        const int slot = cut_slot(p.material);
        complete_cut_materials(mesh);
        const std::uint32_t base = static_cast<std::uint32_t>(mesh.positions.size());
        if (!all_have_uvs) mesh.uvs.clear();
        mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
        mesh.normals.insert(mesh.normals.end(), part.normals.begin(), part.normals.end());
        if (all_have_uvs) mesh.uvs.insert(mesh.uvs.end(), part.uvs.begin(), part.uvs.end());
        for (std::uint32_t i : part.indices) mesh.indices.push_back(base + i);
        append_cuts(slot, part, where);
    }

    void add_mesh(int index, int node, const glm::dmat4& world) {
        if (index < 0 || static_cast<std::size_t>(index) >= model.meshes.size())
            throw Problem{"node " + std::to_string(node) + " refers to mesh " + std::to_string(index) +
                          " but the file has " + std::to_string(model.meshes.size())};
        const tinygltf::Mesh& m = model.meshes[static_cast<std::size_t>(index)];
        for (std::size_t p = 0; p < m.primitives.size(); ++p)
            add_primitive(m.primitives[p], "mesh " + std::to_string(index) + " primitive " + std::to_string(p), world);
    }

    void note_lights(int node, const glm::dmat4& world) {
        if (const auto it = lights->area_of_node.find(node); it != lights->area_of_node.end())
            if (area_uses++ == 0) first_area = LightUse{node, it->second, world};
        if (const auto it = lights->punctual_of_node.find(node); it != lights->punctual_of_node.end()) {
            if (lights->punctual_types[static_cast<std::size_t>(it->second)] != "directional")
                ++other_punctual_uses;
            else if (directional_uses++ == 0)
                first_directional = LightUse{node, it->second, world};
        }
    }

    // The scene's lights from what note_lights met: the first area light as the rectangle, the first
    // directional light's direction as the sun's; a line in `warnings` for what else there was.
    void place_lights(Scene& scene) {
        if (first_area) {
            const AreaLightDefinition& d = lights->area[static_cast<std::size_t>(first_area->light)];
            scene.file_light = place_area_light(d, first_area->world, first_area->node);
            if (d.disk)
                warnings.push_back(
                    d.label + " on node " + std::to_string(first_area->node) +
                    " is a disk, which penumbra's shadows cannot serve (allowed: rect); it is lit as "
                    "the square of the same area, " +
                    number_text(scene.file_light->width) + " x " + number_text(scene.file_light->height) +
                    ", in its place, as Babylon.js does (--light-size W,H sets another size)");
            if (area_uses > 1)
                warnings.push_back("the scene has " + std::to_string(area_uses) +
                                   " area lights (EXT_lights_area); the first, " + d.label + " on node " +
                                   std::to_string(first_area->node) +
                                   ", is used (penumbra shades one rectangle)");
        }
        if (first_directional) {
            const std::string& label =
                lights->punctual_labels[static_cast<std::size_t>(first_directional->light)];
            const glm::dvec3 d = glm::dvec3(first_directional->world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
            const double length = glm::length(d);
            if (!std::isfinite(length) || !(length > 1e-12))
                throw Problem{
                    label + " on node " + std::to_string(first_directional->node) +
                    ": its node's transform has no direction for it (a zero scale along z); allowed: a "
                    "transform that keeps the node's z axis"};
            scene.file_sun_direction = d / length;
            if (directional_uses > 1)
                warnings.push_back("the scene has " + std::to_string(directional_uses) +
                                   " directional lights (KHR_lights_punctual); the first, " + label +
                                   " on node " + std::to_string(first_directional->node) + ", is the sun");
        }
        if (other_punctual_uses > 0)
            warnings.push_back(
                std::to_string(other_punctual_uses) + " KHR_lights_punctual point or spot light" +
                (other_punctual_uses == 1 ? "" : "s") +
                " ignored: penumbra shades a rectangle (EXT_lights_area) or the sun (a directional light)");
    }

    // Depth first from the roots; a node met again on its own path is a cycle (invalid glTF).
    void add_nodes(const std::vector<int>& roots, const std::string& roots_name) {
        struct Entry {
            int node;
            glm::dmat4 parent;
            std::size_t depth;
        };
        std::vector<Entry> stack;
        std::vector<int> path; // the nodes from the root to the current one
        for (auto it = roots.rbegin(); it != roots.rend(); ++it) stack.push_back({*it, glm::dmat4(1.0), 0});
        std::size_t visits = 0;
        while (!stack.empty()) {
            const Entry e = stack.back();
            stack.pop_back();
            const std::string parent_name = e.depth == 0 ? roots_name : "node " + std::to_string(path[e.depth - 1]);
            if (e.node < 0 || static_cast<std::size_t>(e.node) >= model.nodes.size())
                throw Problem{parent_name + " refers to node " + std::to_string(e.node) + " but the file has " +
                              std::to_string(model.nodes.size())};
            path.resize(e.depth);
            for (int ancestor : path)
                if (ancestor == e.node)
                    throw Problem{"node " + std::to_string(e.node) + " is its own ancestor (a cycle in the nodes' "
                                  "children); a node tree must not loop"};
            if (++visits > node_visit_budget)
                throw Problem{"the node tree reaches more than " + std::to_string(node_visit_budget) +
                              " nodes (a node listed as the child of many others?)"};
            path.push_back(e.node);
            const tinygltf::Node& node = model.nodes[static_cast<std::size_t>(e.node)];
            const glm::dmat4 world = e.parent * local_transform(node, e.node);
            if (node.mesh >= 0) add_mesh(node.mesh, e.node, world);
            if (lights) note_lights(e.node, world);
            for (auto c = node.children.rbegin(); c != node.children.rend(); ++c)
                stack.push_back({*c, world, e.depth + 1});
        }
    }
};

} // namespace

LoadResult load_gltf_scene(const std::string& path) {
    auto failure = [&](const std::string& problem) {
        return LoadResult{std::nullopt, "cannot load glTF file '" + penumbra_gen::printable(path, 200) + "': " + problem, {}};
    };
    const penumbra_gen::BoundedRead file = penumbra_gen::read_bounded_file(path, penumbra_gen::obj_file_limit);
    if (!file.text) return failure(file.problem == "no such file" ? "file does not exist" : file.problem);
    const std::string& bytes = *file.text;
    const std::filesystem::path fs_path(path);
    std::string extension = fs_path.extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool binary = bytes.compare(0, 4, "glTF") == 0;
    if (extension == ".glb" && !binary) return failure("not a binary glTF file: it does not start with 'glTF'");
    if (binary)
        if (std::string problem = check_glb(bytes); !problem.empty()) return failure(problem);

    std::string base_dir = fs_path.parent_path().string();
    if (base_dir.empty()) base_dir = ".";
    tinygltf::TinyGLTF parser;
    FileAccess access;
    const std::string json = binary ? bytes.substr(20, read_u32(bytes, 12)) : bytes;
    access.missing_buffers = missing_buffer_files(json, base_dir);
    // Compressed geometry: what tinygltf would refuse is rewritten first, decoded after the parse.
    const gltf_compression::Prepared compressed = gltf_compression::prepare(json);
    if (!compressed.problem.empty()) return failure(compressed.problem);
    const std::string prepared_bytes =
        !compressed.changed ? std::string() : binary ? gltf_compression::rewrap_glb(bytes, compressed.json) : compressed.json;
    const std::string& parsed = compressed.changed ? prepared_bytes : bytes;
    parser.SetFsCallbacks({&file_exists, &expand_nothing, &read_whole_file, &write_nothing, &access});
    EncodedImages images;
    parser.SetImageLoader(&keep_encoded_image, &images);
    tinygltf::Model model;
    std::string err, warn;
    bool ok = false;
    try {
        ok = binary ? parser.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(parsed.data()),
                                                  static_cast<unsigned int>(parsed.size()), base_dir)
                    : parser.LoadASCIIFromString(&model, &err, &warn, parsed.data(),
                                                 static_cast<unsigned int>(parsed.size()), base_dir);
    } catch (const std::exception& e) {
        return failure(std::string("parser failed: ") + first_line(e.what()));
    }
    if (!ok) {
        for (const std::string& missing : access.missing)
            if (err.find(std::filesystem::path(missing).filename().string()) != std::string::npos)
                return failure("its buffer file '" + penumbra_gen::printable(missing, 200) + "' does not exist");
        return failure(err.empty() ? "parse error" : first_line(err));
    }
    if (!model.asset.version.starts_with("2"))
        return failure("glTF version '" + penumbra_gen::printable(model.asset.version, 20) +
                       "' is not supported; allowed: 2.0");
    for (const std::string& ext : model.extensionsRequired)
        if (ext == "KHR_meshopt_compression")
            return failure("it requires " + penumbra_gen::printable(ext, 60) +
                           ", which is not supported; allowed: EXT_meshopt_compression, KHR_draco_mesh_compression");

    std::map<int, std::string> missing;
    for (const auto& [file, buffer] : access.missing_buffers)
        missing[buffer.buffer] = penumbra_gen::printable(file, 200);
    Loader loader{model, missing, {}, {}};
    loader.images = &images;
    FileLights lights;
    Scene result;
    try {
        lights = read_file_lights(nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false));
        loader.lights = &lights;
        if (const std::string problem = gltf_compression::decode(model, compressed, missing); !problem.empty())
            return failure(problem);
        if (model.defaultScene >= 0 && static_cast<std::size_t>(model.defaultScene) >= model.scenes.size())
            return failure("the default scene is " + std::to_string(model.defaultScene) + " but the file has " +
                           std::to_string(model.scenes.size()) + " scenes");
        if (model.scenes.empty()) return failure("no scenes (nothing to show)");
        const std::size_t scene = model.defaultScene >= 0 ? static_cast<std::size_t>(model.defaultScene) : 0;
        loader.add_nodes(model.scenes[scene].nodes, "scene " + std::to_string(scene));
        loader.place_lights(result); // before finish_scene, which puts them in place of the defaults
    } catch (const Problem& p) {
        return failure(p.text);
    } catch (const std::exception& e) { // std::bad_alloc
        return failure(std::string("out of memory or internal error: ") + e.what());
    }
    if (loader.mesh.indices.empty()) {
        std::string why = "no triangles in the scene's meshes";
        if (!loader.warnings.empty())
            why += " (" + std::to_string(loader.triangles_skipped_primitives) + " primitive" +
                   (loader.triangles_skipped_primitives == 1 ? "" : "s") + " skipped, e.g. " + loader.warnings.front() + ")";
        return failure(why);
    }
    result.name = fs_path.stem().string();
    result.mesh = std::move(loader.mesh);
    finish_scene(result);
    if (const std::string problem = validate_mesh(result.mesh); !problem.empty()) return failure(problem);
    LoadResult out{std::move(result), {}, {}};
    for (const std::string& w : loader.warnings) out.warnings.push_back(penumbra_gen::printable(path, 200) + ": " + w);
    return out;
}

} // namespace penumbra::playground
