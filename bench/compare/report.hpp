// bench/compare/report.hpp — what penumbra-bench-compare writes: results.json's records (how the run was
// made, each scene, costs, error statistics, the signed error, flicker) and the images of the
// representative settings. scripts/compare_report.py reads results.json alone.
#pragma once

#include "frame.hpp"
#include "lights.hpp"
#include "options.hpp"

#include "app/headless_job.hpp"
#include "app/image_io.hpp"
#include "reference/metrics.hpp"
#include "rendering/egl_context.hpp"

#include <penumbra/cost_model.hpp>

#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::bench {

using namespace penumbra::playground;
using json = nlohmann::ordered_json;

// A file-name-safe form of a label: "OT nbuffer 16/512" → "ot-nbuffer-16-512".
inline std::string slug(std::string_view text) {
    std::string out;
    for (char c : text) {
        if (std::isalnum(static_cast<unsigned char>(c))) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        else if (!out.empty() && out.back() != '-') out += '-';
    }
    while (!out.empty() && out.back() == '-') out.pop_back();
    return out;
}

inline std::string scale_text(double scale) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", scale);
    return text;
}

// penumbra/cost_model.hpp's figures for one phase: what a GPU's time follows.
inline json phase_cost_json(const PhaseCost& p) {
    return {{"passes", p.passes}, {"fragments", p.fragments}, {"texel_fetches", p.texel_fetches},
            {"bytes_read", p.bytes_read}, {"bytes_written", p.bytes_written}};
}

// The measured GPU time of the passes from the light (phase "shadow"): every pass but the last (shading).
inline double light_pass_ms(const FrameTimes& t) {
    double sum = 0;
    for (std::size_t i = 0; i + 1 < t.passes.size(); ++i) sum += t.passes[i].milliseconds;
    return sum;
}

inline json stats_json(const ErrorStats& s) {
    return {{"mae", s.mae}, {"rmse", s.rmse}, {"p95", s.p95}, {"pixels", s.count}};
}

// Medians over the timed runs: per pass, the GPU total, and the wall clocks.
inline json cost_json(const std::vector<FrameTimes>& runs) {
    std::vector<int> instances;
    const auto names = pass_totals(runs.front().passes, &instances);
    json passes = json::array();
    for (std::size_t p = 0; p < names.size(); ++p) {
        std::vector<double> ms;
        for (const FrameTimes& r : runs) ms.push_back(pass_totals(r.passes)[p].second);
        passes.push_back({{"name", names[p].first}, {"instances", instances[p]}, {"gpu_ms", median(ms)}});
    }
    std::vector<double> gpu, build, shading, total;
    for (const FrameTimes& r : runs) {
        double sum = 0;
        for (const gl::PassTiming& t : r.passes) sum += t.milliseconds;
        gpu.push_back(sum);
        build.push_back(r.wall_build_ms);
        shading.push_back(r.wall_shading_ms);
        total.push_back(r.wall_build_ms + r.wall_shading_ms);
    }
    return {{"passes", passes},
            {"gpu_ms", median(gpu)},
            {"gpu_ms_fastest", *std::min_element(gpu.begin(), gpu.end())},
            {"wall_ms", {{"shadow_passes", median(build)}, {"shading", median(shading)}, {"total", median(total)}}}};
}

// Mean of estimate − reference over penumbra pixels (either below 0.98, as metrics.cpp counts
// them): positive where a technique is too bright overall (light leaks, missing occluders),
// negative where it is too dark (occlusion counted twice, penumbrae too wide).
inline double penumbra_bias(const std::vector<float>& estimate, const std::vector<unsigned char>& geometry,
                     const std::vector<float>& reference) {
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < estimate.size(); ++i)
        if (geometry[i] && !std::isnan(reference[i]) && (reference[i] < 0.98f || estimate[i] < 0.98f)) {
            sum += static_cast<double>(estimate[i]) - reference[i];
            ++count;
        }
    return count ? sum / count : 0.0;
}

// |Δ visibility| between consecutive frames, averaged over geometry pixels and frame pairs.
inline double mean_frame_delta(const std::vector<std::vector<float>>& frames, const std::vector<unsigned char>& geometry) {
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t f = 1; f < frames.size(); ++f)
        for (std::size_t i = 0; i < geometry.size(); ++i)
            if (geometry[i]) {
                sum += std::abs(static_cast<double>(frames[f][i]) - frames[f - 1][i]);
                ++count;
            }
    return count ? sum / count : 0.0;
}

