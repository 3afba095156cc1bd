// penumbra/gl/runtime.hpp — runs an emission on OpenGL 4.5 core: compiles the programs, allocates
// the layout's textures, runs its passes, and shades a G-buffer of world positions.
//
//   // with a current GL 4.5 core context (libepoxy resolves the entry points)
//   std::string error;
//   auto runtime = penumbra::gl::Runtime::create(config, &error);
//   runtime->set_light(light, bounds_min, bounds_max);
//   runtime->build([&](GLuint program) { /* bind VAO: location 0 = world position; draw */ });
//   GLuint visibility = runtime->shade_deferred(world_positions_texture, width, height); // R32F
//   runtime->reconfigure(other_config);            // recreates only what changed
//   runtime->replace_program("shading_deferred", edited_stages); // hot reload, keeps the last good one
//
// GL errors: in debug builds (or with RuntimeOptions::debug_output) each call collects KHR_debug
// messages and returns them as its diagnostic; otherwise, and without KHR_debug, glGetError.
//
// Header-only; includes <epoxy/gl.h> and nothing of EGL or GLFW.
#pragma once

#include "../emit.hpp"
#include "../light_frame.hpp"
#include "link_program.hpp"

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <charconv>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace penumbra::gl {

struct PassTiming {
    std::string name;
    double milliseconds = 0.0;
};

struct RuntimeOptions {
    // Collect KHR_debug messages of high and medium severity during every runtime call and return
    // them as that call's diagnostic. Default: on in debug builds (NDEBUG not defined).
#ifdef NDEBUG
    bool debug_output = false;
#else
    bool debug_output = true;
#endif
};

namespace detail {

inline std::string gl_error_name(GLenum error) {
    switch (error) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    default: {
        char hex[16];
        std::snprintf(hex, sizeof hex, "0x%04X", error);
        return std::string("GL error ") + hex;
    }
    }
}

// Collects the GL debug messages that one runtime call produces. The callback is installed for the
// lifetime of this object only, and the previous callback, user pointer and enables are restored
// afterwards: no GL state ever points at a dead Runtime, and an engine's own callback keeps
// receiving every message (we forward them while installed).
class DebugCapture {
public:
    // Without `enabled` or without KHR_debug (GL < 4.3 and no extension) only glGetError is used.
    explicit DebugCapture(bool enabled) : active_(enabled && available()) {
        if (!active_) return;
        glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &previous_callback_);
        glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &previous_user_param_);
        output_was_enabled_ = glIsEnabled(GL_DEBUG_OUTPUT);
        synchronous_was_enabled_ = glIsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS);
        glDebugMessageCallback(&DebugCapture::receive, this);
        // Without a debug context GL_DEBUG_OUTPUT starts disabled; Mesa then still reports API
        // errors once it is enabled (other drivers may report less: glGetError stays as a backstop).
        glEnable(GL_DEBUG_OUTPUT);
        // Synchronous: messages arrive on this thread before the call that caused them returns,
        // so they all arrive while this object lives.
        glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    }
    ~DebugCapture() {
        if (!active_) return;
        glDebugMessageCallback(reinterpret_cast<GLDEBUGPROC>(previous_callback_), previous_user_param_);
        if (!output_was_enabled_) glDisable(GL_DEBUG_OUTPUT);
        if (!synchronous_was_enabled_) glDisable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    }
    DebugCapture(const DebugCapture&) = delete;
    DebugCapture& operator=(const DebugCapture&) = delete;

    // KHR_debug is core since GL 4.3.
    static bool available() { return epoxy_gl_version() >= 43 || epoxy_has_gl_extension("GL_KHR_debug"); }

    // The messages collected so far and the pending glGetError codes (always drained, so they do
    // not leak into the caller's next check), as one diagnostic naming `where`; empty when none.
    std::string take_diagnostic(const std::string& where) {
        std::vector<std::string> codes;
        for (GLenum e = glGetError(); e != GL_NO_ERROR && codes.size() < 16; e = glGetError())
            codes.push_back(gl_error_name(e));
        std::string out;
        if (!messages_.empty()) {
            out = "GL error in " + where + ": ";
            for (std::size_t i = 0; i < messages_.size(); ++i) out += (i ? "; " : "") + messages_[i];
            if (dropped_) out += "; and " + std::to_string(dropped_) + " more";
        } else if (!codes.empty()) {
            out = "GL error in " + where + ": ";
            for (std::size_t i = 0; i < codes.size(); ++i) out += (i ? ", " : "") + codes[i];
        }
        messages_.clear();
        dropped_ = 0;
        return out;
    }

