// penumbra/gl/debug_capture.hpp — the GL errors of one runtime call as one diagnostic: the KHR_debug
// messages it raised while a DebugCapture lived, then whatever glGetError still holds.
//
// Header-only; includes <epoxy/gl.h>.
#pragma once

#include <epoxy/gl.h>

#include <cstdio>
#include <string>
#include <vector>

namespace penumbra::gl::detail {

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

} // namespace penumbra::gl::detail
