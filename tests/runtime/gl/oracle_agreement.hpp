// The GPU's visibility against the CPU oracle's, pixel by pixel (docs/model.md §4, question 1): render a
// configuration headless, read back what the oracle needs (the slicing pass's level 0, the adaptive
// boundaries, the frame and the configuration that ran), and count the pixels where the two differ by
// more than the oracle's per-pixel bound. Shared by the GL tests that hold a model feature to the oracle.
#pragma once

#include "reference/oracle.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::playground {

// The GPU run of one configuration: visibility at the shaded world positions, and what the oracle needs
// from the runtime (the slicing output and the frame).
struct GpuRun {
    HeadlessResult result;
    SliceTextures slices;
    SliceFrame frame;
    std::vector<float> boundaries; // adaptive slice placement: the GPU's S + 1 boundaries
    Config config;                 // what ran: level_bound fitted to the light
};

// Renders `scene` at size × size and reads the slices back; false with *error set when either fails.
inline bool render_for_oracle(const Scene& scene, const Config& config, int size, GpuRun& run, std::string* error) {
    bool read = false;
    std::string read_error;
    RenderOptions options{.inspect = [&](const gl::Runtime& runtime) {
        read = read_slice_textures(runtime, run.slices, &read_error) &&
               read_slice_boundaries(runtime, run.boundaries, &read_error);
        run.frame = runtime.frame();
        run.config = runtime.config();
    }};
    if (!render_headless(scene, config, size, size, run.result, error, options)) return false;
    if (!read) *error = read_error;
    return read;
}

// The oracle built from what `run` read back; `precision`: what the renderer's texture units round
// (measure_texture_precision().for_oracle() where a test reads mip chains).
inline Oracle oracle_of(const GpuRun& run, TexturePrecision precision = {}) {
    return Oracle(run.config, run.frame, run.slices, run.boundaries, precision);
}

struct Agreement {
    std::string name;
    double max_difference = 0, mean_difference = 0;
    double max_bound = 0;   // the largest per-pixel bound
    double worst_ratio = 0; // max over the pixels of |GPU − oracle| / bound
    std::size_t pixels = 0, beyond_bound = 0, penumbra_pixels = 0;
    std::size_t beyond_level_bound = 0; // pixels whose kernel asked for a level above config.level_bound
    int level_bound = -1;               // the level_bound the runtime fitted to the light
    // The pixel of the largest |GPU − oracle| / bound, as a failure's message needs it on a renderer nobody
    // here can run: where, both values, the bound, and every slice's lookup there (Oracle::describe_lookups).
    std::string worst;
};

// The GPU's visibility in `result` against the oracle's, over the pixels with geometry.
inline Agreement agreement(const Oracle& oracle, const HeadlessResult& result, Fusion fusion, std::string name) {
    Agreement out;
    out.name = std::move(name);
    double sum = 0;
    std::size_t worst_pixel = 0;
    OracleValue worst_expected;
    for (std::size_t i = 0; i < result.visibility.size(); ++i) {
        if (!result.geometry[i]) continue;
        const OracleValue expected = oracle.visibility(result.positions[i], result.normals[i], fusion);
        const double difference = std::abs(result.visibility[i] - expected.visibility);
        ++out.pixels;
        sum += difference;
        out.max_difference = std::max(out.max_difference, difference);
        out.max_bound = std::max(out.max_bound, expected.bound);
        const double ratio = difference / std::max(expected.bound, 1e-12);
        if (ratio > out.worst_ratio) {
            out.worst_ratio = ratio;
            worst_pixel = i;
            worst_expected = expected;
        }
        out.beyond_bound += difference > expected.bound;
        out.beyond_level_bound += expected.beyond_level_bound;
        out.penumbra_pixels += expected.visibility > 0.02 && expected.visibility < 0.98;
    }
    out.mean_difference = out.pixels ? sum / out.pixels : 0.0;
    if (out.pixels) {
        const std::size_t i = worst_pixel;
        out.worst = "pixel " + std::to_string(i % result.width) + "," + std::to_string(i / result.width) + ": GPU " +
                    std::to_string(result.visibility[i]) + ", oracle " + std::to_string(worst_expected.visibility) + " +- " +
                    std::to_string(worst_expected.bound) + "; by slice (light first): " +
                    oracle.describe_lookups(result.positions[i], result.normals[i]);
    }
    return out;
}

} // namespace penumbra::playground