private:
    static void GLAPIENTRY receive(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                   const GLchar* message, const void* user) {
        auto* self = static_cast<DebugCapture*>(const_cast<void*>(user));
        // Compiler messages (Mesa reports even warnings at high severity) reach the caller through
        // the compile log, with file and line; performance hints (NVIDIA: medium) are not errors.
        const bool counts = (severity == GL_DEBUG_SEVERITY_HIGH || severity == GL_DEBUG_SEVERITY_MEDIUM) &&
                            source != GL_DEBUG_SOURCE_SHADER_COMPILER && type != GL_DEBUG_TYPE_PERFORMANCE;
        if (counts) {
            if (self->messages_.size() < 8)
                self->messages_.emplace_back(message);
            else
                ++self->dropped_;
        }
        if (self->previous_callback_ && self->output_was_enabled_)
            reinterpret_cast<GLDEBUGPROC>(self->previous_callback_)(source, type, id, severity, length,
                                                                    message, self->previous_user_param_);
    }

    bool active_ = false;
    void* previous_callback_ = nullptr;
    void* previous_user_param_ = nullptr;
    bool output_was_enabled_ = false, synchronous_was_enabled_ = false;
    std::vector<std::string> messages_;
    std::size_t dropped_ = 0;
};

// Shader text without comments and blank lines. Every emitted file opens with a comment that
// names the whole configuration, so comparing raw text would rebuild every program on any change;
// comparing code rebuilds only the programs whose code depends on what changed.
inline std::string code_of(std::string_view text) {
    std::string out;
    while (!text.empty()) {
        const std::size_t end = std::min(text.find('\n'), text.size());
        std::string_view line = text.substr(0, end);
        line = line.substr(0, line.find("//")); // GLSL has no string literals; the emitter writes no /* */
        while (!line.empty() && (line.back() == ' ' || line.back() == '\t' || line.back() == '\r'))
            line.remove_suffix(1);
        if (!line.empty()) out.append(line).push_back('\n');
        text.remove_prefix(std::min(end + 1, text.size()));
    }
    return out;
}

inline bool same_code(const Program& a, const Program& b) {
    if (a.stages.size() != b.stages.size()) return false;
    for (std::size_t i = 0; i < a.stages.size(); ++i)
        if (a.stages[i].stage != b.stages[i].stage || code_of(a.stages[i].text) != code_of(b.stages[i].text))
            return false;
    return true;
}

// Same GL storage and sampling: a texture with this description can be kept as it is.
inline bool same_storage(const TextureDesc& a, const TextureDesc& b) {
    return a.target == b.target && a.internal_format == b.internal_format && a.width == b.width &&
           a.height == b.height && a.depth == b.depth && a.mip_levels == b.mip_levels &&
           a.min_filter == b.min_filter && a.mag_filter == b.mag_filter && a.wrap == b.wrap;
}

} // namespace detail

class Runtime {
public:
    using DrawScene = std::function<void(GLuint program)>;

    // Emits and compiles every program and allocates every texture. On failure: nullptr and a
    // diagnostic (validation errors, compile / link logs as "file:line: message", GL errors) in *error.
    static std::unique_ptr<Runtime> create(const Config& config, std::string* error = nullptr,
                                           const RuntimeOptions& options = {}) {
        auto fail = [&](std::string message) -> std::unique_ptr<Runtime> {
            if (error) *error = std::move(message);
            return nullptr;
        };
        std::unique_ptr<Runtime> rt(new Runtime());
        rt->options_ = options;
        // From an empty runtime, reconfigure builds every program and allocates every texture.
        if (std::string d = rt->reconfigure(config); !d.empty()) return fail(d);
        rt->last_reconfigure_ = {};
        detail::DebugCapture capture(options.debug_output);
        glCreateVertexArrays(1, &rt->empty_vao_);
        glCreateFramebuffers(1, &rt->fbo_);
        if (std::string d = capture.take_diagnostic("setup"); !d.empty()) return fail(d);
        return rt;
    }

    ~Runtime() {
        for (auto& [name, id] : programs_) glDeleteProgram(id);
        for (auto& [name, id] : textures_) glDeleteTextures(1, &id);
        if (visibility_) glDeleteTextures(1, &visibility_);
        if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
        if (fbo_) glDeleteFramebuffers(1, &fbo_);
    }
    Runtime(const Runtime&) = delete;
    Runtime& operator=(const Runtime&) = delete;

