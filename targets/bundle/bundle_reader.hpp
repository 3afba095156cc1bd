// targets/bundle/bundle_reader.hpp — a target bundle as penumbra-export-bundle writes it
// (README.md here), read once for every runner: the scene's triangles, the light-frame uniforms,
// the G-buffers, the desktop GL runtime's visibility and the oracle's bound, and the emission
// (its layout.json and the folder of its shader files), and with --technique oim the bake.
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
    // oracle.f32 and bound.f32: the CPU model's visibility and its texture precision bound. The
    // oracle models occlusion textures only: a bundle of another technique (layout.json config
    // technique shadowmap, pcf, pcss, erosion, oim) has neither, and then both stay empty and
    // has_oracle is false; such a run is compared with visibility_gl alone.
    bool has_oracle = false;
    std::vector<float> oracle;
    std::vector<float> bound;
    // uniforms.json "bake_textures" (--technique oim): each texture the layout marks "source":
    // "bake", by name, as RGBA floats, rows from v = 0 (a whole number of RGBA texels; the runner
    // checks the count against the layout's width × height).
    std::map<std::string, std::vector<float>> bake_textures;
};

// Reads every file of the bundle in `dir` and checks each size against the image; on failure
// returns false with one line in *error naming the file (oracle.f32 and bound.f32 are required
// for occlusion textures, optional for the other techniques, and then both or neither).
bool read_bundle(const std::filesystem::path& dir, Bundle& out, std::string* error);

// The text of every file the programs of bundle.layout list, by file name; on failure returns
// false with one line in *error naming the missing file.
bool read_emission_sources(const Bundle& bundle, std::map<std::string, std::string>& out, std::string* error);

// The whole file as bytes; nullopt when it cannot be read.
std::optional<std::string> read_text(const std::filesystem::path& path);

} // namespace penumbra::targets
