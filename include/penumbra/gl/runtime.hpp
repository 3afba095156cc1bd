// penumbra/gl/runtime.hpp — runs an emission on OpenGL 4.5 core: compiles the programs, allocates
// the layout's textures, runs its passes from the layout's data alone (phase "shadow" in build,
// phase "screen" in run_screen / shade_deferred), and shades a G-buffer of world positions.
//
//   // with a current GL 4.5 core context (libepoxy resolves the entry points)
//   std::string error;
//   auto runtime = penumbra::gl::Runtime::create(config, &error);
//   runtime->set_light(light, bounds_min, bounds_max); // fits config.level_bound to the light (RuntimeOptions)
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
#include "../level_bound.hpp"
#include "../light_frame.hpp"
#include "../uniform_values.hpp"
#include "link_program.hpp"

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <array>
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
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
    // Only the filter levels the light's kernels reach (penumbra/level_bound.hpp): for a configuration
    // whose level_bound is -1, set_light / set_frame re-emit with the bound the light and bounds need
    // (the first time exactly, later only when the light grows past it: a smaller light keeps the
    // levels). Off: every level, as configured.
    bool fit_level_bound = true;
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
           a.min_filter == b.min_filter && a.mag_filter == b.mag_filter && a.wrap == b.wrap &&
           a.border_color == b.border_color && a.size == b.size && a.source == b.source && a.compare == b.compare;
}

// The GL enum of a layout.json word (targets, formats, filters, wraps, state); 0 when unknown.
inline GLenum gl_enum(const std::string& name) {
    static const std::map<std::string, GLenum> names{
        {"2D", GL_TEXTURE_2D}, {"2D_ARRAY", GL_TEXTURE_2D_ARRAY}, {"3D", GL_TEXTURE_3D},
        {"RGBA8", GL_RGBA8}, {"RGBA16F", GL_RGBA16F}, {"RGBA32F", GL_RGBA32F}, {"R8", GL_R8},
        {"R16F", GL_R16F}, {"R32F", GL_R32F}, {"RG16F", GL_RG16F}, {"RG32F", GL_RG32F},
        {"RGBA32UI", GL_RGBA32UI}, {"R32UI", GL_R32UI}, {"DEPTH_COMPONENT24", GL_DEPTH_COMPONENT24},
        {"DEPTH_COMPONENT32F", GL_DEPTH_COMPONENT32F},
        {"NEAREST", GL_NEAREST}, {"LINEAR", GL_LINEAR}, {"LINEAR_MIPMAP_LINEAR", GL_LINEAR_MIPMAP_LINEAR},
        {"NEAREST_MIPMAP_NEAREST", GL_NEAREST_MIPMAP_NEAREST}, {"LINEAR_MIPMAP_NEAREST", GL_LINEAR_MIPMAP_NEAREST},
        {"NEAREST_MIPMAP_LINEAR", GL_NEAREST_MIPMAP_LINEAR},
        {"CLAMP_TO_BORDER", GL_CLAMP_TO_BORDER}, {"CLAMP_TO_EDGE", GL_CLAMP_TO_EDGE},
        {"ADD", GL_FUNC_ADD}, {"MAX", GL_MAX}, {"MIN", GL_MIN},
        {"ZERO", GL_ZERO}, {"ONE", GL_ONE}, {"SRC_ALPHA", GL_SRC_ALPHA}, {"ONE_MINUS_SRC_ALPHA", GL_ONE_MINUS_SRC_ALPHA},
        {"DST_COLOR", GL_DST_COLOR},
        {"NEVER", GL_NEVER}, {"LESS", GL_LESS}, {"EQUAL", GL_EQUAL}, {"LEQUAL", GL_LEQUAL}, {"GREATER", GL_GREATER},
        {"NOTEQUAL", GL_NOTEQUAL}, {"GEQUAL", GL_GEQUAL}, {"ALWAYS", GL_ALWAYS},
        {"BACK", GL_BACK}, {"FRONT", GL_FRONT}, {"OR", GL_OR}};
    auto it = names.find(name);
    return it == names.end() ? 0 : it->second;
}

// Two frames give the same uniforms (and so the same shadow phase output).
inline bool same_frame(const SliceFrame& a, const SliceFrame& b) {
    return a.light_from_world == b.light_from_world && a.slice_clip_from_world == b.slice_clip_from_world &&
           a.light_size == b.light_size && a.cop_distance == b.cop_distance && a.slice_depths == b.slice_depths &&
           a.window_half_size == b.window_half_size && a.tan_angular_radius == b.tan_angular_radius &&
           a.contained == b.contained;
}

inline bool is_depth_format(const std::string& format) { return format.starts_with("DEPTH_COMPONENT"); }
inline bool is_integer_format(const std::string& format) { return format.ends_with("UI"); }
// Components of a colour format: R → 1, RG → 2, RGBA → 4.
inline int format_channels(const std::string& format) {
    if (format.starts_with("RGBA")) return 4;
    if (format.starts_with("RG")) return 2;
    return 1;
}
inline GLenum pixel_format(int channels, bool integer) {
    if (integer) return channels == 4 ? GL_RGBA_INTEGER : channels == 2 ? GL_RG_INTEGER : GL_RED_INTEGER;
    return channels == 4 ? GL_RGBA : channels == 2 ? GL_RG : GL_RED;
}

