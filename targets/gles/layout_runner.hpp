// targets/gles/layout_runner.hpp — runs an emission on OpenGL 3.3 core or OpenGL ES 3.0 by
// following its layout.json alone: the textures of `textures`, the programs of `programs`, the
// passes of `passes` in order with their render state, bindings, attachments and integer
// uniforms. Only calls that both APIs have (no direct state access, no texture storage, no
// layout(binding)), except logic_op OR (OpenGL 3.3 only); libepoxy resolves them on whichever
// context is current. The desktop runtime (include/penumbra/gl/runtime.hpp) needs OpenGL 4.5;
// this is the portable one. Every technique: occlusion textures (uniform or adaptive slices),
// the shadow-map techniques (depth attachments, per-binding comparison samplers, erosion's mip
// chain) and oim (its bake uploaded with fill_bake). What the API cannot do (on ES 3.0:
// CLAMP_TO_BORDER, logic_op, a depth texture filtered without comparison) fails with its reason.
//
//   auto runner = LayoutRunner::create(layout_json, sources, &error);  // a context is current
//   runner->set_uniform("penumbra_lightFromWorld", {16 floats, column-major});
//   runner->fill_bake("penumbra_rise0", rgba);                          // a "bake" texture (oim), once
//   runner->run_phase("shadow", draw_triangles, 0, 0);                  // slicing + prefilter, or the shadow map
//   runner->fill_texture("penumbra_worldPositions", w, h, rgba32f);     // a "caller" texture
//   runner->run_phase("screen", nullptr, w, h);                         // deferred visibility
//   std::vector<float> visibility = runner->read_result();              // bottom row first
#pragma once

#include <penumbra/layout_types.hpp>

#include <epoxy/gl.h>
#include <nlohmann/json.hpp>

#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

namespace penumbra::targets {

class LayoutRunner {
public:
    using DrawScene = std::function<void(GLuint program)>; // attribute 0: world position

    // Allocates the fixed-size textures and compiles the programs of the passes of `phases`.
    // `sources`: file name → text. On failure: nullptr and one line in *error naming the texture,
    // program or file.
    static std::unique_ptr<LayoutRunner> create(const nlohmann::json& layout,
                                                const std::map<std::string, std::string>& sources, std::string* error,
                                                const std::vector<Phase>& phases = {Phase::shadow, Phase::screen, Phase::example});
    ~LayoutRunner();
    LayoutRunner(const LayoutRunner&) = delete;
    LayoutRunner& operator=(const LayoutRunner&) = delete;

    // A plain uniform's value by GLSL name (matrices column-major); set on every program that has it.
    void set_uniform(const std::string& name, std::vector<float> value) { values_[name] = std::move(value); }

    // Fills a texture whose source is "caller" (RGBA floats); output-sized ones are allocated here.
    std::string fill_texture(const std::string& name, int width, int height, const float* rgba);

    // Uploads a texture whose source is "bake" (oim's interval maps): RGBA floats, rows from v = 0,
    // exactly the layout's width × height. Empty on success, else a diagnostic naming the texture.
    std::string fill_bake(const std::string& name, const std::vector<float>& rgba);

    // Runs the passes of `phase` ("shadow", "screen", "example") in layout order; width × height
    // is the output size (passes with a 0 × 0 viewport). Empty on success, else a diagnostic.
    std::string run_phase(Phase phase, const DrawScene& draw, int width, int height);

    // The layout's result texture (visibility) as floats, bottom row first.
    std::vector<float> read_result();

    // The location layout.json's programs give vertex input `input` (penumbra_position, …); -1 if none.
    int vertex_location(const std::string& input) const;

    // Extensions the layout made us require ("GL_EXT_color_buffer_float" on ES for float targets).
    const std::vector<std::string>& required_extensions() const { return extensions_; }

private:
    struct Texture {
        GLuint id = 0;
        GLenum target = 0;
        int width = 0, height = 0;
        const nlohmann::json* desc = nullptr;
        TextureFormat format = TextureFormat::rgba8;
        TextureSource source = TextureSource::passes;
        TextureSize size = TextureSize::fixed;
    };
    struct Program {
        GLuint id = 0;
        const nlohmann::json* desc = nullptr;
    };

    LayoutRunner() = default;
    std::string allocate(const nlohmann::json& desc, int width, int height);
    std::string link(const nlohmann::json& desc, const std::map<std::string, std::string>& sources);
    std::string allocate_output_sized(int width, int height);
    std::string run_pass(const nlohmann::json& pass, const DrawScene& draw, int width, int height);
    std::string bind_outputs(const nlohmann::json& pass, std::vector<bool>& integer_buffers, bool& has_depth);
    std::string clear(const nlohmann::json& state, const std::vector<bool>& integer_buffers, bool has_depth);
    void attach(GLenum framebuffer, GLenum attachment, const std::string& texture, int level, int layer);
    void apply_uniforms(const Program& program);
    std::string sampler(const nlohmann::json& sampling, const std::string& where, GLuint* id, bool depth_texture);
    std::string apply_state(const nlohmann::json& state);
    std::vector<float> read_texture(const Texture& t);

    nlohmann::json layout_;
    std::map<std::string, Texture> textures_;
    std::map<std::string, Program> programs_;
    std::map<std::string, std::vector<float>> values_;
    std::vector<std::string> extensions_;
    std::set<std::string> filled_; // caller and bake textures filled since their allocation
    std::map<Sampling, GLuint> samplers_; // one per distinct sampling
    std::set<Phase> phases_;             // the phases create linked programs for
    GLuint framebuffer_ = 0, read_framebuffer_ = 0, empty_vao_ = 0;
    int output_width_ = 0, output_height_ = 0;
};

} // namespace penumbra::targets
