// targets/vulkan/runner.hpp — the Vulkan layout runner (layout_runner.hpp says what it does), in parts:
// layout.json's words in Vulkan's terms and the checks of Vulkan's guaranteed limits in
// layout_words.hpp; the Runner here, its resources (images, buffers, samplers, views, uploads and
// read-back) in runner_resources.cpp, its programs and pipelines (SPIR-V, descriptor set layouts,
// uniform blocks, render state) in runner_pipelines.cpp, and the passes it records in runner_passes.cpp.
// Private to penumbra-vulkan-run: run_layout (layout_runner.cpp) is the entry point.
#pragma once

#include "layout_words.hpp"

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::vulkan::detail {

struct Texture {
    std::string name;
    TextureTarget target = TextureTarget::texture_2d;
    FormatInfo format;
    std::uint32_t width = 0, height = 0, depth = 1, levels = 1;
    // zero, caller, bake (layout_version 3; else from "source"); none: "undefined", this runner's
    // own word for a texture it need not clear (every texel the passes read is written first)
    std::optional<TextureInitial> initial;
    const json* desc = nullptr;
    VkImage image = VK_NULL_HANDLE;
    std::uint32_t layers() const { return target == TextureTarget::texture_2d_array ? depth : 1; }
    std::uint32_t extent_depth() const { return target == TextureTarget::texture_3d ? depth : 1; }
};

struct Block {
    int size = 0;
    std::vector<json> members;
};

// Where a parameter lives: descriptor set ("set", 0 when absent) and binding.
using SetBinding = std::pair<int, int>;

struct VertexInputs {
    int position = -1, normal = -1; // attribute locations; -1: not read
};

struct Program {
    const json* desc = nullptr;
    std::vector<VkPipelineShaderStageCreateInfo> stages;
    std::vector<VkDescriptorSetLayout> set_layouts; // index = set number, empty layouts in gaps
    VkPipelineLayout pipeline_layout = VK_NULL_HANDLE;
    std::map<SetBinding, Block> blocks;  // uniform blocks
    std::map<SetBinding, json> samplers; // sampler parameters
    VertexInputs vertex_inputs;
};

struct Buffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    void* mapped = nullptr;
};

class Runner {
public:
    Runner(const Context& context, const LayoutInputs& inputs) : c_(context), in_(inputs), device_(context.device()) {}
    ~Runner() {
        vkDeviceWaitIdle(device_);
        for (auto it = cleanup_.rbegin(); it != cleanup_.rend(); ++it) (*it)();
    }
    Runner(const Runner&) = delete;
    Runner& operator=(const Runner&) = delete;

    void run(LayoutOutput& out);

private:
    template <class F> void on_cleanup(F f) { cleanup_.emplace_back(std::move(f)); }

    // What draw_scene passes draw: per vertex the world position (location of penumbra_position)
    // and the triangle's unit face normal (penumbra_normal: the bundle has positions only, and its
    // scenes are flat-shaded), interleaved, 6 floats a vertex.
    void fill_vertices(float* out) const;

    Texture& texture(const std::string& name);

    VkDeviceMemory allocate(VkMemoryRequirements req, VkMemoryPropertyFlags flags, const std::string& what);

    // A host-visible, coherent buffer, mapped for its lifetime.
    Buffer create_buffer(std::size_t bytes, VkBufferUsageFlags usage);

    // The parameter `name` of program `program` (nullptr when there is none).
    const json* parameter(const std::string& program, const std::string& name) const;

    // How a pass input is read: its "sampling" (version 3), else its sampler parameter's, else
    // (version 2) the texture's filters, wrap and compare.
    Sampling input_sampling(const json& pass, const json& input) const;

    // What the passes do with a texture decides its usage flags and the format features it needs.
    void create_texture(const json& t, const std::vector<const json*>& passes);

    // One VkSampler per distinct sampling state. A sampler parameter declared as a shadow sampler
    // (sampler2DShadow, ...) must be read with a compare function, and any other without one.
    static void check_sampler_type(const Sampling& sampling, const std::string& type, const std::string& what);