// Sets a uniform of `program` from a uniform_values.hpp value; no-op when the program lacks it.
inline void set_uniform(GLuint program, GLint location, const UniformValue& value) {
    if (location < 0) return;
    std::visit(
        [&](const auto& v) {
            using V = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<V, int>) glProgramUniform1i(program, location, v);
            else if constexpr (std::is_same_v<V, float>) glProgramUniform1f(program, location, v);
            else if constexpr (std::is_same_v<V, glm::vec2>) glProgramUniform2fv(program, location, 1, glm::value_ptr(v));
            else if constexpr (std::is_same_v<V, glm::vec4>) glProgramUniform4fv(program, location, 1, glm::value_ptr(v));
            else glProgramUniformMatrix4fv(program, location, 1, GL_FALSE, glm::value_ptr(v));
        },
        value);
}

// Applies a pass's fixed-function state (everything RenderState names; the rest is left alone).
inline void apply_state(const RenderState& s) {
    if (s.blend) {
        glEnable(GL_BLEND);
        glBlendEquation(gl_enum(s.blend_equation));
        glBlendFunc(gl_enum(s.blend_src), gl_enum(s.blend_dst));
    } else {
        glDisable(GL_BLEND);
    }
    if (s.depth_test) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(gl_enum(s.depth_func));
    } else {
        glDisable(GL_DEPTH_TEST);
    }
    glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
    glColorMask(s.color_mask[0], s.color_mask[1], s.color_mask[2], s.color_mask[3]);
    if (s.cull == "NONE") {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(gl_enum(s.cull));
    }
    if (s.logic_op != "NONE") { // integer targets: each fragment OR-ed into the texel (no blending)
        glEnable(GL_COLOR_LOGIC_OP);
        glLogicOp(gl_enum(s.logic_op));
    } else {
        glDisable(GL_COLOR_LOGIC_OP);
    }
    if (s.polygon_offset_factor != 0.0f || s.polygon_offset_units != 0.0f) {
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(s.polygon_offset_factor, s.polygon_offset_units);
    } else {
        glDisable(GL_POLYGON_OFFSET_FILL);
    }
}

// GL's defaults for what apply_state touches, restored after the runtime's passes.
inline void reset_state() {
    RenderState defaults;
    defaults.depth_write = true;
    apply_state(defaults);
}

} // namespace detail

// Runs a layout generically: every texture, pass, binding, state and uniform comes from the
// layout's data (penumbra/layout.hpp); nothing here knows a pass, program or technique by name.
class Runtime {
public:
    using DrawScene = std::function<void(GLuint program)>;
    using TextureMap = std::map<std::string, GLuint>;

    // Emits and compiles every program and allocates every fixed-size texture. On failure: nullptr and
    // a diagnostic (validation errors, compile / link logs as "file:line: message", GL errors) in *error.
    static std::unique_ptr<Runtime> create(const Config& config, std::string* error = nullptr,
                                           const RuntimeOptions& options = {}) {
        Result<Emission> result = emit(config);
        if (!result.value) {
            if (error) *error = invalid_configuration(result.errors);
            return nullptr;
        }
        std::unique_ptr<Runtime> rt = create(std::move(*result.value), error, options);
        if (rt) rt->fits_levels_ = options.fit_level_bound && config.level_bound < 0;
        return rt;
    }
    // The same from an emission (a layout and its programs), e.g. one edited or built by hand.
    static std::unique_ptr<Runtime> create(Emission emission, std::string* error = nullptr,
                                           const RuntimeOptions& options = {}) {
        auto fail = [&](std::string message) -> std::unique_ptr<Runtime> {
            if (error) *error = std::move(message);
            return nullptr;
        };
        std::unique_ptr<Runtime> rt(new Runtime());
        rt->options_ = options;
        // From an empty runtime, adopt builds every program and allocates every texture.
        if (std::string d = rt->adopt(std::move(emission)); !d.empty()) return fail(d);
        rt->last_reconfigure_ = {};
        rt->requested_ = rt->config_;
        detail::DebugCapture capture(options.debug_output);
        glCreateVertexArrays(1, &rt->empty_vao_);
        glCreateFramebuffers(1, &rt->fbo_);
        if (std::string d = capture.take_diagnostic("setup"); !d.empty()) return fail(d);
        return rt;
    }

    ~Runtime() {
        for (auto& [name, id] : programs_) glDeleteProgram(id);
        for (auto& [name, id] : textures_) glDeleteTextures(1, &id);
        for (auto& [name, id] : output_textures_) glDeleteTextures(1, &id);
        if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
        if (fbo_) glDeleteFramebuffers(1, &fbo_);
    }
    Runtime(const Runtime&) = delete;
    Runtime& operator=(const Runtime&) = delete;