    // What runs: the emission of config(), with the stages of replaced programs (replace_program).
    const Emission& emission() const { return emission_; }
    const Config& config() const { return config_; }
    const SliceFrame& frame() const { return frame_; }
    // True when calls report KHR_debug messages (RuntimeOptions::debug_output and KHR_debug present).
    bool debug_output() const { return options_.debug_output && detail::DebugCapture::available(); }
    GLuint program(const std::string& name) const {
        auto it = programs_.find(name);
        return it == programs_.end() ? 0 : it->second;
    }
    // Intermediate textures by layout name (penumbra_slices, penumbra_level0, …), for inspection.
    GLuint texture(const std::string& name) const {
        auto it = textures_.find(name);
        return it == textures_.end() ? 0 : it->second;
    }

    void set_frame(const SliceFrame& frame) {
        frame_ = frame;
        light_ = std::monostate{}; // a frame set by hand is not recomputed by reconfigure
    }
    void set_light(const RectLight& light, glm::dvec3 bounds_min, glm::dvec3 bounds_max) {
        frame_ = slice_frame(light, bounds_min, bounds_max, config_.slices);
        light_ = light;
        bounds_min_ = bounds_min;
        bounds_max_ = bounds_max;
    }
    void set_light(const SunLight& sun, glm::dvec3 bounds_min, glm::dvec3 bounds_max) {
        frame_ = slice_frame(sun, bounds_min, bounds_max, config_.slices);
        light_ = sun;
        bounds_min_ = bounds_min;
        bounds_max_ = bounds_max;
    }

    // Switches to `config`: re-emits, rebuilds only the programs whose text changed and reallocates only the
    // textures whose description changed. On any failure (invalid configuration, compile/link error, GL
    // error) returns a diagnostic and leaves the runtime exactly as it was. Empty string on success. "Text"
    // is compared without comments (see detail::code_of). The frame is recomputed for the new slice count
    // from the last set_light; after changing config.light, call set_light again. Kept textures keep their
    // old contents until the next build().
    std::string reconfigure(const Config& config) {
        Result<Emission> result = emit(config);
        if (!result.value) return invalid_configuration(result.errors);
        Emission next = std::move(*result.value);
        detail::DebugCapture capture(options_.debug_output);
        std::map<std::string, GLuint> next_programs, next_textures;
        std::vector<GLuint> new_programs, new_textures;
        auto discard = [&](std::string diagnostic) {
            for (GLuint id : new_programs) glDeleteProgram(id);
            for (GLuint id : new_textures) glDeleteTextures(1, &id);
            capture.take_diagnostic("reconfigure"); // what failed is reported; clear the GL error flags
            return diagnostic;
        };
        for (const Program& p : next.programs) {
            const Program* running = find_program(p.name);
            if (running && detail::same_code(*running, p)) {
                next_programs[p.name] = programs_.at(p.name);
                continue;
            }
            std::string log;
            const GLuint id = link_program(p, &log);
            if (!id) return discard("program " + p.name + ": " + log);
            next_programs[p.name] = id;
            new_programs.push_back(id);
        }
        for (const TextureDesc& t : next.layout.textures) {
            const TextureDesc* current = find_texture(t.name);
            if (current && detail::same_storage(*current, t)) {
                next_textures[t.name] = textures_.at(t.name);
                continue;
            }
            std::string log;
            const GLuint id = allocate(t, &log);
            if (!id) return discard("texture " + t.name + ": " + log);
            next_textures[t.name] = id;
            new_textures.push_back(id);
        }
        if (std::string d = capture.take_diagnostic("reconfigure"); !d.empty()) return discard(d);

        // Commit: release what the new configuration no longer uses.
        for (auto& [name, id] : programs_)
            if (next_programs.count(name) == 0 || next_programs.at(name) != id) glDeleteProgram(id);
        for (auto& [name, id] : textures_)
            if (next_textures.count(name) == 0 || next_textures.at(name) != id) glDeleteTextures(1, &id);
        programs_ = std::move(next_programs);
        textures_ = std::move(next_textures);
        emission_ = std::move(next);
        config_ = config;
        if (const auto* rect = std::get_if<RectLight>(&light_))
            frame_ = slice_frame(*rect, bounds_min_, bounds_max_, config_.slices);
        if (const auto* sun = std::get_if<SunLight>(&light_))
            frame_ = slice_frame(*sun, bounds_min_, bounds_max_, config_.slices);
        last_reconfigure_ = {static_cast<int>(new_programs.size()), static_cast<int>(new_textures.size())};
        return {};
    }
    struct ReconfigureStats {
        int programs_rebuilt = 0, textures_reallocated = 0;
    };
    const ReconfigureStats& last_reconfigure() const { return last_reconfigure_; }

