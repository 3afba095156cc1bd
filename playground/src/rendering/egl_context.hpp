// playground/src/rendering/egl_context.hpp — an OpenGL 4.5 core context with no window and no display.
//
// Tests, benchmarks and image dumps render into framebuffer objects, so they need a context but
// no surface. EGL gives us one on Mesa's llvmpipe (CI machines without a GPU) and on NVIDIA's
// driver (GPU machines without an X server) through the same code.
#pragma once

#include <optional>
#include <string>

namespace penumbra::playground {

// Which context to make: desktop OpenGL core profile (default 4.5, what the GL runtime needs) or
// OpenGL ES. EGL may hand back a newer compatible version; on Mesa, MESA_GL_VERSION_OVERRIDE /
// MESA_GLES_VERSION_OVERRIDE cap it (the dialect tests set them).
struct ContextRequest {
    bool es = false; // true: eglBindAPI(EGL_OPENGL_ES_API); false: EGL_OPENGL_API, core profile
    int major = 4, minor = 5;
};

class HeadlessContext {
public:
    // Tries, in order, until one yields a current context of `request` (default 4.5 core):
    //   1. Mesa's surfaceless platform (EGL_MESA_platform_surfaceless) — llvmpipe or a Mesa GPU;
    //   2. each EGL device (EGL_EXT_device_enumeration + EGL_EXT_platform_device) — NVIDIA
    //      without a display;
    //   3. eglGetDisplay(EGL_DEFAULT_DISPLAY).
    // Setting the environment variable PENUMBRA_EGL_PLATFORM=device swaps 1 and 2: on a machine
    // with both Mesa and a GPU driver, the surfaceless platform would give llvmpipe.
    // On success the context is current on the calling thread. On failure returns nullopt and, if
    // `error` is given, stores one line that lists why each attempt failed.
    static std::optional<HeadlessContext> create(std::string* error = nullptr, ContextRequest request = {});

    ~HeadlessContext();
    HeadlessContext(HeadlessContext&& other) noexcept;
    HeadlessContext& operator=(HeadlessContext&& other) noexcept;
    HeadlessContext(const HeadlessContext&) = delete;
    HeadlessContext& operator=(const HeadlessContext&) = delete;

    // Makes the context current on the calling thread (a context is current on one thread at a
    // time; call this after handing the object to another thread).
    bool make_current() const;

    const std::string& renderer() const { return renderer_; } // GL_RENDERER, e.g. "llvmpipe (...)"
    const std::string& version() const { return version_; }   // GL_VERSION
    bool es() const { return es_; }                           // an OpenGL ES context
    const std::string& vendor() const { return vendor_; }     // GL_VENDOR
    const std::string& platform() const { return platform_; } // which of the three attempts worked
    int major_version() const { return major_; }
    int minor_version() const { return minor_; }

private:
    HeadlessContext() = default;
    void release() noexcept;

    // EGLDisplay and EGLContext are pointers; kept as void* so this header needs no EGL include.
    void* display_ = nullptr;
    void* context_ = nullptr;
    std::string renderer_, version_, vendor_, platform_;
    int major_ = 0, minor_ = 0;
    bool es_ = false;
};

} // namespace penumbra::playground
