// playground/src/rendering/debug_views.cpp
#include "rendering/debug_views.hpp"

#include "rendering/gpu_scene.hpp"
#include "app/image_io.hpp"
#include "app/palette.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

namespace penumbra::playground {

namespace {

// Shared by every fragment shader: the pixel's position in the viewport, 0 to 1.
constexpr const char* fragment_prelude = R"(#version 450 core
uniform vec4 u_viewport; // x, y, width, height of the viewport being filled
out vec4 color;
vec2 view_uv() { return (gl_FragCoord.xy - u_viewport.xy) / u_viewport.zw; }
// The texel of a size.x × size.y image under this pixel when the image fills the viewport.
ivec2 texel_under_pixel(ivec2 size) { return clamp(ivec2(floor(view_uv() * vec2(size))), ivec2(0), size - 1); }
const vec3 NOT_COMPUTED = vec3(0.0, 1.0, 0.0);
)";

constexpr const char* scalar_fragment = R"(
layout(binding = 0) uniform sampler2D u_values;
uniform vec2 u_range; // value shown black, value shown white
void main() {
    float v = texelFetch(u_values, texel_under_pixel(textureSize(u_values, 0)), 0).r;
    if (isnan(v)) {
        color = vec4(NOT_COMPUTED, 1.0);
        return;
    }
    color = vec4(vec3(clamp((v - u_range.x) / (u_range.y - u_range.x), 0.0, 1.0)), 1.0);
}
)";

// One slice's image inside whatever storage the layout chose: the C++ side turns (packing,
// filter, slice, level) into where the R×R image lives; the shader only fetches.
constexpr const char* slice_texture_fragment = R"(
layout(binding = 0) uniform sampler2D u_texture2D;
layout(binding = 1) uniform sampler2DArray u_textureArray;
layout(binding = 2) uniform sampler3D u_texture3D;
uniform int u_storage;  // 0: 2D (atlas), 1: 2D array, 2: 3D (volume)
uniform int u_lod;      // mip level to fetch from (mipmap filter), else 0
uniform int u_tileX;    // first texel column of the slice's tile in an atlas, else 0
uniform int u_layer;    // array layer or depth of the 3D texture
uniform int u_size;     // side of the slice's image in texels at u_lod (R, or R >> level)
uniform int u_shift;    // N-buffers: a window centred at texel j is stored at j − shift
uniform int u_satSide;  // > 0: summed-area table, mean over a window of this side; 0: direct fetch
uniform vec4 u_channel; // one-hot: the slice's channel

vec4 fetch(ivec2 t) {
    if (u_storage == 0) return texelFetch(u_texture2D, ivec2(u_tileX + t.x, t.y), u_lod);
    if (u_storage == 1) return texelFetch(u_textureArray, ivec3(t, u_layer), u_lod);
    return texelFetch(u_texture3D, ivec3(t, u_layer), u_lod);
}

float direct(ivec2 j) {
    ivec2 t = j - ivec2(u_shift);
    if (any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, ivec2(u_size)))) return 0.0; // border: empty
    return dot(fetch(t), u_channel);
}

// Exclusive table: the sum over texels x < X, y < Y is stored at texel (X, Y), X and Y in [0, R].
float prefix(ivec2 corner) { return dot(fetch(clamp(corner, ivec2(0), ivec2(u_size))), u_channel); }

float box_mean(ivec2 j) {
    ivec2 lo = j - ivec2(u_satSide / 2);
    ivec2 hi = lo + ivec2(u_satSide);
    float sum = prefix(hi) - prefix(ivec2(lo.x, hi.y)) - prefix(ivec2(hi.x, lo.y)) + prefix(lo);
    return sum / float(u_satSide * u_satSide);
}

void main() {
    ivec2 j = texel_under_pixel(ivec2(u_size));
    float occlusion = u_satSide > 0 ? box_mean(j) : direct(j);
    color = vec4(vec3(clamp(occlusion, 0.0, 1.0)), 1.0);
}
)";