    // What runs: the emission of config(), with the stages of replaced programs (replace_program).
    const Emission& emission() const { return emission_; }
    const Layout& layout() const { return emission_.layout; }
    // The configuration that runs: requested_config() with level_bound fitted to the light
    // (RuntimeOptions::fit_level_bound), the one layout() describes.
    const Config& config() const { return config_; }
    // The configuration given to create / reconfigure.
    const Config& requested_config() const { return requested_; }
    const SliceFrame& frame() const { return frame_; }
    // True when calls report KHR_debug messages (RuntimeOptions::debug_output and KHR_debug present).
    bool debug_output() const { return options_.debug_output && detail::DebugCapture::available(); }
    GLuint program(const std::string& name) const {
        auto it = programs_.find(name);
        return it == programs_.end() ? 0 : it->second;
    }
    // Textures by layout name (penumbra_slices, penumbra_level0, penumbra_visibility, …): the runtime's
    // own, the output-sized ones of the last screen run, and bake textures given by supply_texture.
    GLuint texture(const std::string& name) const {
        for (const TextureMap* map : {&supplied_, &textures_, &output_textures_})
            if (auto it = map->find(name); it != map->end()) return it->second;
        return 0;
    }

    // Each returns an empty string, or the diagnostic of re-emitting with a larger level_bound (the
    // runtime then keeps running with the levels it had).
    std::string set_frame(const SliceFrame& frame) {
        if (!detail::same_frame(frame_, frame)) shadow_current_ = false;
        frame_ = frame;
        light_ = std::monostate{}; // a frame set by hand is not recomputed by reconfigure
        return fit_level_bound();
    }
    std::string set_light(const RectLight& light, glm::dvec3 bounds_min, glm::dvec3 bounds_max) {
        const SliceFrame frame = slice_frame(light, bounds_min, bounds_max, config_.slices);
        if (!detail::same_frame(frame_, frame)) shadow_current_ = false;
        frame_ = frame;
        light_ = light;
        bounds_min_ = bounds_min;
        bounds_max_ = bounds_max;
        return fit_level_bound();
    }
    std::string set_light(const SunLight& sun, glm::dvec3 bounds_min, glm::dvec3 bounds_max) {
        const SliceFrame frame = slice_frame(sun, bounds_min, bounds_max, config_.slices);
        if (!detail::same_frame(frame_, frame)) shadow_current_ = false;
        frame_ = frame;
        light_ = sun;
        bounds_min_ = bounds_min;
        bounds_max_ = bounds_max;
        return fit_level_bound();
    }
    // The sun's time window along its path (penumbra/sun_path.hpp), for techniques whose light is a
    // sun on a fixed path (occlusion interval maps): start, end, 1 / (end − start), centre t.
    void set_time_window(glm::vec4 window) { time_window_ = window; }

    // What "light" (and "camera") uniforms are computed from (penumbra/uniform_values.hpp).
    UniformInputs uniform_inputs() const { return {frame_, config_.light, std::nullopt, shadow_frame(), time_window_}; }
    // The shadow-map camera (shadow map techniques) of the last set_light; the default frame after set_frame.
    ShadowFrame shadow_frame() const {
        if (const auto* rect = std::get_if<RectLight>(&light_)) return penumbra::shadow_frame(*rect, bounds_min_, bounds_max_);
        if (const auto* sun = std::get_if<SunLight>(&light_)) return penumbra::shadow_frame(*sun, bounds_min_, bounds_max_);
        return {};
    }

    // Switches to `config`: re-emits, rebuilds only the programs whose text changed and reallocates only the
    // textures whose description changed. On any failure (invalid configuration, compile/link error, GL
    // error) returns a diagnostic and leaves the runtime exactly as it was. Empty string on success. "Text"
    // is compared without comments (see detail::code_of). The frame is recomputed for the new slice count
    // from the last set_light; after changing config.light, call set_light again. Kept textures keep their
    // old contents until the next build(). A level_bound of -1 is fitted to the last light (see
    // RuntimeOptions::fit_level_bound).
    std::string reconfigure(const Config& config) {
        const bool fits = options_.fit_level_bound && config.level_bound < 0;
        Config next = config;
        if (fits && has_frame()) {
            SliceFrame frame = frame_;
            if (const auto* rect = std::get_if<RectLight>(&light_)) frame = slice_frame(*rect, bounds_min_, bounds_max_, config.slices);
            if (const auto* sun = std::get_if<SunLight>(&light_)) frame = slice_frame(*sun, bounds_min_, bounds_max_, config.slices);
            next.level_bound = kernel_level_bound(frame, config);
        }
        Result<Emission> result = emit(next);
        if (!result.value) return invalid_configuration(result.errors);
        if (std::string d = adopt(std::move(*result.value)); !d.empty()) return d;
        requested_ = config;
        fits_levels_ = fits;
        fitted_ = fits && has_frame();
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
        shadow_current_ = false; // a replaced program may be one of the shadow phase
        return {};
    }

