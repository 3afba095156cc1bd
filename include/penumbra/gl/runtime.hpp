// penumbra/gl/runtime.hpp — runs an emission on OpenGL 4.5 core: compiles the programs, allocates
// the layout's textures, runs its passes from the layout's data alone (phase "shadow" in build,
// phase "screen" in run_screen / shade_deferred), and shades a G-buffer of world positions.
// The include for users; its parts, each readable alone:
//   resources.hpp      textures from their layout description, the passes' framebuffer
//   passes.hpp         running a layout's passes (draws, copies, mipmaps, timings)
//   state.hpp          fixed-function state, samplers and computed uniforms of a pass
//   debug_capture.hpp  GL errors of one call as a diagnostic
//   layout_enums.hpp   GL enums of layout.json's words
// This file holds the Runtime: what runs (emission, configuration, light) and its lifecycle.
//
//   // with a current GL 4.5 core context (libepoxy resolves the entry points)
//   std::string error;
//   auto runtime = penumbra::gl::Runtime::create(config, &error);
//   runtime->set_light(light, bounds_min, bounds_max); // fits config.level_bound to the light (RuntimeOptions)
//   // or, lit from the start (each program linked once, fitted): create(config, light, bounds_min, bounds_max, &error)
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
#include "debug_capture.hpp"
#include "link_program.hpp"
#include "passes.hpp"
#include "resources.hpp"
#include "state.hpp"

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
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

