// playground/src/window/frame_renderer.hpp — one frame of the window on the GPU: G-buffer of the
// scene (plus the optional moving object), the runtime's passes, deferred visibility, and a
// small Lambert compose shader into the window's framebuffer. Split screen: two runtimes, the
// left half shaded by one and the right half by the other.
#pragma once

#include "rendering/debug_views.hpp"
#include "frame_stats.hpp"
#include "rendering/gpu_scene.hpp"
#include "scenes/scene.hpp"

#include <penumbra/gl/runtime.hpp>

#include <memory>
#include <optional>
#include <string>

namespace penumbra::playground {

enum class View : int {
    shaded,        // Lambert × visibility
    visibility,    // visibility only, grey
    truth,         // Embree ground truth (TruthWorker), grey; green where not traced yet
    error,         // |visibility − truth|, heat map (debug_views.hpp colours)
    slice_texture, // one slice's occlusion texture at one filter level
    slice_map,     // which slice contains each pixel's point
    level_map,     // which filter level the shading reads for each pixel
    texture,       // any texture of the technique's layout (shadow map depth, levels, intermediates)
};
inline constexpr int view_count = 8;
const char* to_string(View view);

struct FrameSettings {
    OrbitCamera camera;
    penumbra::RectLight rect;
    penumbra::SunLight sun;
    std::optional<glm::mat4> moving_object; // model matrix of the animated box, when shown
    View view = View::shaded;
    GLuint truth_texture = 0;  // R32F, window size; used by the truth and error views
    float error_scale = 0.25f; // |error| shown at full heat
    int slice = 0;             // slice_texture: which slice; level_map: which slice (−1: nearest above)
    int level = 0;             // slice_texture: which filter level
    LayoutTextureView texture; // texture view: which texture, level, layer, channel, value range
};

class FrameRenderer {
public:
    static std::unique_ptr<FrameRenderer> create(const Scene& scene, std::string* error);
    ~FrameRenderer();
    FrameRenderer(const FrameRenderer&) = delete;
    FrameRenderer& operator=(const FrameRenderer&) = delete;

    // Renders into framebuffer 0 (width × height). `right`, when given, shades the right half.
    // Returns an empty string or a diagnostic; the GPU time of every pass goes to `stats`.
    std::string render(penumbra::gl::Runtime& left, penumbra::gl::Runtime* right,
                       const FrameSettings& settings, int width, int height, FrameStats& stats);

    const GBuffer* gbuffer() const { return gbuffer_.get(); }
    // Bounds of everything that can cast a shadow, the moving object's whole path included (the
    // slicing range then stays fixed while it moves).
    glm::vec3 bounds_min() const { return bounds_min_; }
    glm::vec3 bounds_max() const { return bounds_max_; }
    // The moving object's model matrix at `seconds` of animation time.
    glm::mat4 moving_object_at(double seconds) const;

private:
    FrameRenderer() = default;
    // True when the geometry changed (first frame, the moving object moved or appeared).
    bool update_meshes(const std::optional<glm::mat4>& moving_object);
    std::string draw_debug_view(penumbra::gl::Runtime* runtimes[2], const GLuint visibility[2],
                                const FrameSettings& settings, int width, int height);

    const Scene* scene_ = nullptr;
    std::unique_ptr<MeshBuffers> mesh_;
    std::optional<glm::mat4> mesh_object_; // the moving object baked into mesh_, if any
    bool mesh_built_ = false;
    std::unique_ptr<GBuffer> gbuffer_;
    std::unique_ptr<DebugViews> debug_views_;
    std::string debug_views_error_; // why debug_views_ is missing
    GLuint compose_program_ = 0, empty_vao_ = 0;
    GLuint queries_[3] = {0, 0, 0};
    glm::vec3 bounds_min_{0.0f}, bounds_max_{0.0f};
    float object_size_ = 1.0f, object_radius_ = 1.0f, object_height_ = 1.0f;
};

} // namespace penumbra::playground
