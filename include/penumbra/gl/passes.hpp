// penumbra/gl/passes.hpp — runs the passes of a layout from its data alone: every texture, binding,
// state and uniform a pass needs comes from layout.json (penumbra/layout.hpp); nothing here knows a
// pass, program or technique by name.
//
// Header-only; includes <epoxy/gl.h>.
#pragma once

#include "../layout.hpp"
#include "../uniform_values.hpp"
#include "resources.hpp"
#include "state.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <array>
#include <functional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace penumbra::gl {

struct PassTiming {
    std::string name;
    double milliseconds = 0.0;
};

namespace detail {

using DrawScene = std::function<void(GLuint program)>;

// What the passes of a layout run with: the runtime's framebuffer and empty vertex array, its
// programs and textures by layout name, the output size and the inputs of computed uniforms.
struct PassContext {
    const Layout& layout;
    GLuint framebuffer = 0;
    GLuint empty_vertex_array = 0;
    std::function<GLuint(const std::string&)> program; // 0 when there is none of that name
    std::function<GLuint(const std::string&)> texture; // the GL texture of a layout texture name
    std::function<GLuint(const Sampling&)> sampler;     // the sampler object of a binding's sampling
    int output_width = 0, output_height = 0;           // of the textures whose size is "output"
    UniformInputs uniforms;                             // for the "light" and "camera" uniforms
};

// Size of level `level` of the texture an attachment names (output-sized: the output size).
inline std::pair<int, int> attachment_size(const PassContext& c, const AttachmentDesc& out) {
    const TextureDesc* t = find_texture(c.layout, out.texture);
    if (!t) return {0, 0};
    const bool output_sized = t->size == TextureSize::output;
    const int w = output_sized ? c.output_width : t->width, h = output_sized ? c.output_height : t->height;
    return {std::max(w >> out.level, 1), std::max(h >> out.level, 1)};
}

// Binds a pass's inputs as samplers (a binding with a level reads that level only, restricted until
// unbind_inputs) and sets its int_uniforms and computed uniforms on `program`, which is in use.
inline std::string bind_inputs(const PassContext& c, const PassDesc& pass, GLuint program, std::vector<GLuint>& restricted) {
    for (const BindingDesc& in : pass.inputs) {
        const GLuint id = c.texture(in.texture);
        if (!id) return "pass " + pass.name + ": no texture " + in.texture + " for " + in.sampler;
        if (in.level >= 0) { // read one level only; the pass may render another level of it
            glTextureParameteri(id, GL_TEXTURE_BASE_LEVEL, in.level);
            glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, in.level);
            restricted.push_back(id);
        }
        bind_sampler(program, in.sampler, in.binding, id, c.sampler(in.sampling));
    }
    for (const auto& [name, value] : pass.int_uniforms)
        glProgramUniform1i(program, glGetUniformLocation(program, name.c_str()), value);
    return set_computed_uniforms(c.layout, pass, program, c.uniforms);
}

// Undoes bind_inputs: every level readable again, no sampler objects, no program.
inline void unbind_inputs(const PassContext& c, const PassDesc& pass, const std::vector<GLuint>& restricted) {
    for (GLuint id : restricted) {
        const TextureDesc* t = nullptr;
        for (const BindingDesc& in : pass.inputs)
            if (c.texture(in.texture) == id) t = find_texture(c.layout, in.texture);
        glTextureParameteri(id, GL_TEXTURE_BASE_LEVEL, 0);
        glTextureParameteri(id, GL_TEXTURE_MAX_LEVEL, t ? t->mip_levels - 1 : 1000);
    }
    for (const BindingDesc& in : pass.inputs) glBindSampler(static_cast<GLuint>(in.binding), 0);
    glUseProgram(0);
}

