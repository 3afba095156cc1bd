// penumbra/gl/resources.hpp — the GL objects a layout's textures and passes need: textures allocated
// from their layout description (format, levels, default sampling, initial zeros), and the framebuffer the
// passes render through.
//
// Header-only; includes <epoxy/gl.h>.
#pragma once

#include "../layout.hpp"
#include "layout_enums.hpp"

#include <epoxy/gl.h>

#include <string>

namespace penumbra::gl::detail {

// Same GL storage and sampling: a texture with this description can be kept as it is.
inline bool same_storage(const TextureDesc& a, const TextureDesc& b) {
    return a.target == b.target && a.format == b.format && a.width == b.width && a.height == b.height &&
           a.depth == b.depth && a.mip_levels == b.mip_levels && a.min_filter == b.min_filter &&
           a.mag_filter == b.mag_filter && a.wrap == b.wrap && a.border_color == b.border_color && a.size == b.size &&
           a.source == b.source;
}

// A texture of description `t` at width × height (a fixed size or the output size), its levels
// cleared to zero (initial zero; the others are the caller's or a bake's and are overwritten).
// Comparison is the binding's sampler's, not the texture's. 0 with *log set on failure.
inline GLuint allocate_texture(const TextureDesc& t, int width, int height, std::string* log) {
    const GLenum target = detail::gl_enum(t.target), format = detail::gl_enum(t.format);
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
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    const GLuint zero_u[4] = {0, 0, 0, 0};
    for (int level = 0; level < t.mip_levels; ++level) {
        if (is_depth(t.format)) glClearTexImage(id, level, GL_DEPTH_COMPONENT, GL_FLOAT, zero);
        else if (is_integer(t.format)) glClearTexImage(id, level, GL_RGBA_INTEGER, GL_UNSIGNED_INT, zero_u);
        else glClearTexImage(id, level, GL_RGBA, GL_FLOAT, zero);
    }
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        *log = "GL error " + std::to_string(e);
        glDeleteTextures(1, &id);
        return 0;
    }
    return id;
}

// Detaches every attachment a pass may have used from `framebuffer`.
inline void detach_all(GLuint framebuffer) {
    for (int i = 0; i < 8; ++i) glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0 + i, 0, 0);
    glNamedFramebufferTexture(framebuffer, GL_DEPTH_ATTACHMENT, 0, 0);
}

} // namespace penumbra::gl::detail
