// targets/vulkan/layout_runner.hpp — runs an emission for the vulkan target by following its
// layout.json alone: the textures become images (colour, depth, integer), each program's GLSL is
// compiled to SPIR-V with glslang, descriptor set layouts come from the parameters' sets and
// bindings and the uniform blocks from their std140 offsets, every sampled binding gets the
// VkSampler its "sampling" describes (filters, wrap, border, depth comparison; layout_version 2:
// the texture's), draw_scene passes feed position and normal to the locations "vertex_inputs"
// names, and the passes of the "shadow" phase, then the "screen" phase, are recorded in order
// (dynamic rendering with colour and depth attachments; copies and mipmap blits as transfer
// commands, per their "copy" and "mipmap" details). Textures start as their "initial" says: zero
// (cleared), undefined, caller or bake (uploaded from the inputs).
//
// Every image rests in VK_IMAGE_LAYOUT_GENERAL (passes sample and render it there, depth images
// too), transfer commands move the subresources they touch to TRANSFER_SRC/DST_OPTIMAL and back,
// and a full memory barrier separates consecutive commands: simple and valid, not fast (this
// runner checks correctness, it is not an engine).
#pragma once

#include "vulkan_context.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace penumbra::vulkan {

struct LayoutInputs {
    nlohmann::json layout;                     // layout.json
    std::filesystem::path emission_dir;        // the folder of layout.json: its "files" are read from here
    int width = 0, height = 0;                 // the output size (textures and passes sized "output")
    std::vector<float> triangles;              // what "draw_scene" passes draw: xyz, 3 vertices a triangle
    std::map<std::string, std::vector<float>> uniforms; // values of parameters whose source is "light"
    // Textures whose "initial" is "caller" (G-buffers) or "bake" (precomputed maps, e.g. OIM's):
    // texture name → RGBA floats, 4 a texel, rows from 0 up; converted to the texture's format.
    std::map<std::string, std::vector<float>> caller_textures;
    std::map<std::string, std::vector<float>> bake_textures;
};

struct LayoutOutput {
    std::vector<float> result;       // the layout's "result" texture, one float per texel, rows from 0 up
    std::vector<std::string> passes; // the passes that ran, in order
};

// Runs every pass of the "shadow" and "screen" phases. Returns an empty string on success, else
// one line naming the texture, program or pass that could not be created or run and why.
std::string run_layout(const Context& context, const LayoutInputs& inputs, LayoutOutput& output);

} // namespace penumbra::vulkan
