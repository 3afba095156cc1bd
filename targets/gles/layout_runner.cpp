// targets/gles/layout_runner.cpp — see layout_runner.hpp.
#include "layout_runner.hpp"

#include <penumbra/detail/problem.hpp>
#include <penumbra/gl/layout_enums.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string_view>

namespace penumbra::targets {

namespace {

using nlohmann::json;

using penumbra::gl::detail::gl_enum;
using penumbra::gl::detail::gl_format;

// The layout enum layout.json spells `key` of `object` with (`fallback` when absent): strings end
// here. Empty on success, else "<key> '<word>' unknown; allowed: …".
template <class Enum> std::string read_word(const json& object, const char* key, std::string_view fallback, Enum* out) {
    const std::string word = object.value(key, std::string(fallback));
    if (const std::optional<Enum> value = parse_enum<Enum>(word)) {
        *out = *value;
        return {};
    }
    return std::string(key) + " '" + word + "' unknown; allowed: " + penumbra::detail::joined_names<Enum>().str();
}

// A binding's "sampling" (filters, wrap, border, comparison; compare "" is none).
std::string read_sampling(const json& j, Sampling* s) {
    std::string e = read_word(j, "min_filter", "", &s->min_filter);
    if (e.empty()) e = read_word(j, "mag_filter", "", &s->mag_filter);
    if (e.empty()) e = read_word(j, "wrap", "", &s->wrap);
    if (e.empty() && !j.value("compare", std::string()).empty()) {
        CompareFunc func{};
        e = read_word(j, "compare", "", &func);
        s->compare = func;
    }
    if (e.empty() && j.contains("border_color")) {
        const std::vector<float> border = j["border_color"];
        if (border.size() != 4) return "border_color " + j["border_color"].dump() + " is not 4 numbers";
        std::copy(border.begin(), border.end(), s->border_color.begin());
    }
    return e;
}

std::string gl_error_text(const std::string& where) {
    GLenum e = glGetError();
    if (e == GL_NO_ERROR) return {};
    char hex[16];
    std::snprintf(hex, sizeof hex, "0x%04X", e);
    while (glGetError() != GL_NO_ERROR) {
    }
    return where + ": GL error " + hex;
}

bool has_binding(const json& param) { return param.contains("binding") && param["binding"].get<int>() >= 0; }

} // namespace

std::unique_ptr<LayoutRunner> LayoutRunner::create(const json& layout, const std::map<std::string, std::string>& sources,
                                                   std::string* error, const std::vector<Phase>& phases) {
    auto fail = [&](std::string message) -> std::unique_ptr<LayoutRunner> {
        if (error) *error = std::move(message);
        return nullptr;
    };
    if (!layout.contains("layout_version")) return fail("layout.json: no layout_version (an older layout); this runner reads version 3");
    if (layout["layout_version"] != 3)
        return fail("layout.json: layout_version " + layout["layout_version"].dump() + "; this runner reads version 3");
    std::unique_ptr<LayoutRunner> runner(new LayoutRunner());
    runner->layout_ = layout;
    for (Phase phase : phases) runner->phases_.insert(phase);
    const bool es = !epoxy_is_desktop_gl();
    const json& l = runner->layout_;

    // Extensions, only where the layout needs them: ES 3.0 renders to float textures with
    // EXT_color_buffer_float and filters 32-bit floats linearly with OES_texture_float_linear.
    std::vector<std::string> rendered;
    for (const json& pass : l["passes"])
        for (const json& out : pass["outputs"]) rendered.push_back(out["texture"]);
    for (const json& pass : l["passes"]) {
        const std::string where = "pass " + pass.value("name", std::string()) + ": ";
        PassAction action{};
        Phase phase{};
        if (std::string e = read_word(pass, "action", "", &action); !e.empty()) return fail(where + e);
        if (std::string e = read_word(pass, "phase", "shadow", &phase); !e.empty()) return fail(where + e);
        // compute dispatches (prefilter_stage compute, target glsl450) need OpenGL 4.3: refused before anything runs
        if (action == PassAction::dispatch)
            return fail(where + "action 'dispatch' runs a compute shader (prefilter_stage compute), which this OpenGL "
                                "3.3 / ES 3.0 runner does not have; emit with prefilter_stage fragment");
    }
    for (const json& t : l["textures"]) {
        const std::string name = t["name"];
        TextureDesc d; // what this runner keeps of the description
        TextureInitial initial{};
        for (std::string e : {read_word(t, "internal_format", "", &d.format), read_word(t, "target", "", &d.target),
                              read_word(t, "min_filter", "", &d.min_filter), read_word(t, "mag_filter", "", &d.mag_filter),
                              read_word(t, "wrap", "", &d.wrap), read_word(t, "size", "fixed", &d.size),
                              read_word(t, "source", "passes", &d.source), read_word(t, "initial", "zero", &initial)})
            if (!e.empty()) return fail("texture " + name + ": " + e);
        // layout.json "initial": zero (cleared at allocation, as here), caller (filled every run
        // with fill_texture) or bake (uploaded once with fill_bake); a pass reading a caller or bake
        // texture that was never filled fails with its name.
        if (initial != initial_contents(d))
            return fail("texture " + name + ": initial '" + std::string(to_string(initial)) + "' with source '" +
                        std::string(to_string(d.source)) + "'; allowed: initial zero exactly for source passes");
        const std::string format(to_string(d.format));
        auto need = [&](const std::string& extension, const std::string& why) {
            if (!es || std::find(runner->extensions_.begin(), runner->extensions_.end(), extension) != runner->extensions_.end())
                return std::string();
            if (!epoxy_has_gl_extension(extension.c_str())) return why + " needs " + extension + ", which this context lacks";
            runner->extensions_.push_back(extension);
            return std::string();
        };
        std::string missing;
        if (is_float(d.format) && std::find(rendered.begin(), rendered.end(), name) != rendered.end())
            missing = need("GL_EXT_color_buffer_float", "rendering to " + name + " (" + format + ")");
        // 32-bit floats filter linearly only with OES_texture_float_linear (16-bit ones always)
        const bool linear = filters_linearly(d.mag_filter) || filters_linearly(d.min_filter);
        if (missing.empty() && is_float(d.format) && bytes_per_channel(d.format) == 4 && linear)
            missing = need("GL_OES_texture_float_linear", "LINEAR filtering of " + name + " (" + format + ")");
        if (!missing.empty()) return fail(missing);
        if (d.size == TextureSize::fixed)
            if (std::string e = runner->allocate(t, t["width"], t["height"]); !e.empty()) return fail(e);
    }
    std::vector<std::string> used;
    for (const json& pass : l["passes"]) {
        Phase phase{};
        read_word(pass, "phase", "shadow", &phase); // checked above
        if (runner->phases_.count(phase)) used.push_back(pass.value("program", ""));
    }
    for (const json& p : l["programs"])
        if (std::find(used.begin(), used.end(), p["name"]) != used.end())
            if (std::string e = runner->link(p, sources); !e.empty()) return fail(e);
    glGenFramebuffers(1, &runner->framebuffer_);
    glGenFramebuffers(1, &runner->read_framebuffer_);
    glGenVertexArrays(1, &runner->empty_vao_);
    if (std::string e = gl_error_text("setup"); !e.empty()) return fail(e);
    return runner;
}

LayoutRunner::~LayoutRunner() {
    for (auto& [name, t] : textures_) glDeleteTextures(1, &t.id);
    for (auto& [name, p] : programs_) glDeleteProgram(p.id);
    for (auto& [key, id] : samplers_) glDeleteSamplers(1, &id);
    if (framebuffer_) glDeleteFramebuffers(1, &framebuffer_);
    if (read_framebuffer_) glDeleteFramebuffers(1, &read_framebuffer_);
    if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
}

// The sampler object of one binding's "sampling" (filters, wrap, border, comparison), made once:
// bindings read through samplers, so one texture may be read two ways (PCSS's shadow map).
std::string LayoutRunner::sampler(const json& sampling, const std::string& where, GLuint* id, bool depth_texture) {
    Sampling s;
    if (std::string e = read_sampling(sampling, &s); !e.empty()) return where + ": sampling " + e;
    // OpenGL ES 3.0 (§3.8.13): a depth texture read without comparison is incomplete unless both
    // filters are NEAREST (desktop GL 3.3 filters it); it would read as zero, silently.
    if (depth_texture && !epoxy_is_desktop_gl() && !s.compare &&
        (s.min_filter != TextureFilter::nearest || s.mag_filter != TextureFilter::nearest))
        return where + ": a depth texture read without comparison through " + std::string(to_string(s.min_filter)) +
               "/" + std::string(to_string(s.mag_filter)) +
               " filters, which OpenGL ES 3.0 cannot (incomplete texture); allowed: NEAREST filters, or a compare function";
    if (auto it = samplers_.find(s); it != samplers_.end()) {
        *id = it->second;
        return {};
    }
    if (s.wrap == Wrap::clamp_to_border && !epoxy_is_desktop_gl())
        return where + ": wrap CLAMP_TO_BORDER does not exist in OpenGL ES 3.0";
    glGenSamplers(1, id);
    glSamplerParameteri(*id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(gl_enum(s.min_filter)));
    glSamplerParameteri(*id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(gl_enum(s.mag_filter)));
    for (GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glSamplerParameteri(*id, axis, static_cast<GLint>(gl_enum(s.wrap)));
    if (s.wrap == Wrap::clamp_to_border) glSamplerParameterfv(*id, GL_TEXTURE_BORDER_COLOR, s.border_color.data());
    if (s.compare) {
        glSamplerParameteri(*id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(*id, GL_TEXTURE_COMPARE_FUNC, static_cast<GLint>(gl_enum(*s.compare)));
    }
    samplers_[s] = *id;
    return gl_error_text(where + ": sampler");
}

int LayoutRunner::vertex_location(const std::string& input) const {
    for (const json& program : layout_["programs"])
        for (const json& v : program.value("vertex_inputs", json::array()))
            if (v.value("name", "") == input) return v.value("location", -1);
    return -1;
}

// glTexImage per level with zeros (GL 3.3 has no glTexStorage; both APIs take sized formats).
std::string LayoutRunner::allocate(const json& desc, int width, int height) {
    const std::string name = desc["name"];
    Texture t{0, 0, width, height, &desc};
    TextureTarget target{};
    TextureFilter min{}, mag{};
    Wrap wrap{};
    for (std::string e : {read_word(desc, "target", "", &target), read_word(desc, "internal_format", "", &t.format),
                          read_word(desc, "min_filter", "", &min), read_word(desc, "mag_filter", "", &mag),
                          read_word(desc, "wrap", "", &wrap), read_word(desc, "source", "passes", &t.source),
                          read_word(desc, "size", "fixed", &t.size)})
        if (!e.empty()) return "texture " + name + ": " + e;
    if (wrap == Wrap::clamp_to_border && !epoxy_is_desktop_gl())
        return "texture " + name + ": wrap CLAMP_TO_BORDER does not exist in OpenGL ES 3.0";
    t.target = gl_enum(target);
    const int depth = desc.value("depth", 1), levels = desc.value("mip_levels", 1);
    const penumbra::gl::detail::GlFormat f = gl_format(t.format);
    glGenTextures(1, &t.id);
    glBindTexture(t.target, t.id);
    std::vector<std::uint8_t> zeros(static_cast<std::size_t>(width) * height * depth * bytes_per_texel(t.format), 0);
    for (int level = 0; level < levels; ++level) {
        const int w = std::max(width >> level, 1), h = std::max(height >> level, 1);
        const int d = target == TextureTarget::texture_3d ? std::max(depth >> level, 1) : depth;
        if (target == TextureTarget::texture_2d)
            glTexImage2D(t.target, level, static_cast<GLint>(f.internal), w, h, 0, f.format, f.type, zeros.data());
        else
            glTexImage3D(t.target, level, static_cast<GLint>(f.internal), w, h, d, 0, f.format, f.type, zeros.data());
    }
    glTexParameteri(t.target, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(gl_enum(min)));
    glTexParameteri(t.target, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(gl_enum(mag)));
    for (GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(t.target, axis, static_cast<GLint>(gl_enum(wrap)));
    if (wrap == Wrap::clamp_to_border) {
        std::vector<float> border = desc.value("border_color", std::vector<float>{0, 0, 0, 0});
        glTexParameterfv(t.target, GL_TEXTURE_BORDER_COLOR, border.data());
    }
    glTexParameteri(t.target, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(t.target, GL_TEXTURE_MAX_LEVEL, levels - 1);
    glBindTexture(t.target, 0);
    if (auto it = textures_.find(name); it != textures_.end()) glDeleteTextures(1, &it->second.id);
    textures_[name] = t;
    filled_.erase(name); // caller and bake textures hold zeros until filled again
    return gl_error_text("texture " + name);
}

std::string LayoutRunner::allocate_output_sized(int width, int height) {
    if (width == output_width_ && height == output_height_) return {};
    for (const json& t : layout_["textures"]) {
        TextureSize size{};
        if (std::string e = read_word(t, "size", "fixed", &size); !e.empty()) return e;
        if (size == TextureSize::output)
            if (std::string e = allocate(t, width, height); !e.empty()) return e;
    }
    output_width_ = width;
    output_height_ = height;
    return {};
}

std::string LayoutRunner::link(const json& desc, const std::map<std::string, std::string>& sources) {
    const std::string name = desc["name"];
    const std::vector<std::string> files = desc["files"];
    // layout.json states each file's stage (stages[i] of files[i]); this runner links vertex + fragment
    const std::vector<std::string> file_stages = desc["stages"];
    if (files.size() != 2 || file_stages != std::vector<std::string>{"vertex", "fragment"}) {
        std::string listed;
        for (const std::string& stage : file_stages) listed += (listed.empty() ? "" : ", ") + stage;
        return "program " + name + ": stages [" + listed + "]; expected vertex, fragment";
    }
    const GLuint program = glCreateProgram();
    const GLenum stages[2] = {GL_VERTEX_SHADER, GL_FRAGMENT_SHADER};
    for (std::size_t i = 0; i < 2; ++i) {
        auto source = sources.find(files[i]);
        if (source == sources.end()) return "program " + name + ": no file " + files[i];
        const GLuint shader = glCreateShader(stages[i]);
        const char* text = source->second.c_str();
        glShaderSource(shader, 1, &text, nullptr);
        glCompileShader(shader);
        GLint ok = 0;
        glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char log[2048] = {};
            glGetShaderInfoLog(shader, sizeof log, nullptr, log);
            glDeleteShader(shader);
            glDeleteProgram(program);
            return files[i] + ": " + log;
        }
        glAttachShader(program, shader);
        glDeleteShader(shader);
    }
    glLinkProgram(program);
    GLint ok = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(program, sizeof log, nullptr, log);
        glDeleteProgram(program);
        return "program " + name + ": " + log;
    }
    // Neither GLSL 3.30 nor ESSL 3.00 has layout(binding): samplers get their units here.
    glUseProgram(program);
    for (const json& param : desc["parameters"])
        if (has_binding(param))
            glUniform1i(glGetUniformLocation(program, std::string(param["name"]).c_str()), param["binding"].get<int>());
    glUseProgram(0);
    programs_[name] = {program, &desc};
    return gl_error_text("program " + name);
}

void LayoutRunner::apply_uniforms(const Program& program) {
    for (const json& param : (*program.desc)["parameters"]) {
        if (has_binding(param)) continue;
        auto value = values_.find(param["name"]);
        if (value == values_.end()) continue;
        const GLint location = glGetUniformLocation(program.id, std::string(param["name"]).c_str());
        if (location < 0) continue;
        const std::vector<float>& v = value->second;
        const std::string type = param["type"];
        if (type == "float") glUniform1f(location, v.at(0));
        else if (type == "vec2") glUniform2fv(location, 1, v.data());
        else if (type == "vec3") glUniform3fv(location, 1, v.data());
        else if (type == "vec4") glUniform4fv(location, 1, v.data());
        else if (type == "mat4") glUniformMatrix4fv(location, 1, GL_FALSE, v.data());
        else if (type == "int") glUniform1i(location, static_cast<GLint>(v.at(0)));
    }
}

std::string LayoutRunner::apply_state(const json& s) {
    auto on = [](GLenum cap, bool enabled) { enabled ? glEnable(cap) : glDisable(cap); };
    // Logical operations: OpenGL 3.3 has them (more than 32 slices OR their bits into RGBA32UI);
    // ES 3.0 has no glLogicOp (penumbra emits none for essl300).
    RenderState r; // the words of `s`; absent ones are RenderState's defaults (off)
    for (std::string e : {read_word(s, "logic_op", "NONE", &r.logic_op), read_word(s, "blend_equation", "ADD", &r.blend_equation),
                          read_word(s, "blend_src", "ONE", &r.blend_src), read_word(s, "blend_dst", "ZERO", &r.blend_dst),
                          read_word(s, "depth_func", "LESS", &r.depth_func), read_word(s, "cull", "NONE", &r.cull)})
        if (!e.empty()) return "state: " + e;
    if (r.logic_op != LogicOp::none) {
        if (!epoxy_is_desktop_gl())
            return "state: logic_op " + std::string(to_string(r.logic_op)) + " is not available on OpenGL ES; allowed: NONE";
        glLogicOp(gl_enum(r.logic_op));
    }
    if (epoxy_is_desktop_gl()) on(GL_COLOR_LOGIC_OP, r.logic_op != LogicOp::none);
    on(GL_BLEND, s.value("blend", false));
    if (s.value("blend", false)) {
        glBlendEquation(gl_enum(r.blend_equation));
        glBlendFunc(gl_enum(r.blend_src), gl_enum(r.blend_dst));
    }
    on(GL_DEPTH_TEST, s.value("depth_test", false));
    if (s.value("depth_test", false)) glDepthFunc(gl_enum(r.depth_func));
    on(GL_CULL_FACE, r.cull != Cull::none);
    if (r.cull != Cull::none) glCullFace(gl_enum(r.cull));
    const std::vector<bool> mask = s.value("color_mask", std::vector<bool>{true, true, true, true});
    glColorMask(mask[0], mask[1], mask[2], mask[3]);
    const float factor = s.value("polygon_offset_factor", 0.0f), units = s.value("polygon_offset_units", 0.0f);
    on(GL_POLYGON_OFFSET_FILL, factor != 0.0f || units != 0.0f);
    glPolygonOffset(factor, units);
    glDepthMask(s.value("depth_write", false) ? GL_TRUE : GL_FALSE);
    return {};
}

// The pass's clears, as the desktop runtime does them: every colour output with full write masks
// (integer ones, R32UI, with glClearBufferuiv: glClear would be an error), the depth output with
// depth writes on; both APIs have glClearBuffer*.
std::string LayoutRunner::clear(const json& s, const std::vector<bool>& integer_buffers, bool has_depth) {
    if (s.contains("clear_color") && !s["clear_color"].is_null()) {
        const std::vector<float> c = s["clear_color"];
        if (c.size() != 4) return "state: clear_color " + s["clear_color"].dump() + " is not 4 numbers";
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        for (std::size_t i = 0; i < integer_buffers.size(); ++i) {
            if (integer_buffers[i]) {
                const GLuint value[4] = {static_cast<GLuint>(c[0]), static_cast<GLuint>(c[1]), static_cast<GLuint>(c[2]),
                                         static_cast<GLuint>(c[3])};
                glClearBufferuiv(GL_COLOR, static_cast<GLint>(i), value);
            } else {
                glClearBufferfv(GL_COLOR, static_cast<GLint>(i), c.data());
            }
        }
    }
    if (has_depth && s.contains("clear_depth") && !s["clear_depth"].is_null()) {
        const float depth = s["clear_depth"].get<float>();
        glDepthMask(GL_TRUE);
        glClearBufferfv(GL_DEPTH, 0, &depth);
    }
    return {};
}

void LayoutRunner::attach(GLenum framebuffer, GLenum attachment, const std::string& texture, int level, int layer) {
    const Texture& t = textures_.at(texture);
    if (layer >= 0)
        glFramebufferTextureLayer(framebuffer, attachment, t.id, level, layer);
    else
        glFramebufferTexture2D(framebuffer, attachment, GL_TEXTURE_2D, t.id, level);
}

std::string LayoutRunner::bind_outputs(const json& pass, std::vector<bool>& integer_buffers, bool& has_depth) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    for (GLenum i = 0; i < 8; ++i) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, 0, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
    std::vector<GLenum> buffers;
    for (const json& out : pass["outputs"]) {
        const std::string texture = out["texture"];
        if (!textures_.count(texture)) return "pass " + std::string(pass["name"]) + ": no texture " + texture;
        const TextureFormat format = textures_.at(texture).format;
        AttachmentKind kind{};
        if (std::string e = read_word(out, "kind", "color", &kind); !e.empty())
            return "pass " + std::string(pass["name"]) + ": " + e;
        if (kind == AttachmentKind::depth) {
            if (!is_depth(format)) return "pass " + std::string(pass["name"]) + ": depth output " + texture + " has a colour format";
            attach(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, texture, out["level"], out["layer"]);
            has_depth = true;
            continue;
        }
        const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(buffers.size());
        attach(GL_FRAMEBUFFER, attachment, texture, out["level"], out["layer"]);
        buffers.push_back(attachment);
        integer_buffers.push_back(is_integer(format));
    }
    glReadBuffer(buffers.empty() ? GL_NONE : GL_COLOR_ATTACHMENT0);
    if (buffers.empty()) buffers.push_back(GL_NONE); // a depth-only pass (the shadow map)
    glDrawBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return "pass " + std::string(pass["name"]) + ": framebuffer incomplete";
    return {};
}

std::string LayoutRunner::run_pass(const json& pass, const DrawScene& draw, int width, int height) {
    const std::string name = pass["name"];
    PassAction action{};
    if (std::string e = read_word(pass, "action", "", &action); !e.empty()) return "pass " + name + ": " + e;
    if (action == PassAction::generate_mipmap) { // 2x2 box levels ("mipmap": downsample box)
        if (pass.value("mipmap", json::object()).value("downsample", "") != "box")
            return "pass " + name + ": generate_mipmap needs \"mipmap\" with downsample \"box\"";
        const Texture& t = textures_.at(pass["outputs"][0]["texture"]);
        glBindTexture(t.target, t.id);
        glGenerateMipmap(t.target);
        glBindTexture(t.target, 0);
        return {};
    }
    if (action == PassAction::copy) { // the region "copy" names, through a read framebuffer (texel for texel)
        if (!pass.contains("copy")) return "pass " + name + ": a copy pass needs \"copy\" (levels, layers, size)";
        const json& copy = pass["copy"];
        const Texture& t = textures_.at(pass["outputs"][0]["texture"]);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, read_framebuffer_);
        attach(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, pass["inputs"][0]["texture"], copy["source_level"],
               copy["source_layer"]);
        glReadBuffer(GL_COLOR_ATTACHMENT0);
        glBindTexture(t.target, t.id);
        const int w = copy["width"], h = copy["height"], level = copy["target_level"], layer = copy["target_layer"];
        if (t.target == GL_TEXTURE_2D)
            glCopyTexSubImage2D(t.target, level, 0, 0, 0, 0, w, h);
        else
            glCopyTexSubImage3D(t.target, level, 0, 0, std::max(layer, 0), 0, 0, w, h);
        glBindTexture(t.target, 0);
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        return {};
    }
    auto program = programs_.find(pass["program"]);
    if (program == programs_.end()) return "pass " + name + ": no program " + std::string(pass["program"]);
    std::vector<bool> integer_buffers;
    bool has_depth = false;
    if (std::string e = bind_outputs(pass, integer_buffers, has_depth); !e.empty()) return e;
    // A 0 x 0 viewport is the size of the first output at its level (the desktop runtime's rule:
    // erosion's reductions render a 32 x 32 level of a 64 x 64 output), else the output size.
    int vw = pass["viewport"][0], vh = pass["viewport"][1];
    if (vw <= 0 || vh <= 0) {
        vw = width;
        vh = height;
        if (!pass["outputs"].empty()) {
            const json& out = pass["outputs"][0];
            const Texture& t = textures_.at(out["texture"]);
            const int level = out.value("level", 0);
            vw = std::max(t.width >> level, 1);
            vh = std::max(t.height >> level, 1);
        }
    }
    glViewport(0, 0, vw, vh);
    if (std::string e = clear(pass["state"], integer_buffers, has_depth); !e.empty()) return "pass " + name + ": " + e;
    glUseProgram(program->second.id);
    apply_uniforms(program->second);
    for (const auto& [uniform, value] : pass["int_uniforms"].items())
        glUniform1i(glGetUniformLocation(program->second.id, uniform.c_str()), value.get<int>());
    std::vector<const Texture*> level_limited;
    for (const json& input : pass["inputs"]) {
        auto t = textures_.find(input["texture"]);
        if (t == textures_.end()) return "pass " + name + ": no texture " + std::string(input["texture"]);
        const TextureSource source = t->second.source;
        if (source != TextureSource::passes && !filled_.count(t->first))
            return "pass " + name + ": texture " + t->first + " (source " + std::string(to_string(source)) +
                   ") was never filled" +
                   (source == TextureSource::bake ? " (a bake: uniforms.json bake_textures names its file)"
                                                  : " (a caller G-buffer: uniforms.json caller_textures names its file)");
        GLuint sampler_id = 0;
        if (input.contains("sampling"))
            if (std::string e = sampler(input["sampling"], "pass " + name + " input " + std::string(input["texture"]),
                                        &sampler_id, is_depth(t->second.format));
                !e.empty())
                return e;
        glActiveTexture(GL_TEXTURE0 + input["binding"].get<GLenum>());
        glBindTexture(t->second.target, t->second.id);
        glBindSampler(input["binding"].get<GLuint>(), sampler_id);
        if (const int level = input.value("level", -1); level >= 0) { // the pass reads only this level
            glTexParameteri(t->second.target, GL_TEXTURE_BASE_LEVEL, level);
            glTexParameteri(t->second.target, GL_TEXTURE_MAX_LEVEL, level);
            level_limited.push_back(&t->second);
        }
    }
    if (std::string e = apply_state(pass["state"]); !e.empty()) return "pass " + name + ": " + e;
    if (action == PassAction::draw_scene) {
        if (!draw) return "pass " + name + ": draws the scene, and the caller gave no scene for phase " + pass.value("phase", "shadow");
        draw(program->second.id);
    } else {
        glBindVertexArray(empty_vao_);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
    }
    for (const Texture* t : level_limited) {
        glBindTexture(t->target, t->id);
        glTexParameteri(t->target, GL_TEXTURE_BASE_LEVEL, 0);
        glTexParameteri(t->target, GL_TEXTURE_MAX_LEVEL, t->desc->value("mip_levels", 1) - 1);
    }
    for (const json& input : pass["inputs"]) {
        glActiveTexture(GL_TEXTURE0 + input["binding"].get<GLenum>());
        glBindTexture(textures_.at(input["texture"]).target, 0);
        glBindSampler(input["binding"].get<GLuint>(), 0);
    }
    glActiveTexture(GL_TEXTURE0);
    apply_state(json::object());
    glUseProgram(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return gl_error_text("pass " + name);
}

std::string LayoutRunner::run_phase(Phase phase, const DrawScene& draw, int width, int height) {
    if (phase == Phase::screen)
        if (std::string e = allocate_output_sized(width, height); !e.empty()) return e;
    for (const json& pass : layout_["passes"]) {
        Phase pass_phase{};
        read_word(pass, "phase", "shadow", &pass_phase); // checked by create
        if (pass_phase != phase) continue;
        if (std::string e = run_pass(pass, draw, width, height); !e.empty()) return e;
    }
    return {};
}

std::string LayoutRunner::fill_texture(const std::string& name, int width, int height, const float* rgba) {
    const json* desc = nullptr;
    for (const json& t : layout_["textures"])
        if (t["name"] == name) desc = &t;
    if (!desc) return "no texture " + name + " in layout.json";
    TextureSource source{};
    TextureSize size{};
    read_word(*desc, "source", "passes", &source); // checked by create
    read_word(*desc, "size", "fixed", &size);
    if (source != TextureSource::caller) return "texture " + name + " is not filled by the caller";
    if (size == TextureSize::output)
        if (std::string e = allocate_output_sized(width, height); !e.empty()) return e;
    const Texture& t = textures_.at(name);
    glBindTexture(t.target, t.id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(t.target, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba);
    glBindTexture(t.target, 0);
    if (std::string e = gl_error_text("fill " + name); !e.empty()) return e;
    filled_.insert(name);
    return {};
}

std::string LayoutRunner::fill_bake(const std::string& name, const std::vector<float>& rgba) {
    std::string bakes;
    for (const auto& [texture, t] : textures_)
        if (t.source == TextureSource::bake) bakes += (bakes.empty() ? "" : ", ") + texture;
    auto it = textures_.find(name);
    if (it == textures_.end() || it->second.source != TextureSource::bake)
        return "texture " + name + " is not a bake texture of this layout; bake textures: " + (bakes.empty() ? "none" : bakes);
    const Texture& t = it->second;
    if (t.target != GL_TEXTURE_2D || channels(t.format) != 4 || is_integer(t.format) || is_depth(t.format))
        return "bake texture " + name + ": " + std::string(to_string(t.format)) + " " + std::string((*t.desc)["target"]) +
               "; this runner uploads RGBA floats into 2D RGBA textures only";
    const std::size_t expected = 4 * static_cast<std::size_t>(t.width) * t.height;
    if (rgba.size() != expected)
        return "bake texture " + name + ": " + std::to_string(rgba.size()) + " floats; the layout's " +
               std::to_string(t.width) + " x " + std::to_string(t.height) + " RGBA texture needs " + std::to_string(expected) +
               " (a bake of another resolution?)";
    // The GL converts the floats to the texture's format (RGBA16F: round to nearest), as the
    // desktop runtime's upload does.
    glBindTexture(t.target, t.id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(t.target, 0, 0, 0, t.width, t.height, GL_RGBA, GL_FLOAT, rgba.data());
    glBindTexture(t.target, 0);
    if (std::string e = gl_error_text("bake " + name); !e.empty()) return e;
    filled_.insert(name);
    return {};
}

std::vector<float> LayoutRunner::read_texture(const Texture& t) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_framebuffer_);
    attach(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, (*t.desc)["name"], 0, -1);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    const std::size_t n = static_cast<std::size_t>(t.width) * t.height;
    std::vector<float> rgba(4 * n);
    // RGBA/UNSIGNED_BYTE (normalised) and RGBA/FLOAT (float buffers) are readable on both APIs.
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (is_float(t.format)) {
        glReadPixels(0, 0, t.width, t.height, GL_RGBA, GL_FLOAT, rgba.data());
    } else {
        std::vector<std::uint8_t> bytes(4 * n);
        glReadPixels(0, 0, t.width, t.height, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
        for (std::size_t i = 0; i < bytes.size(); ++i) rgba[i] = bytes[i] / 255.0f;
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    return rgba;
}

std::vector<float> LayoutRunner::read_result() {
    auto t = textures_.find(layout_.value("result", ""));
    if (t == textures_.end()) return {};
    const std::vector<float> rgba = read_texture(t->second);
    std::vector<float> out(rgba.size() / 4);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = rgba[4 * i];
    return out;
}

} // namespace penumbra::targets
