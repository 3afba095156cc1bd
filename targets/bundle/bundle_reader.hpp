// targets/bundle/bundle_reader.hpp — a target bundle as penumbra-export-bundle writes it
// (README.md here), read once for every runner: the scene's triangles, the light-frame uniforms,
// the G-buffers, the desktop GL runtime's visibility and the oracle's bound, and the emission
// (its layout.json and the folder of its shader files).
//
//   penumbra::targets::Bundle bundle;
//   if (!read_bundle(dir, bundle, &error)) ...;              // every file, sizes checked
//   read_emission_sources(bundle, sources, &error);          // the shader files layout.json lists
#pragma once

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::targets {

struct Bundle {
    std::filesystem::path emission_dir;          // emission/: layout.json and the shader files
    nlohmann::json layout;                       // emission/layout.json
    int width = 0, height = 0;                   // the output image
    std::vector<float> triangles;                // mesh.f32: xyz, 3 vertices per triangle
    std::map<std::string, std::vector<float>> uniforms; // uniforms.json "uniforms": GLSL name → floats
    // The G-buffers of uniforms.json "caller_textures" (positions.f32, normals.f32, ...) by texture
    // name: RGBA32F, bottom row first. A runner fills those the layout declares with source "caller".
    std::map<std::string, std::vector<float>> caller_textures;
    std::vector<float> visibility_gl;            // visibility_gl.f32: the desktop GL runtime's
    std::vector<float> oracle;                   // oracle.f32: the CPU model's visibility
    std::vector<float> bound;                    // bound.f32: the oracle's texture precision bound
};

// Reads every file of the bundle in `dir` and checks each size against the image; on failure
// returns false with one line in *error naming the file.
bool read_bundle(const std::filesystem::path& dir, Bundle& out, std::string* error);

// The text of every file the programs of bundle.layout list, by file name; on failure returns
// false with one line in *error naming the missing file.
bool read_emission_sources(const Bundle& bundle, std::map<std::string, std::string>& out, std::string* error);

// The whole file as bytes; nullopt when it cannot be read.
std::optional<std::string> read_text(const std::filesystem::path& path);

} // namespace penumbra::targets