    // A texture whose layout source is "bake": the caller's own texture (not owned; 0 goes back to the
    // runtime's), used wherever the layout names it. Empty string on success.
    std::string supply_texture(const std::string& name, GLuint id) {
        if (std::string d = check_bake(name); !d.empty()) return d;
        shadow_current_ = false;
        if (id) supplied_[name] = id;
        else supplied_.erase(name);
        return {};
    }
    // The same with texels uploaded into the runtime's texture at `level`: width × height × depth
    // texels of the format's channels (R: 1, RG: 2, RGBA: 4), rows bottom first, layers in order.
    std::string supply_texture(const std::string& name, const std::vector<float>& texels, int level = 0) {
        return upload(name, texels.data(), texels.size(), GL_FLOAT, false, level);
    }
    std::string supply_texture(const std::string& name, const std::vector<std::uint32_t>& texels, int level = 0) {
        return upload(name, texels.data(), texels.size(), GL_UNSIGNED_INT, true, level);
    }

    // Runs the layout's passes of phase "shadow" in order (draw_scene passes call `draw`).
    // Returns an empty string on success, else a diagnostic (GL errors raised inside `draw` included).
    // With `timings`, one entry per pass (GL_TIME_ELAPSED queries; waits for the results).
    std::string build(const DrawScene& draw, std::vector<PassTiming>* timings = nullptr) {
        detail::DebugCapture capture(options_.debug_output);
        std::string diagnostic = run_phase("shadow", draw, timings);
        if (std::string d = capture.take_diagnostic("build"); diagnostic.empty()) diagnostic = d;
        shadow_current_ = diagnostic.empty();
        return diagnostic;
    }

    // build() only when what the shadow phase depends on changed since the last build (layout.json
    // "phase_inputs"): the light (a set_light or set_frame that changed the frame), the
    // configuration (reconfigure, a grown level bound), or the geometry, which only the caller knows
    // (`geometry_changed`). A camera-only change runs nothing: the occlusion textures stay valid.
    // *ran tells whether the passes ran. Empty string on success, else build()'s diagnostic.
    std::string update(const DrawScene& draw, bool geometry_changed, bool* ran = nullptr,
                       std::vector<PassTiming>* timings = nullptr) {
        const bool needed = geometry_changed || !shadow_current_;
        if (ran) *ran = needed;
        if (!needed) {
            if (timings) timings->clear();
            return {};
        }
        return build(draw, timings);
    }
    // False when the next update() will run the shadow phase whatever the geometry does.
    bool shadow_current() const { return shadow_current_; }

    // Runs the passes of phase "screen" at width × height over the caller's textures (every texture
    // whose source is "caller", by layout name). Output-sized textures are (re)allocated for this size.
    // Returns an empty string on success, else a diagnostic. Afterwards texture(layout().result) holds
    // the visibility.
    std::string run_screen(const TextureMap& caller_textures, int width, int height,
                           std::vector<PassTiming>* timings = nullptr) {
        detail::DebugCapture capture(options_.debug_output);
        std::string diagnostic = screen("run_screen", caller_textures, width, height, timings);
        if (std::string d = capture.take_diagnostic("run_screen"); diagnostic.empty()) diagnostic = d;
        return diagnostic;
    }

    // Deferred visibility over a G-buffer of world positions (RGBA32F, w = 1 on geometry): run_screen
    // with {"penumbra_worldPositions": world_positions}. Returns the result texture, width × height
    // (owned by the runtime), or 0 with *error set. With `timing`, the GPU time of the screen passes
    // (named after the pass when there is one; GL_TIME_ELAPSED, waits for the result).
    // `world_normals`: the G-buffer's normals (RGBA32F, xyz = the normal of the side the viewer
    // sees), the caller texture penumbra_worldNormals of configurations that read the receiver's normal
    // (reads_receiver_normal: the tangent clip, the shadow maps' normal offset).
    GLuint shade_deferred(GLuint world_positions, int width, int height, std::string* error = nullptr,
                          PassTiming* timing = nullptr, GLuint world_normals = 0) {
        detail::DebugCapture capture(options_.debug_output);
        std::vector<PassTiming> timings;
        TextureMap caller{{"penumbra_worldPositions", world_positions}};
        if (world_normals) caller["penumbra_worldNormals"] = world_normals;
        std::string diagnostic = screen("shade_deferred", caller, width, height, timing ? &timings : nullptr);
        if (std::string d = capture.take_diagnostic("shade_deferred"); diagnostic.empty()) diagnostic = d;
        if (!diagnostic.empty()) {
            if (error) *error = diagnostic;
            return 0;
        }
        if (timing) {
            *timing = {};
            for (const PassTiming& t : timings) {
                timing->name += (timing->name.empty() ? "" : "+") + t.name;
                timing->milliseconds += t.milliseconds;
            }
        }
        return texture(emission_.layout.result);
    }

