// penumbra/gl/runtime.hpp end to end on llvmpipe (or a GPU): the planes scene, default config,
// compared with Embree ground truth; GL errors through KHR_debug and glGetError. Label "gl".
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>
#include <string>

using namespace penumbra::playground;

TEST_CASE("gl runtime: every program of the default configuration compiles and links") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto runtime = penumbra::gl::Runtime::create(penumbra::Config{}, &error);
    CHECK_MESSAGE(runtime, error);
}

TEST_CASE("gl runtime: invalid configuration gives a diagnostic, not a crash") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto runtime = penumbra::gl::Runtime::create(penumbra::Config{.slices = 0}, &error);
    CHECK(!runtime);
    CHECK(!error.empty());
}

TEST_CASE("gl runtime: planes, default config, 128x128, against Embree 16x16") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const std::optional<Scene> scene = make_scene("planes");
    REQUIRE(scene);
    HeadlessResult result;
    REQUIRE_MESSAGE(render_headless(*scene, penumbra::Config{}, 128, 128, result, &error), error);
    int shadowed = 0, lit = 0, geometry = 0;
    for (std::size_t i = 0; i < result.visibility.size(); ++i) {
        if (!result.geometry[i]) continue;
        ++geometry;
        shadowed += result.visibility[i] < 0.5f;
        lit += result.visibility[i] > 0.95f;
    }
    const std::vector<float> truth = reference_visibility(*scene, result, 16);
    const Metrics m = compare(result, truth);
    std::printf("planes 128x128 default config (%s): geometry %d, shadowed %d, lit %d\n"
                "  all:      MAE %.4f RMSE %.4f p95 %.4f (%zu px)\n  penumbra: MAE %.4f RMSE %.4f p95 %.4f "
                "(%zu px)\n",
                context->renderer().c_str(), geometry, shadowed, lit, m.all.mae, m.all.rmse, m.all.p95,
                m.all.count, m.penumbra.mae, m.penumbra.rmse, m.penumbra.p95, m.penumbra.count);
    CHECK(shadowed > 0);
    CHECK(lit > 0);
    CHECK(m.all.mae < 0.05);
}

// --- GL errors: KHR_debug messages in debug builds or on request, glGetError otherwise ----------

namespace {

const penumbra::Config kTiny{.slices = 4, .resolution = 64};

// Stands in for an engine's own debug callback.
struct MessageCount {
    int messages = 0;
};
void GLAPIENTRY count_message(GLenum, GLenum, GLuint, GLenum, GLsizei, const GLchar*, const void* user) {
    ++static_cast<MessageCount*>(const_cast<void*>(user))->messages;
}

} // namespace

TEST_CASE("gl runtime: a GL error provoked during build is caught by the KHR_debug path") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto runtime = penumbra::gl::Runtime::create(kTiny, &error, {.debug_output = true});
    REQUIRE_MESSAGE(runtime, error);
    REQUIRE(runtime->debug_output()); // Mesa and NVIDIA both have KHR_debug (core in 4.3)
    GLint flags = 0;
    glGetIntegerv(GL_CONTEXT_FLAGS, &flags);
    // HeadlessContext asks for no debug context; Mesa reports API errors once GL_DEBUG_OUTPUT is on anyway.
    MESSAGE("debug context: " << std::string((flags & GL_CONTEXT_FLAG_DEBUG_BIT) ? "yes" : "no") << " ("
                              << context->renderer() << ")");

    const std::string diagnostic =
        runtime->build([](GLuint) { glBindTexture(0x1234, 0); }); // not a texture target
    MESSAGE(diagnostic);
    CHECK(diagnostic.find("GL_INVALID_ENUM") != std::string::npos);
    // the driver's own words come through (Mesa: "glBindTexture(target)"; NVIDIA: "Invalid target."),
    // not only the error code that glGetError gives
    CHECK(diagnostic.size() > std::string("GL error in build: GL_INVALID_ENUM").size());
    CHECK(runtime->build([](GLuint) {}) == "");                   // the error was consumed, not carried over

    // Between calls no callback is installed: nothing can point at the runtime once it is gone.
    void* callback = &error;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &callback);
    CHECK(callback == nullptr);
    CHECK(!glIsEnabled(GL_DEBUG_OUTPUT));

    // shade_deferred reports the same way: texture names that do not exist (positions and normals).
    std::string shade_error;
    CHECK(runtime->shade_deferred(987654, 16, 16, &shade_error, nullptr, 987655) == 0);
    MESSAGE(shade_error);
    CHECK(shade_error.find("GL error in shade_deferred") != std::string::npos);
    CHECK(shade_error.find("GL_INVALID_OPERATION") != std::string::npos);
}

TEST_CASE("gl runtime: without debug output a GL error is still caught, through glGetError") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto runtime = penumbra::gl::Runtime::create(kTiny, &error, {.debug_output = false});
    REQUIRE_MESSAGE(runtime, error);
    CHECK(!runtime->debug_output());
    const std::string diagnostic = runtime->build([](GLuint) { glBindTexture(0x1234, 0); });
    CHECK(diagnostic == "GL error in build: GL_INVALID_ENUM");
    CHECK(runtime->build([](GLuint) {}) == "");
}

TEST_CASE(
    "gl runtime: an engine's debug callback is forwarded to and restored, also after the runtime dies") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    MessageCount engine;
    glDebugMessageCallback(count_message, &engine);
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    {
        auto runtime = penumbra::gl::Runtime::create(kTiny, &error, {.debug_output = true});
        REQUIRE_MESSAGE(runtime, error);
        CHECK(!runtime->build([](GLuint) { glBindTexture(0x1234, 0); }).empty());
        CHECK(engine.messages >= 1); // forwarded while the runtime's callback was installed
    }
    void* callback = nullptr;
    void* user = nullptr;
    glGetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &callback);
    glGetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &user);
    CHECK(callback == reinterpret_cast<void*>(&count_message));
    CHECK(user == &engine);
    CHECK(glIsEnabled(GL_DEBUG_OUTPUT));
    CHECK(glGetError() == GL_NO_ERROR); // the runtime left no error flag set in the engine's context
    const int before = engine.messages;
    // Texture 0 always exists, so the target is the only thing wrong. With name 1 (once a texture of
    // another target) an NVIDIA H200 answered GL_INVALID_OPERATION here: the spec names no order.
    glBindTexture(0x1234, 0);
    CHECK(engine.messages == before + 1);
    CHECK(glGetError() == GL_INVALID_ENUM);
    glDebugMessageCallback(nullptr, nullptr);
    glDisable(GL_DEBUG_OUTPUT);
}
