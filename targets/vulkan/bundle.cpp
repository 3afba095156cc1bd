#include "bundle.hpp"

#include <nlohmann/json.hpp>

#include <fstream>

namespace penumbra::vulkan {
namespace {

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

} // namespace

bool read_bundle(const std::filesystem::path& dir, Bundle& out, std::string* error) {
    const std::filesystem::path uniforms_path = dir / "uniforms.json";
    std::ifstream file(uniforms_path);
    if (!file) {
        *error = "cannot read " + uniforms_path.string() + " (is " + dir.string() + " a bundle?)";
        return false;
    }
    std::map<std::string, std::string> caller_files; // texture name → file in the bundle
    try {
        const nlohmann::json json = nlohmann::json::parse(file);
        out.width = json.at("width").get<int>();
        out.height = json.at("height").get<int>();
        for (const auto& [name, value] : json.at("uniforms").items())
            out.uniforms[name] = value.is_array() ? value.get<std::vector<float>>() : std::vector<float>{value.get<float>()};
        for (const auto& [name, file] : json.at("caller_textures").items()) caller_files[name] = file.get<std::string>();
    } catch (const nlohmann::json::exception& e) {
        *error = uniforms_path.string() + ": " + e.what();
        return false;
    }
    if (out.width < 1 || out.height < 1) {
        *error = uniforms_path.string() + ": empty image size";
        return false;
    }
    const std::size_t pixels = static_cast<std::size_t>(out.width) * out.height;
    out.emission_dir = dir / "emission";
    if (!read_floats(dir / "mesh.f32", 0, out.triangles, error)) return false;
    if (out.triangles.size() % 9 != 0) {
        *error = (dir / "mesh.f32").string() + ": " + std::to_string(out.triangles.size()) +
                 " floats, not whole triangles (9 floats each)";
        return false;
    }
    for (const auto& [name, file] : caller_files)
        if (!read_floats(dir / file, 4 * pixels, out.caller_textures[name], error)) return false;
    return read_floats(dir / "visibility_gl.f32", pixels, out.visibility_gl, error) &&
           read_floats(dir / "oracle.f32", pixels, out.oracle, error) &&
           read_floats(dir / "bound.f32", pixels, out.bound, error);
}

} // namespace penumbra::vulkan
