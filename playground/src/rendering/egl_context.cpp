// playground/src/rendering/egl_context.cpp
//
// Only libepoxy's headers: <EGL/egl.h> next to <epoxy/egl.h> redefines khronos_boolean_enum_t.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include "rendering/egl_context.hpp"

#include <cstdlib>
#include <map>
#include <mutex>
#include <vector>

namespace penumbra::playground {

namespace {

// eglInitialize/eglTerminate are not reference counted (without EGL_KHR_display_reference), and
// Mesa returns the same EGLDisplay for the same platform arguments. Two live contexts on one
// display must therefore not terminate it under each other: count users per display here.
std::mutex display_mutex;
std::map<EGLDisplay, int> display_users;

void acquire_display(EGLDisplay display) {
    std::lock_guard<std::mutex> lock(display_mutex);
    ++display_users[display];
}

void release_display(EGLDisplay display) {
    std::lock_guard<std::mutex> lock(display_mutex);
    if (--display_users[display] <= 0) {
        display_users.erase(display);
        eglTerminate(display);
    }
}

std::string egl_error_name(EGLint code) {
    switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: return "EGL error " + std::to_string(code);
    }
}

// Client extensions (queried on EGL_NO_DISPLAY) decide which platforms we may ask for.
bool has_client_extension(const char* name) {
    const char* list = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!list) return false; // EGL < 1.5 without EGL_EXT_client_extensions
    const std::string all = std::string(" ") + list + " ";
    return all.find(std::string(" ") + name + " ") != std::string::npos;
}

} // namespace

std::optional<HeadlessContext> HeadlessContext::create(std::string* error, ContextRequest request) {
    const std::string wanted = std::string(request.es ? "OpenGL ES " : "OpenGL ") + std::to_string(request.major) + "." +
                               std::to_string(request.minor) + (request.es ? "" : " core");
    std::vector<std::string> failures;
    auto fail = [&](const std::string& where, const std::string& why) { failures.push_back(where + ": " + why); };

    // Initialises `display` and makes a context of `request` current on it, or records why not.
    // Displays are obtained lazily, in order of preference, so that a working surfaceless
    // platform never touches the other platforms (eglGetDisplay may try to reach a window system).
    auto try_display = [&](EGLDisplay display, const std::string& where) -> std::optional<HeadlessContext> {
        EGLint egl_major = 0, egl_minor = 0;
        if (!eglInitialize(display, &egl_major, &egl_minor)) {
            fail(where, "eglInitialize: " + egl_error_name(eglGetError()));
            return std::nullopt;
        }
        acquire_display(display);
        auto give_up = [&](const std::string& why) {
            fail(where, why);
            release_display(display);
        };
        if (!epoxy_has_egl_extension(display, "EGL_KHR_surfaceless_context")) {
            give_up("EGL_KHR_surfaceless_context not supported");
            return std::nullopt;
        }
        if (!eglBindAPI(request.es ? EGL_OPENGL_ES_API : EGL_OPENGL_API)) {
            give_up(std::string("eglBindAPI(") + (request.es ? "EGL_OPENGL_ES_API" : "EGL_OPENGL_API") +
                    "): " + egl_error_name(eglGetError()));
            return std::nullopt;
        }
        const EGLint renderable = request.es ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT;
        // We never create a surface, so any config that can render desktop GL will do; prefer
        // one that at least supports pbuffers (drivers list those for off-screen use), then any,
        // then no config at all where EGL_KHR_no_config_context allows it.
        EGLConfig config = nullptr;
        EGLint config_count = 0;
        const EGLint pbuffer_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, renderable, EGL_NONE};
        const EGLint any_attribs[] = {EGL_SURFACE_TYPE, 0, EGL_RENDERABLE_TYPE, renderable, EGL_NONE};
        if (!eglChooseConfig(display, pbuffer_attribs, &config, 1, &config_count) || config_count < 1) {
            config_count = 0;
            if (!eglChooseConfig(display, any_attribs, &config, 1, &config_count) || config_count < 1) {
                if (epoxy_has_egl_extension(display, "EGL_KHR_no_config_context")) {
                    config = EGL_NO_CONFIG_KHR;
                } else {
                    give_up("no EGLConfig renders " + wanted);
                    return std::nullopt;
                }
            }
        }
        const EGLint desktop_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, request.major,
                                          EGL_CONTEXT_MINOR_VERSION, request.minor,
                                          EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                          EGL_NONE};
        const EGLint es_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, request.major, EGL_CONTEXT_MINOR_VERSION, request.minor,
                                     EGL_NONE};
        EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, request.es ? es_attribs : desktop_attribs);
        if (context == EGL_NO_CONTEXT) {
            give_up("eglCreateContext(" + wanted + "): " + egl_error_name(eglGetError()));
            return std::nullopt;
        }
        if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            const std::string why = "eglMakeCurrent without surface: " + egl_error_name(eglGetError());
            eglDestroyContext(display, context);
            give_up(why);
            return std::nullopt;
        }

        HeadlessContext result;
        result.display_ = display;
        result.context_ = context;
        result.platform_ = where;
        result.es_ = request.es;
        auto gl_string = [](GLenum name) {
            const auto* s = reinterpret_cast<const char*>(glGetString(name));
            return std::string(s ? s : "");
        };
        result.renderer_ = gl_string(GL_RENDERER);
        result.version_ = gl_string(GL_VERSION);
        result.vendor_ = gl_string(GL_VENDOR);
        glGetIntegerv(GL_MAJOR_VERSION, &result.major_);
        glGetIntegerv(GL_MINOR_VERSION, &result.minor_);
        if (result.major_ * 10 + result.minor_ < request.major * 10 + request.minor) {
            // `result` releases the context and the display when it goes out of scope.
            fail(where, "got " + result.version_ + ", need " + wanted);
            return std::nullopt;
        }
        return std::optional<HeadlessContext>(std::move(result));
    };

    const bool platform_base = has_client_extension("EGL_EXT_platform_base");
    auto try_surfaceless = [&]() -> std::optional<HeadlessContext> {
        if (!platform_base || !has_client_extension("EGL_MESA_platform_surfaceless")) {
            fail("surfaceless", "EGL_MESA_platform_surfaceless not available");
            return std::nullopt;
        }
        EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
        if (d != EGL_NO_DISPLAY) return try_display(d, "surfaceless (Mesa)");
        fail("surfaceless", egl_error_name(eglGetError()));
        return std::nullopt;
    };
    auto try_devices = [&]() -> std::optional<HeadlessContext> {
        if (!platform_base || !has_client_extension("EGL_EXT_device_enumeration") ||
            !has_client_extension("EGL_EXT_platform_device")) {
            fail("device", "EGL_EXT_device_enumeration/EGL_EXT_platform_device not available");
            return std::nullopt;
        }
        EGLint count = 0;
        EGLDeviceEXT devices[16];
        if (!eglQueryDevicesEXT(16, devices, &count) || count < 1) {
            fail("device", "no EGL devices");
            return std::nullopt;
        }
        for (EGLint i = 0; i < count; ++i) {
            const std::string where = "device " + std::to_string(i);
            EGLDisplay d = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
            if (d == EGL_NO_DISPLAY)
                fail(where, egl_error_name(eglGetError()));
            else if (auto context = try_display(d, where))
                return context;
        }
        return std::nullopt;
    };
    auto try_default = [&]() -> std::optional<HeadlessContext> {
        EGLDisplay d = eglGetDisplay(EGL_DEFAULT_DISPLAY);
        if (d != EGL_NO_DISPLAY) return try_display(d, "default display");
        fail("default display", "eglGetDisplay returned EGL_NO_DISPLAY");
        return std::nullopt;
    };

    // Where Mesa is installed next to a GPU driver, the surfaceless platform yields llvmpipe;
    // PENUMBRA_EGL_PLATFORM=device puts the device platform (the GPU) first.
    const char* preference = std::getenv("PENUMBRA_EGL_PLATFORM");
    const bool device_first = preference && std::string(preference) == "device";
    if (device_first) {
        if (auto c = try_devices()) return c;
        if (auto c = try_surfaceless()) return c;
    } else {
        if (auto c = try_surfaceless()) return c;
        if (auto c = try_devices()) return c;
    }
    if (auto c = try_default()) return c;

    if (error) {
        std::string message = "no headless " + wanted + " context:";
        for (std::size_t i = 0; i < failures.size(); ++i) message += (i ? "; " : " ") + failures[i];
        *error = message;
    }
    return std::nullopt;
}

