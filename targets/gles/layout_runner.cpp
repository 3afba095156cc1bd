// targets/gles/layout_runner.cpp — see layout_runner.hpp.
#include "layout_runner.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace penumbra::targets {

namespace {

using nlohmann::json;

struct Format {
    GLenum internal, format, type;
    int bytes;       // per texel
    bool is_float;   // rendering to it needs EXT_color_buffer_float on ES 3.0
    bool filterable; // LINEAR filtering without OES_texture_float_linear
};

const Format* format_of(const std::string& name) {
    static const std::map<std::string, Format> formats{
        {"RGBA8", {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, 4, false, true}},
        {"R8", {GL_R8, GL_RED, GL_UNSIGNED_BYTE, 1, false, true}},
        {"RGBA16F", {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT, 8, true, true}},
        {"RG16F", {GL_RG16F, GL_RG, GL_HALF_FLOAT, 4, true, true}},
        {"R16F", {GL_R16F, GL_RED, GL_HALF_FLOAT, 2, true, true}},
        {"RGBA32F", {GL_RGBA32F, GL_RGBA, GL_FLOAT, 16, true, false}},
        {"RG32F", {GL_RG32F, GL_RG, GL_FLOAT, 8, true, false}},
        {"R32F", {GL_R32F, GL_RED, GL_FLOAT, 4, true, false}},
        {"RGBA32UI", {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT, 16, false, false}},
        {"DEPTH_COMPONENT24", {GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, 4, false, true}},
        {"DEPTH_COMPONENT32F", {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, 4, false, true}},
    };
    auto it = formats.find(name);
    return it == formats.end() ? nullptr : &it->second;
}

// GL_<name> for the enum strings layout.json uses; 0 when unknown.
GLenum gl_enum(const std::string& name) {
    static const std::map<std::string, GLenum> names{
        {"2D", GL_TEXTURE_2D}, {"2D_ARRAY", GL_TEXTURE_2D_ARRAY}, {"3D", GL_TEXTURE_3D},
        {"NEAREST", GL_NEAREST}, {"LINEAR", GL_LINEAR}, {"LINEAR_MIPMAP_LINEAR", GL_LINEAR_MIPMAP_LINEAR},
        {"NEAREST_MIPMAP_NEAREST", GL_NEAREST_MIPMAP_NEAREST}, {"LINEAR_MIPMAP_NEAREST", GL_LINEAR_MIPMAP_NEAREST},
        {"NEAREST_MIPMAP_LINEAR", GL_NEAREST_MIPMAP_LINEAR},
        {"CLAMP_TO_EDGE", GL_CLAMP_TO_EDGE}, {"CLAMP_TO_BORDER", GL_CLAMP_TO_BORDER}, {"REPEAT", GL_REPEAT},
        {"ADD", GL_FUNC_ADD}, {"MAX", GL_MAX}, {"MIN", GL_MIN},
        {"ZERO", GL_ZERO}, {"ONE", GL_ONE}, {"SRC_ALPHA", GL_SRC_ALPHA}, {"ONE_MINUS_SRC_ALPHA", GL_ONE_MINUS_SRC_ALPHA},
        {"NEVER", GL_NEVER}, {"LESS", GL_LESS}, {"LEQUAL", GL_LEQUAL}, {"EQUAL", GL_EQUAL}, {"GREATER", GL_GREATER},
        {"GEQUAL", GL_GEQUAL}, {"NOTEQUAL", GL_NOTEQUAL}, {"ALWAYS", GL_ALWAYS},
        {"BACK", GL_BACK}, {"FRONT", GL_FRONT},
    };
    auto it = names.find(name);
    return it == names.end() ? 0 : it->second;
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
                                                   std::string* error, const std::vector<std::string>& phases) {
    auto fail = [&](std::string message) -> std::unique_ptr<LayoutRunner> {
        if (error) *error = std::move(message);
        return nullptr;
    };
    if (!layout.contains("layout_version")) return fail("layout.json: no layout_version (an older layout); this runner reads version 3");
    if (layout["layout_version"] != 3)
        return fail("layout.json: layout_version " + layout["layout_version"].dump() + "; this runner reads version 3");
    std::unique_ptr<LayoutRunner> runner(new LayoutRunner());
    runner->layout_ = layout;
    const bool es = !epoxy_is_desktop_gl();
    const json& l = runner->layout_;

    // Extensions, only where the layout needs them: ES 3.0 renders to float textures with
    // EXT_color_buffer_float and filters 32-bit floats linearly with OES_texture_float_linear.
    std::vector<std::string> rendered;
    for (const json& pass : l["passes"])
        for (const json& out : pass["outputs"]) rendered.push_back(out["texture"]);
    for (const json& t : l["textures"]) {
        const std::string name = t["name"], format = t["internal_format"];
        const Format* f = format_of(format);
        if (!f) return fail("texture " + name + ": internal_format '" + format + "' unknown");
        auto need = [&](const std::string& extension, const std::string& why) {
            if (!es || std::find(runner->extensions_.begin(), runner->extensions_.end(), extension) != runner->extensions_.end())
                return std::string();
            if (!epoxy_has_gl_extension(extension.c_str())) return why + " needs " + extension + ", which this context lacks";
            runner->extensions_.push_back(extension);
            return std::string();
        };
        std::string missing;
        if (f->is_float && std::find(rendered.begin(), rendered.end(), name) != rendered.end())
            missing = need("GL_EXT_color_buffer_float", "rendering to " + name + " (" + format + ")");
        const bool linear = t["mag_filter"] == "LINEAR" || std::string(t["min_filter"]).starts_with("LINEAR");
        if (missing.empty() && f->is_float && !f->filterable && linear)
            missing = need("GL_OES_texture_float_linear", "LINEAR filtering of " + name + " (" + format + ")");
        if (!missing.empty()) return fail(missing);
        if (t.value("size", "fixed") != "output")
            if (std::string e = runner->allocate(t, t["width"], t["height"]); !e.empty()) return fail(e);
    }
    std::vector<std::string> used;
    for (const json& pass : l["passes"])
        if (std::find(phases.begin(), phases.end(), pass.value("phase", "shadow")) != phases.end())
            used.push_back(pass.value("program", ""));
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
std::string LayoutRunner::sampler(const json& sampling, const std::string& where, GLuint* id) {
    const std::string key = sampling.dump();
    if (auto it = samplers_.find(key); it != samplers_.end()) {
        *id = it->second;
        return {};
    }
    const std::string wrap_name = sampling.value("wrap", ""), compare = sampling.value("compare", "");
    const GLenum min = gl_enum(sampling.value("min_filter", "")), mag = gl_enum(sampling.value("mag_filter", ""));
    const GLenum wrap = gl_enum(wrap_name);
    if (!min || !mag || !wrap) return where + ": sampling " + key + " has an unknown filter or wrap";
    if (wrap == GL_CLAMP_TO_BORDER && !epoxy_is_desktop_gl())
        return where + ": wrap CLAMP_TO_BORDER does not exist in OpenGL ES 3.0";
    glGenSamplers(1, id);
    glSamplerParameteri(*id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(min));
    glSamplerParameteri(*id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(mag));
    for (GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glSamplerParameteri(*id, axis, static_cast<GLint>(wrap));
    if (wrap == GL_CLAMP_TO_BORDER) {
        std::vector<float> border = sampling.value("border_color", std::vector<float>{0, 0, 0, 0});
        glSamplerParameterfv(*id, GL_TEXTURE_BORDER_COLOR, border.data());
    }
    if (!compare.empty()) {
        const GLenum func = gl_enum(compare);
        if (!func) return where + ": compare '" + compare + "' unknown";
        glSamplerParameteri(*id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glSamplerParameteri(*id, GL_TEXTURE_COMPARE_FUNC, static_cast<GLint>(func));
    }
    samplers_[key] = *id;
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
    const GLenum target = gl_enum(desc["target"]);
    const Format* f = format_of(desc["internal_format"]);
    if (target == 0) return "texture " + name + ": target '" + std::string(desc["target"]) + "' unknown; allowed: 2D, 2D_ARRAY, 3D";
    const std::string wrap_name = desc["wrap"];
    const GLenum wrap = gl_enum(wrap_name);
    if (wrap == 0) return "texture " + name + ": wrap '" + wrap_name + "' unknown";
    if (wrap == GL_CLAMP_TO_BORDER && !epoxy_is_desktop_gl())
        return "texture " + name + ": wrap CLAMP_TO_BORDER does not exist in OpenGL ES 3.0";
    const int depth = desc.value("depth", 1), levels = desc.value("mip_levels", 1);
    Texture t{0, target, width, height, &desc};
    glGenTextures(1, &t.id);
    glBindTexture(target, t.id);
    std::vector<std::uint8_t> zeros(static_cast<std::size_t>(width) * height * depth * f->bytes, 0);
    for (int level = 0; level < levels; ++level) {
        const int w = std::max(width >> level, 1), h = std::max(height >> level, 1);
        const int d = target == GL_TEXTURE_3D ? std::max(depth >> level, 1) : depth;
        if (target == GL_TEXTURE_2D)
            glTexImage2D(target, level, static_cast<GLint>(f->internal), w, h, 0, f->format, f->type, zeros.data());
        else
            glTexImage3D(target, level, static_cast<GLint>(f->internal), w, h, d, 0, f->format, f->type, zeros.data());
    }
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(gl_enum(desc["min_filter"])));
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(gl_enum(desc["mag_filter"])));
    for (GLenum axis : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R})
        glTexParameteri(target, axis, static_cast<GLint>(wrap));
    if (wrap == GL_CLAMP_TO_BORDER) {
        std::vector<float> border = desc.value("border_color", std::vector<float>{0, 0, 0, 0});
        glTexParameterfv(target, GL_TEXTURE_BORDER_COLOR, border.data());
    }
    glTexParameteri(target, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(target, GL_TEXTURE_MAX_LEVEL, levels - 1);
    glBindTexture(target, 0);
    if (auto it = textures_.find(name); it != textures_.end()) glDeleteTextures(1, &it->second.id);
    textures_[name] = t;
    return gl_error_text("texture " + name);
}

std::string LayoutRunner::allocate_output_sized(int width, int height) {
    if (width == output_width_ && height == output_height_) return {};
    for (const json& t : layout_["textures"])
        if (t.value("size", "fixed") == "output")
            if (std::string e = allocate(t, width, height); !e.empty()) return e;
    output_width_ = width;
    output_height_ = height;
    return {};
}

std::string LayoutRunner::link(const json& desc, const std::map<std::string, std::string>& sources) {
    const std::string name = desc["name"];
    const std::vector<std::string> files = desc["files"];
    if (files.size() != 2) return "program " + name + ": " + std::to_string(files.size()) + " files; expected vertex + fragment";
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
    if (s.value("logic_op", "NONE") != "NONE") // ES 3.0 has no glLogicOp (penumbra emits none for essl300)
        return "state: logic_op " + s.value("logic_op", "") + " is not available on OpenGL ES; allowed: NONE";
    on(GL_BLEND, s.value("blend", false));
    if (s.value("blend", false)) {
        const GLenum equation = gl_enum(s["blend_equation"]), src = gl_enum(s["blend_src"]), dst = gl_enum(s["blend_dst"]);
        if (!equation || !src || !dst) return "state: blend " + s.dump() + " unknown";
        glBlendEquation(equation);
        glBlendFunc(src, dst);
    }
    on(GL_DEPTH_TEST, s.value("depth_test", false));
    if (s.value("depth_test", false)) glDepthFunc(gl_enum(s["depth_func"]));
    const std::string cull = s.value("cull", "NONE");
    on(GL_CULL_FACE, cull != "NONE");
    if (cull != "NONE") glCullFace(gl_enum(cull));
    const std::vector<bool> mask = s.value("color_mask", std::vector<bool>{true, true, true, true});
    glColorMask(mask[0], mask[1], mask[2], mask[3]);
    const float factor = s.value("polygon_offset_factor", 0.0f), units = s.value("polygon_offset_units", 0.0f);
    on(GL_POLYGON_OFFSET_FILL, factor != 0.0f || units != 0.0f);
    glPolygonOffset(factor, units);
    GLbitfield clear = 0;
    if (s.contains("clear_color") && !s["clear_color"].is_null()) {
        const std::vector<float> c = s["clear_color"];
        glClearColor(c[0], c[1], c[2], c[3]);
        clear |= GL_COLOR_BUFFER_BIT;
    }
    if (s.contains("clear_depth") && !s["clear_depth"].is_null()) {
        const float depth = s["clear_depth"].get<float>();
        epoxy_is_desktop_gl() ? glClearDepth(depth) : glClearDepthf(depth); // glClearDepthf: GL 4.1
        glDepthMask(GL_TRUE);
        clear |= GL_DEPTH_BUFFER_BIT;
    }
    if (clear) glClear(clear);
    glDepthMask(s.value("depth_write", false) ? GL_TRUE : GL_FALSE);
    return {};
}

void LayoutRunner::attach(GLenum framebuffer, GLenum attachment, const std::string& texture, int level, int layer) {
    const Texture& t = textures_.at(texture);
    if (layer >= 0)
        glFramebufferTextureLayer(framebuffer, attachment, t.id, level, layer);
    else
        glFramebufferTexture2D(framebuffer, attachment, GL_TEXTURE_2D, t.id, level);
}

std::string LayoutRunner::bind_outputs(const json& pass) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    for (GLenum i = 0; i < 8; ++i) glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, 0, 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, 0, 0);
    std::vector<GLenum> buffers;
    for (const json& out : pass["outputs"]) {
        const std::string texture = out["texture"];
        if (!textures_.count(texture)) return "pass " + std::string(pass["name"]) + ": no texture " + texture;
        if (out.value("kind", "color") == "depth") {
            attach(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, texture, out["level"], out["layer"]);
            continue;
        }
        const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(buffers.size());
        attach(GL_FRAMEBUFFER, attachment, texture, out["level"], out["layer"]);
        buffers.push_back(attachment);
    }
    if (buffers.empty()) buffers.push_back(GL_NONE);
    glDrawBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return "pass " + std::string(pass["name"]) + ": framebuffer incomplete";
    return {};
}