// Visibility in grey and, with a truth, the signed error (estimate − truth) in false colour; the
// background (no geometry) in a sky colour so that lit ground and sky differ.
inline bool write_visibility_images(const std::string& directory, const std::string& name, const Pixels& pixels,
                             const std::vector<float>& estimate, const std::vector<float>* truth, std::string* error) {
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    const int w = pixels.gbuffer->width(), h = pixels.gbuffer->height();
    const glm::vec3 sky(0.55f, 0.65f, 0.8f), error_background(0.6f);
    std::vector<float> grey(3 * estimate.size()), signed_error(estimate.size());
    for (std::size_t i = 0; i < estimate.size(); ++i) {
        const glm::vec3 c = pixels.frame.geometry[i] ? glm::vec3(estimate[i]) : sky;
        for (int k = 0; k < 3; ++k) grey[3 * i + k] = c[k];
        if (truth) signed_error[i] = estimate[i] - (*truth)[i];
    }
    if (!write_png_rgb(directory + "/" + name + ".png", w, h, grey, RowOrder::top_down, error)) return false;
    if (!truth) return true;
    std::vector<float> colours = signed_error_colors(signed_error, 0.25f);
    for (std::size_t i = 0; i < estimate.size(); ++i)
        if (!pixels.frame.geometry[i])
            for (int k = 0; k < 3; ++k) colours[3 * i + k] = error_background[k];
    return write_png_rgb(directory + "/" + name + ".error.png", w, h, colours, RowOrder::top_down, error);
}

inline std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

// results.json before the first measurement: how the run was made, and empty lists.
inline json results_skeleton(int argc, char** argv, const Options& options, const HeadlessContext& context) {
    std::string command;
    for (int i = 0; i < argc; ++i) command += (i ? " " : "") + std::string(argv[i]);
    json light_scales = json::array(), lights = json::array();
    for (double s : options.light_scales) light_scales.push_back(s);
    for (Light l : options.lights) lights.push_back(std::string(to_string(l)));
    return {
        {"meta",
         {{"tool", "penumbra-bench-compare"},
          {"command", command},
          {"set", options.set == bench::LadderSet::quick ? "quick" : options.set == bench::LadderSet::full ? "full" : "standard"},
          {"started", utc_now()},
          {"renderer", context.renderer()},
          {"gl_version", context.version()},
          {"egl_platform", context.platform()},
          {"image", {options.width, options.height}},
          {"truth_rays_per_axis", options.samples},
          {"timed_runs", options.runs},
          {"warmup_runs", 1},
          {"lights", lights},
          {"light_scales", light_scales},
          {"settings", options.settings.empty() ? json("all") : json(options.settings)},
          {"penumbra_threshold", 0.98},
          {"flicker_frames", options.flicker_frames},
          {"flicker_step_of_ground_span", options.flicker_step},
          {"sun_flicker_step_t", sun_flicker_step},
          {"sun_path", "through each scene's sun at t = 0.5, from 80 degrees of azimuth before it to 80 after, "
                       "10 degrees up at both ends"},
          {"flicker_light_scale", 1.0}}},
        {"scenes", json::array()},
        {"measurements", json::array()},
        {"flicker", json::array()},
        {"bakes", json::array()},
        {"skipped", json::array()},
    };
}

// A scene's entry in results.json; each light's run adds its truth, pixels and light to it.
inline json scene_json(const SceneInput& input, const Scene& scene, double load_ms) {
    json record = {{"name", scene.name},
                   {"kind", input.kind},
                   {"ground", scene.ground},
                   {"triangles", scene.mesh.triangle_count()},
                   {"load_ms", load_ms},
                   {"default_light", {{"width", scene.light.width}, {"height", scene.light.height}}},
                   // the rectangle and camera used (after --light-*, --camera-*), x1 of --light-scales
                   {"light", light_json(scene, Light::rect)},
                   {"camera", camera_json(scene.camera)},
                   {"truth", json::array()}};
    if (input.kind != "built-in") record["file"] = input.name_or_path;
    if (input.corpus)
        record["corpus"] = {{"triangles_in_file", input.corpus->triangles},
                            {"source", input.corpus->source},
                            {"licence", input.corpus->licence}};
    return record;
}

} // namespace penumbra::bench
