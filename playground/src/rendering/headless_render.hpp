// playground/src/rendering/headless_render.hpp — headless rendering of a scene with the generated
// shaders: G-buffer, runtime passes, deferred visibility, optional Embree reference and error
// metrics. Needs a current GL 4.5 context.
#pragma once

#include "reference/metrics.hpp"
#include "scenes/scene.hpp"

#include <penumbra/config.hpp>
#include <penumbra/gl/runtime.hpp>

#include <functional>
#include <optional>
#include <utility>

#include <string>
#include <vector>

namespace penumbra::playground {

struct HeadlessResult {
    int width = 0, height = 0;
    std::vector<float> visibility;       // width·height, top row first; 1 on background
    std::vector<glm::vec3> positions;    // world positions, top row first; NaN on background
    std::vector<glm::vec3> normals;      // unit normals, zero on background
    std::vector<glm::vec2> tex_coords;   // the mesh's texture coordinates (0 without them or on background)
    std::vector<unsigned char> geometry; // 1 where a surface was rasterised
    std::vector<float>
        light_term; // the example shading's unoccluded light (rendering/light_term.hpp), 0 on background
    std::vector<float> rgb;                        // the example shading: example_shading(*this, visibility)
    std::vector<penumbra::gl::PassTiming> timings; // GPU time of each pass (timer queries), shading last
    bool warm = false;                             // timings of a second run (RenderOptions::warm_up)
    long long texture_bytes = 0;                   // the layout's textures at this output size
};

struct RenderOptions {
    // Called after the deferred shading pass, while the runtime and its textures still exist:
    // lets tests and the oracle read back intermediate textures (runtime.texture(name)).
    std::function<void(const penumbra::gl::Runtime&)> inspect;
    // Textures the layout marks "bake" (name → texels, RGBA floats at the layout's size) and the sun's
    // time window along its path (occlusion interval maps; bake/oim_scene.hpp prepares both).
    std::vector<std::pair<std::string, std::vector<float>>> bake_textures;
    std::optional<glm::vec4> time_window;
    // Run the passes once before the timed run, so the timings are warm: llvmpipe (and some
    // drivers) compile a shader at its first draw, which the first run's GPU time would include.
    bool warm_up = false;
};

// The example shading of `result`'s pixels with `visibility` in place of the estimate (3 floats per
// pixel, top row first): ambient plus the light term times the visibility on geometry, sky elsewhere.
// With the ray-traced truth's visibility it is the image the estimate's shading should match.
std::vector<float> example_shading(const HeadlessResult& result, const std::vector<float>& visibility);

// The kind of light a configuration is lit by: occlusion interval maps follow the sun.
Light shading_light(const Config& config);

// Runs the whole pipeline; returns false with *error set on any failure (never throws for GL).
bool render_headless(const Scene& scene, const Config& config, int width, int height, HeadlessResult& out,
                     std::string* error, const RenderOptions& options = {});

// Ground-truth visibility (Embree) at the read-back positions; background pixels get 1.
std::vector<float> reference_visibility(const Scene& scene, const HeadlessResult& result, int samples_per_axis,
                                       Light light = Light::rect);

Metrics compare(const HeadlessResult& result, const std::vector<float>& reference);

// The three ground truths of reference/metrics.hpp at the read-back positions: today's
// visibility, and the fair ones (oriented, irradiance) for the side of each surface that faces
// the scene's camera (the side a viewer sees), with the unoccluded irradiance that weighs the
// shaded reference; background pixels get 1.
struct References {
    std::vector<float> visibility, oriented, irradiance, unoccluded;
};
References reference_all(const Scene& scene, const HeadlessResult& result, int samples_per_axis,
                         Light light = Light::rect);

QualityMetrics compare_quality(const HeadlessResult& result, const References& references);

} // namespace penumbra::playground
