// penumbra/gl/generic_shading.hpp — runs the generic reference program (penumbra/generic.hpp)
// on OpenGL 4.5 core over the textures a Runtime has built, for a G-buffer of world positions.
//
//   std::string error;
//   auto generic = penumbra::gl::GenericVisibilityPass::create(runtime->config(), &error);
//   // after runtime->build(...):
//   if (std::string d = generic->shade(*runtime, world_positions, width, height, world_normals); !d.empty()) { /* d */ }
//   std::vector<float> visibility = generic->read_visibility(); // R32F, bottom row first
//
// One compiled pass serves every runtime whose configuration shares its program text
// (same filter, packing, light, target and tangent clip): slices, resolution, fusion and fade are uniforms set
// at each shade() from that runtime's configuration. Header-only; <epoxy/gl.h>, no EGL or GLFW.
#pragma once

#include "../generic.hpp"
#include "runtime.hpp"

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace penumbra::gl {

class GenericVisibilityPass {
public:
    // Emits and links the generic program of `config`. On failure: nullptr and a diagnostic (the
    // validator's messages, or the compile / link log) in *error.
    static std::unique_ptr<GenericVisibilityPass> create(const Config& config, std::string* error = nullptr) {
        auto fail = [&](std::string message) -> std::unique_ptr<GenericVisibilityPass> {
            if (error) *error = std::move(message);
            return nullptr;
        };
        if (config.target == Target::vulkan) return fail("target: vulkan cannot run on OpenGL; allowed: glsl330, glsl450, essl300");
        Result<GenericShading> result = emit_generic(config);
        if (!result.value) {
            std::string m = "invalid configuration:";
            for (const ConfigError& e : result.errors) m += " " + e.message + ";";
            return fail(m);
        }
        std::unique_ptr<GenericVisibilityPass> pass(new GenericVisibilityPass());
        pass->config_ = config;
        pass->program_text_ = result.value->program;
        std::string log;
        pass->program_ = link_program(pass->program_text_, &log);
        if (!pass->program_) return fail("program " + pass->program_text_.name + ": " + log);
        glCreateVertexArrays(1, &pass->empty_vao_);
        glCreateFramebuffers(1, &pass->fbo_);
        if (const GLenum e = glGetError(); e != GL_NO_ERROR) return fail("GL error " + std::to_string(e) + " at setup");
        return pass;
    }

    ~GenericVisibilityPass() {
        if (program_) glDeleteProgram(program_);
        if (visibility_) glDeleteTextures(1, &visibility_);
        if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
        if (fbo_) glDeleteFramebuffers(1, &fbo_);
    }
    GenericVisibilityPass(const GenericVisibilityPass&) = delete;
    GenericVisibilityPass& operator=(const GenericVisibilityPass&) = delete;

    const Program& program_text() const { return program_text_; }
    GLuint program() const { return program_; }
    GLuint visibility() const { return visibility_; } // R32F, width × height of the last shade()

    // Visibility of every G-buffer texel (RGBA32F world positions, w = 1 on geometry) from the
    // textures `runtime` built, with its light frame and its configuration's values. With the
    // tangent clip, `world_normals` (RGBA32F, xyz = normal of the side the viewer sees) is required.
    // Returns an empty string on success, else a diagnostic.
    std::string shade(const Runtime& runtime, GLuint world_positions, int width, int height, GLuint world_normals = 0) {
        const Config& config = runtime.config();
        if (!shares_generic_program(config_, config))
            return "generic pass built for " + penumbra::detail::describe_generic(config_).str() +
                   " cannot shade a runtime of " + penumbra::detail::describe_generic(config).str();
        if (width <= 0 || height <= 0)
            return "G-buffer size " + std::to_string(width) + "x" + std::to_string(height) + " is empty";
        resize(width, height);
        GLint previous_fbo = 0, previous_viewport[4];
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_fbo);
        glGetIntegerv(GL_VIEWPORT, previous_viewport);
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, visibility_, 0);
        const GLenum buffer = GL_COLOR_ATTACHMENT0;
        glNamedFramebufferDrawBuffers(fbo_, 1, &buffer);
        std::string diagnostic = bind_inputs(runtime, world_positions, world_normals);
        if (diagnostic.empty() && glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            diagnostic = "generic visibility framebuffer incomplete";
        if (diagnostic.empty()) {
            glViewport(0, 0, width, height);
            glDisable(GL_BLEND);
            glDisable(GL_DEPTH_TEST);
            glDisable(GL_CULL_FACE);
            glUseProgram(program_);
            glBindVertexArray(empty_vao_);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindVertexArray(0);
            glUseProgram(0);
        }
        // detached again, so the next shade() is a framebuffer change: llvmpipe then starts a new
        // scene, without which back-to-back passes under-report GL_TIME_ELAPSED
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, 0, 0);
        glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous_fbo));
        glViewport(previous_viewport[0], previous_viewport[1], previous_viewport[2], previous_viewport[3]);
        if (diagnostic.empty())
            if (const GLenum e = glGetError(); e != GL_NO_ERROR)
                diagnostic = "GL error " + std::to_string(e) + " in the generic visibility pass";
        return diagnostic;
    }

    // The visibility of the last shade(), bottom row first (like Runtime::read_visibility).
    std::vector<float> read_visibility() const {
        std::vector<float> out(static_cast<std::size_t>(width_) * height_);
        if (visibility_) glGetTextureImage(visibility_, 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.size() * 4), out.data());
        return out;
    }

