// penumbra/gl/runtime.hpp — runs an emission on OpenGL 4.5 core: compiles the programs, allocates
// the layout's textures, runs its passes, and shades a G-buffer of world positions.
//
//   // with a current GL 4.5 core context (libepoxy resolves the entry points)
//   std::string error;
//   auto runtime = penumbra::gl::Runtime::create(config, &error);
//   runtime->set_light(light, bounds_min, bounds_max);
//   runtime->build([&](GLuint program) { /* bind VAO: location 0 = world position; draw */ });
//   GLuint visibility = runtime->shade_deferred(world_positions_texture, width, height); // R32F
//
// Header-only; includes <epoxy/gl.h> and nothing of EGL or GLFW.
#pragma once

#include "../emit.hpp"
#include "../light_frame.hpp"

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::gl {

struct PassTiming {
    std::string name;
    double milliseconds = 0.0;
};

class Runtime {
public:
    using DrawScene = std::function<void(GLuint program)>;

    // Emits and compiles every program and allocates every texture. On failure: nullopt and a
    // diagnostic (validation errors, compile / link logs, GL errors) in *error.
    static std::unique_ptr<Runtime> create(const Config& config, std::string* error = nullptr) {
        auto fail = [&](std::string message) -> std::unique_ptr<Runtime> {
            if (error) *error = std::move(message);
            return nullptr;
        };
        Result<Emission> result = emit(config);
        if (!result.value) {
            std::string m = "invalid configuration:";
            for (const ConfigError& e : result.errors) m += " " + e.message + ";";
            return fail(m);
        }
        std::unique_ptr<Runtime> rt(new Runtime());
        rt->config_ = config;
        rt->emission_ = std::move(*result.value);
        for (const Program& program : rt->emission_.programs) {
            std::string log;
            const GLuint id = link(program, &log);
            if (!id) return fail("program " + program.name + ": " + log);
            rt->programs_[program.name] = id;
        }
        for (const TextureDesc& t : rt->emission_.layout.textures) {
            std::string log;
            const GLuint id = allocate(t, &log);
            if (!id) return fail("texture " + t.name + ": " + log);
            rt->textures_[t.name] = id;
        }
        glCreateVertexArrays(1, &rt->empty_vao_);
        glCreateFramebuffers(1, &rt->fbo_);
        if (const GLenum e = glGetError(); e != GL_NO_ERROR) return fail("GL error " + std::to_string(e) + " at setup");
        return rt;
    }

    ~Runtime() {
        for (auto& [name, id] : programs_) glDeleteProgram(id);
        for (auto& [name, id] : textures_) glDeleteTextures(1, &id);
        if (visibility_) glDeleteTextures(1, &visibility_);
        if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
        if (fbo_) glDeleteFramebuffers(1, &fbo_);
        for (GLuint q : queries_) glDeleteQueries(1, &q);
    }
    Runtime(const Runtime&) = delete;
    Runtime& operator=(const Runtime&) = delete;

    const Emission& emission() const { return emission_; }
    const Config& config() const { return config_; }
    const SliceFrame& frame() const { return frame_; }
    GLuint program(const std::string& name) const {
        auto it = programs_.find(name);
        return it == programs_.end() ? 0 : it->second;
    }
    GLuint texture(const std::string& name) const {
        auto it = textures_.find(name);
        return it == textures_.end() ? 0 : it->second;
    }

    void set_frame(const SliceFrame& frame) { frame_ = frame; }
    void set_light(const RectLight& light, glm::dvec3 bounds_min, glm::dvec3 bounds_max) {
        frame_ = slice_frame(light, bounds_min, bounds_max, config_.slices);
    }
    void set_light(const SunLight& sun, glm::dvec3 bounds_min, glm::dvec3 bounds_max) {
        frame_ = slice_frame(sun, bounds_min, bounds_max, config_.slices);
    }

    // Runs every pass of the layout except shading: slicing (draw_scene with `draw`), prefilter.
    // Returns an empty string on success, else a diagnostic. With `timings`, one entry per pass
    // (GL_TIME_ELAPSED queries; waits for the results).
    std::string build(const DrawScene& draw, std::vector<PassTiming>* timings = nullptr) {
        GLint previous_fbo = 0, previous_viewport[4];
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_fbo);
        glGetIntegerv(GL_VIEWPORT, previous_viewport);
        std::vector<std::pair<std::string, GLuint>> pending;
        std::string diagnostic;
        for (const PassDesc& pass : emission_.layout.passes) {
            if (pass.name == "shading") continue;
            GLuint query = 0;
            if (timings) {
                glGenQueries(1, &query);
                glBeginQuery(GL_TIME_ELAPSED, query);
            }
            diagnostic = run_pass(pass, draw);
            if (timings) {
                glEndQuery(GL_TIME_ELAPSED);
                pending.push_back({pass.name, query});
            }
            if (!diagnostic.empty()) break;
        }
        for (auto& [name, query] : pending) {
            GLuint64 ns = 0;
            glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
            timings->push_back({name, ns * 1e-6});
            glDeleteQueries(1, &query);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous_fbo));
        glViewport(previous_viewport[0], previous_viewport[1], previous_viewport[2], previous_viewport[3]);
        glDisable(GL_BLEND);
        if (diagnostic.empty())
            if (const GLenum e = glGetError(); e != GL_NO_ERROR) diagnostic = "GL error " + std::to_string(e);
        return diagnostic;
    }

    // Binds the visibility samplers and light uniforms of a program that includes the snippet
    // (shading_example, shading_deferred, or the engine's own); the program must be in use.
    void bind_visibility(GLuint program) const {
        for (const ProgramDesc& p : emission_.layout.programs) {
            if (p.name != "shading_example") continue;
            for (const ParamDesc& param : p.parameters)
                if (param.binding >= 0 && !param.texture.empty()) bind_sampler(program, param.name, param.binding, texture(param.texture));
        }
        set_light_uniforms(program);
    }

    // Deferred visibility over a G-buffer of world positions (RGBA32F, w = 1 on geometry):
    // returns an R32F texture width × height (owned by the runtime) or 0 with *error set.
    GLuint shade_deferred(GLuint world_positions, int width, int height, std::string* error = nullptr) {
        if (!visibility_ || visibility_width_ != width || visibility_height_ != height) {
            if (visibility_) glDeleteTextures(1, &visibility_);
            glCreateTextures(GL_TEXTURE_2D, 1, &visibility_);
            glTextureStorage2D(visibility_, 1, GL_R32F, width, height);
            glTextureParameteri(visibility_, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
            glTextureParameteri(visibility_, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
            visibility_width_ = width;
            visibility_height_ = height;
        }
        GLint previous_fbo = 0, previous_viewport[4];
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_fbo);
        glGetIntegerv(GL_VIEWPORT, previous_viewport);
        const GLuint program = this->program("shading_deferred");
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        detach_all();
        glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0, visibility_, 0);
        const GLenum buffer = GL_COLOR_ATTACHMENT0;
        glNamedFramebufferDrawBuffers(fbo_, 1, &buffer);
        std::string diagnostic;
        if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            diagnostic = "deferred framebuffer incomplete";
        if (diagnostic.empty()) {
            glViewport(0, 0, width, height);
            glDisable(GL_BLEND);
            glDisable(GL_DEPTH_TEST);
            glDisable(GL_CULL_FACE);
            glUseProgram(program);
            bind_visibility(program);
            for (const ProgramDesc& p : emission_.layout.programs)
                if (p.name == "shading_deferred")
                    for (const ParamDesc& param : p.parameters)
                        if (param.name == "penumbra_worldPositions") bind_sampler(program, param.name, param.binding, world_positions);
            glBindVertexArray(empty_vao_);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindVertexArray(0);
            glUseProgram(0);
        }
        glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous_fbo));
        glViewport(previous_viewport[0], previous_viewport[1], previous_viewport[2], previous_viewport[3]);
        if (diagnostic.empty())
            if (const GLenum e = glGetError(); e != GL_NO_ERROR) diagnostic = "GL error " + std::to_string(e) + " in shade_deferred";
        if (!diagnostic.empty()) {
            if (error) *error = diagnostic;
            return 0;
        }
        return visibility_;
    }

    // Reads back the visibility texture of the last shade_deferred (bottom row first).
    std::vector<float> read_visibility() const {
        std::vector<float> out(static_cast<std::size_t>(visibility_width_) * visibility_height_);
        if (visibility_) glGetTextureImage(visibility_, 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.size() * 4), out.data());
        return out;
    }