    // Binds the samplers of the layout's "example" passes and sets every uniform the table computes
    // (uniform_values.hpp) on a program that includes the snippet (shading_example, shading_deferred, or
    // the engine's own); the program must be in use.
    void bind_visibility(GLuint program, const std::optional<glm::mat4>& clip_from_world = std::nullopt) const {
        for (const PassDesc& pass : emission_.layout.passes)
            if (pass.phase == "example")
                for (const BindingDesc& in : pass.inputs) bind_sampler(program, in.sampler, in.binding, texture(in.texture));
        UniformInputs inputs = uniform_inputs();
        inputs.clip_from_world = clip_from_world;
        for (const UniformRule& rule : uniform_rules())
            if (const std::optional<UniformValue> v = rule.value(inputs))
                detail::set_uniform(program, glGetUniformLocation(program, std::string(rule.name).c_str()), *v);
    }

    // Reads back level 0 of the result texture of the last screen run (bottom row first).
    std::vector<float> read_visibility() const {
        std::vector<float> out(static_cast<std::size_t>(output_width_) * output_height_);
        if (const GLuint id = texture(emission_.layout.result); id && !out.empty())
            glGetTextureImage(id, 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(out.size() * 4), out.data());
        return out;
    }

private:
    Runtime() = default;

    static std::string invalid_configuration(const std::vector<ConfigError>& errors) {
        std::string m = "invalid configuration:";
        for (const ConfigError& e : errors) m += " " + e.message + ";";
        return m;
    }

    // The runtime allocates fixed-size textures at once and output-sized ones per screen size;
    // "caller" textures come with every screen run.
    static bool allocated_at_create(const TextureDesc& t) { return t.source != "caller" && t.size != "output"; }

    bool has_frame() const { return !std::holds_alternative<std::monostate>(light_) || frame_set_by_hand_; }

    // RuntimeOptions::fit_level_bound: the first frame sets the bound it needs, later ones grow it.
    std::string fit_level_bound() {
        frame_set_by_hand_ = std::holds_alternative<std::monostate>(light_);
        if (!fits_levels_) return {};
        const int needed = kernel_level_bound(frame_, requested_);
        if (needed < 0 || (fitted_ && needed <= config_.level_bound)) return {};
        Config next = requested_;
        next.level_bound = needed;
        Result<Emission> result = emit(next);
        if (!result.value) return invalid_configuration(result.errors);
        const ReconfigureStats stats = last_reconfigure_;
        if (std::string d = adopt(std::move(*result.value)); !d.empty()) return "level_bound " + std::to_string(needed) + ": " + d;
        last_reconfigure_ = stats; // what reconfigure did stays reported
        fitted_ = true;
        return {};
    }

    // Switches to `next`; see reconfigure.
    std::string adopt(Emission next) {
        detail::DebugCapture capture(options_.debug_output);
        TextureMap next_programs, next_textures;
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
            if (!allocated_at_create(t)) continue;
            const TextureDesc* current = find_texture(t.name);
            if (current && detail::same_storage(*current, t) && textures_.count(t.name)) {
                next_textures[t.name] = textures_.at(t.name);
                continue;
            }
            std::string log;
            const GLuint id = allocate(t, t.width, t.height, &log);
            if (!id) return discard("texture " + t.name + ": " + log);
            next_textures[t.name] = id;
            new_textures.push_back(id);
        }
        if (std::string d = capture.take_diagnostic("reconfigure"); !d.empty()) return discard(d);

        // Commit: release what the new layout no longer uses.
        for (auto& [name, id] : programs_)
            if (next_programs.count(name) == 0 || next_programs.at(name) != id) glDeleteProgram(id);
        for (auto& [name, id] : textures_)
            if (next_textures.count(name) == 0 || next_textures.at(name) != id) glDeleteTextures(1, &id);
        for (auto it = output_textures_.begin(); it != output_textures_.end();) {
            const TextureDesc* before = find_texture(it->first);
            const TextureDesc* after = nullptr;
            for (const TextureDesc& t : next.layout.textures)
                if (t.name == it->first) after = &t;
            if (before && after && detail::same_storage(*before, *after)) {
                ++it;
                continue;
            }
            glDeleteTextures(1, &it->second);
            it = output_textures_.erase(it);
        }
        for (auto it = supplied_.begin(); it != supplied_.end();) {
            bool still_bake = false;
            for (const TextureDesc& t : next.layout.textures) still_bake = still_bake || (t.name == it->first && t.source == "bake");
            it = still_bake ? std::next(it) : supplied_.erase(it);
        }
        programs_ = std::move(next_programs);
        textures_ = std::move(next_textures);
        shadow_current_ = false; // new programs or textures: the shadow phase runs again
        config_ = next.layout.config;
        emission_ = std::move(next);
        if (const auto* rect = std::get_if<RectLight>(&light_))
            frame_ = slice_frame(*rect, bounds_min_, bounds_max_, config_.slices);
        if (const auto* sun = std::get_if<SunLight>(&light_))
            frame_ = slice_frame(*sun, bounds_min_, bounds_max_, config_.slices);
        last_reconfigure_ = {static_cast<int>(new_programs.size()), static_cast<int>(new_textures.size())};
        return {};
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