// Any texture of a layout, one channel in grey: 2D, 2D array (one layer) or 3D (one depth slice)
// at one mip level. Depth textures are read through a sampler object without comparison, so a
// shadow map shows its stored depth.
constexpr const char* layout_texture_fragment = R"(
layout(binding = 0) uniform sampler2D u_texture2D;
layout(binding = 1) uniform sampler2DArray u_textureArray;
layout(binding = 2) uniform sampler3D u_texture3D;
uniform int u_storage;  // 0: 2D, 1: 2D array, 2: 3D
uniform int u_lod;      // mip level
uniform int u_layer;    // array layer or depth slice
uniform vec4 u_channel; // one-hot: the channel shown
uniform vec2 u_range;   // value shown black, value shown white
void main() {
    vec4 texel;
    if (u_storage == 0)
        texel = texelFetch(u_texture2D, texel_under_pixel(textureSize(u_texture2D, u_lod)), u_lod);
    else if (u_storage == 1)
        texel = texelFetch(u_textureArray, ivec3(texel_under_pixel(textureSize(u_textureArray, u_lod).xy), u_layer), u_lod);
    else
        texel = texelFetch(u_texture3D, ivec3(texel_under_pixel(textureSize(u_texture3D, u_lod).xy), u_layer), u_lod);
    float v = dot(texel, u_channel);
    if (isnan(v)) {
        color = vec4(NOT_COMPUTED, 1.0);
        return;
    }
    color = vec4(vec3(clamp((v - u_range.x) / (u_range.y - u_range.x), 0.0, 1.0)), 1.0);
}
)";

// Same slice and kernel arithmetic as the emitted penumbraVisibility (docs/model.md §1, detail/occlusion/emit_visibility.hpp).
constexpr const char* slice_level_fragment = R"(
layout(binding = 0) uniform sampler2D u_positions;
uniform mat4 u_lightFromWorld;
uniform vec2 u_sliceDepths; // z0, thickness
uniform int u_slices;
uniform int u_sun;          // 0: rectangle (perspective slicing), 1: sun (orthographic)
uniform float u_copDistance;
uniform float u_windowHalfSize;
uniform float u_tanAngularRadius;
uniform float u_resolution;
uniform float u_maxLevel;
uniform float u_levelBias;  // Gaussian pyramid: log2(sqrt(6) / 4), else 0
uniform int u_mode;         // 0: slice index, 1: filter level
uniform int u_levelSlice;   // −1: nearest slice above the point, else that slice
uniform vec3 u_slicePalette[32];
uniform vec3 u_levelPalette[13];
uniform vec3 u_background;
uniform vec3 u_noSlice;

// Side of the kernel square on the plane at depth zeta, in uv units of the slice texture.
float kernel_side(vec3 p, float zeta) {
    if (u_sun == 1) return max(p.z - zeta, 0.0) * u_tanAngularRadius / u_windowHalfSize;
    return max(p.z - zeta, 0.0) * u_copDistance / (p.z * (u_copDistance + zeta));
}

void main() {
    vec4 world = texelFetch(u_positions, texel_under_pixel(textureSize(u_positions, 0)), 0);
    if (world.w < 0.5) {
        color = vec4(u_background, 1.0);
        return;
    }
    vec3 p = (u_lightFromWorld * vec4(world.xyz, 1.0)).xyz;
    // slice s holds depths (z0 + s·Δ, z0 + (s+1)·Δ]
    int s = clamp(int(ceil((p.z - u_sliceDepths.x) / u_sliceDepths.y)) - 1, 0, u_slices - 1);
    if (u_mode == 0) {
        color = vec4(u_slicePalette[s % 32], 1.0); // 64 or 128 slices: the colours repeat every 32
        return;
    }
    int k = u_levelSlice < 0 ? s - 1 : u_levelSlice;
    float zeta = u_sliceDepths.x + float(k + 1) * u_sliceDepths.y; // the slice's bottom plane
    if (k < 0 || zeta >= p.z) {
        color = vec4(u_noSlice, 1.0);
        return;
    }
    float level = clamp(log2(max(kernel_side(p, zeta) * u_resolution, 1.0)) + u_levelBias, 0.0, u_maxLevel);
    int lo = int(floor(level));
    int hi = min(lo + 1, 12);
    color = vec4(mix(u_levelPalette[lo], u_levelPalette[hi], level - float(lo)), 1.0);
}
)";

