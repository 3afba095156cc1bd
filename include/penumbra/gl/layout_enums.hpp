// penumbra/gl/layout_enums.hpp — the GL enum of each layout enum (penumbra/layout_types.hpp) and
// texture format (penumbra/formats.hpp): texture targets, formats, filters, wraps, render state,
// image access and memory barriers. Shared by the OpenGL 4.5 runtime and the portable GL 3.3 /
// ES 3.0 runner (targets/gles).
//
// Header-only; includes <epoxy/gl.h>.
#pragma once

#include "../layout_types.hpp"

#include <epoxy/gl.h>

namespace penumbra::gl::detail {

inline GLenum gl_enum(TextureTarget t) {
    switch (t) {
    case TextureTarget::texture_2d: return GL_TEXTURE_2D;
    case TextureTarget::texture_2d_array: return GL_TEXTURE_2D_ARRAY;
    case TextureTarget::texture_3d: return GL_TEXTURE_3D;
    }
    return 0;
}

// The sized internal format, and the pixel format and type of glTexImage / glClearTexImage data.
struct GlFormat {
    GLenum internal, format, type;
};
inline GlFormat gl_format(TextureFormat f) {
    switch (f) {
    case TextureFormat::rgba8: return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case TextureFormat::rgba16f: return {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT};
    case TextureFormat::rgba32f: return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case TextureFormat::r8: return {GL_R8, GL_RED, GL_UNSIGNED_BYTE};
    case TextureFormat::r16f: return {GL_R16F, GL_RED, GL_HALF_FLOAT};
    case TextureFormat::r32f: return {GL_R32F, GL_RED, GL_FLOAT};
    case TextureFormat::rg16f: return {GL_RG16F, GL_RG, GL_HALF_FLOAT};
    case TextureFormat::rg32f: return {GL_RG32F, GL_RG, GL_FLOAT};
    case TextureFormat::rgba32ui: return {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT};
    case TextureFormat::r32ui: return {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT};
    case TextureFormat::depth24: return {GL_DEPTH_COMPONENT24, GL_DEPTH_COMPONENT, GL_UNSIGNED_INT};
    case TextureFormat::depth32f: return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
    }
    return {0, 0, 0};
}
inline GLenum gl_enum(TextureFormat f) { return gl_format(f).internal; }

// The pixel format of `channels` components (1, 2 or 4) of floats or of unsigned integers.
inline GLenum pixel_format(int channels, bool integer) {
    if (integer) return channels == 4 ? GL_RGBA_INTEGER : channels == 2 ? GL_RG_INTEGER : GL_RED_INTEGER;
    return channels == 4 ? GL_RGBA : channels == 2 ? GL_RG : GL_RED;
}

inline GLenum gl_enum(TextureFilter f) {
    switch (f) {
    case TextureFilter::nearest: return GL_NEAREST;
    case TextureFilter::linear: return GL_LINEAR;
    case TextureFilter::linear_mipmap_linear: return GL_LINEAR_MIPMAP_LINEAR;
    case TextureFilter::nearest_mipmap_nearest: return GL_NEAREST_MIPMAP_NEAREST;
    case TextureFilter::linear_mipmap_nearest: return GL_LINEAR_MIPMAP_NEAREST;
    case TextureFilter::nearest_mipmap_linear: return GL_NEAREST_MIPMAP_LINEAR;
    }
    return 0;
}

inline GLenum gl_enum(Wrap w) { return w == Wrap::clamp_to_border ? GL_CLAMP_TO_BORDER : GL_CLAMP_TO_EDGE; }

inline GLenum gl_enum(CompareFunc f) {
    switch (f) {
    case CompareFunc::never: return GL_NEVER;
    case CompareFunc::less: return GL_LESS;
    case CompareFunc::equal: return GL_EQUAL;
    case CompareFunc::lequal: return GL_LEQUAL;
    case CompareFunc::greater: return GL_GREATER;
    case CompareFunc::notequal: return GL_NOTEQUAL;
    case CompareFunc::gequal: return GL_GEQUAL;
    case CompareFunc::always: return GL_ALWAYS;
    }
    return 0;
}

inline GLenum gl_enum(BlendEquation e) {
    switch (e) {
    case BlendEquation::add: return GL_FUNC_ADD;
    case BlendEquation::max: return GL_MAX;
    case BlendEquation::min: return GL_MIN;
    }
    return 0;
}

inline GLenum gl_enum(BlendFactor f) {
    switch (f) {
    case BlendFactor::zero: return GL_ZERO;
    case BlendFactor::one: return GL_ONE;
    case BlendFactor::src_alpha: return GL_SRC_ALPHA;
    case BlendFactor::one_minus_src_alpha: return GL_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::dst_color: return GL_DST_COLOR;
    }
    return 0;
}

// The face culled; 0 for Cull::none (culling off).
inline GLenum gl_enum(Cull c) { return c == Cull::back ? GL_BACK : c == Cull::front ? GL_FRONT : 0; }

// The logic operation; 0 for LogicOp::none (off).
inline GLenum gl_enum(LogicOp op) { return op == LogicOp::bitwise_or ? GL_OR : 0; }

inline GLenum gl_enum(ImageAccess a) {
    switch (a) {
    case ImageAccess::write_only: return GL_WRITE_ONLY;
    case ImageAccess::read_only: return GL_READ_ONLY;
    case ImageAccess::read_write: return GL_READ_WRITE;
    }
    return 0;
}

inline GLbitfield gl_enum(MemoryBarrierBit b) {
    switch (b) {
    case MemoryBarrierBit::texture_fetch: return GL_TEXTURE_FETCH_BARRIER_BIT;
    case MemoryBarrierBit::texture_update: return GL_TEXTURE_UPDATE_BARRIER_BIT;
    case MemoryBarrierBit::shader_image_access: return GL_SHADER_IMAGE_ACCESS_BARRIER_BIT;
    case MemoryBarrierBit::framebuffer: return GL_FRAMEBUFFER_BARRIER_BIT;
    }
    return 0;
}

} // namespace penumbra::gl::detail