    std::string check_bake(const std::string& name) const {
        const TextureDesc* t = find_texture(name);
        if (!t || t->source != "bake") {
            std::string names;
            for (const TextureDesc& d : emission_.layout.textures)
                if (d.source == "bake") names += (names.empty() ? "" : ", ") + d.name;
            return "supply_texture: '" + name + "' is not a bake texture of this layout; bake textures: " +
                   (names.empty() ? "none" : names);
        }
        return {};
    }

    std::string upload(const std::string& name, const void* data, std::size_t count, GLenum type, bool integer,
                       int level) {
        if (std::string d = check_bake(name); !d.empty()) return d;
        const TextureDesc& t = *find_texture(name);
        if (integer != detail::is_integer_format(t.internal_format) || detail::is_depth_format(t.internal_format))
            return "supply_texture " + name + ": " + (integer ? "integer" : "float") + " texels given for format " +
                   t.internal_format;
        if (level < 0 || level >= t.mip_levels)
            return "supply_texture " + name + ": level " + std::to_string(level) + "; allowed: 0 to " +
                   std::to_string(t.mip_levels - 1);
        const int w = std::max(t.width >> level, 1), h = std::max(t.height >> level, 1);
        const int d = t.target == "3D" ? std::max(t.depth >> level, 1) : t.depth;
        const int channels = detail::format_channels(t.internal_format);
        const std::size_t expected = static_cast<std::size_t>(w) * h * d * channels;
        if (count != expected)
            return "supply_texture " + name + ": " + std::to_string(count) + " values given; level " +
                   std::to_string(level) + " needs " + std::to_string(expected) + " (" + std::to_string(w) + "x" +
                   std::to_string(h) + "x" + std::to_string(d) + " texels x " + std::to_string(channels) + ")";
        supplied_.erase(name);
        detail::DebugCapture capture(options_.debug_output);
        const GLuint id = textures_.at(name);
        const GLenum format = detail::pixel_format(channels, integer);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        if (t.target == "2D")
            glTextureSubImage2D(id, level, 0, 0, w, h, format, type, data);
        else
            glTextureSubImage3D(id, level, 0, 0, 0, w, h, d, format, type, data);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        return capture.take_diagnostic("supply_texture " + name);
    }