constexpr const char* error_fragment = R"(
layout(binding = 0) uniform sampler2D u_a;
layout(binding = 1) uniform sampler2D u_b;
layout(binding = 2) uniform sampler1D u_ramp; // magnitude_colors() over [0, 1], 256 entries
uniform float u_maxError;
void main() {
    ivec2 t = texel_under_pixel(textureSize(u_a, 0));
    float a = texelFetch(u_a, t, 0).r;
    float b = texelFetch(u_b, t, 0).r;
    if (isnan(a) || isnan(b)) {
        color = vec4(NOT_COMPUTED, 1.0);
        return;
    }
    float x = clamp(abs(a - b) / u_maxError, 0.0, 1.0);
    color = vec4(textureLod(u_ramp, (x * 255.0 + 0.5) / 256.0, 0.0).rgb, 1.0);
}
)";

constexpr int ramp_entries = 256;

// Compiles and links the full-screen vertex with prelude + body; 0 and *log on failure.
GLuint build_view_program(const char* name, const char* fragment_body, std::string* log) {
    return build_program(std::string("debug_view_") + name, fullscreen_triangle_vertex,
                         std::string(fragment_prelude) + fragment_body, log);
}

GLint location(GLuint program, const char* name) { return glGetUniformLocation(program, name); }

// Saves what a draw changes and puts it back, so views can be drawn in the middle of a frame.
class StateGuard {
public:
    StateGuard() {
        glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
        glGetIntegerv(GL_VIEWPORT, viewport_);
        depth_ = glIsEnabled(GL_DEPTH_TEST);
        blend_ = glIsEnabled(GL_BLEND);
        cull_ = glIsEnabled(GL_CULL_FACE);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
    }
    ~StateGuard() {
        glUseProgram(static_cast<GLuint>(program_));
        glBindVertexArray(static_cast<GLuint>(vertex_array_));
        if (depth_) glEnable(GL_DEPTH_TEST);
        if (blend_) glEnable(GL_BLEND);
        if (cull_) glEnable(GL_CULL_FACE);
    }
    StateGuard(const StateGuard&) = delete;
    StateGuard& operator=(const StateGuard&) = delete;
    const GLint* viewport() const { return viewport_; }

private:
    GLint program_ = 0, vertex_array_ = 0, viewport_[4] = {0, 0, 0, 0};
    GLboolean depth_ = GL_FALSE, blend_ = GL_FALSE, cull_ = GL_FALSE;
};

// Describes a texture for messages and checks it is a usable 2D texture; empty when fine.
std::string check_2d_texture(const char* role, GLuint texture, int* width = nullptr, int* height = nullptr) {
    if (!texture || !glIsTexture(texture))
        return std::string(role) + " is not a texture (name " + std::to_string(texture) + ")";
    GLint target = 0;
    glGetTextureParameteriv(texture, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D) return std::string(role) + " must be a 2D texture (GL_TEXTURE_2D)";
    GLint w = 0, h = 0;
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_WIDTH, &w);
    glGetTextureLevelParameteriv(texture, 0, GL_TEXTURE_HEIGHT, &h);
    if (w <= 0 || h <= 0) return std::string(role) + " has no storage";
    if (width) *width = w;
    if (height) *height = h;
    return {};
}

