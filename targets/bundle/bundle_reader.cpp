#include "bundle_reader.hpp"

#include <fstream>
#include <sstream>

namespace penumbra::targets {
namespace {

// A file of floats, `expected` of them (0: any whole number of floats).
bool read_floats(const std::filesystem::path& path, std::size_t expected, std::vector<float>& out, std::string* error) {
    std::ifstream file(path, std::ios::binary | std::ios::ate);
    if (!file) {
        *error = "cannot read " + path.string();
        return false;
    }
    const auto bytes = static_cast<std::size_t>(file.tellg());
    if (bytes % sizeof(float) != 0 || (expected && bytes != expected * sizeof(float))) {
        *error = path.string() + ": " + std::to_string(bytes) + " bytes; expected " +
                 (expected ? std::to_string(expected * sizeof(float)) : std::string("a multiple of 4"));
        return false;
    }
    out.resize(bytes / sizeof(float));
    file.seekg(0);
    file.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(bytes));
    if (!file) *error = "cannot read " + path.string();
    return static_cast<bool>(file);
}

bool read_json(const std::filesystem::path& path, nlohmann::json& out, std::string* error, const std::string& hint) {
    std::ifstream file(path);
    if (!file) {
        *error = "cannot read " + path.string() + hint;
        return false;
    }
    try {
        out = nlohmann::json::parse(file);
    } catch (const nlohmann::json::exception& e) {
        *error = path.string() + ": " + e.what();
        return false;
    }
    return true;
}

} // namespace

std::optional<std::string> read_text(const std::filesystem::path& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) return std::nullopt;
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

bool read_bundle(const std::filesystem::path& dir, Bundle& out, std::string* error) {
    const std::filesystem::path uniforms_path = dir / "uniforms.json";
    const std::string not_a_bundle = " (is " + dir.string() + " a bundle?)";
    out.emission_dir = dir / "emission";
    nlohmann::json info;
    if (!read_json(uniforms_path, info, error, not_a_bundle) ||
        !read_json(out.emission_dir / "layout.json", out.layout, error, not_a_bundle))
        return false;
    std::map<std::string, std::string> caller_files; // texture name → file in the bundle
    std::map<std::string, std::string> bake_files;   // uniforms.json bake_textures (oim)
    std::string technique = "occlusion";
    if (out.layout.is_object() && out.layout.contains("config") && out.layout["config"].is_object() &&
        out.layout["config"].contains("technique") && out.layout["config"]["technique"].is_string())
        technique = out.layout["config"]["technique"].get<std::string>();
    try {
        out.width = info.at("width").get<int>();
        out.height = info.at("height").get<int>();
        for (const auto& [name, value] : info.at("uniforms").items())
            out.uniforms[name] = value.is_array() ? value.get<std::vector<float>>() : std::vector<float>{value.get<float>()};
        const nlohmann::json callers = info.value("caller_textures", nlohmann::json::object()); // kept: items() refers to it
        for (const auto& [name, file] : callers.items()) caller_files[name] = file.get<std::string>();
        const nlohmann::json bakes = info.value("bake_textures", nlohmann::json::object());
        for (const auto& [name, file] : bakes.items()) bake_files[name] = file.get<std::string>();
    } catch (const nlohmann::json::exception& e) {
        *error = uniforms_path.string() + ": " + e.what();
        return false;
    }
    if (out.width < 1 || out.height < 1) {
        *error = uniforms_path.string() + ": empty image size";
        return false;
    }
    const std::size_t pixels = static_cast<std::size_t>(out.width) * out.height;
    if (!read_floats(dir / "mesh.f32", 0, out.triangles, error)) return false;
    if (out.triangles.size() % 9 != 0) {
        *error = (dir / "mesh.f32").string() + ": " + std::to_string(out.triangles.size()) +
                 " floats, not whole triangles (9 floats each)";
        return false;
    }
    for (const auto& [name, file] : caller_files)
        if (!read_floats(dir / file, 4 * pixels, out.caller_textures[name], error)) return false;
    for (const auto& [name, file] : bake_files) {
        std::vector<float>& texels = out.bake_textures[name];
        if (!read_floats(dir / file, 0, texels, error)) return false;
        if (texels.empty() || texels.size() % 4 != 0) {
            *error = (dir / file).string() + ": " + std::to_string(texels.size()) +
                     " floats, not whole RGBA texels (uniforms.json bake_textures " + name + ")";
            return false;
        }
    }
    if (!read_floats(dir / "visibility_gl.f32", pixels, out.visibility_gl, error)) return false;
    // The oracle models occlusion textures only (targets/bundle/README.md): other techniques' bundles
    // have neither oracle.f32 nor bound.f32.
    const bool oracle_files = std::filesystem::exists(dir / "oracle.f32") || std::filesystem::exists(dir / "bound.f32");
    if (technique != "occlusion" && !oracle_files) return true;
    out.has_oracle = read_floats(dir / "oracle.f32", pixels, out.oracle, error) &&
                     read_floats(dir / "bound.f32", pixels, out.bound, error);
    return out.has_oracle;
}

bool read_emission_sources(const Bundle& bundle, std::map<std::string, std::string>& out, std::string* error) {
    try {
        for (const nlohmann::json& program : bundle.layout.at("programs"))
            for (const nlohmann::json& entry : program.at("files")) {
                const std::string file = entry.get<std::string>();
                std::optional<std::string> text = read_text(bundle.emission_dir / file);
                if (!text) {
                    *error = "cannot read " + (bundle.emission_dir / file).string() + " (listed in layout.json)";
                    return false;
                }
                out[file] = std::move(*text);
            }
    } catch (const nlohmann::json::exception& e) {
        *error = (bundle.emission_dir / "layout.json").string() + ": " + e.what();
        return false;
    }
    return true;
}

} // namespace penumbra::targets
