// penumbra/gl/state.hpp — the GL state a pass runs with: its fixed-function state (RenderState),
// its samplers, and the uniforms computed from the light and camera (penumbra/uniform_values.hpp).
//
// Header-only; includes <epoxy/gl.h>.
#pragma once

#include "../layout.hpp"
#include "../uniform_values.hpp"
#include "layout_enums.hpp"

#include <epoxy/gl.h>
#include <glm/gtc/type_ptr.hpp>

#include <map>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

namespace penumbra::gl::detail {

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

// GL sampler objects, one per distinct layout.json "sampling" (filters, wrap, border, comparison):
// a binding reads its texture through the sampler of its own sampling, so two bindings may read one
// texture two ways (PCSS: the shadow map with and without comparison). Owns the objects.
class SamplerCache {
public:
    SamplerCache() = default;
    SamplerCache(const SamplerCache&) = delete;
    SamplerCache& operator=(const SamplerCache&) = delete;
    ~SamplerCache() {
        for (auto& [sampling, id] : samplers_) glDeleteSamplers(1, &id);
    }

    // The sampler of `s`.
    GLuint get(const Sampling& s) {
        if (auto it = samplers_.find(s); it != samplers_.end()) return it->second;
        GLuint id = 0;
        glCreateSamplers(1, &id);
        glSamplerParameteri(id, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(gl_enum(s.min_filter)));
        glSamplerParameteri(id, GL_TEXTURE_MAG_FILTER, static_cast<GLint>(gl_enum(s.mag_filter)));
        const GLint wrap = static_cast<GLint>(gl_enum(s.wrap));
        glSamplerParameteri(id, GL_TEXTURE_WRAP_S, wrap);
        glSamplerParameteri(id, GL_TEXTURE_WRAP_T, wrap);
        glSamplerParameteri(id, GL_TEXTURE_WRAP_R, wrap);
        glSamplerParameterfv(id, GL_TEXTURE_BORDER_COLOR, s.border_color.data());
        if (s.compare) {
            glSamplerParameteri(id, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
            glSamplerParameteri(id, GL_TEXTURE_COMPARE_FUNC, static_cast<GLint>(gl_enum(*s.compare)));
        }
        samplers_.emplace(s, id);
        return id;
    }

private:
    std::map<Sampling, GLuint> samplers_;
};

// Binds `texture_id` to texture unit `unit` with sampler object `sampler` (0: the texture's own
// parameters) and points sampler `name` of `program` at it.
inline void bind_sampler(GLuint program, const std::string& name, int unit, GLuint texture_id, GLuint sampler) {
    glBindTextureUnit(static_cast<GLuint>(unit), texture_id);
    glBindSampler(static_cast<GLuint>(unit), sampler);
    const GLint location = glGetUniformLocation(program, name.c_str());
    if (location >= 0) glProgramUniform1i(program, location, unit); // glsl330: no layout(binding)
}

// The uniforms of `program` (that of `pass`) that the table computes ("light" and "camera" sources).
inline std::string set_computed_uniforms(const Layout& layout, const PassDesc& pass, GLuint program,
                                         const UniformInputs& inputs) {
    for (const ProgramDesc& p : layout.programs) {
        if (p.name != pass.program) continue;
        for (const ParamDesc& param : p.parameters) {
            if (param.source != UniformSource::light && param.source != UniformSource::camera) continue;
            const UniformResult v = uniform_value(param.name, inputs);
            if (!v) {
                if (param.source == UniformSource::camera) continue; // no camera in the runtime's own passes
                return "pass " + pass.name + ": no value for uniform " + v.error;
            }
            set_uniform(program, glGetUniformLocation(program, param.name.c_str()), *v);
        }
    }
    return {};
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
    if (s.cull == Cull::none) {
        glDisable(GL_CULL_FACE);
    } else {
        glEnable(GL_CULL_FACE);
        glCullFace(gl_enum(s.cull));
    }
    if (s.logic_op != LogicOp::none) { // integer targets: each fragment OR-ed into the texel (no blending)
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

} // namespace penumbra::gl::detail
