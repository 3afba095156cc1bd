// What the current renderer's texture units round, measured with two draws: the weight between two
// texels of a bilinear fetch, and the weight between two mip levels of a trilinear one. GL leaves
// both to the implementation (Vulkan states them as subTexelPrecisionBits and mipmapPrecisionBits,
// at least 4 bits each), and drivers may also skip the blend near whole levels ("brilinear"). The
// oracle's bound takes what is measured here, never less than its 8-bit default (llvmpipe: 2^-8 for
// both on a 64² chain, 4.9e-3 for the level weight on a 4² one; an NVIDIA H200: 2.0e-3 and 2.9e-3).
// Needs a current GL 4.5 context.
#pragma once

#include "reference/oracle.hpp"

#include <penumbra/gl/link_program.hpp>
#include <penumbra/program.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace penumbra::playground {

struct MeasuredTexturePrecision {
    // the largest |fetched − exact| over the probed fractions (the exact blend of a 0 and a 1)
    double sub_texel = 0.0;
    double level_fraction = 0.0;
    // the upper level's weight at a few fractions t of each pair of levels, "t → weight", for messages and notes
    std::string level_curve;
    std::string error; // non-empty when the probe could not run (then the values above are 0)

    // What the oracle's bound should assume: the measured error, at least the 8-bit default.
    TexturePrecision for_oracle() const {
        const TexturePrecision defaults;
        return {.sub_texel = std::max(defaults.sub_texel, sub_texel),
                .level_fraction = std::max(defaults.level_fraction, level_fraction)};
    }
};

namespace texture_precision_detail {

// One fetch per pixel of a probes × 1 R32F target. Sub-texel: a bilinear fetch between a 0 texel and a
// 1 texel at fraction f = (i mod per_range) / per_range. Levels: a trilinear fetch at level
// λ = i / per_range of a 64² mip chain cut at level 3, as the runtime cuts its chains at the fitted
// level bound, whose levels hold 0, 1, 0, 1: between levels l and l + 1 it reads the weight of the
// level of ones, the fraction going up from an even level, one minus it from an odd one; the last
// range ends at the last level.
constexpr int probes = 2048;
constexpr int per_range = 512;
constexpr int level_ranges = 3;

inline const char* vertex_source() {
    return "#version 450 core\n"
           "void main() {\n"
           "    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
           "    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);\n"
           "}\n";
}

inline std::string fragment_source(bool levels) {
    const std::string n = std::to_string(per_range) + ".0";
    std::string body = levels
        ? "    // levels 0, 1, 2, 3 hold 0, 1, 0, 1: the fetch is the weight of the levels of ones\n"
          "    fraction = textureLod(probe, vec3(0.5, 0.5, 0.0), float(i) / " + n + ").r;\n"
        : "    // texels 0 and 1 of a 2 x 1 level hold 0 and 1: at x = (0.5 + f) / 2 the fetch is f\n"
          "    float f = float(i % " + std::to_string(per_range) + ") / " + n + ";\n"
          "    fraction = textureLod(probe, vec3((0.5 + f) / 2.0, 0.5, 0.0), 0.0).r;\n";
    return "#version 450 core\n"
           "layout(binding = 0) uniform sampler2DArray probe;\n"
           "layout(location = 0) out float fraction;\n"
           "void main() {\n"
           "    int i = int(gl_FragCoord.x);\n" +
           body + "}\n";
}

// An RGBA8 array texture of one layer, as the runtime's mip chains are, clamped at its edges.
inline GLuint probe_texture(int width, int height, int levels, GLint min_filter) {
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &texture);
    glTextureStorage3D(texture, levels, GL_RGBA8, width, height, 1);
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, min_filter);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_MAX_LEVEL, levels - 1);
    return texture;
}