// A dispatch pass: the compute program over dispatch.groups, its inputs bound as samplers and its
// images as images (in their textures' formats), then the memory barrier the passes after it need.
inline std::string run_dispatch(const PassContext& c, const PassDesc& pass) {
    const DispatchDesc& dispatch = pass.dispatch;
    GLbitfield barrier = 0;
    for (MemoryBarrierBit bit : dispatch.memory_barrier) barrier |= detail::gl_enum(bit);
    const GLuint program = c.program(pass.program);
    if (!program) return "pass " + pass.name + ": no program " + pass.program;
    for (const ImageBindingDesc& image : dispatch.images) {
        const GLuint id = c.texture(image.texture);
        const TextureDesc* t = find_texture(c.layout, image.texture);
        if (!id || !t) return "pass " + pass.name + ": no texture " + image.texture + " for " + image.image;
        glBindImageTexture(static_cast<GLuint>(image.unit), id, image.level, GL_FALSE, std::max(image.layer, 0),
                           detail::gl_enum(image.access), detail::gl_enum(t->format));
    }
    glUseProgram(program);
    std::vector<GLuint> restricted;
    std::string diagnostic = bind_inputs(c, pass, program, restricted);
    if (diagnostic.empty()) {
        glDispatchCompute(static_cast<GLuint>(dispatch.groups[0]), static_cast<GLuint>(dispatch.groups[1]),
                          static_cast<GLuint>(dispatch.groups[2]));
        if (barrier) glMemoryBarrier(barrier);
    }
    unbind_inputs(c, pass, restricted);
    for (const ImageBindingDesc& image : dispatch.images)
        glBindImageTexture(static_cast<GLuint>(image.unit), 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
    return diagnostic;
}

// Runs one pass: a copy, a mipmap generation, a compute dispatch, or a draw of `program` into the
// pass's outputs.
inline std::string run_pass(const PassContext& c, const PassDesc& pass, const DrawScene& draw) {
    switch (pass.action) {
    case PassAction::generate_mipmap: // every level above the base, each a 2x2 box of the one below
        if (pass.outputs.size() != 1) return "pass " + pass.name + ": generate_mipmap needs one output";
        glGenerateTextureMipmap(c.texture(pass.outputs[0].texture));
        return {};
    case PassAction::copy: { // the region copy_region names, texel for texel
        if (pass.inputs.size() != 1 || pass.outputs.size() != 1)
            return "pass " + pass.name + ": a copy pass needs one input and one output";
        const CopyDesc copy = copy_region(pass);
        auto target_of = [&](const std::string& name) {
            const TextureDesc* t = find_texture(c.layout, name);
            return t ? detail::gl_enum(t->target) : GL_TEXTURE_2D;
        };
        const std::string &from = pass.inputs[0].texture, &to = pass.outputs[0].texture;
        glCopyImageSubData(c.texture(from), target_of(from), copy.source_level, 0, 0, std::max(copy.source_layer, 0),
                           c.texture(to), target_of(to), copy.target_level, 0, 0, std::max(copy.target_layer, 0),
                           copy.width, copy.height, 1);
        return {};
    }
    case PassAction::dispatch: return run_dispatch(c, pass);
    case PassAction::draw_scene:
    case PassAction::fullscreen: break;
    }
    const GLuint program = c.program(pass.program);
    if (!program) return "pass " + pass.name + ": no program " + pass.program;
    glBindFramebuffer(GL_FRAMEBUFFER, c.framebuffer);
    detach_all(c.framebuffer);
    std::vector<GLenum> buffers;
    std::vector<bool> integer_buffers; // cleared with glClearBufferuiv
    bool has_depth = false;
    for (const AttachmentDesc& out : pass.outputs) {
        const bool depth = attachment_kind(c.layout, out) == AttachmentKind::depth;
        const GLenum attachment = depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(buffers.size());
        if (out.layer >= 0)
            glNamedFramebufferTextureLayer(c.framebuffer, attachment, c.texture(out.texture), out.level, out.layer);
        else
            glNamedFramebufferTexture(c.framebuffer, attachment, c.texture(out.texture), out.level);
        if (depth) {
            has_depth = true;
        } else {
            buffers.push_back(attachment);
            const TextureDesc* desc = find_texture(c.layout, out.texture);
            integer_buffers.push_back(desc && is_integer(desc->format));
        }
    }
    if (buffers.empty()) glNamedFramebufferDrawBuffer(c.framebuffer, GL_NONE);
    else glNamedFramebufferDrawBuffers(c.framebuffer, static_cast<GLsizei>(buffers.size()), buffers.data());
    if (glCheckNamedFramebufferStatus(c.framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return "pass " + pass.name + ": framebuffer incomplete";
    int width = pass.viewport_width, height = pass.viewport_height;
    if ((width == 0 || height == 0) && !pass.outputs.empty())
        std::tie(width, height) = attachment_size(c, pass.outputs.front());
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
    std::string diagnostic = bind_inputs(c, pass, program, restricted);
    if (diagnostic.empty()) {
        if (pass.action == PassAction::draw_scene) {
            draw(program);
        } else {
            glBindVertexArray(c.empty_vertex_array);
            glDrawArrays(GL_TRIANGLES, 0, 3);
            glBindVertexArray(0);
        }
    }
    unbind_inputs(c, pass, restricted);
    return diagnostic;
}

// Runs every pass of `phase` in layout order, restoring the caller's framebuffer and viewport.
inline std::string run_phase(const PassContext& c, Phase phase, const DrawScene& draw,
                             std::vector<PassTiming>* timings) {
    GLint previous_fbo = 0, previous_viewport[4];
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previous_fbo);
    glGetIntegerv(GL_VIEWPORT, previous_viewport);
    std::vector<std::pair<std::string, GLuint>> pending;
    std::string diagnostic;
    for (const PassDesc& pass : c.layout.passes) {
        if (pass.phase != phase) continue;
        GLuint query = 0;
        if (timings) {
            glGenQueries(1, &query);
            glBeginQuery(GL_TIME_ELAPSED, query);
        }
        diagnostic = run_pass(c, pass, draw);
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

} // namespace detail
} // namespace penumbra::gl
