// playground/src/rendering/debug_views.hpp — debug visualisations of a penumbra::gl::Runtime: a scalar
// texture in grey, one slice's occlusion texture at any filter level, which slice / filter level
// each pixel uses, and an error heatmap between two visibility textures.
//
// Every draw_* call fills the currently bound framebuffer's current viewport with one full-screen
// triangle, so a window can tile several views (a strip of filter levels, a split screen) by
// setting viewports. Needs a current OpenGL 4.5 core context; uses texture units 0 to 2 and
// restores the program, vertex array, depth test, blending and culling it changes.
//
//   std::string error;
//   auto views = DebugViews::create(&error);                 // compiles the shaders once
//   glViewport(0, 0, w, h);
//   error = views->draw_slice_texture(*runtime, {.slice = 3, .level = 2});
//   error = views->draw_error(visibility, truth, {.max_error = 0.25f});
//
// Colours (also exposed below so the window can draw legends that match exactly):
//   background (no geometry in the G-buffer)  black
//   scalar view                               grey = (value − min) / (max − min); NaN green
//   slice k                                   slice_color(k): 8 Tableau hues (blue, orange, red,
//                                             teal, green, yellow, purple, pink) for k mod 8,
//                                             darkened ×1, ×0.7, ×0.5, ×0.35 for k / 8 = 0..3
//   filter level λ                            level_color(λ): viridis, fixed per level (level 0
//                                             dark purple, 6 teal-green, 12 yellow) so a level
//                                             keeps its colour across resolutions; fractional λ
//                                             blends the two neighbours as the filter does
//   no slice above the point / slice not      no_slice_color: mid grey
//     above the point (level view)
//   error |a − b|                             magnitude_colors() of image_io.hpp (black → purple →
//                                             orange → yellow-white) over [0, max_error]; NaN green
#pragma once

#include "rendering/headless_render.hpp" // Metrics, ErrorStats, compare

#include <penumbra/gl/runtime.hpp>

#include <epoxy/gl.h>
#include <glm/glm.hpp>

#include <memory>
#include <optional>
#include <span>
#include <string>

namespace penumbra::playground {

inline constexpr glm::vec3 background_color{0.0f, 0.0f, 0.0f};
inline constexpr glm::vec3 no_slice_color{0.5f, 0.5f, 0.5f};
inline constexpr glm::vec3 not_computed_color{0.0f, 1.0f, 0.0f}; // NaN (image_io.hpp's convention)
inline constexpr int max_palette_slices = 32;                    // colours; slices 32 to 127 repeat them
inline constexpr int max_palette_level = 12;                     // resolution 4096: levels 0 to 12

glm::vec3 slice_color(int slice);   // slice in [0, 32), repeating every 32 slices; negative: slice 0
glm::vec3 level_color(float level); // level in [0, 12]; others clamp

struct ScalarView {
    float min_value = 0.0f; // shown black
    float max_value = 1.0f; // shown white
};

// Any texture of the runtime's layout (a technique's shadow map, its occlusion storage, an
// output-sized intermediate, a baked texture), one channel at one mip level and layer.
struct LayoutTextureView {
    std::string texture;    // the layout's name, e.g. "penumbra_shadowMap"
    int level = 0;          // mip level
    int layer = 0;          // array layer / depth slice of a 3D texture; 0 for 2D
    int channel = 0;        // 0 to 3 (r, g, b, a); depth textures: 0
    float min_value = 0.0f; // shown black
    float max_value = 1.0f; // shown white
};

struct SliceTextureView {
    int slice = 0; // 0 (nearest the light) to slices − 1
    // Filter level 0 (the binary coverage) to L = log2(resolution). Level l shows the mean
    // occlusion over a 2^l-texel window: mipmap = the stored mip level (blocks of 2^l texels);
    // N-buffers = the stored level read at its anchor − 2^(l−1) texels, so the window is centred
    // on the texel corner as in the shading lookup; summed-area table = that same centred window
    // computed from the table (4 fetches); Gaussian = the stored blur level (centred).
    int level = 0;
};

enum class SliceLevelMode {
    slice, // colour = slice_color of the slice that contains the pixel's point
    level, // colour = level_color of the filter level λ the shading reads for one slice
};

struct SliceLevelView {
    SliceLevelMode mode = SliceLevelMode::slice;
    // Level mode: −1 = the nearest slice above the point (the one that fades in, paper §3.4.2),
    // else that slice; points with no such slice above them get no_slice_color.
    int slice = -1;
};

struct ErrorView {
    float max_error = 0.25f; // |a − b| at which the colour scale saturates; > 0
};

class DebugViews {
public:
    // nullptr with *error set ("debug view 'slice_texture': 0:12(3): error: ...") when a shader
    // does not compile or link.
    static std::unique_ptr<DebugViews> create(std::string* error = nullptr);
    ~DebugViews();
    DebugViews(const DebugViews&) = delete;
    DebugViews& operator=(const DebugViews&) = delete;

    // Each returns an empty string on success, else a one-line diagnostic (and draws nothing).

    // (a) A single-channel texture (visibility: R32F) in grey, stretched over the viewport.
    std::string draw_scalar(GLuint texture, const ScalarView& view = {}) const;

    // (b) Slice `view.slice`'s occlusion at filter level `view.level`, for every packing
    // (atlas tile + channel, array layer + channel, volume depth + channel) and filter. Coverage
    // is white, empty black; the R×R slice (R >> level for mipmaps) fills the viewport.
    std::string draw_slice_texture(const penumbra::gl::Runtime& runtime, const SliceTextureView& view) const;

    // (b') Any texture of the layout (LayoutTextureView), the whole texture over the viewport;
    // depth textures are read without comparison. Integer formats are refused with a message.
    std::string draw_layout_texture(const penumbra::gl::Runtime& runtime, const LayoutTextureView& view) const;

    // (c) Which slice / filter level each pixel uses, from a G-buffer of world positions
    // (RGBA32F, w = 1 on geometry; GBuffer::positions()) and runtime.frame() / config().
    std::string draw_slice_level(const penumbra::gl::Runtime& runtime, GLuint world_positions,
                                 const SliceLevelView& view = {}) const;

    // (d) |a − b| of two R32F textures of the same size, in false colour.
    std::string draw_error(GLuint a, GLuint b, const ErrorView& view = {}) const;

private:
    DebugViews() = default;
    struct Programs;
    std::unique_ptr<Programs> programs_;
};

// MAE / RMSE / p95 of |estimate − reference| (headless_render.hpp's compare) over the pixels
// where geometry is non-zero and the reference is not NaN (pixels TruthWorker has not reached
// yet are left out). nullopt and *error when the three sizes differ.
std::optional<Metrics> visibility_error(std::span<const float> estimate, std::span<const float> reference,
                                        std::span<const unsigned char> geometry,
                                        std::string* error = nullptr);

} // namespace penumbra::playground