void HeadlessContext::release() noexcept {
    if (!display_) return;
    auto display = static_cast<EGLDisplay>(display_);
    if (eglGetCurrentContext() == static_cast<EGLContext>(context_))
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (context_) eglDestroyContext(display, static_cast<EGLContext>(context_));
    release_display(display);
    display_ = nullptr;
    context_ = nullptr;
}

HeadlessContext::~HeadlessContext() { release(); }

HeadlessContext::HeadlessContext(HeadlessContext&& other) noexcept
    : display_(other.display_), context_(other.context_), renderer_(std::move(other.renderer_)),
      version_(std::move(other.version_)), vendor_(std::move(other.vendor_)), platform_(std::move(other.platform_)),
      major_(other.major_), minor_(other.minor_), es_(other.es_) {
    other.display_ = nullptr;
    other.context_ = nullptr;
}

HeadlessContext& HeadlessContext::operator=(HeadlessContext&& other) noexcept {
    if (this != &other) {
        release();
        display_ = other.display_;
        context_ = other.context_;
        renderer_ = std::move(other.renderer_);
        version_ = std::move(other.version_);
        vendor_ = std::move(other.vendor_);
        platform_ = std::move(other.platform_);
        major_ = other.major_;
        minor_ = other.minor_;
        es_ = other.es_;
        other.display_ = nullptr;
        other.context_ = nullptr;
    }
    return *this;
}

bool HeadlessContext::make_current() const {
    return display_ && eglMakeCurrent(static_cast<EGLDisplay>(display_), EGL_NO_SURFACE, EGL_NO_SURFACE,
                                      static_cast<EGLContext>(context_)) == EGL_TRUE;
}

} // namespace penumbra::playground