private:
    Runtime() = default;

    static GLenum stage_enum(Stage stage) {
        switch (stage) {
        case Stage::vertex: return GL_VERTEX_SHADER;
        case Stage::compute: return GL_COMPUTE_SHADER;
        default: return GL_FRAGMENT_SHADER;
        }
    }

    static GLuint link(const Program& program, std::string* log) {
        const GLuint id = glCreateProgram();
        std::vector<GLuint> shaders;
        bool ok = true;
        for (const ShaderFile& file : program.stages) {
            const GLuint s = glCreateShader(stage_enum(file.stage));
            const char* text = file.text.c_str();
            glShaderSource(s, 1, &text, nullptr);
            glCompileShader(s);
            GLint status = 0;
            glGetShaderiv(s, GL_COMPILE_STATUS, &status);
            if (!status) {
                GLint length = 0;
                glGetShaderiv(s, GL_INFO_LOG_LENGTH, &length);
                std::string text_log(static_cast<std::size_t>(std::max(length, 1)), '\0');
                glGetShaderInfoLog(s, length, nullptr, text_log.data());
                *log += file.file_name + ": " + text_log.c_str();
                ok = false;
            }
            glAttachShader(id, s);
            shaders.push_back(s);
        }
        if (ok) {
            glLinkProgram(id);
            GLint status = 0;
            glGetProgramiv(id, GL_LINK_STATUS, &status);
            if (!status) {
                GLint length = 0;
                glGetProgramiv(id, GL_INFO_LOG_LENGTH, &length);
                std::string text_log(static_cast<std::size_t>(std::max(length, 1)), '\0');
                glGetProgramInfoLog(id, length, nullptr, text_log.data());
                *log += std::string("link: ") + text_log.c_str();
                ok = false;
            }
        }
        for (GLuint s : shaders) glDeleteShader(s);
        if (!ok) {
            glDeleteProgram(id);
            return 0;
        }
        return id;
    }

    static GLenum gl_enum(const std::string& name) {
        static const std::map<std::string, GLenum> names{
            {"2D", GL_TEXTURE_2D}, {"2D_ARRAY", GL_TEXTURE_2D_ARRAY}, {"3D", GL_TEXTURE_3D},
            {"RGBA8", GL_RGBA8}, {"RGBA16F", GL_RGBA16F}, {"RGBA32F", GL_RGBA32F},
            {"NEAREST", GL_NEAREST}, {"LINEAR", GL_LINEAR}, {"LINEAR_MIPMAP_LINEAR", GL_LINEAR_MIPMAP_LINEAR},
            {"CLAMP_TO_BORDER", GL_CLAMP_TO_BORDER}, {"CLAMP_TO_EDGE", GL_CLAMP_TO_EDGE}};
        auto it = names.find(name);
        return it == names.end() ? 0 : it->second;
    }

    static GLuint allocate(const TextureDesc& t, std::string* log) {
        const GLenum target = gl_enum(t.target), format = gl_enum(t.internal_format);
        if (!target || !format) {
            *log = "unknown target or format " + t.target + " " + t.internal_format;
            return 0;
        }
        GLuint id = 0;
        glCreateTextures(target, 1, &id);
        if (target == GL_TEXTURE_2D) glTextureStorage2D(id, t.mip_levels, format, t.width, t.height);
        else glTextureStorage3D(id, t.mip_levels, format, t.width, t.height, t.depth);
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(gl_enum(t.min_filter)));
        glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(gl_enum(t.mag_filter)));
        const GLint wrap = static_cast<GLint>(gl_enum(t.wrap));
        glTextureParameteri(id, GL_TEXTURE_WRAP_S, wrap);
        glTextureParameteri(id, GL_TEXTURE_WRAP_T, wrap);
        glTextureParameteri(id, GL_TEXTURE_WRAP_R, wrap);
        const float border[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glTextureParameterfv(id, GL_TEXTURE_BORDER_COLOR, border);
        glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, t.mip_levels - 1);
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        for (int level = 0; level < t.mip_levels; ++level) glClearTexImage(id, level, GL_RGBA, GL_FLOAT, zero);
        if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
            *log = "GL error " + std::to_string(e);
            glDeleteTextures(1, &id);
            return 0;
        }
        return id;
    }

    static void bind_sampler(GLuint program, const std::string& name, int unit, GLuint texture_id) {
        glBindTextureUnit(static_cast<GLuint>(unit), texture_id);
        const GLint location = glGetUniformLocation(program, name.c_str());
        if (location >= 0) glProgramUniform1i(program, location, unit); // glsl330: no layout(binding)
    }

    void set_light_uniforms(GLuint program) const {
        auto loc = [&](const char* name) { return glGetUniformLocation(program, name); };
        glProgramUniformMatrix4fv(program, loc("penumbra_lightFromWorld"), 1, GL_FALSE, glm::value_ptr(frame_.light_from_world));
        glProgramUniformMatrix4fv(program, loc("penumbra_sliceClipFromWorld"), 1, GL_FALSE,
                                  glm::value_ptr(frame_.slice_clip_from_world));
        glProgramUniform2fv(program, loc("penumbra_lightSize"), 1, glm::value_ptr(frame_.light_size));
        glProgramUniform1f(program, loc("penumbra_copDistance"), frame_.cop_distance);
        glProgramUniform2fv(program, loc("penumbra_sliceDepths"), 1, glm::value_ptr(frame_.slice_depths));
        glProgramUniform1f(program, loc("penumbra_windowHalfSize"), frame_.window_half_size);
        glProgramUniform1f(program, loc("penumbra_tanAngularRadius"), frame_.tan_angular_radius);
    }

    void detach_all() {
        for (int i = 0; i < 8; ++i) glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0 + i, 0, 0);
    }

    std::string run_pass(const PassDesc& pass, const DrawScene& draw) {
        if (pass.action == "generate_mipmap") {
            glGenerateTextureMipmap(texture(pass.outputs.at(0).texture));
            return {};
        }
        if (pass.action == "copy") {
            const GLuint src = texture(pass.inputs.at(0).texture), dst = texture(pass.outputs.at(0).texture);
            const AttachmentDesc& out = pass.outputs.at(0);
            GLenum dst_target = GL_TEXTURE_2D;
            for (const TextureDesc& t : emission_.layout.textures)
                if (t.name == out.texture) dst_target = gl_enum(t.target);
            glCopyImageSubData(src, GL_TEXTURE_2D, 0, 0, 0, 0, dst, dst_target, out.level, 0, 0,
                               std::max(out.layer, 0), pass.viewport_width, pass.viewport_height, 1);
            return {};
        }
        const GLuint program = this->program(pass.program);
        if (!program) return "pass " + pass.name + ": no program " + pass.program;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        detach_all();
        std::vector<GLenum> buffers;
        for (std::size_t i = 0; i < pass.outputs.size(); ++i) {
            const AttachmentDesc& out = pass.outputs[i];
            const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
            if (out.layer >= 0) glNamedFramebufferTextureLayer(fbo_, attachment, texture(out.texture), out.level, out.layer);
            else glNamedFramebufferTexture(fbo_, attachment, texture(out.texture), out.level);
            buffers.push_back(attachment);
        }
        glNamedFramebufferDrawBuffers(fbo_, static_cast<GLsizei>(buffers.size()), buffers.data());
        if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return "pass " + pass.name + ": framebuffer incomplete";
        glViewport(0, 0, pass.viewport_width, pass.viewport_height);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glUseProgram(program);
        for (const BindingDesc& in : pass.inputs) bind_sampler(program, in.sampler, in.binding, texture(in.texture));
        for (const auto& [name, value] : pass.int_uniforms) glProgramUniform1i(program, glGetUniformLocation(program, name.c_str()), value);
        if (pass.action == "draw_scene") {
            set_light_uniforms(program);
            const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            for (std::size_t i = 0; i < buffers.size(); ++i) glClearBufferfv(GL_COLOR, static_cast<GLint>(i), zero);
            glEnable(GL_BLEND);
            glBlendEquation(GL_MAX);
            glBlendFunc(GL_ONE, GL_ONE);
            draw(program);
            glDisable(GL_BLEND);
        } else {
            glDisable(GL_BLEND);
            glBindVertexArray(empty_vao_);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindVertexArray(0);
        }
        glUseProgram(0);
        return {};
    }

    Config config_;
    Emission emission_;
    SliceFrame frame_;
    std::map<std::string, GLuint> programs_, textures_;
    std::vector<GLuint> queries_;
    GLuint empty_vao_ = 0, fbo_ = 0, visibility_ = 0;
    int visibility_width_ = 0, visibility_height_ = 0;
};

} // namespace penumbra::gl
