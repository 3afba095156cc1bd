// playground/src/rendering/headless_render.hpp — headless rendering of a scene with the generated
// shaders: G-buffer, runtime passes, deferred visibility, optional Embree reference and error
// metrics. Needs a current GL 4.5 context.
#pragma once

#include "reference/metrics.hpp"
#include "scenes/scene.hpp"

#include <penumbra/config.hpp>
#include <penumbra/gl/runtime.hpp>

#include <functional>

#include <string>
#include <vector>

namespace penumbra::playground {

struct HeadlessResult {
    int width = 0, height = 0;
    std::vector<float> visibility;       // width·height, top row first; 1 on background
    std::vector<glm::vec3> positions;    // world positions, top row first; NaN on background
    std::vector<glm::vec3> normals;      // unit normals, zero on background
    std::vector<unsigned char> geometry; // 1 where a surface was rasterised
    std::vector<float> rgb;              // Lambert shading, 3 floats per pixel, top row first
    std::vector<penumbra::gl::PassTiming> timings; // GPU time of each pass (timer queries), shading last
    bool warm = false;                             // timings of a second run (RenderOptions::warm_up)
    long long texture_bytes = 0;                   // the layout's textures at this output size
};

struct RenderOptions {
    // Called after the deferred shading pass, while the runtime and its textures still exist:
    // lets tests and the oracle read back intermediate textures (runtime.texture(name)).
    std::function<void(const penumbra::gl::Runtime&)> inspect;
    // Run the passes once before the timed run, so the timings are warm: llvmpipe (and some
    // drivers) compile a shader at its first draw, which the first run's GPU time would include.
    bool warm_up = false;
};

// Runs the whole pipeline; returns false with *error set on any failure (never throws for GL).
bool render_headless(const Scene& scene, const Config& config, int width, int height, HeadlessResult& out,
                     std::string* error, const RenderOptions& options = {});

// Ground-truth visibility (Embree) at the read-back positions; background pixels get 1.
std::vector<float> reference_visibility(const Scene& scene, const HeadlessResult& result, int samples_per_axis,
                                       Light light = Light::rect);

Metrics compare(const HeadlessResult& result, const std::vector<float>& reference);

} // namespace penumbra::playground