std::string number(float value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", static_cast<double>(value));
    return text;
}

std::string gl_error_after(const char* what) {
    if (const GLenum e = glGetError(); e != GL_NO_ERROR)
        return std::string("GL error ") + std::to_string(e) + " in " + what;
    return {};
}

void draw_fullscreen(GLuint program, GLuint vertex_array, const GLint* viewport) {
    glProgramUniform4f(program, location(program, "u_viewport"), static_cast<float>(viewport[0]),
                       static_cast<float>(viewport[1]), static_cast<float>(viewport[2]),
                       static_cast<float>(viewport[3]));
    glUseProgram(program);
    glBindVertexArray(vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

// Where slice `slice` at filter level `level` lives, in the storage the layout describes.
struct SliceSource {
    std::string texture; // name in the layout
    int storage = 0;     // 0: 2D, 1: 2D array, 2: 3D (shader's u_storage)
    int lod = 0, tile_x = 0, layer = 0, size = 0, shift = 0, sat_side = 0;
};

SliceSource locate_slice(const penumbra::Config& config, int slice, int level) {
    const int R = config.resolution, T = penumbra::texture_count(config), t = slice / 4;
    const bool atlas = config.packing == penumbra::Packing::atlas;
    SliceSource s;
    s.size = R;
    if (config.filter == penumbra::Filter::mipmap) {
        s.texture = atlas ? "penumbra_occlusionAtlas" : "penumbra_occlusion";
        s.storage = atlas ? 0 : 1;
        s.lod = level;
        s.size = R >> level;
        s.tile_x = atlas ? t * s.size : 0;
        s.layer = atlas ? 0 : t;
    } else if (config.filter == penumbra::Filter::sat) {
        s.texture = atlas ? "penumbra_satAtlas" : "penumbra_sat";
        s.storage = atlas ? 0 : 1;
        s.tile_x = atlas ? t * (R + 1) : 0; // tiles of R + 1 texels: one more corner than texels
        s.layer = atlas ? 0 : t;
        s.sat_side = 1 << level;
    } else {
        // reduced atlas levels (level_reduction): R / spacing texels per tile, the shift in those texels
        const int spacing = penumbra::level_spacing(config, level);
        if (config.filter == penumbra::Filter::nbuffer && level > 0) s.shift = (1 << (level - 1)) / spacing;
        if (atlas) {
            s.texture = "penumbra_level" + std::to_string(level);
            s.size = R / spacing;
            s.tile_x = t * s.size;
        } else if (config.packing == penumbra::Packing::array) {
            s.texture = "penumbra_levels";
            s.storage = 1;
            s.layer = level * T + t;
        } else {
            s.texture = "penumbra_volume" + std::to_string(t);
            s.storage = 2;
            s.layer = level;
        }
    }
    return s;
}

} // namespace

glm::vec3 slice_color(int slice) {
    // Tableau 10 without its grey and brown: distinct hues for neighbouring slices.
    static constexpr std::array<glm::vec3, 8> hues{
        glm::vec3(0.306f, 0.475f, 0.655f), glm::vec3(0.949f, 0.557f, 0.169f),
        glm::vec3(0.882f, 0.341f, 0.349f), glm::vec3(0.463f, 0.718f, 0.698f),
        glm::vec3(0.349f, 0.631f, 0.310f), glm::vec3(0.929f, 0.788f, 0.282f),
        glm::vec3(0.690f, 0.478f, 0.631f), glm::vec3(1.000f, 0.616f, 0.655f)};
    static constexpr std::array<float, 4> band_brightness{1.0f, 0.7f, 0.5f, 0.35f};
    slice = std::max(slice, 0) % max_palette_slices;
    return hues[static_cast<std::size_t>(slice % 8)] * band_brightness[static_cast<std::size_t>(slice / 8)];
}

glm::vec3 level_color(float level) {
    static constexpr std::array<glm::vec3, 5> viridis{
        glm::vec3(0.267f, 0.005f, 0.329f), glm::vec3(0.229f, 0.322f, 0.546f),
        glm::vec3(0.128f, 0.567f, 0.551f), glm::vec3(0.369f, 0.789f, 0.383f),
        glm::vec3(0.993f, 0.906f, 0.144f)};
    // Integer levels take the ramp's colour at level / 12; in between, the two neighbours blend
    // linearly (as the shader does), not the ramp itself.
    level = std::clamp(level, 0.0f, static_cast<float>(max_palette_level));
    const int lo = std::min(static_cast<int>(level), max_palette_level - 1);
    const glm::vec3 a = ramp(viridis, static_cast<float>(lo) / max_palette_level);
    const glm::vec3 b = ramp(viridis, static_cast<float>(lo + 1) / max_palette_level);
    return glm::mix(a, b, level - static_cast<float>(lo));
}

struct DebugViews::Programs {
    GLuint scalar = 0, slice_texture = 0, slice_level = 0, error = 0, layout_texture = 0;
    GLuint vertex_array = 0; // empty: the vertex shader makes its own positions
    GLuint raw_sampler = 0;  // nearest, no comparison: how the layout-texture view reads depth
    GLuint error_ramp = 0;   // 1D RGBA32F, magnitude_colors() at 256 evenly spaced values

    ~Programs() {
        for (GLuint p : {scalar, slice_texture, slice_level, error, layout_texture})
            if (p) glDeleteProgram(p);
        if (raw_sampler) glDeleteSamplers(1, &raw_sampler);
        if (vertex_array) glDeleteVertexArrays(1, &vertex_array);
        if (error_ramp) glDeleteTextures(1, &error_ramp);
    }
};

std::unique_ptr<DebugViews> DebugViews::create(std::string* error) {
    std::unique_ptr<DebugViews> views(new DebugViews());
    views->programs_ = std::make_unique<Programs>();
    Programs& p = *views->programs_;
    std::string log;
    const std::pair<GLuint*, std::pair<const char*, const char*>> programs[] = {
        {&p.scalar, {"scalar", scalar_fragment}},
        {&p.slice_texture, {"slice_texture", slice_texture_fragment}},
        {&p.slice_level, {"slice_level", slice_level_fragment}},
        {&p.error, {"error", error_fragment}},
        {&p.layout_texture, {"layout_texture", layout_texture_fragment}}};
    for (const auto& [slot, source] : programs) {
        *slot = build_view_program(source.first, source.second, &log);
        if (!*slot) {
            if (error) *error = log;
            return nullptr;
        }
    }
    glCreateVertexArrays(1, &p.vertex_array);
    glCreateSamplers(1, &p.raw_sampler);
    glSamplerParameteri(p.raw_sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
    glSamplerParameteri(p.raw_sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(p.raw_sampler, GL_TEXTURE_COMPARE_MODE, GL_NONE);

    std::vector<float> values(ramp_entries);
    for (int i = 0; i < ramp_entries; ++i)
        values[static_cast<std::size_t>(i)] = static_cast<float>(i) / (ramp_entries - 1);
    const std::vector<float> rgb = magnitude_colors(values, 1.0f);
    glCreateTextures(GL_TEXTURE_1D, 1, &p.error_ramp);
    glTextureStorage1D(p.error_ramp, 1, GL_RGB32F, ramp_entries);
    glTextureSubImage1D(p.error_ramp, 0, 0, ramp_entries, GL_RGB, GL_FLOAT, rgb.data());
    glTextureParameteri(p.error_ramp, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(p.error_ramp, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(p.error_ramp, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);

    // Palettes are uniforms set once: the shader and slice_color / level_color cannot disagree.
    std::vector<glm::vec3> slices(max_palette_slices), levels(max_palette_level + 1);
    for (int k = 0; k < max_palette_slices; ++k) slices[static_cast<std::size_t>(k)] = slice_color(k);
    for (int l = 0; l <= max_palette_level; ++l)
        levels[static_cast<std::size_t>(l)] = level_color(static_cast<float>(l));
    glProgramUniform3fv(p.slice_level, location(p.slice_level, "u_slicePalette"), max_palette_slices,
                        glm::value_ptr(slices[0]));
    glProgramUniform3fv(p.slice_level, location(p.slice_level, "u_levelPalette"), max_palette_level + 1,
                        glm::value_ptr(levels[0]));
    glProgramUniform3fv(p.slice_level, location(p.slice_level, "u_background"), 1,
                        glm::value_ptr(background_color));
    glProgramUniform3fv(p.slice_level, location(p.slice_level, "u_noSlice"), 1,
                        glm::value_ptr(no_slice_color));

    if (std::string e = gl_error_after("DebugViews::create"); !e.empty()) {
        if (error) *error = e;
        return nullptr;
    }
    return views;
}

DebugViews::~DebugViews() = default;

std::string DebugViews::draw_scalar(GLuint texture, const ScalarView& view) const {
    if (std::string problem = check_2d_texture("scalar view: the texture", texture); !problem.empty())
        return problem;
    if (!(view.max_value > view.min_value))
        return "scalar view: max_value (" + number(view.max_value) + ") must be greater than min_value (" +
               number(view.min_value) + ")";
    const GLuint program = programs_->scalar;
    StateGuard guard;
    glBindTextureUnit(0, texture);
    glProgramUniform2f(program, location(program, "u_range"), view.min_value, view.max_value);
    draw_fullscreen(program, programs_->vertex_array, guard.viewport());
    return gl_error_after("draw_scalar");
}

std::string DebugViews::draw_layout_texture(const penumbra::gl::Runtime& runtime,
                                            const LayoutTextureView& view) const {
    const std::vector<penumbra::TextureDesc>& textures = runtime.layout().textures;
    const penumbra::TextureDesc* desc = nullptr;
    for (const penumbra::TextureDesc& t : textures)
        if (t.name == view.texture) desc = &t;
    if (!desc) {
        std::string names;
        for (const penumbra::TextureDesc& t : textures) names += (names.empty() ? "" : ", ") + t.name;
        return "texture view: '" + view.texture + "' is not a texture of this layout; allowed: " + names;
    }
    const GLuint id = runtime.texture(desc->name);
    if (!id) return "texture view: '" + desc->name + "' is not allocated yet (source " + std::string(penumbra::to_string(desc->source)) + ")";
    if (penumbra::is_integer(desc->format)) // RGBA32UI, R32UI
        return "texture view: '" + desc->name + "' holds integers (" + std::string(penumbra::to_string(desc->format)) +
               "); this view shows float and depth textures";
    if (view.level < 0 || view.level >= desc->mip_levels)
        return "texture view: level " + std::to_string(view.level) + " is out of range; '" + desc->name +
               "' has levels 0 to " + std::to_string(desc->mip_levels - 1);
    using penumbra::TextureTarget;
    const int layers = desc->target == TextureTarget::texture_2d   ? 1
                       : desc->target == TextureTarget::texture_3d ? std::max(desc->depth >> view.level, 1)
                                                                   : desc->depth;
    if (view.layer < 0 || view.layer >= layers)
        return "texture view: layer " + std::to_string(view.layer) + " is out of range; '" + desc->name +
               "' has layers 0 to " + std::to_string(layers - 1) + " at level " + std::to_string(view.level);
    if (view.channel < 0 || view.channel > 3)
        return "texture view: channel " + std::to_string(view.channel) + " is out of range; allowed: 0 to 3";
    if (!(view.max_value > view.min_value))
        return "texture view: max_value (" + number(view.max_value) + ") must be greater than min_value (" +
               number(view.min_value) + ")";
    const int storage = desc->target == TextureTarget::texture_2d ? 0 : desc->target == TextureTarget::texture_2d_array ? 1 : 2;
    const GLuint program = programs_->layout_texture;
    StateGuard guard;
    glBindTextureUnit(static_cast<GLuint>(storage), id);
    glBindSampler(static_cast<GLuint>(storage), programs_->raw_sampler);
    float channel[4] = {0, 0, 0, 0};
    channel[view.channel] = 1.0f;
    glProgramUniform1i(program, location(program, "u_storage"), storage);
    glProgramUniform1i(program, location(program, "u_lod"), view.level);
    glProgramUniform1i(program, location(program, "u_layer"), view.layer);
    glProgramUniform4fv(program, location(program, "u_channel"), 1, channel);
    glProgramUniform2f(program, location(program, "u_range"), view.min_value, view.max_value);
    draw_fullscreen(program, programs_->vertex_array, guard.viewport());
    glBindSampler(static_cast<GLuint>(storage), 0);
    return gl_error_after("draw_layout_texture");
}

std::string DebugViews::draw_slice_texture(const penumbra::gl::Runtime& runtime,
                                           const SliceTextureView& view) const {
    const penumbra::Config& config = runtime.config();
    const int L = penumbra::max_level(config);
    if (view.slice < 0 || view.slice >= config.slices)
        return "slice view: slice " + std::to_string(view.slice) +
               " is out of range: the configuration has " + std::to_string(config.slices) + " slices (0 to " +
               std::to_string(config.slices - 1) + ")";
    if (view.level < 0 || view.level > L)
        return "slice view: level " + std::to_string(view.level) + " is out of range: resolution " +
               std::to_string(config.resolution) + " has filter levels 0 to " + std::to_string(L);
    const SliceSource source = locate_slice(config, view.slice, view.level);
    const GLuint texture = runtime.texture(source.texture);
    if (!texture)
        return "slice view: the runtime has no texture '" + source.texture + "' for filter " +
               std::string(penumbra::to_string(config.filter)) + ", packing " +
               std::string(penumbra::to_string(config.packing));

    const GLuint program = programs_->slice_texture;
    StateGuard guard;
    glBindTextureUnit(static_cast<GLuint>(source.storage), texture); // units match the sampler bindings
    glm::vec4 channel(0.0f);
    channel[view.slice % 4] = 1.0f;
    glProgramUniform1i(program, location(program, "u_storage"), source.storage);
    glProgramUniform1i(program, location(program, "u_lod"), source.lod);
    glProgramUniform1i(program, location(program, "u_tileX"), source.tile_x);
    glProgramUniform1i(program, location(program, "u_layer"), source.layer);
    glProgramUniform1i(program, location(program, "u_size"), source.size);
    glProgramUniform1i(program, location(program, "u_shift"), source.shift);
    glProgramUniform1i(program, location(program, "u_satSide"), source.sat_side);
    glProgramUniform4fv(program, location(program, "u_channel"), 1, glm::value_ptr(channel));
    draw_fullscreen(program, programs_->vertex_array, guard.viewport());
    return gl_error_after("draw_slice_texture");
}

std::string DebugViews::draw_slice_level(const penumbra::gl::Runtime& runtime, GLuint world_positions,
                                         const SliceLevelView& view) const {
    const penumbra::Config& config = runtime.config();
    if (std::string problem = check_2d_texture("slice/level view: the world positions", world_positions);
        !problem.empty())
        return problem;
    if (view.slice < -1 || view.slice >= config.slices)
        return "slice/level view: slice " + std::to_string(view.slice) +
               " is out of range: −1 (nearest above) or 0 to " + std::to_string(config.slices - 1);
    const penumbra::SliceFrame& frame = runtime.frame();
    if (!(frame.slice_depths.y > 0.0f))
        return "slice/level view: the runtime has no light yet (call set_light)";

    const GLuint program = programs_->slice_level;
    StateGuard guard;
    glBindTextureUnit(0, world_positions);
    const bool sun = config.light == penumbra::Light::sun;
    const float bias = config.filter == penumbra::Filter::gaussian
                           ? static_cast<float>(penumbra::detail::gaussian_level_bias)
                           : 0.0f;
    glProgramUniformMatrix4fv(program, location(program, "u_lightFromWorld"), 1, GL_FALSE,
                              glm::value_ptr(frame.light_from_world));
    glProgramUniform2fv(program, location(program, "u_sliceDepths"), 1, glm::value_ptr(frame.slice_depths));
    glProgramUniform1i(program, location(program, "u_slices"), config.slices);
    glProgramUniform1i(program, location(program, "u_sun"), sun ? 1 : 0);
    glProgramUniform1f(program, location(program, "u_copDistance"), frame.cop_distance);
    glProgramUniform1f(program, location(program, "u_windowHalfSize"), frame.window_half_size);
    glProgramUniform1f(program, location(program, "u_tanAngularRadius"), frame.tan_angular_radius);
    glProgramUniform1f(program, location(program, "u_resolution"), static_cast<float>(config.resolution));
    glProgramUniform1f(program, location(program, "u_maxLevel"),
                       static_cast<float>(penumbra::max_level(config)));
    glProgramUniform1f(program, location(program, "u_levelBias"), bias);
    glProgramUniform1i(program, location(program, "u_mode"), view.mode == SliceLevelMode::level ? 1 : 0);
    glProgramUniform1i(program, location(program, "u_levelSlice"), view.slice);
    draw_fullscreen(program, programs_->vertex_array, guard.viewport());
    return gl_error_after("draw_slice_level");
}

std::string DebugViews::draw_error(GLuint a, GLuint b, const ErrorView& view) const {
    int wa = 0, ha = 0, wb = 0, hb = 0;
    if (std::string problem = check_2d_texture("error view: texture a", a, &wa, &ha); !problem.empty())
        return problem;
    if (std::string problem = check_2d_texture("error view: texture b", b, &wb, &hb); !problem.empty())
        return problem;
    if (wa != wb || ha != hb)
        return "error view: texture a is " + std::to_string(wa) + "x" + std::to_string(ha) + " but b is " +
               std::to_string(wb) + "x" + std::to_string(hb) + "; give two textures of the same size";
    if (!(view.max_error > 0.0f)) return "error view: max_error must be > 0, got " + number(view.max_error);
    const GLuint program = programs_->error;
    StateGuard guard;
    glBindTextureUnit(0, a);
    glBindTextureUnit(1, b);
    glBindTextureUnit(2, programs_->error_ramp);
    glProgramUniform1f(program, location(program, "u_maxError"), view.max_error);
    draw_fullscreen(program, programs_->vertex_array, guard.viewport());
    return gl_error_after("draw_error");
}

std::optional<Metrics> visibility_error(std::span<const float> estimate, std::span<const float> reference,
                                        std::span<const unsigned char> geometry, std::string* error) {
    if (estimate.size() != reference.size() || geometry.size() != reference.size()) {
        if (error)
            *error = "visibility error: sizes differ (estimate " + std::to_string(estimate.size()) +
                     ", reference " + std::to_string(reference.size()) + ", geometry " +
                     std::to_string(geometry.size()) + ")";
        return std::nullopt;
    }
    HeadlessResult result; // compare() reads only visibility and geometry
    result.visibility.assign(estimate.begin(), estimate.end());
    result.geometry.assign(geometry.begin(), geometry.end());
    std::vector<float> truth(reference.begin(), reference.end());
    for (std::size_t i = 0; i < truth.size(); ++i)
        if (std::isnan(truth[i]) || std::isnan(result.visibility[i])) result.geometry[i] = 0;
    return compare(result, truth);
}

} // namespace penumbra::playground