private:
    GenericVisibilityPass() = default;

    void resize(int width, int height) {
        if (visibility_ && width_ == width && height_ == height) return;
        if (visibility_) glDeleteTextures(1, &visibility_);
        glCreateTextures(GL_TEXTURE_2D, 1, &visibility_);
        glTextureStorage2D(visibility_, 1, GL_R32F, width, height);
        glTextureParameteri(visibility_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(visibility_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        width_ = width;
        height_ = height;
    }

    // Light uniforms from the runtime's frame, the configuration's values, and the textures.
    std::string bind_inputs(const Runtime& runtime, GLuint world_positions, GLuint world_normals) const {
        auto location = [&](const std::string& name) { return glGetUniformLocation(program_, name.c_str()); };
        const UniformInputs inputs = runtime.uniform_inputs();
        for (const UniformRule& rule : uniform_rules())
            if (const UniformResult v = rule.value(inputs))
                detail::set_uniform(program_, location(std::string(rule.name)), *v);
        for (const GenericValue& v : generic_values(runtime.config())) {
            if (v.type == "int") glProgramUniform1i(program_, location(v.name), static_cast<GLint>(v.value));
            else glProgramUniform1f(program_, location(v.name), static_cast<GLfloat>(v.value));
        }
        for (const GenericSampler& s : generic_samplers(runtime.config())) {
            GLuint texture = 0; // array elements this configuration does not use read nothing
            if (s.texture == "penumbra_worldPositions") texture = world_positions;
            else if (s.texture == "penumbra_worldNormals") texture = world_normals;
            else if (!s.texture.empty()) texture = runtime.texture(s.texture);
            if (s.texture == "penumbra_worldNormals" && !texture)
                return "the tangent clip reads the caller's world normals: pass the penumbra_worldNormals G-buffer to shade()";
            if (!s.texture.empty() && !texture) return "the runtime has no texture " + s.texture + " for " + s.name;
            glBindTextureUnit(static_cast<GLuint>(s.binding), texture);
            // glsl330 and essl300 have no layout(binding): the unit is set here
            glProgramUniform1i(program_, location(s.name), s.binding);
        }
        return {};
    }

    Config config_;
    Program program_text_;
    GLuint program_ = 0, visibility_ = 0, empty_vao_ = 0, fbo_ = 0;
    int width_ = 0, height_ = 0;
};

} // namespace penumbra::gl