std::string LayoutRunner::run_pass(const json& pass, const DrawScene& draw, int width, int height) {
    const std::string name = pass["name"], action = pass["action"];
    if (action == "generate_mipmap") { // 2x2 box levels ("mipmap": downsample box)
        if (pass.value("mipmap", json::object()).value("downsample", "") != "box")
            return "pass " + name + ": generate_mipmap needs \"mipmap\" with downsample \"box\"";
        const Texture& t = textures_.at(pass["outputs"][0]["texture"]);
        glBindTexture(t.target, t.id);
        glGenerateMipmap(t.target);
        glBindTexture(t.target, 0);
        return {};
    }
    if (action == "copy") { // the region "copy" names, through a read framebuffer (texel for texel)
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
    if (action != "fullscreen" && action != "draw_scene")
        return "pass " + name + ": action '" + action + "' unknown; allowed: draw_scene, fullscreen, generate_mipmap, copy";
    auto program = programs_.find(pass["program"]);
    if (program == programs_.end()) return "pass " + name + ": no program " + std::string(pass["program"]);
    if (std::string e = bind_outputs(pass); !e.empty()) return e;
    const int vw = pass["viewport"][0], vh = pass["viewport"][1];
    glViewport(0, 0, vw > 0 ? vw : width, vw > 0 ? vh : height);
    glUseProgram(program->second.id);
    apply_uniforms(program->second);
    for (const auto& [uniform, value] : pass["int_uniforms"].items())
        glUniform1i(glGetUniformLocation(program->second.id, uniform.c_str()), value.get<int>());
    std::vector<const Texture*> level_limited;
    for (const json& input : pass["inputs"]) {
        auto t = textures_.find(input["texture"]);
        if (t == textures_.end()) return "pass " + name + ": no texture " + std::string(input["texture"]);
        GLuint sampler_id = 0;
        if (input.contains("sampling"))
            if (std::string e = sampler(input["sampling"], "pass " + name + " input " + std::string(input["texture"]),
                                        &sampler_id);
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
    if (action == "draw_scene") {
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

std::string LayoutRunner::run_phase(const std::string& phase, const DrawScene& draw, int width, int height) {
    if (phase == "screen")
        if (std::string e = allocate_output_sized(width, height); !e.empty()) return e;
    for (const json& pass : layout_["passes"]) {
        if (pass.value("phase", "shadow") != phase) continue;
        if (std::string e = run_pass(pass, draw, width, height); !e.empty()) return e;
    }
    return {};
}

std::string LayoutRunner::fill_texture(const std::string& name, int width, int height, const float* rgba) {
    const json* desc = nullptr;
    for (const json& t : layout_["textures"])
        if (t["name"] == name) desc = &t;
    if (!desc) return "no texture " + name + " in layout.json";
    if (desc->value("source", "passes") != "caller") return "texture " + name + " is not filled by the caller";
    if (desc->value("size", "fixed") == "output")
        if (std::string e = allocate_output_sized(width, height); !e.empty()) return e;
    const Texture& t = textures_.at(name);
    glBindTexture(t.target, t.id);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(t.target, 0, 0, 0, width, height, GL_RGBA, GL_FLOAT, rgba);
    glBindTexture(t.target, 0);
    return gl_error_text("fill " + name);
}

std::vector<float> LayoutRunner::read_texture(const Texture& t) {
    const Format* f = format_of((*t.desc)["internal_format"]);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, read_framebuffer_);
    attach(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, (*t.desc)["name"], 0, -1);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    const std::size_t n = static_cast<std::size_t>(t.width) * t.height;
    std::vector<float> rgba(4 * n);
    // RGBA/UNSIGNED_BYTE (normalised) and RGBA/FLOAT (float buffers) are readable on both APIs.
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    if (f->is_float) {
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