    static GLuint allocate(const TextureDesc& t, int width, int height, std::string* log) {
        const GLenum target = detail::gl_enum(t.target), format = detail::gl_enum(t.internal_format);
        if (!target || !format) {
            *log = "unknown target or format " + t.target + " " + t.internal_format;
            return 0;
        }
        if (width < 1 || height < 1) {
            *log = "size " + std::to_string(width) + "x" + std::to_string(height) + " is empty";
            return 0;
        }
        GLuint id = 0;
        glCreateTextures(target, 1, &id);
        if (target == GL_TEXTURE_2D)
            glTextureStorage2D(id, t.mip_levels, format, width, height);
        else
            glTextureStorage3D(id, t.mip_levels, format, width, height, t.depth);
        glTextureParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(detail::gl_enum(t.min_filter)));
        glTextureParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(detail::gl_enum(t.mag_filter)));
        const GLint wrap = static_cast<GLint>(detail::gl_enum(t.wrap));
        glTextureParameteri(id, GL_TEXTURE_WRAP_S, wrap);
        glTextureParameteri(id, GL_TEXTURE_WRAP_T, wrap);
        glTextureParameteri(id, GL_TEXTURE_WRAP_R, wrap);
        glTextureParameterfv(id, GL_TEXTURE_BORDER_COLOR, t.border_color.data());
        glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, t.mip_levels - 1);
        if (!t.compare.empty()) {
            glTextureParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
            glTextureParameteri(id, GL_TEXTURE_COMPARE_FUNC, static_cast<GLint>(detail::gl_enum(t.compare)));
        }
        const bool depth = detail::is_depth_format(t.internal_format);
        const bool integer = detail::is_integer_format(t.internal_format);
        const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        const GLuint zero_u[4] = {0, 0, 0, 0};
        for (int level = 0; level < t.mip_levels; ++level) {
            if (depth) glClearTexImage(id, level, GL_DEPTH_COMPONENT, GL_FLOAT, zero);
            else if (integer) glClearTexImage(id, level, GL_RGBA_INTEGER, GL_UNSIGNED_INT, zero_u);
            else glClearTexImage(id, level, GL_RGBA, GL_FLOAT, zero);
        }
        if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
            *log = "GL error " + std::to_string(e);
            glDeleteTextures(1, &id);
            return 0;
        }
        return id;
    }

    // Output-sized textures at width × height, reallocated when the size changed.
    std::string ensure_output_textures(int width, int height) {
        if (width == output_width_ && height == output_height_ && !output_textures_.empty()) return {};
        for (auto& [name, id] : output_textures_) glDeleteTextures(1, &id);
        output_textures_.clear();
        for (const TextureDesc& t : emission_.layout.textures) {
            if (t.size != "output" || t.source == "caller") continue;
            std::string log;
            const GLuint id = allocate(t, width, height, &log);
            if (!id) return "texture " + t.name + ": " + log;
            output_textures_[t.name] = id;
        }
        output_width_ = width;
        output_height_ = height;
        return {};
    }

    static void bind_sampler(GLuint program, const std::string& name, int unit, GLuint texture_id) {
        glBindTextureUnit(static_cast<GLuint>(unit), texture_id);
        const GLint location = glGetUniformLocation(program, name.c_str());
        if (location >= 0) glProgramUniform1i(program, location, unit); // glsl330: no layout(binding)
    }

    // The uniforms of `program` that the table computes ("light" and "camera" sources).
    std::string set_computed_uniforms(const PassDesc& pass, GLuint program) const {
        const UniformInputs inputs = uniform_inputs();
        for (const ProgramDesc& p : emission_.layout.programs) {
            if (p.name != pass.program) continue;
            for (const ParamDesc& param : p.parameters) {
                if (param.source != "light" && param.source != "camera") continue;
                const std::optional<UniformValue> v = uniform_value(param.name, inputs);
                if (!v) {
                    if (param.source == "camera") continue; // no camera in the runtime's own passes
                    return "pass " + pass.name + ": no value for uniform " + param.name +
                           " (penumbra/uniform_values.hpp has no rule for it)";
                }
                detail::set_uniform(program, glGetUniformLocation(program, param.name.c_str()), *v);
            }
        }
        return {};
    }

    void detach_all() {
        for (int i = 0; i < 8; ++i) glNamedFramebufferTexture(fbo_, GL_COLOR_ATTACHMENT0 + i, 0, 0);
        glNamedFramebufferTexture(fbo_, GL_DEPTH_ATTACHMENT, 0, 0);
    }

    // The layout texture `name`: the caller's (screen runs), a supplied bake, or the runtime's own.
    GLuint resolve(const std::string& name) const {
        if (auto it = caller_.find(name); it != caller_.end()) return it->second;
        return texture(name);
    }

    std::string screen(const std::string& where, const TextureMap& caller_textures, int width, int height,
                       std::vector<PassTiming>* timings) {
        if (width < 1 || height < 1)
            return where + ": size " + std::to_string(width) + "x" + std::to_string(height) +
                   " is empty; allowed: at least 1x1";
        for (const TextureDesc& t : emission_.layout.textures)
            if (t.source == "caller" && caller_textures.count(t.name) == 0)
                return where + ": no texture given for " + t.name + " (source \"caller\": " + t.purpose + ")";
        if (std::string d = ensure_output_textures(width, height); !d.empty()) return where + ": " + d;
        caller_ = caller_textures;
        std::string diagnostic = run_phase("screen", {}, timings);
        caller_.clear();
        return diagnostic;
    }

    // Runs every pass of `phase` in layout order, restoring the caller's framebuffer and viewport.
    std::string run_phase(const std::string& phase, const DrawScene& draw, std::vector<PassTiming>* timings) {
        GLint previous_fbo = 0, previous_viewport[4];
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_fbo);
        glGetIntegerv(GL_VIEWPORT, previous_viewport);
        std::vector<std::pair<std::string, GLuint>> pending;
        std::string diagnostic;
        for (const PassDesc& pass : emission_.layout.passes) {
            if (pass.phase != phase) continue;
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
        detail::reset_state();
        return diagnostic;
    }

    // Size of level `level` of the texture an attachment names (output-sized: the output size).
    std::pair<int, int> attachment_size(const AttachmentDesc& out) const {
        const TextureDesc* t = find_texture(out.texture);
        if (!t) return {0, 0};
        const int w = t->size == "output" ? output_width_ : t->width, h = t->size == "output" ? output_height_ : t->height;
        return {std::max(w >> out.level, 1), std::max(h >> out.level, 1)};
    }

    std::string run_pass(const PassDesc& pass, const DrawScene& draw) {
        if (pass.action == "generate_mipmap") {
            glGenerateTextureMipmap(resolve(pass.outputs.at(0).texture));
            return {};
        }
        if (pass.action == "copy") {
            const GLuint src = resolve(pass.inputs.at(0).texture), dst = resolve(pass.outputs.at(0).texture);
            const AttachmentDesc& out = pass.outputs.at(0);
            const TextureDesc* dst_desc = find_texture(out.texture);
            const GLenum dst_target = dst_desc ? detail::gl_enum(dst_desc->target) : GL_TEXTURE_2D;
            glCopyImageSubData(src, GL_TEXTURE_2D, 0, 0, 0, 0, dst, dst_target, out.level, 0, 0,
                               std::max(out.layer, 0), pass.viewport_width, pass.viewport_height, 1);
            return {};
        }
        if (pass.action != "draw_scene" && pass.action != "fullscreen")
            return "pass " + pass.name + ": unknown action '" + pass.action +
                   "'; allowed: draw_scene, fullscreen, generate_mipmap, copy";
        const GLuint program = this->program(pass.program);
        if (!program) return "pass " + pass.name + ": no program " + pass.program;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        detach_all();
        std::vector<GLenum> buffers;
        std::vector<bool> integer_buffers; // cleared with glClearBufferuiv
        bool has_depth = false;
        for (const AttachmentDesc& out : pass.outputs) {
            const bool depth = out.kind == "depth";
            const GLenum attachment = depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(buffers.size());
            if (out.layer >= 0)
                glNamedFramebufferTextureLayer(fbo_, attachment, resolve(out.texture), out.level, out.layer);
            else
                glNamedFramebufferTexture(fbo_, attachment, resolve(out.texture), out.level);
            if (depth) {
                has_depth = true;
            } else {
                buffers.push_back(attachment);
                const TextureDesc* desc = find_texture(out.texture);
                integer_buffers.push_back(desc && detail::is_integer_format(desc->internal_format));
            }
        }
        if (buffers.empty()) glNamedFramebufferDrawBuffer(fbo_, GL_NONE);
        else glNamedFramebufferDrawBuffers(fbo_, static_cast<GLsizei>(buffers.size()), buffers.data());
        if (glCheckNamedFramebufferStatus(fbo_, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
            return "pass " + pass.name + ": framebuffer incomplete";
        int width = pass.viewport_width, height = pass.viewport_height;
        if ((width == 0 || height == 0) && !pass.outputs.empty())
            std::tie(width, height) = attachment_size(pass.outputs.front());
        glViewport(0, 0, width, height);

        // Clear with full write masks, then the pass's state.
        const RenderState& state = pass.state;
        if (state.clear_color) {
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
            for (std::size_t i = 0; i < buffers.size(); ++i) {
                if (integer_buffers[i]) {
                    std::array<GLuint, 4> value{};
                    for (int c = 0; c < 4; ++c) value[c] = static_cast<GLuint>((*state.clear_color)[c]);
                    glClearBufferuiv(GL_COLOR, static_cast<GLint>(i), value.data());
                } else {
                    glClearBufferfv(GL_COLOR, static_cast<GLint>(i), state.clear_color->data());
                }
            }
        }
        if (state.clear_depth && has_depth) {
            glDepthMask(GL_TRUE);
            glClearBufferfv(GL_DEPTH, 0, &*state.clear_depth);
        }
        detail::apply_state(state);

        glUseProgram(program);
        std::vector<GLuint> restricted;
        for (const BindingDesc& in : pass.inputs) {
            const GLuint id = resolve(in.texture);
            if (!id) {
                glUseProgram(0);
                return "pass " + pass.name + ": no texture " + in.texture + " for " + in.sampler;
            }
            if (in.level >= 0) { // read one level only; the pass may render another level of it
                glTextureParameteri(id, GL_TEXTURE_BASE_LEVEL, in.level);
                glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, in.level);
                restricted.push_back(id);
            }
            bind_sampler(program, in.sampler, in.binding, id);
        }
        for (const auto& [name, value] : pass.int_uniforms)
            glProgramUniform1i(program, glGetUniformLocation(program, name.c_str()), value);
        std::string diagnostic = set_computed_uniforms(pass, program);
        if (diagnostic.empty()) {
            if (pass.action == "draw_scene") {
                draw(program);
            } else {
                glBindVertexArray(empty_vao_);
                glDrawArrays(GL_TRIANGLES, 0, 3);
                glBindVertexArray(0);
            }
        }
        for (GLuint id : restricted) {
            const TextureDesc* t = nullptr;
            for (const BindingDesc& in : pass.inputs)
                if (resolve(in.texture) == id) t = find_texture(in.texture);
            glTextureParameteri(id, GL_TEXTURE_BASE_LEVEL, 0);
            glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, t ? t->mip_levels - 1 : 1000);
        }
        glUseProgram(0);
        return diagnostic;
    }

    Config config_;    // what runs (level_bound fitted)
    Config requested_; // what create / reconfigure were given
    bool fits_levels_ = false, fitted_ = false, frame_set_by_hand_ = false;
    bool shadow_current_ = false; // the shadow phase ran since the light, configuration or textures changed
    Emission emission_;
    SliceFrame frame_;
    RuntimeOptions options_;
    TextureMap programs_, textures_;
    TextureMap output_textures_; // size "output", at output_width_ × output_height_
    TextureMap supplied_;        // bake textures the caller gave (not owned)
    TextureMap caller_;          // the caller's textures during a screen run
    GLuint empty_vao_ = 0, fbo_ = 0;
    int output_width_ = 0, output_height_ = 0;
    std::variant<std::monostate, RectLight, SunLight> light_; // last set_light, for reconfigure
    std::optional<glm::vec4> time_window_;                    // last set_time_window
    glm::dvec3 bounds_min_{0.0}, bounds_max_{0.0};
    ReconfigureStats last_reconfigure_;
};

} // namespace penumbra::gl