// Two frames give the same uniforms (and so the same shadow phase output).
inline bool same_frame(const SliceFrame& a, const SliceFrame& b) {
    return a.light_from_world == b.light_from_world && a.slice_clip_from_world == b.slice_clip_from_world &&
           a.light_size == b.light_size && a.cop_distance == b.cop_distance && a.slice_depths == b.slice_depths &&
           a.window_half_size == b.window_half_size && a.tan_angular_radius == b.tan_angular_radius &&
           a.contained == b.contained;
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
    // The same, already lit by `light` in `bounds` (as create then set_light): with a level_bound of -1
    // and RuntimeOptions::fit_level_bound, each program is linked once, with the levels this light
    // reaches, where create then set_light links every level's programs first and the fitted ones at
    // set_light (on a driver that compiles at link, llvmpipe's, that is twice the compile time).
    static std::unique_ptr<Runtime> create(const Config& config, const RectLight& light, glm::dvec3 bounds_min,
                                           glm::dvec3 bounds_max, std::string* error = nullptr,
                                           const RuntimeOptions& options = {}) {
        return create_lit(config, light, bounds_min, bounds_max, error, options);
    }
    static std::unique_ptr<Runtime> create(const Config& config, const SunLight& sun, glm::dvec3 bounds_min,
                                           glm::dvec3 bounds_max, std::string* error = nullptr,
                                           const RuntimeOptions& options = {}) {
        return create_lit(config, sun, bounds_min, bounds_max, error, options);
    }
    // The same from an emission (a layout and its programs), e.g. one edited or built by hand.
    static std::unique_ptr<Runtime> create(Emission emission, std::string* error = nullptr,
                                           const RuntimeOptions& options = {}) {
        std::unique_ptr<Runtime> rt(new Runtime());
        rt->options_ = options;
        // From an empty runtime, adopt builds every program and allocates every texture.
        if (std::string d = rt->adopt(std::move(emission)); !d.empty()) return failed(d, error);
        rt->requested_ = rt->config_;
        return finish_create(std::move(rt), error);
    }

    ~Runtime() {
        for (auto& [name, id] : programs_) glDeleteProgram(id);
        for (const RetiredProgram& retired : retired_) glDeleteProgram(retired.id);
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
    // old contents until the next build(). A level_bound of -1 is fitted to the last light and to `config`
    // (see RuntimeOptions::fit_level_bound): extent and clustered fusion read one level more than the
    // other rules, so a switch to or from them adds or drops that level's texture.
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
    // programs_rebuilt: programs whose code changed; programs_linked: those of them compiled and linked
    // anew, the others taken back from the programs a recent reconfiguration retired (switching to a
    // setting and back links nothing the second time).
    struct ReconfigureStats {
        int programs_rebuilt = 0, textures_reallocated = 0, programs_linked = 0;
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
        GLuint id = 0;
        if (const auto retired = find_retired(candidate); retired != retired_.end()) {
            id = retired->id; // an edit undone: the program it had is still linked
            retired_.erase(retired);
        } else {
            std::string log;
            id = link_program(candidate, &log);
            if (!id) {
                capture.take_diagnostic("replace_program");
                return log;
            }
            if (std::string d = capture.take_diagnostic("replace_program " + name); !d.empty()) {
                glDeleteProgram(id);
                return d;
            }
        }
        retire(*running, programs_.at(name));
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

    // alpha_test (cut-out casters): inside a draw_scene pass's `draw`, the material of the next draw of
    // `program` — its alpha texture, bound at the unit the layout gives penumbra_alphaTexture with
    // `sampler` (0: the texture's own filtering and wrap), and its cutoff (penumbra_alphaCutoff). A
    // program without those parameters (alpha_test off, or one that draws no casters) is left alone.
    void bind_caster_material(GLuint program, GLuint alpha_texture, GLuint sampler, float cutoff) const {
        for_each_draw_param(program, [&](const ParamDesc& param) {
            if (param.name == uniform_def(Uniform::alpha_texture).name && param.binding >= 0)
                detail::bind_sampler(program, param.name, param.binding, alpha_texture, sampler);
            if (param.name == uniform_def(Uniform::alpha_cutoff).name)
                if (const GLint at = glGetUniformLocation(program, param.name.c_str()); at >= 0)
                    glProgramUniform1f(program, at, cutoff);
        });
    }

    // solid_casters: inside the slicing pass's `draw`, whether the next draws of `program` are a closed
    // mesh (watertight, counter-clockwise outward faces: the slices between its surfaces are filled, by
    // a logical XOR) or open casters (their surfaces only, OR). Draw every closed mesh before the open
    // ones: an XOR after them would toggle their marks. A program without penumbra_casterClosed
    // (solid_casters off, or one that draws no slices) is left alone.
    void bind_caster_closed(GLuint program, bool closed) const {
        for_each_draw_param(program, [&](const ParamDesc& param) {
            if (param.name == uniform_def(Uniform::caster_closed).name)
                if (const GLint at = glGetUniformLocation(program, param.name.c_str()); at >= 0) {
                    glProgramUniform1f(program, at, closed ? 1.0f : 0.0f);
                    glLogicOp(closed ? GL_XOR : GL_OR);
                }
        });
    }

    // Runs the layout's passes of phase "shadow" in order (draw_scene passes call `draw`).
    // Returns an empty string on success, else a diagnostic (GL errors raised inside `draw` included).
    // With `timings`, one entry per pass (GL_TIME_ELAPSED queries; waits for the results).
    std::string build(const DrawScene& draw, std::vector<PassTiming>* timings = nullptr) {
        detail::DebugCapture capture(options_.debug_output);
        std::string diagnostic = run_phase(Phase::shadow, draw, timings);
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

    // Binds the samplers of the layout's "example" passes (texture and sampler object at each unit, left
    // bound for the caller's draw) and sets every uniform the table computes (uniform_values.hpp) on a
    // program that includes the snippet (shading_example, shading_deferred, or the engine's own); the
    // program must be in use.
    void bind_visibility(GLuint program, const std::optional<glm::mat4>& clip_from_world = std::nullopt) const {
        for (const PassDesc& pass : emission_.layout.passes)
            if (pass.phase == Phase::example)
                for (const BindingDesc& in : pass.inputs)
                    detail::bind_sampler(program, in.sampler, in.binding, texture(in.texture), samplers_->get(in.sampling));
        UniformInputs inputs = uniform_inputs();
        inputs.clip_from_world = clip_from_world;
        for (const UniformRule& rule : uniform_rules())
            if (const UniformResult v = rule.value(inputs)) // the camera's only when given
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
    // `visit` on each per-draw parameter (source "draw") of the layout program compiled as `program`.
    template <class Visit> void for_each_draw_param(GLuint program, Visit&& visit) const {
        for (const auto& [name, id] : programs_) {
            if (id != program) continue;
            for (const ProgramDesc& p : emission_.layout.programs)
                if (p.name == name)
                    for (const ParamDesc& param : p.parameters)
                        if (param.source == UniformSource::draw) visit(param);
        }
    }

    Runtime() = default;

    static std::string invalid_configuration(const std::vector<ConfigError>& errors) {
        std::string m = "invalid configuration:";
        for (const ConfigError& e : errors) m += " " + e.message + ";";
        return m;
    }

    // The runtime allocates fixed-size textures at once and output-sized ones per screen size;
    // "caller" textures come with every screen run.
    static bool allocated_at_create(const TextureDesc& t) { return t.source != TextureSource::caller && t.size != TextureSize::output; }

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
        std::vector<GLuint> unretired; // retired programs this emission takes back (at commit)
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
            if (const auto retired = find_retired(p); retired != retired_.end() &&
                std::find(unretired.begin(), unretired.end(), retired->id) == unretired.end()) {
                next_programs[p.name] = retired->id;
                unretired.push_back(retired->id);
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
            const GLuint id = detail::allocate_texture(t, t.width, t.height, &log);
            if (!id) return discard("texture " + t.name + ": " + log);
            next_textures[t.name] = id;
            new_textures.push_back(id);
        }
        if (std::string d = capture.take_diagnostic("reconfigure"); !d.empty()) return discard(d);

        // Commit: retire the programs the new layout no longer uses, release the textures.
        const int rebuilt = static_cast<int>(new_programs.size() + unretired.size());
        std::erase_if(retired_, [&](const RetiredProgram& r) {
            return std::find(unretired.begin(), unretired.end(), r.id) != unretired.end();
        });
        for (auto& [name, id] : programs_)
            if (next_programs.count(name) == 0 || next_programs.at(name) != id) retire(*find_program(name), id);
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
            for (const TextureDesc& t : next.layout.textures) still_bake = still_bake || (t.name == it->first && t.source == TextureSource::bake);
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
        last_reconfigure_ = {rebuilt, static_cast<int>(new_textures.size()), static_cast<int>(new_programs.size())};
        return {};
    }

    // Programs a reconfiguration or replace_program took out of use, newest last, kept linked so that
    // going back to a setting (or undoing an edit) links nothing; the oldest go past kRetiredPrograms.
    struct RetiredProgram {
        Program program;
        GLuint id = 0;
    };
    static constexpr std::size_t kRetiredPrograms = 32;
    std::vector<RetiredProgram>::iterator find_retired(const Program& program) {
        return std::find_if(retired_.begin(), retired_.end(),
                            [&](const RetiredProgram& r) { return detail::same_code(r.program, program); });
    }
    void retire(const Program& program, GLuint id) {
        retired_.push_back({program, id});
        if (retired_.size() > kRetiredPrograms) {
            glDeleteProgram(retired_.front().id);
            retired_.erase(retired_.begin());
        }
    }

    static std::unique_ptr<Runtime> failed(const std::string& message, std::string* error) {
        if (error) *error = message;
        return nullptr;
    }
    // create's last steps, once the first emission is adopted.
    static std::unique_ptr<Runtime> finish_create(std::unique_ptr<Runtime> rt, std::string* error) {
        rt->last_reconfigure_ = {};
        detail::DebugCapture capture(rt->options_.debug_output);
        glCreateVertexArrays(1, &rt->empty_vao_);
        glCreateFramebuffers(1, &rt->fbo_);
        if (std::string d = capture.take_diagnostic("setup"); !d.empty()) return failed(d, error);
        return rt;
    }
    template <class AnyLight>
    static std::unique_ptr<Runtime> create_lit(const Config& config, const AnyLight& light, glm::dvec3 bounds_min,
                                               glm::dvec3 bounds_max, std::string* error, const RuntimeOptions& options) {
        std::unique_ptr<Runtime> rt(new Runtime());
        rt->options_ = options;
        rt->light_ = light;
        rt->bounds_min_ = bounds_min;
        rt->bounds_max_ = bounds_max;
        // From an empty runtime lit by `light`, reconfigure emits fitted to it and adopts everything.
        if (std::string d = rt->reconfigure(config); !d.empty()) return failed(d, error);
        return finish_create(std::move(rt), error);
    }

    Program* find_program(const std::string& name) {
        for (Program& p : emission_.programs)
            if (p.name == name) return &p;
        return nullptr;
    }
    const TextureDesc* find_texture(const std::string& name) const { return penumbra::find_texture(emission_.layout, name); }

    std::string check_bake(const std::string& name) const {
        const TextureDesc* t = find_texture(name);
        if (!t || t->source != TextureSource::bake) {
            std::string names;
            for (const TextureDesc& d : emission_.layout.textures)
                if (d.source == TextureSource::bake) names += (names.empty() ? "" : ", ") + d.name;
            return "supply_texture: '" + name + "' is not a bake texture of this layout; bake textures: " +
                   (names.empty() ? "none" : names);
        }
        return {};
    }

    std::string upload(const std::string& name, const void* data, std::size_t count, GLenum type, bool integer,
                       int level) {
        if (std::string d = check_bake(name); !d.empty()) return d;
        const TextureDesc& t = *find_texture(name);
        if (integer != is_integer(t.format) || is_depth(t.format))
            return "supply_texture " + name + ": " + (integer ? "integer" : "float") + " texels given for format " +
                   std::string(to_string(t.format));
        if (level < 0 || level >= t.mip_levels)
            return "supply_texture " + name + ": level " + std::to_string(level) + "; allowed: 0 to " +
                   std::to_string(t.mip_levels - 1);
        const int w = std::max(t.width >> level, 1), h = std::max(t.height >> level, 1);
        const int d = t.target == TextureTarget::texture_3d ? std::max(t.depth >> level, 1) : t.depth;
        const int channels = penumbra::channels(t.format);
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
        if (t.target == TextureTarget::texture_2d)
            glTextureSubImage2D(id, level, 0, 0, w, h, format, type, data);
        else
            glTextureSubImage3D(id, level, 0, 0, 0, w, h, d, format, type, data);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        return capture.take_diagnostic("supply_texture " + name);
    }


    // Output-sized textures at width × height, reallocated when the size changed.
    std::string ensure_output_textures(int width, int height) {
        if (width == output_width_ && height == output_height_ && !output_textures_.empty()) return {};
        for (auto& [name, id] : output_textures_) glDeleteTextures(1, &id);
        output_textures_.clear();
        for (const TextureDesc& t : emission_.layout.textures) {
            if (t.size != TextureSize::output || t.source == TextureSource::caller) continue;
            std::string log;
            const GLuint id = detail::allocate_texture(t, width, height, &log);
            if (!id) return "texture " + t.name + ": " + log;
            output_textures_[t.name] = id;
        }
        output_width_ = width;
        output_height_ = height;
        return {};
    }




    // The layout texture `name`: the caller's (screen runs), a supplied bake, or the runtime's own.
    GLuint resolve(const std::string& name) const {
        if (auto it = caller_.find(name); it != caller_.end()) return it->second;
        return texture(name);
    }

    // The passes run with the runtime's framebuffer, programs and textures (the caller's first).
    detail::PassContext pass_context() const {
        return {emission_.layout,
                fbo_,
                empty_vao_,
                [this](const std::string& name) { return program(name); },
                [this](const std::string& name) { return resolve(name); },
                [this](const Sampling& s) { return samplers_->get(s); },
                output_width_,
                output_height_,
                uniform_inputs()};
    }
    std::string run_phase(Phase phase, const DrawScene& draw, std::vector<PassTiming>* timings) {
        return detail::run_phase(pass_context(), phase, draw, timings);
    }

    std::string screen(const std::string& where, const TextureMap& caller_textures, int width, int height,
                       std::vector<PassTiming>* timings) {
        if (width < 1 || height < 1)
            return where + ": size " + std::to_string(width) + "x" + std::to_string(height) +
                   " is empty; allowed: at least 1x1";
        for (const TextureDesc& t : emission_.layout.textures)
            if (t.source == TextureSource::caller && caller_textures.count(t.name) == 0)
                return where + ": no texture given for " + t.name + " (source \"caller\": " + t.purpose + ")";
        if (std::string d = ensure_output_textures(width, height); !d.empty()) return where + ": " + d;
        caller_ = caller_textures;
        std::string diagnostic = run_phase(Phase::screen, {}, timings);
        caller_.clear();
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
    // the bindings' sampler objects (one per distinct sampling); a pointer so bind_visibility stays const
    std::unique_ptr<detail::SamplerCache> samplers_ = std::make_unique<detail::SamplerCache>();
    int output_width_ = 0, output_height_ = 0;
    std::variant<std::monostate, RectLight, SunLight> light_; // last set_light, for reconfigure
    std::optional<glm::vec4> time_window_;                    // last set_time_window
    glm::dvec3 bounds_min_{0.0}, bounds_max_{0.0};
    ReconfigureStats last_reconfigure_;
    std::vector<RetiredProgram> retired_;
};

} // namespace penumbra::gl