// A side × side mip chain with one value per level, filtered trilinearly.
inline GLuint level_chain_texture(int side, const std::vector<unsigned char>& levels) {
    const int count = static_cast<int>(levels.size());
    const GLuint texture = probe_texture(side, side, count, GL_LINEAR_MIPMAP_LINEAR);
    for (int l = 0; l < count; ++l) {
        const int s = std::max(side >> l, 1);
        const std::vector<unsigned char> rgba(std::size_t(4) * s * s, levels[l]);
        glTextureSubImage3D(texture, l, 0, 0, 0, s, s, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    }
    return texture;
}

// One level: a row of texels, filtered bilinearly.
inline GLuint texel_row_texture(const std::vector<unsigned char>& row) {
    const int width = static_cast<int>(row.size());
    const GLuint texture = probe_texture(width, 1, 1, GL_LINEAR);
    std::vector<unsigned char> rgba;
    for (unsigned char v : row) rgba.insert(rgba.end(), {v, v, v, v});
    glTextureSubImage3D(texture, 0, 0, 0, 0, width, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    return texture;
}

// The probes' fetched fractions, or empty with *error set.
inline std::vector<float> fetch_fractions(bool levels, std::string* error) {
    const Program program{.name = levels ? "probe_levels" : "probe_sub_texel",
                          .stages = {{"probe.vert", Stage::vertex, vertex_source()},
                                     {"probe.frag", Stage::fragment, fragment_source(levels)}}};
    std::string log;
    const GLuint id = gl::link_program(program, &log);
    if (!id) {
        *error = "texture precision probe: " + log;
        return {};
    }
    const GLuint texture = levels ? level_chain_texture(64, {0, 255, 0, 255}) : texel_row_texture({0, 255});
    GLuint target = 0, framebuffer = 0, vertex_array = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &target);
    glTextureStorage2D(target, 1, GL_R32F, probes, 1);
    glCreateFramebuffers(1, &framebuffer);
    glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, target, 0);
    glCreateVertexArrays(1, &vertex_array);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, probes, 1);
    glUseProgram(id);
    glBindTextureUnit(0, texture);
    glBindVertexArray(vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> fetched(probes);
    glGetTextureImage(target, 0, GL_RED, GL_FLOAT, static_cast<GLsizei>(fetched.size() * sizeof(float)), fetched.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glBindVertexArray(0);
    glUseProgram(0);
    glDeleteVertexArrays(1, &vertex_array);
    glDeleteFramebuffers(1, &framebuffer);
    glDeleteTextures(1, &target);
    glDeleteTextures(1, &texture);
    glDeleteProgram(id);
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        *error = "texture precision probe: GL error " + std::to_string(e);
        return {};
    }
    return fetched;
}

} // namespace texture_precision_detail

inline MeasuredTexturePrecision measure_texture_precision() {
    using namespace texture_precision_detail;
    MeasuredTexturePrecision out;
    const std::vector<float> sub_texel = fetch_fractions(false, &out.error);
    if (!out.error.empty()) return out;
    const std::vector<float> levels = fetch_fractions(true, &out.error);
    if (!out.error.empty()) return out;
    for (int i = 0; i < probes; ++i) {
        const double f = double(i % per_range) / per_range;
        out.sub_texel = std::max(out.sub_texel, std::abs(sub_texel[i] - f));
        const int range = i / per_range;
        if (range >= level_ranges) continue;
        const double weight = range % 2 == 0 ? f : 1.0 - f;
        out.level_fraction = std::max(out.level_fraction, std::abs(levels[i] - weight));
    }
    // the weight of level l + 1 at a few fractions t, in each range l → l + 1
    for (int range = 0; range < level_ranges; ++range) {
        out.level_curve += (range ? "; levels " : "levels ") + std::to_string(range) + "-" + std::to_string(range + 1) + ":";
        for (double t : {1.0 / 64, 0.05, 0.1, 0.5, 0.9, 0.95}) {
            const float fetched = levels[static_cast<std::size_t>(range * per_range + std::lround(t * per_range))];
            char entry[40];
            std::snprintf(entry, sizeof entry, " %.3f → %.4f", t, range % 2 == 0 ? fetched : 1.0f - fetched);
            out.level_curve += entry;
        }
    }
    return out;
}

} // namespace penumbra::playground
