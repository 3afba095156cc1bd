// targets/vulkan/bundle.hpp — a target bundle as penumbra-export-bundle writes it
// (targets/bundle/README.md): the scene's triangles, the light-frame uniforms, the G-buffers, the
// GL runtime's visibility and the oracle's bound, and the emission's folder.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace penumbra::vulkan {

struct Bundle {
    std::filesystem::path emission_dir;          // emission/: layout.json and the shader files
    int width = 0, height = 0;                   // the output image
    std::vector<float> triangles;                // mesh.f32: xyz, 3 vertices per triangle
    std::map<std::string, std::vector<float>> uniforms; // uniforms.json "uniforms": GLSL name → floats
    // The G-buffers of uniforms.json "caller_textures" (positions.f32, normals.f32) by texture name:
    // RGBA32F, bottom row first. The runner fills those the layout declares with source "caller".
    std::map<std::string, std::vector<float>> caller_textures;
    std::vector<float> visibility_gl;            // visibility_gl.f32
    std::vector<float> oracle;                   // oracle.f32: the CPU model's visibility
    std::vector<float> bound;                    // bound.f32
};

// Reads every file of the bundle in `dir`; on failure returns false with one line in *error.
bool read_bundle(const std::filesystem::path& dir, Bundle& out, std::string* error);

} // namespace penumbra::vulkan