    // Replaces the shader sources of program `name` (same stages as its Program in emission(); e.g. a file
    // edited by hand). On a compile or link error returns the log with each message as "file_name:line:
    // message" and keeps the previous program running. Empty string on success.
    std::string replace_program(const std::string& name, const std::vector<ShaderFile>& stages) {
        Program* running = find_program(name);
        if (!running) {
            std::string names;
            for (const Program& p : emission_.programs) names += (names.empty() ? "" : ", ") + p.name;
            return "replace_program: no program named '" + name + "'; programs: " + names;
        }
        auto stage_list = [](const std::vector<ShaderFile>& files) {
            std::string s;
            for (const ShaderFile& f : files)
                s += (s.empty() ? "" : ", ") + std::string(stage_extension(f.stage));
            return s;
        };
        bool same_stages = stages.size() == running->stages.size();
        for (std::size_t i = 0; same_stages && i < stages.size(); ++i)
            same_stages = stages[i].stage == running->stages[i].stage;
        if (!same_stages)
            return "replace_program " + name + ": stages " + stage_list(stages) + " given; the program has " +
                   stage_list(running->stages);
        detail::DebugCapture capture(options_.debug_output);
        const Program candidate{name, stages};
        std::string log;
        const GLuint id = link_program(candidate, &log);
        if (!id) {
            capture.take_diagnostic("replace_program");
            return log;
        }
        if (std::string d = capture.take_diagnostic("replace_program " + name); !d.empty()) {
            glDeleteProgram(id);
            return d;
        }
        glDeleteProgram(programs_.at(name));
        programs_[name] = id;
        running->stages = stages;
        return {};
    }

    // Runs every pass of the layout except shading: slicing (draw_scene with `draw`), prefilter.
    // Returns an empty string on success, else a diagnostic (GL errors raised inside `draw` included).
    // With `timings`, one entry per pass (GL_TIME_ELAPSED queries; waits for the results).
    std::string build(const DrawScene& draw, std::vector<PassTiming>* timings = nullptr) {
        detail::DebugCapture capture(options_.debug_output);
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
        if (std::string d = capture.take_diagnostic("build"); diagnostic.empty()) diagnostic = d;
        return diagnostic;
    }

    // Binds the visibility samplers and light uniforms of a program that includes the snippet
    // (shading_example, shading_deferred, or the engine's own); the program must be in use.
    void bind_visibility(GLuint program) const {
        for (const ProgramDesc& p : emission_.layout.programs) {
            if (p.name != "shading_example") continue;
            for (const ParamDesc& param : p.parameters)
                if (param.binding >= 0 && !param.texture.empty())
                    bind_sampler(program, param.name, param.binding, texture(param.texture));
        }
        set_light_uniforms(program);
    }

    // Deferred visibility over a G-buffer of world positions (RGBA32F, w = 1 on geometry):
    // returns an R32F texture width × height (owned by the runtime) or 0 with *error set.
    // With `timing`, the GPU time of the pass ("shading", GL_TIME_ELAPSED; waits for the result).
    // `world_normals`: the G-buffer's normals (RGBA32F, xyz = the normal of the side the viewer
    // sees), needed when the configuration has tangent_clip on, unused otherwise.
    GLuint shade_deferred(GLuint world_positions, int width, int height, std::string* error = nullptr,
                          PassTiming* timing = nullptr, GLuint world_normals = 0) {
        detail::DebugCapture capture(options_.debug_output);
        if (width < 1 || height < 1) {
            if (error)
                *error = "shade_deferred: size " + std::to_string(width) + "x" + std::to_string(height) +
                         " is empty; allowed: at least 1x1";
            return 0;
        }
        if (config_.tangent_clip && !world_normals) {
            if (error) *error = "shade_deferred: tangent_clip is on, so the G-buffer's normals are needed; pass world_normals";
            return 0;
        }
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
            GLuint query = 0;
            if (timing) {
                glGenQueries(1, &query);
                glBeginQuery(GL_TIME_ELAPSED, query);
            }
            glViewport(0, 0, width, height);
            glDisable(GL_BLEND);
            glDisable(GL_DEPTH_TEST);
            glDisable(GL_CULL_FACE);
            glUseProgram(program);
            bind_visibility(program);
            for (const ProgramDesc& p : emission_.layout.programs)
                if (p.name == "shading_deferred")
                    for (const ParamDesc& param : p.parameters)
                        if (param.name == "penumbra_worldPositions")
                            bind_sampler(program, param.name, param.binding, world_positions);
                        else if (param.name == "penumbra_worldNormals")
                            bind_sampler(program, param.name, param.binding, world_normals);
            glBindVertexArray(empty_vao_);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindVertexArray(0);
            glUseProgram(0);
            if (timing) {
                glEndQuery(GL_TIME_ELAPSED);
                GLuint64 ns = 0;
                glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
                glDeleteQueries(1, &query);
                *timing = {"shading", ns * 1e-6};
            }
        }
        glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous_fbo));
        glViewport(previous_viewport[0], previous_viewport[1], previous_viewport[2], previous_viewport[3]);
        if (std::string d = capture.take_diagnostic("shade_deferred"); diagnostic.empty()) diagnostic = d;
        if (!diagnostic.empty()) {
            if (error) *error = diagnostic;
            return 0;
        }
        return visibility_;
    }

    // Reads back the visibility texture of the last shade_deferred (bottom row first).
    std::vector<float> read_visibility() const {
        std::vector<float> out(static_cast<std::size_t>(visibility_width_) * visibility_height_);
        if (visibility_)
            glGetTextureImage(visibility_, 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.size() * 4),
                              out.data());
        return out;
    }