    VkSampler sampler(const Sampling& sampling, const std::string& type, const std::string& what);

    // Views, made once per (texture, type, level range, layer range).
    VkImageView view(const Texture& t, VkImageViewType type, std::uint32_t level, std::uint32_t levels, std::uint32_t layer, std::uint32_t layers);

    // What a sampler reads: the whole texture, or only level `level` (>= 0).
    VkImageView sampled_view(const Texture& t, int level);

    // What a pass renders to: one level of one layer (array layer, or depth slice of a 3D texture).
    VkImageView attachment_view(const Texture& t, int level, int layer);

    Program& program(const std::string& name);

    // At most RequiredLimits::bound_descriptor_sets sets a pass, each within the per-stage limits.
    void create_descriptor_pool(std::size_t passes);

    // The value of one block member: "light" parameters from the inputs, "pass" ones from the
    // pass's int_uniforms (std140: an int is 4 bytes, a mat4 four vec4 columns).
    void write_member(const json& param, const json& pass, unsigned char* block);

    // `depth_format`: the depth attachment's format, VK_FORMAT_UNDEFINED when the pass has none.
    VkPipeline pipeline(const std::string& program_name, Program& prog, const json& pass, const std::vector<VkFormat>& formats, VkFormat depth_format);

    // Creates what one pass needs and returns the function that records it.
    std::function<void(VkCommandBuffer)> prepare_pass(const json& pass);

    // Each level from the one above it, halving: "mipmap" {base_level, levels, downsample "box"}
    // (layout_version 3; levels counts the chain from base_level on, base included), else the
    // whole chain from level 0. A 2:1 linear blit averages 2×2 texels (2×2×2 in 3D): the box.
    std::function<void(VkCommandBuffer)> prepare_mipmaps(const json& pass);

    // inputs[0] into outputs[0]: "copy" {source_level, source_layer, target_level, target_layer,
    // width, height} (layout_version 3; a layer is an array layer or a 3D depth slice, -1 meaning
    // 0), else the input's level (0 when it names all), the output's level and layer and the
    // viewport's size. Depth textures copy their depth aspect.
    std::function<void(VkCommandBuffer)> prepare_copy(const json& pass);

    // Textures whose initial contents come from outside ("initial" caller: the G-buffers; bake:
    // precomputed maps), from the inputs' RGBA floats into staging buffers in the texture's format
    // (32-bit floats as given, 16-bit floats rounded to nearest even, as GL converts them).
    std::vector<Buffer> stage_caller_textures();

    // IEEE binary16 of a float, rounded to nearest even; overflow to infinity, NaN kept.
    static std::uint16_t to_half(float value);

    // Every image by its "initial": zero cleared to 0 (all levels and layers; depth to 0.0), caller
    // and bake uploaded, undefined left as it is; then all in GENERAL, the layout in which passes
    // sample and render them.
    void initialise_images(VkCommandBuffer cmd, const std::vector<Buffer>& uploads);

    // A layout change of `range`, ordered after everything before and before everything after.
    static void transition(VkCommandBuffer cmd, VkImage image, const VkImageSubresourceRange& range, VkImageLayout from, VkImageLayout to);

    // Everything written before is visible to everything after.
    static void barrier(VkCommandBuffer cmd);

    // The first channel of every texel, as float.
    static std::vector<float> to_floats(const Texture& t, const void* data);

    const Context& c_;
    const LayoutInputs& in_;
    VkDevice device_;
    std::vector<std::function<void()>> cleanup_;
    std::map<std::string, Texture> textures_;
    Target target_ = Target::vulkan;             // the layout's: vulkan (GLSL) or hlsl
    std::vector<std::string> caller_order_;      // the textures stage_caller_textures filled, in order
    std::map<std::string, VkImageView> views_;
    std::map<std::string, Program> programs_;
    std::map<std::string, VkPipeline> pipelines_;
    std::map<std::pair<Sampling, bool>, VkSampler> samplers_; // by sampling, and whether it reads integers
    VkDescriptorPool pool_ = VK_NULL_HANDLE;
    Buffer vertices_;
};

} // namespace penumbra::vulkan::detail
