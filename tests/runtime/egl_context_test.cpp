// tests/runtime/egl_context_test.cpp — headless OpenGL 4.5 core through EGL (llvmpipe on CI).
#include <doctest/doctest.h>

#include <epoxy/gl.h>

#include "rendering/egl_context.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

using namespace penumbra::playground;

namespace {

// Clears a size×size framebuffer with `internal_format` to `colour` and reads it back as floats.
std::vector<float> clear_and_read(GLenum internal_format, std::array<float, 4> colour, int size) {
    GLuint texture = 0, framebuffer = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, internal_format, size, size);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, texture, 0);
    CHECK(glCheckNamedFramebufferStatus(framebuffer, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, size, size);
    glClearColor(colour[0], colour[1], colour[2], colour[3]);
    glClear(GL_COLOR_BUFFER_BIT);
    std::vector<float> pixels(static_cast<std::size_t>(size) * size * 4, -1.0f);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, size, size, GL_RGBA, GL_FLOAT, pixels.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &texture);
    CHECK(glGetError() == GL_NO_ERROR);
    return pixels;
}

} // namespace

TEST_CASE("EGL: a headless OpenGL 4.5 core context comes up and renders into an FBO") {
    std::string error;
    std::optional<HeadlessContext> context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context.has_value(), error);
    MESSAGE("EGL platform: " << context->platform() << "; GL_RENDERER: " << context->renderer()
                             << "; GL_VERSION: " << context->version());
    CHECK(context->major_version() * 10 + context->minor_version() >= 45);
    CHECK_FALSE(context->renderer().empty());
    CHECK(context->version().find("4.") != std::string::npos);
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    CHECK((profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0);

    SUBCASE("8-bit colour") {
        const std::vector<float> px = clear_and_read(GL_RGBA8, {0.25f, 0.5f, 0.75f, 1.0f}, 64);
        std::size_t wrong = 0;
        for (std::size_t i = 0; i < px.size(); i += 4) {
            // Unorm8 storage: within one step of the cleared value (0.5 lies halfway between
            // 127/255 and 128/255; GL lets the implementation round either way).
            wrong += std::abs(px[i] - 0.25f) > 1.0f / 255 || std::abs(px[i + 1] - 0.5f) > 1.0f / 255 ||
                     std::abs(px[i + 2] - 0.75f) > 1.0f / 255 || px[i + 3] != 1.0f;
        }
        CHECK(wrong == 0);
    }
    SUBCASE("32-bit float colour (occlusion and visibility targets)") {
        const std::vector<float> px = clear_and_read(GL_RGBA32F, {0.125f, -2.5f, 1e-3f, 7.0f}, 32);
        std::size_t wrong = 0;
        for (std::size_t i = 0; i < px.size(); i += 4)
            wrong += px[i] != 0.125f || px[i + 1] != -2.5f || px[i + 2] != 1e-3f || px[i + 3] != 7.0f;
        CHECK(wrong == 0);
    }
}

TEST_CASE("EGL: two contexts coexist; destroying one leaves the other usable") {
    std::string error;
    std::optional<HeadlessContext> first = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(first.has_value(), error);
    {
        std::optional<HeadlessContext> second = HeadlessContext::create(&error);
        REQUIRE_MESSAGE(second.has_value(), error);
        // Moving keeps ownership in one place (the moved-from object releases nothing).
        HeadlessContext moved = std::move(*second);
        second.reset();
        CHECK(moved.make_current());
        CHECK(clear_and_read(GL_RGBA32F, {1, 2, 3, 4}, 8)[1] == 2.0f);
    }
    REQUIRE(first->make_current());
    CHECK(clear_and_read(GL_RGBA32F, {5, 6, 7, 8}, 8)[3] == 8.0f);
}