private:
    Runtime() = default;

    static std::string invalid_configuration(const std::vector<ConfigError>& errors) {
        std::string m = "invalid configuration:";
        for (const ConfigError& e : errors) m += " " + e.message + ";";
        return m;
    }

    Program* find_program(const std::string& name) {
        for (Program& p : emission_.programs)
            if (p.name == name) return &p;
        return nullptr;
    }
    const TextureDesc* find_texture(const std::string& name) const {
        for (const TextureDesc& t : emission_.layout.textures)
            if (t.name == name) return &t;
        return nullptr;
    }

    static GLenum gl_enum(const std::string& name) {
        static const std::map<std::string, GLenum> names{{"2D", GL_TEXTURE_2D},
                                                         {"2D_ARRAY", GL_TEXTURE_2D_ARRAY},
                                                         {"3D", GL_TEXTURE_3D},
                                                         {"RGBA8", GL_RGBA8},
                                                         {"RGBA16F", GL_RGBA16F},
                                                         {"RGBA32F", GL_RGBA32F},
                                                         {"NEAREST", GL_NEAREST},
                                                         {"LINEAR", GL_LINEAR},
                                                         {"LINEAR_MIPMAP_LINEAR", GL_LINEAR_MIPMAP_LINEAR},
                                                         {"CLAMP_TO_BORDER", GL_CLAMP_TO_BORDER},
                                                         {"CLAMP_TO_EDGE", GL_CLAMP_TO_EDGE}};
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
        if (target == GL_TEXTURE_2D)
            glTextureStorage2D(id, t.mip_levels, format, t.width, t.height);
        else
            glTextureStorage3D(id, t.mip_levels, format, t.width, t.height, t.depth);
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
        for (int level = 0; level < t.mip_levels; ++level)
            glClearTexImage(id, level, GL_RGBA, GL_FLOAT, zero);
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
        glProgramUniformMatrix4fv(program, loc("penumbra_lightFromWorld"), 1, GL_FALSE,
                                  glm::value_ptr(frame_.light_from_world));
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
            if (out.layer >= 0)
                glNamedFramebufferTextureLayer(fbo_, attachment, texture(out.texture), out.level, out.layer);
            else
                glNamedFramebufferTexture(fbo_, attachment, texture(out.texture), out.level);
            buffers.push_back(attachment);
        }
        glNamedFramebufferDrawBuffers(fbo_, static_cast<GLsizei>(buffers.size()), buffers.data());
        if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return "pass " + pass.name + ": framebuffer incomplete";
        glViewport(0, 0, pass.viewport_width, pass.viewport_height);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glUseProgram(program);
        for (const BindingDesc& in : pass.inputs)
            bind_sampler(program, in.sampler, in.binding, texture(in.texture));
        for (const auto& [name, value] : pass.int_uniforms)
            glProgramUniform1i(program, glGetUniformLocation(program, name.c_str()), value);
        if (pass.action == "draw_scene") {
            set_light_uniforms(program);
            const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
            for (std::size_t i = 0; i < buffers.size(); ++i)
                glClearBufferfv(GL_COLOR, static_cast<GLint>(i), zero);
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
    RuntimeOptions options_;
    std::map<std::string, GLuint> programs_, textures_;
    GLuint empty_vao_ = 0, fbo_ = 0, visibility_ = 0;
    int visibility_width_ = 0, visibility_height_ = 0;
    std::variant<std::monostate, RectLight, SunLight> light_; // last set_light, for reconfigure
    glm::dvec3 bounds_min_{0.0}, bounds_max_{0.0};
    ReconfigureStats last_reconfigure_;
};

} // namespace penumbra::gl
