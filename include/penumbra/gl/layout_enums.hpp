// penumbra/gl/layout_enums.hpp — the GL enum of each word layout.json uses for texture targets,
// formats, filters, wraps, render state, image access and memory barriers.
//
// Header-only; includes <epoxy/gl.h>.
#pragma once

#include <epoxy/gl.h>

#include <map>
#include <string>

namespace penumbra::gl::detail {

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

// The access of a "dispatch" pass's image output (image_outputs[].access); 0 when unknown.
inline GLenum image_access(const std::string& name) {
    static const std::map<std::string, GLenum> names{
        {"WRITE_ONLY", GL_WRITE_ONLY}, {"READ_ONLY", GL_READ_ONLY}, {"READ_WRITE", GL_READ_WRITE}};
    auto it = names.find(name);
    return it == names.end() ? 0 : it->second;
}

// A memory barrier bit of a "dispatch" pass (dispatch.memory_barrier[]); 0 when unknown.
inline GLbitfield memory_barrier_bit(const std::string& name) {
    static const std::map<std::string, GLbitfield> names{
        {"TEXTURE_FETCH", GL_TEXTURE_FETCH_BARRIER_BIT}, {"TEXTURE_UPDATE", GL_TEXTURE_UPDATE_BARRIER_BIT},
        {"SHADER_IMAGE_ACCESS", GL_SHADER_IMAGE_ACCESS_BARRIER_BIT}, {"FRAMEBUFFER", GL_FRAMEBUFFER_BARRIER_BIT}};
    auto it = names.find(name);
    return it == names.end() ? 0 : it->second;
}

} // namespace penumbra::gl::detail
