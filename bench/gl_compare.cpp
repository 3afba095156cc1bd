// penumbra-bench-compare — every technique against ray-traced truth, at equal time, as the light
// grows. For every scene × light (--lights: the scene's rectangle, its sun, or one run of each) ×
// technique setting (compare/ladder.hpp; a setting that cannot run under the light is skipped with
// its reason) × light size (×1 … ×32 of the scene's default) it measures
//   cost:      GPU time of every pass (GL_TIME_ELAPSED) and the wall clock to glFinish of the
//              shadow passes and of the shading pass, medians of --runs runs after one warm-up run
//              (llvmpipe compiles a shader variant at its first draw), and the texture memory. The
//              runs of one scene and light size are interleaved (run 1 of every setting, then run
//              2, ...) so that load from other processes affects the settings alike;
//   quality:   MAE, RMSE and p95 |error| against the Embree ground truth at the same pixels, over
//              penumbra pixels (truth or estimate < 0.98) and over all geometry pixels;
//   stability: for the representative settings, the light moves slowly over --flicker-frames
//              frames; excess flicker = mean |Δ visibility| between consecutive frames minus
//              that of the truth, so the shadow's real motion is not counted.
// It writes DIR/results.json (every number; scripts/compare_report.py builds the report from it
// alone) and DIR/images/ (visibility and signed error of the representative settings).
// The ground truth is cached in DIR/cache/ (it does not depend on the technique), and the bakes of
// occlusion interval maps (the sun only) in DIR/cache/oim/; a bake's time is a precomputation,
// recorded apart from the frame's cost.
// Scenes: the built-in ones, mesh files, and with --corpus the real meshes of the corpus
// (scripts/get_corpus.sh), whose names, sources and licences results.json carries.
//
//   penumbra-bench-compare [--quick | --full] [--scenes a,b] [FILE ...] [--corpus [DIR]] [--settings a,b]
//                          [--size N] [--samples N] [--runs N] [--lights rect,sun] [--light-scales 1,2,4] [--flicker-frames N]
//                          [--out DIR]
#include "arguments.hpp"
#include "compare/frame.hpp"
#include "compare/ladder.hpp"
#include "compare/progress.hpp"
#include "compare/truth_cache.hpp"
#include "corpus/manifest.hpp"

#include "app/headless_job.hpp"
#include "app/image_io.hpp"
#include "bake/oim_scene.hpp"
#include "reference/metrics.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/gpu_scene.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/config_fields.hpp>
#include <penumbra_tools/file_transaction.hpp>

#include <penumbra/cost_model.hpp>
#include <penumbra/gl/runtime.hpp>
#include <penumbra/layout.hpp>
#include <penumbra/sun_path.hpp>
#include <penumbra/texture_memory.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

using namespace penumbra;
using namespace penumbra::playground;
using json = nlohmann::ordered_json;
using bench::FrameTimes;
using bench::median;
using bench::milliseconds_since;
using bench::pass_totals;
using bench::Pixels;
using bench::read_visibility;
using bench::render_pixels;
using bench::run_frame;

namespace {

using bench::parse_number;
using bench::split;

// One scene to run: a built-in name, a mesh file, or a corpus mesh (a file with its manifest entry).
struct SceneInput {
    std::string name_or_path;
    std::string kind; // "built-in", "file" or "corpus"
    std::optional<bench::CorpusMesh> corpus;
};

struct Options {
    bench::LadderSet set = bench::LadderSet::standard;
    std::vector<SceneInput> scenes;  // built-in scenes, then files, then the corpus, in order
    std::vector<std::string> settings; // ladder labels to keep (empty: the whole ladder)
    int width = 128, height = 128;
    int samples = 32;                // ground-truth rays per light axis
    int runs = 7;                    // timed runs per measurement, after one warm-up run
    std::vector<double> light_scales{1, 2, 4, 8, 16, 32};
    std::vector<Light> lights{Light::rect}; // --lights: each a run of the whole ladder, in this order
    int flicker_frames = 8;
    double flicker_step = 0.005;     // light motion per frame, as a fraction of the scene's ground span
    std::string out_dir = "out/compare";
    bool ground = true;              // --no-ground: no floor under the mesh files
};

constexpr const char* usage_text =
    "usage: penumbra-bench-compare [--quick | --full] [--scenes a,b,...] [FILE ...] [--corpus [DIR]] [--no-ground]\n"
    "                              [--settings a,b,...] [--size N|WxH] [--samples N] [--runs N]\n"
    "                              [--lights rect,sun] [--light-scales 1,2,...] [--flicker-frames N] [--out DIR]\n"
    "  (default)         every built-in scene, the standard ladder under each scene's rectangle light,\n"
    "                    light x1 x2 x4 x8 x16 x32, 128x128,\n"
    "                    32x32 rays, 7 runs, 8 flicker frames (about 30 minutes on 2 llvmpipe cores)\n"
    "  --quick           boxes only, two settings, light x1 and x4, 64x64, 8x8 rays, 4 flicker frames\n"
    "                    (a smoke test: the report states the ray count)\n"
    "  --full            the full ladder (adds 1024-texel settings and OIM 8/256), 256x256, 16 flicker frames\n"
    "  --scenes          built-in scenes, comma-separated (default all: see penumbra-playground --help;\n"
    "                    --scenes '' for none, e.g. to run only files or the corpus)\n"
    "  FILE              mesh files (what penumbra-playground --scene loads), added to the scenes: light\n"
    "                    and camera from their bounds\n"
    "  --no-ground       no floor under the mesh files and the corpus (default: each stands on one, as in\n"
    "                    penumbra-playground)\n"
    "  --corpus [DIR]    adds every mesh of the corpus in DIR (default ~/.cache/penumbra/corpus, or\n"
    "                    $XDG_CACHE_HOME/penumbra/corpus), fetched by scripts/get_corpus.sh\n"
    "  --settings        only these ladder settings, by label, comma-separated (e.g. 'OT nbuffer 16/512,\n"
    "                    PCSS 16/16'; default the whole ladder of the set: occlusion textures, hard shadow\n"
    "                    map, PCF, PCSS, 'erosion r16' and 'OIM 8/128' (intervals/resolution, sun only))\n"
    "  --lights          the lights the ladder runs under, each a run of its own, comma-separated: rect\n"
    "                    (each scene's rectangle, the default), sun (each scene's sun, on a path through\n"
    "                    it: occlusion interval maps run only under it and bake it once into DIR/cache/oim,\n"
    "                    a precomputation timed apart from the frame). A setting that cannot run under a\n"
    "                    light is skipped with its reason (printed and in results.json)\n"
    "  --size            image size (square N or WxH, 16 to 1024)\n"
    "  --samples         ground-truth rays per light axis, 1 to 128 (the truth uses N x N stratified rays)\n"
    "  --runs            timed runs per measurement after one warm-up run, 1 to 100 (medians reported)\n"
    "  --light-scales    multiples of each scene's default light size (the rectangle's sides, the sun's\n"
    "                    angular diameter), each > 0 and <= 64\n"
    "  --flicker-frames  frames of the slowly moving light for the flicker measurement, 2 to 64\n"
    "  --out             output folder (default out/compare): results.json, images/, cache/ (the truth;\n"
    "                    cache/oim: the bakes of occlusion interval maps)\n"
    "flags after --quick or --full override what they set.\n";

// Options from argv, or an error message (one line).
std::optional<Options> parse(int argc, char** argv, std::string& error) {
    Options o;
    std::vector<std::string> built_in;
    std::vector<SceneInput> files, corpus;
    std::vector<std::string> settings;
    bool scenes_given = false;
    auto fail = [&](std::string message) {
        error = std::move(message);
        return std::nullopt;
    };
    for (int i = 1; i < argc; ++i) {
        const std::string_view flag = argv[i];
        if (flag == "--quick") {
            o.set = bench::LadderSet::quick;
            built_in = {"boxes"};
            o.width = o.height = 64;
            o.samples = 8;
            o.light_scales = {1, 4};
            o.flicker_frames = 4;
            continue;
        }
        if (flag == "--no-ground") {
            o.ground = false;
            continue;
        }
        if (flag == "--full") {
            o.set = bench::LadderSet::full;
            o.width = o.height = 256;
            o.flicker_frames = 16;
            continue;
        }
        if (!flag.starts_with("--")) { // a mesh file: load_scene says whether it can read it
            files.push_back({std::string(flag), "file", std::nullopt});
            continue;
        }
        if (flag == "--corpus") {
            const std::string dir = bench::corpus_dir_argument(argc, argv, i);
            std::optional<std::vector<bench::CorpusMesh>> meshes = bench::read_corpus(dir, &error);
            if (!meshes) return std::nullopt;
            for (bench::CorpusMesh& m : *meshes) corpus.push_back({m.path, "corpus", std::move(m)});
            continue;
        }
        constexpr std::string_view valued[] = {"--scenes", "--size", "--samples", "--runs", "--flicker-frames",
                                               "--light-scales", "--lights", "--out", "--settings"};
        if (std::find(std::begin(valued), std::end(valued), flag) == std::end(valued))
            return fail("unknown flag '" + std::string(flag) +
                        "'; allowed: --quick, --full, --scenes, --corpus, --no-ground, --settings, --size, --samples, --runs, "
                        "--light-scales, --lights, --flicker-frames, --out, --help, FILE");
        if (i + 1 >= argc) return fail(std::string(flag) + ": missing value (see --help)");
        const std::string_view value = argv[++i];
        if (flag == "--scenes") {
            built_in.clear();
            scenes_given = true;
            for (std::string_view name : split(value)) {
                if (!make_scene(name)) {
                    std::string allowed;
                    for (std::string_view n : scene_names()) allowed += (allowed.empty() ? "" : ", ") + std::string(n);
                    return fail("--scenes: unknown scene '" + std::string(name) + "'; allowed: " + allowed);
                }
                built_in.emplace_back(name);
            }
        } else if (flag == "--settings") {
            settings.clear();
            for (std::string_view label : split(value)) {
                while (label.starts_with(' ')) label.remove_prefix(1);
                while (label.ends_with(' ')) label.remove_suffix(1);
                if (!label.empty()) settings.emplace_back(label);
            }
            if (settings.empty()) return fail("--settings: empty; allowed: labels of the ladder, e.g. 'OT nbuffer 16/512,PCSS 16/16'");
        } else if (flag == "--size") {
            const std::size_t x = value.find('x');
            const bool ok = x == std::string_view::npos
                                ? parse_number(value, o.width) && (o.height = o.width, true)
                                : parse_number(value.substr(0, x), o.width) && parse_number(value.substr(x + 1), o.height);
            if (!ok || o.width < 16 || o.height < 16 || o.width > 1024 || o.height > 1024)
                return fail("--size: '" + std::string(value) + "' is not allowed; allowed: N or WxH, 16 to 1024 each");
        } else if (flag == "--samples") {
            if (!parse_number(value, o.samples) || o.samples < 1 || o.samples > 128)
                return fail("--samples: '" + std::string(value) + "' is not allowed; allowed: 1 to 128");
        } else if (flag == "--runs") {
            if (!parse_number(value, o.runs) || o.runs < 1 || o.runs > 100)
                return fail("--runs: '" + std::string(value) + "' is not allowed; allowed: 1 to 100");
        } else if (flag == "--flicker-frames") {
            if (!parse_number(value, o.flicker_frames) || o.flicker_frames < 2 || o.flicker_frames > 64)
                return fail("--flicker-frames: '" + std::string(value) + "' is not allowed; allowed: 2 to 64");
        } else if (flag == "--light-scales") {
            o.light_scales.clear();
            for (std::string_view part : split(value)) {
                double scale = 0;
                if (!parse_number(part, scale) || !(scale > 0) || scale > 64)
                    return fail("--light-scales: '" + std::string(part) + "' is not allowed; allowed: numbers above 0, at most 64");
                o.light_scales.push_back(scale);
            }
            if (o.light_scales.empty()) return fail("--light-scales: empty; allowed: numbers above 0, at most 64");
        } else if (flag == "--lights") {
            o.lights.clear();
            for (std::string_view part : split(value)) {
                const std::optional<Light> light = parse_enum<Light>(part);
                if (!light || std::find(o.lights.begin(), o.lights.end(), *light) != o.lights.end())
                    return fail("--lights: '" + std::string(part) + "' is not allowed; allowed: rect, sun, each once");
                o.lights.push_back(*light);
            }
            if (o.lights.empty()) return fail("--lights: empty; allowed: rect, sun or rect,sun");
        } else { // --out
            if (value.empty()) return fail("--out: empty; allowed: a folder");
            o.out_dir = std::string(value);
        }
    }
    if (built_in.empty() && !scenes_given && o.set != bench::LadderSet::quick)
        for (std::string_view n : scene_names()) built_in.emplace_back(n);
    for (const std::string& name : built_in) o.scenes.push_back({name, "built-in", std::nullopt});
    o.scenes.insert(o.scenes.end(), files.begin(), files.end());
    o.scenes.insert(o.scenes.end(), corpus.begin(), corpus.end());
    if (o.scenes.empty()) return fail("no scene: give --scenes, a mesh file or --corpus");
    // The ladder's labels are known only with the set, after every flag.
    const std::vector<bench::LadderEntry> ladder = bench::technique_ladder(o.set);
    for (const std::string& label : settings)
        if (std::none_of(ladder.begin(), ladder.end(), [&](const bench::LadderEntry& e) { return e.label == label; })) {
            std::string allowed;
            for (const bench::LadderEntry& e : ladder) allowed += (allowed.empty() ? "" : ", ") + e.label;
            return fail("--settings: '" + label + "' is not a setting of this set's ladder; allowed: " + allowed);
        }
    o.settings = settings;
    return o;
}

// A file-name-safe form of a label: "OT nbuffer 16/512" → "ot-nbuffer-16-512".
std::string slug(std::string_view text) {
    std::string out;
    for (char c : text) {
        if (std::isalnum(static_cast<unsigned char>(c))) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        else if (!out.empty() && out.back() != '-') out += '-';
    }
    while (!out.empty() && out.back() == '-') out.pop_back();
    return out;
}

std::string scale_text(double scale) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", scale);
    return text;
}

// penumbra/cost_model.hpp's figures for one phase: what a GPU's time follows.
json phase_cost_json(const PhaseCost& p) {
    return {{"passes", p.passes}, {"fragments", p.fragments}, {"texel_fetches", p.texel_fetches},
            {"bytes_read", p.bytes_read}, {"bytes_written", p.bytes_written}};
}

// The measured GPU time of the passes from the light (phase "shadow"): every pass but the last (shading).
double light_pass_ms(const FrameTimes& t) {
    double sum = 0;
    for (std::size_t i = 0; i + 1 < t.passes.size(); ++i) sum += t.passes[i].milliseconds;
    return sum;
}

json stats_json(const ErrorStats& s) {
    return {{"mae", s.mae}, {"rmse", s.rmse}, {"p95", s.p95}, {"pixels", s.count}};
}

// Medians over the timed runs: per pass, the GPU total, and the wall clocks.
json cost_json(const std::vector<FrameTimes>& runs) {
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
double penumbra_bias(const std::vector<float>& estimate, const std::vector<unsigned char>& geometry,
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
double mean_frame_delta(const std::vector<std::vector<float>>& frames, const std::vector<unsigned char>& geometry) {
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

RectLight scaled_light(const RectLight& light, double scale) {
    RectLight out = light;
    out.width *= scale;
    out.height *= scale;
    return out;
}

// Frame f of the flicker sequence: the light's centre moved along its u axis.
RectLight moved_light(const RectLight& light, double step, int frame) {
    RectLight out = light;
    out.center += light.u_axis * (step * frame);
    return out;
}

double ground_span(const Scene& scene) {
    return std::max(scene.bounds_max.x - scene.bounds_min.x, scene.bounds_max.z - scene.bounds_min.z);
}

// Visibility in grey and, with a truth, the signed error (estimate − truth) in false colour; the
// background (no geometry) in a sky colour so that lit ground and sky differ.
bool write_visibility_images(const std::string& directory, const std::string& name, const Pixels& pixels,
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

std::string utc_now() {
    const std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

// The sun moves this far along its path (in t, 0 to 1) per flicker frame: about 0.3 degrees.
constexpr double sun_flicker_step = 0.002;

// The sun's path for a scene's sun, through it at t = 0.5, from 80 degrees of azimuth before it to
// 80 after it, 10 degrees above the horizon at both ends: what occlusion interval maps bake. Every
// setting under the sun sees the same sun, at the same t.
SunPath path_through(const SunLight& sun) {
    const glm::dvec3 to_sun = -glm::normalize(sun.direction);
    const double elevation = glm::degrees(std::asin(std::clamp(to_sun.y, -1.0, 1.0)));
    const double azimuth = glm::degrees(std::atan2(to_sun.x, -to_sun.z)); // clockwise from north (-z)
    return {{{azimuth - 80.0, 10.0}, {azimuth, elevation}, {azimuth + 80.0, 10.0}}};
}

// One light of a measurement: the scene's rectangle or its sun at a multiple of its size (the
// rectangle's sides, the sun's angular diameter), at frame `frame` of the flicker motion (the
// rectangle moves along its u axis by rect_step per frame, the sun along its path).
struct LightAt {
    RectLight rect;
    SunLight sun;
    double t = 0.5; // the sun's time on its path
};

LightAt light_at(const Scene& scene, const SunPath& path, double scale, double rect_step, int frame) {
    LightAt l{moved_light(scaled_light(scene.light, scale), rect_step, frame), scene.sun, 0.5 + sun_flicker_step * frame};
    l.sun.direction = -sun_direction(path, l.t);
    l.sun.angular_diameter *= scale;
    return l;
}

void set_light(gl::Runtime& runtime, const Scene& scene, Light kind, const SunPath& path, const LightAt& l, bool oim) {
    if (kind == Light::sun) runtime.set_light(l.sun, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
    else runtime.set_light(l.rect, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
    if (oim) runtime.set_time_window(oim_time_window(path, l.t, l.sun.angular_diameter));
}

// One setting of the ladder as it runs under one light: its runtime and, for occlusion interval
// maps, the bake and the scene with the charts it was baked on (its own mesh and G-buffer, of the
// same pixels as the others').
struct Active {
    const bench::LadderEntry* entry = nullptr;
    std::unique_ptr<gl::Runtime> runtime;
    std::vector<std::unique_ptr<gl::Runtime>> later_frames; // a temporal variant's frames 1 to N-1 (smrt.frame)
    std::optional<OimSetup> oim;
    std::unique_ptr<MeshBuffers> oim_mesh;
    std::optional<Pixels> oim_pixels;
    json config;
    std::uint64_t texture_bytes = 0;
};

using penumbra::cli::fail;

// The settings of the ladder that --settings keeps (all without it).
std::vector<bench::LadderEntry> selected_ladder(const Options& options) {
    std::vector<bench::LadderEntry> ladder = bench::technique_ladder(options.set);
    if (!options.settings.empty())
        std::erase_if(ladder, [&](const bench::LadderEntry& e) {
            return std::find(options.settings.begin(), options.settings.end(), e.label) == options.settings.end();
        });
    return ladder;
}

// Every scene of the run, named for the report, with the time its loading took.
struct LoadedScenes {
    std::vector<Scene> scenes;
    std::vector<double> load_ms;
};

// The scenes, or the loader's error (bad input: exit status 2).
std::optional<LoadedScenes> load_scenes(const Options& options, std::string* error) {
    LoadedScenes out;
    for (const SceneInput& input : options.scenes) {
        const auto load_start = std::chrono::steady_clock::now();
        SceneLoad loaded = load_scene(input.name_or_path, options.ground);
        if (!loaded.scene) {
            *error = loaded.error;
            return std::nullopt;
        }
        out.load_ms.push_back(milliseconds_since(load_start));
        if (input.corpus) loaded.scene->name = input.corpus->name;
        else if (input.kind == "file") loaded.scene->name = std::filesystem::path(input.name_or_path).stem().string();
        out.scenes.push_back(std::move(*loaded.scene));
    }
    return out;
}

// How many steps of each kind the run takes, for the progress lines and their time estimate.
void plan_progress(bench::Progress& progress, const Options& options, std::size_t scene_count,
                   const std::vector<bench::LadderEntry>& ladder) {
    int representatives = 0, oim_settings = 0;
    for (const bench::LadderEntry& e : ladder) {
        representatives += e.representative;
        oim_settings += e.config.technique == Technique::oim;
    }
    const int scale_count = static_cast<int>(options.light_scales.size());
    const int runs_of_ladder = static_cast<int>(scene_count * options.lights.size()); // scene × light
    progress.plan("truth", runs_of_ladder * (scale_count + options.flicker_frames));
    progress.plan("warm-up", runs_of_ladder * static_cast<int>(ladder.size()) * scale_count);
    progress.plan("timed round", runs_of_ladder * scale_count * options.runs);
    progress.plan("flicker", runs_of_ladder * representatives);
    if (std::find(options.lights.begin(), options.lights.end(), Light::sun) != options.lights.end())
        progress.plan("bake", static_cast<int>(scene_count) * oim_settings);
}

// results.json before the first measurement: how the run was made, and empty lists.
json results_skeleton(int argc, char** argv, const Options& options, const HeadlessContext& context) {
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
json scene_json(const SceneInput& input, const Scene& scene, double load_ms) {
    json record = {{"name", scene.name},
                   {"kind", input.kind},
                   {"ground", scene.ground},
                   {"triangles", scene.mesh.triangle_count()},
                   {"load_ms", load_ms},
                   {"default_light", {{"width", scene.light.width}, {"height", scene.light.height}}},
                   {"truth", json::array()}};
    if (input.kind != "built-in") record["file"] = input.name_or_path;
    if (input.corpus)
        record["corpus"] = {{"triangles_in_file", input.corpus->triangles},
                            {"source", input.corpus->source},
                            {"licence", input.corpus->licence}};
    return record;
}

// Where the run writes: results.json in `out`, the truth and the bakes in `cache`, the images in `images`.
struct OutputDirs {
    std::string out, cache, images;
};

// One run of the ladder: one scene under one kind of light. Its steps, in order (run()): the
// G-buffer, the truth for every light size and flicker frame, a runtime for every setting that can
// run under the light, every light size measured, then the flicker of the representative settings.
// Each step returns "" or the message that ends the program.
class LightRun {
public:
    LightRun(const Options& options, const OutputDirs& dirs, bench::Progress& progress, json& results,
             json& scene_record, const Scene& scene, Light light_kind)
        : options_(options), dirs_(dirs), progress_(progress), results_(results), scene_record_(scene_record),
          scene_(scene), path_(path_through(scene.sun)), light_kind_(light_kind), lit_by_(to_string(light_kind)),
          light_dir_(light_kind == Light::sun ? "/sun" : "") {
        // Under the sun: the scene's sun on the path through it at t = 0.5.
        if (light_kind_ == Light::sun) scene_.sun.direction = -sun_direction(path_, 0.5);
        mesh_ = std::make_unique<MeshBuffers>(scene_.mesh);
        step_ = options_.flicker_step * ground_span(scene_);
    }

    std::string run(const std::vector<bench::LadderEntry>& ladder) {
        if (std::string e = render_gbuffer(); !e.empty()) return e;
        if (std::string e = trace_truths(); !e.empty()) return e;
        if (std::string e = start_settings(ladder); !e.empty()) return e;
        for (std::size_t s = 0; s < options_.light_scales.size(); ++s)
            if (std::string e = measure_light_size(s); !e.empty()) return e;
        if (std::string e = measure_flicker(); !e.empty()) return e;
        progress_.finish();
        return {};
    }

private:
    // The positions and normals every setting shades, and the geometry mask every metric counts.
    std::string render_gbuffer() {
        std::string error;
        pixels_ = render_pixels(scene_, *mesh_, options_.width, options_.height, &error);
        if (!pixels_) return scene_.name + ": " + error;
        std::size_t geometry_pixels = 0;
        for (unsigned char g : pixels_->frame.geometry) geometry_pixels += g;
        scene_record_["geometry_pixels"] = geometry_pixels;
        return {};
    }

    // The truth for every light size and every flicker frame, from the cache where it can be.
    std::string trace_truths() {
        std::string error;
        Scene lit = scene_; // the scene under the light being traced
        auto truth_for = [&](const LightAt& light, const std::string& what) -> std::optional<bench::CachedTruth> {
            progress_.step("truth", scene_.name + ": ground truth, " + lit_by_ + " " + what);
            lit.light = light.rect;
            lit.sun = light.sun;
            std::optional<bench::CachedTruth> t =
                bench::cached_truth(dirs_.cache, lit, pixels_->frame, options_.samples, &error, light_kind_);
            if (t) scene_record_["truth"].push_back({{"light", lit_by_}, {"for", what},
                                                     {"file", std::filesystem::relative(t->file, dirs_.out).string()},
                                                     {"cached", t->from_cache}, {"ms", t->milliseconds}});
            return t;
        };
        for (double scale : options_.light_scales) {
            std::optional<bench::CachedTruth> t =
                truth_for(light_at(scene_, path_, scale, step_, 0), "light x" + scale_text(scale));
            if (!t) return scene_.name + ": " + error;
            if (!write_visibility_images(dirs_.images + "/" + scene_.name + light_dir_ + "/x" + scale_text(scale),
                                         "truth", *pixels_, t->references.visibility, nullptr, &error))
                return error;
            truths_.push_back(std::move(t->references));
        }
        for (int f = 0; f < options_.flicker_frames; ++f) {
            std::optional<bench::CachedTruth> t =
                truth_for(light_at(scene_, path_, 1.0, step_, f), "flicker frame " + std::to_string(f + 1));
            if (!t) return scene_.name + ": " + error;
            truth_frames_.push_back(std::move(t->references.visibility));
        }
        progress_.finish();
        truth_delta_ = mean_frame_delta(truth_frames_, pixels_->frame.geometry);
        if (light_kind_ == Light::sun) {
            json points = json::array();
            for (const SunPathPoint& p : path_.points) points.push_back({p.azimuth_degrees, p.elevation_degrees});
            scene_record_["sun"] = {{"direction", {scene_.sun.direction.x, scene_.sun.direction.y, scene_.sun.direction.z}},
                                    {"angular_diameter", scene_.sun.angular_diameter},
                                    {"path_azimuth_elevation_degrees", points},
                                    {"flicker_step_t", sun_flicker_step},
                                    {"truth_flicker", truth_delta_}};
        } else {
            scene_record_["flicker_step"] = step_;
            scene_record_["truth_flicker"] = truth_delta_;
        }
        return {};
    }

    void skip(const bench::LadderEntry& entry, const std::string& where, const std::string& why) {
        std::printf("skip: %s: %s\n", where.c_str(), why.c_str());
        results_["skipped"].push_back({{"scene", scene_.name}, {"light", lit_by_}, {"label", entry.label}, {"reason", why}});
    }

    // Occlusion interval maps: the bake (or its cache) on the scene with the charts it needs, and
    // the mesh and G-buffer of those charts. False with *why when the bake fails (the setting is
    // skipped); a G-buffer that fails ends the program (*fatal).
    bool bake(Active& a, const Config& config, const std::string& where, std::string* why, std::string* fatal) {
        progress_.step("bake", scene_.name + ": occlusion interval maps, bake of " + a.entry->label);
        Scene charted = scene_;
        std::string error;
        a.oim = prepare_oim(charted, config, path_, 0.5, dirs_.cache + "/oim", &error);
        if (!a.oim) {
            *why = "no bake: " + error;
            return false;
        }
        progress_.finish();
        const OimBake& b = a.oim->cached.bake;
        std::printf("bake: %s: %dx%d, %d intervals, %d samples, %s %s (%.0f ms to bake, %llu rays)\n", where.c_str(),
                    b.resolution, b.resolution, b.intervals, b.samples, a.oim->cached.from_cache ? "read" : "baked into",
                    a.oim->cached.file.string().c_str(), b.bake_ms, static_cast<unsigned long long>(b.rays));
        if (!a.oim->cached.warning.empty()) std::cerr << "warning: " << a.oim->cached.warning << "\n";
        results_["bakes"].push_back({{"scene", scene_.name}, {"light", lit_by_}, {"label", a.entry->label},
                                     {"resolution", b.resolution}, {"intervals", b.intervals}, {"samples", b.samples},
                                     {"from_cache", a.oim->cached.from_cache}, {"bake_ms", b.bake_ms},
                                     {"rays", b.rays}, {"merged_texels", b.merged_texels},
                                     {"file", std::filesystem::relative(a.oim->cached.file, dirs_.out).string()},
                                     {"file_bytes", a.oim->cached.file_bytes}});
        a.oim_mesh = std::make_unique<MeshBuffers>(charted.mesh);
        a.oim_pixels = render_pixels(charted, *a.oim_mesh, options_.width, options_.height, &error);
        if (!a.oim_pixels) *fatal = where + ": " + error;
        return true;
    }

    // One runtime per setting that can run under this light, alive together, so that the timed
    // runs can be interleaved; the others skipped with their reason.
    std::string start_settings(const std::vector<bench::LadderEntry>& ladder) {
        std::string error;
        for (const bench::LadderEntry& entry : ladder) {
            const std::string where = scene_.name + ", " + lit_by_ + " light, " + entry.label;
            if (const std::string why = bench::refusal(entry, light_kind_); !why.empty()) {
                skip(entry, where, why);
                continue;
            }
            Active a;
            a.entry = &entry;
            Config config = entry.config;
            config.light = light_kind_;
            config.alpha_test = scene_.mesh.cuts(); // cut-out casters cast as their materials cut
            const bool oim = config.technique == Technique::oim;
            if (oim) {
                std::string why, fatal;
                if (!bake(a, config, where, &why, &fatal)) {
                    skip(entry, where, why);
                    continue;
                }
                if (!fatal.empty()) return fatal;
            }
            a.runtime = gl::Runtime::create(config, &error);
            if (!a.runtime) return where + ": " + error;
            for (int f = 1; f < entry.accumulate; ++f) { // the temporal variant: one program per turn of the pattern
                Config frame = config;
                frame.smrt.frame = f;
                a.later_frames.push_back(gl::Runtime::create(frame, &error));
                if (!a.later_frames.back()) return where + ", frame " + std::to_string(f) + ": " + error;
            }
            if (oim)
                for (const auto& [name, texels] : a.oim->textures)
                    if (std::string d = a.runtime->supply_texture(name, texels); !d.empty()) return where + ": " + d;
            const Layout& layout = a.runtime->layout();
            a.texture_bytes = static_cast<std::uint64_t>(penumbra::texture_bytes(layout, options_.width, options_.height));
            a.config = json::parse(config_to_json(layout.config));
            active_.push_back(std::move(a));
        }
        return {};
    }

    // Frame f's runtime of a setting: a temporal variant turns its pattern per frame (f mod N).
    gl::Runtime& runtime_of(Active& a, int f) {
        const int n = static_cast<int>(a.later_frames.size()) + 1;
        const int k = ((f % n) + n) % n;
        return k == 0 ? *a.runtime : *a.later_frames[static_cast<std::size_t>(k - 1)];
    }

    // The visibility of frame f of a setting under `light` (a temporal variant: that frame's pattern).
    std::optional<std::vector<float>> frame_visibility(Active& a, int f, const LightAt& light, std::string* error) {
        gl::Runtime& runtime = runtime_of(a, f);
        set_light(runtime, scene_, light_kind_, path_, light, a.oim.has_value());
        FrameTimes times;
        if (!run_frame(runtime, mesh_of(a), pixels_of(a), times, error)) return std::nullopt;
        return read_visibility(runtime, pixels_of(a));
    }

    // Occlusion interval maps draw their own mesh (with the charts' texture coordinates) into their own G-buffer.
    const MeshBuffers& mesh_of(const Active& a) const { return a.oim_mesh ? *a.oim_mesh : *mesh_; }
    const Pixels& pixels_of(const Active& a) const { return a.oim_pixels ? *a.oim_pixels : *pixels_; }

    // What one light size measured for every active setting.
    struct Cell {
        double scale = 1.0;
        std::string where, image_cell; // "boxes, rect x4"; "boxes/x4" (images/<scene>[/sun]/x<scale>)
        std::vector<QualityMetrics> quality;
        std::vector<double> bias, bias_oriented;
        std::vector<std::vector<FrameTimes>> timed;
        std::vector<CostModel> costs;
    };

    // One light size: the warm-up run of every setting (its quality, cost model and images), the
    // timed runs, then one measurement record per setting.
    std::string measure_light_size(std::size_t s) {
        Cell cell;
        cell.scale = options_.light_scales[s];
        cell.where = scene_.name + ", " + lit_by_ + " x" + scale_text(cell.scale);
        cell.image_cell = scene_.name + light_dir_ + "/x" + scale_text(cell.scale);
        cell.quality.resize(active_.size());
        cell.bias.resize(active_.size());
        cell.bias_oriented.resize(active_.size());
        cell.timed.resize(active_.size());
        cell.costs.resize(active_.size());
        if (std::string e = warm_up(cell, truths_[s]); !e.empty()) return e;
        if (std::string e = timed_rounds(cell); !e.empty()) return e;
        for (std::size_t e = 0; e < active_.size(); ++e) record_measurement(cell, e);
        return {};
    }

    std::string warm_up(Cell& cell, const References& truth) {
        std::string error;
        for (std::size_t e = 0; e < active_.size(); ++e) {
            Active& a = active_[e];
            const bench::LadderEntry& entry = *a.entry;
            progress_.step("warm-up", cell.where + ": warm-up and quality, " + entry.label);
            set_light(*a.runtime, scene_, light_kind_, path_, light_at(scene_, path_, cell.scale, step_, 0), a.oim.has_value());
            FrameTimes warmup;
            if (!run_frame(*a.runtime, mesh_of(a), pixels_of(a), warmup, &error)) return entry.label + ": " + error;
            // set_light fitted level_bound to this light: memory, configuration and cost as they run
            a.texture_bytes = static_cast<std::uint64_t>(penumbra::texture_bytes(a.runtime->layout(), options_.width, options_.height));
            a.config = json::parse(config_to_json(a.runtime->layout().config));
            cell.costs[e] = cost_model(a.runtime->layout(), options_.width, options_.height);
            std::vector<float> visibility = read_visibility(*a.runtime, pixels_of(a));
            if (!a.later_frames.empty()) { // a temporal variant under a still light: the mean of its N frames
                for (int f = 1; f <= static_cast<int>(a.later_frames.size()); ++f) {
                    const std::optional<std::vector<float>> v =
                        frame_visibility(a, f, light_at(scene_, path_, cell.scale, step_, 0), &error);
                    if (!v) return entry.label + ": " + error;
                    for (std::size_t i = 0; i < visibility.size(); ++i) visibility[i] += (*v)[i];
                }
                for (float& v : visibility) v /= static_cast<float>(a.later_frames.size() + 1);
            }
            const std::vector<unsigned char>& geometry = pixels_->frame.geometry;
            cell.quality[e] = compare_quality(visibility, geometry, truth.visibility, truth.oriented, truth.irradiance);
            cell.bias[e] = penumbra_bias(visibility, geometry, truth.visibility);
            cell.bias_oriented[e] = penumbra_bias(visibility, geometry, truth.oriented);
            if (entry.representative &&
                !write_visibility_images(dirs_.images + "/" + cell.image_cell, slug(entry.label), *pixels_, visibility,
                                         &truth.visibility, &error))
                return error;
        }
        return {};
    }

    // Round-robin: run r of every setting, then run r + 1. A burst of load from other processes
    // then slows every setting of the cell alike, and the ratios survive it.
    std::string timed_rounds(Cell& cell) {
        std::string error;
        for (int r = 0; r < options_.runs; ++r) {
            progress_.step("timed round", cell.where + ": timed run " + std::to_string(r + 1) + "/" +
                                              std::to_string(options_.runs) + " of every setting");
            for (std::size_t e = 0; e < active_.size(); ++e) {
                FrameTimes t;
                if (!run_frame(*active_[e].runtime, mesh_of(active_[e]), pixels_of(active_[e]), t, &error))
                    return active_[e].entry->label + ": " + error;
                cell.timed[e].push_back(std::move(t));
            }
        }
        return {};
    }

    // Setting e's record of the cell in results.json, and its line on stdout.
    void record_measurement(const Cell& cell, std::size_t e) {
        const Active& a = active_[e];
        const bench::LadderEntry& entry = *a.entry;
        const double scale = cell.scale;
        json record = {{"scene", scene_.name}, {"ground", scene_.ground},
                       {"light", lit_by_},
                       {"family", entry.family},
                       {"label", entry.label},
                       {"representative", entry.representative},
                       {"light_scale", scale}};
        if (light_kind_ == Light::sun) record["sun_angular_diameter"] = scene_.sun.angular_diameter * scale;
        else record["light_size"] = {scene_.light.width * scale, scene_.light.height * scale};
        record["config"] = a.config;
        if (entry.accumulate > 1) record["accumulate_frames"] = entry.accumulate; // time: one frame's
        record["texture_bytes"] = a.texture_bytes;
        if (a.oim) // a precomputation, like the truth: not in the frame's cost
            record["bake"] = {{"ms", a.oim->cached.bake.bake_ms}, {"from_cache", a.oim->cached.from_cache}};
        record.update(cost_json(cell.timed[e]));
        std::vector<double> light_ms;
        for (const FrameTimes& t : cell.timed[e]) light_ms.push_back(light_pass_ms(t));
        record["light_passes_gpu_ms"] = median(light_ms);
        const CostModel& cost = cell.costs[e];
        record["cost_model"] = {{"shadow", phase_cost_json(cost.shadow)}, {"screen", phase_cost_json(cost.screen)}};
        // "all"/"penumbra": against the visibility of the whole light (rays behind the
        // receiver's tangent plane blocked); the fair references beside it.
        const QualityMetrics& q = cell.quality[e];
        record["quality"] = {{"all", stats_json(q.visibility.all)},
                             {"penumbra", stats_json(q.visibility.penumbra)},
                             {"penumbra_bias", cell.bias[e]},
                             {"oriented", {{"all", stats_json(q.oriented.all)}, {"penumbra", stats_json(q.oriented.penumbra)},
                                           {"penumbra_bias", cell.bias_oriented[e]}}},
                             {"irradiance", {{"all", stats_json(q.irradiance.all)}, {"penumbra", stats_json(q.irradiance.penumbra)}}}};
        if (entry.representative) {
            const std::string dir = "images/" + cell.image_cell;
            record["images"] = {{"visibility", dir + "/" + slug(entry.label) + ".png"},
                                {"error", dir + "/" + slug(entry.label) + ".error.png"},
                                {"truth", dir + "/truth.png"}};
        }
        std::printf("%-10s %-4s x%-4s %-20s GPU %8.2f ms  wall %8.2f ms  textures %7.1f MiB  penumbra MAE %.4f  "
                    "oriented %.4f  light passes %7.2f ms, model %6.1f MB %6.1f Mfetch; shading model %6.1f Mfetch\n",
                    scene_.name.c_str(), lit_by_.c_str(), scale_text(scale).c_str(), entry.label.c_str(),
                    record["gpu_ms"].get<double>(), record["wall_ms"]["total"].get<double>(),
                    a.texture_bytes / 1048576.0, q.visibility.penumbra.mae, q.oriented.penumbra.mae,
                    record["light_passes_gpu_ms"].get<double>(), cost.shadow.bytes() / 1e6,
                    cost.shadow.texel_fetches / 1e6, cost.screen.texel_fetches / 1e6);
        std::fflush(stdout);
        results_["measurements"].push_back(std::move(record));
    }

    // The representative settings under a slowly moving light: excess flicker over the truth's.
    std::string measure_flicker() {
        std::string error;
        for (Active& a : active_) {
            const bench::LadderEntry& entry = *a.entry;
            if (!entry.representative) continue;
            progress_.step("flicker", scene_.name + ": flicker, " + std::to_string(options_.flicker_frames) +
                                          " frames of a moving " + lit_by_ + " light: " + entry.label);
            // A temporal variant shows at frame f the mean of frames f-N+1 to f, each rendered under the
            // light of its own frame with its own turn of the pattern (the history starts N-1 frames early).
            const int n = static_cast<int>(a.later_frames.size()) + 1;
            std::vector<std::vector<float>> rendered;
            for (int f = 1 - n; f < options_.flicker_frames; ++f) {
                std::optional<std::vector<float>> v = frame_visibility(a, f, light_at(scene_, path_, 1.0, step_, f), &error);
                if (!v) return entry.label + ": " + error;
                rendered.push_back(std::move(*v));
            }
            std::vector<std::vector<float>> frames;
            for (int f = 0; f < options_.flicker_frames; ++f) {
                std::vector<float> mean(rendered.front().size(), 0.0f);
                for (int k = 0; k < n; ++k)
                    for (std::size_t i = 0; i < mean.size(); ++i) mean[i] += rendered[static_cast<std::size_t>(f + k)][i] / n;
                frames.push_back(std::move(mean));
            }
            double error_sum = 0;
            for (int f = 0; f < options_.flicker_frames; ++f)
                error_sum += compare(frames[f], pixels_->frame.geometry, truth_frames_[f]).all.mae;
            const double delta = mean_frame_delta(frames, pixels_->frame.geometry);
            results_["flicker"].push_back({{"scene", scene_.name},
                                           {"light", lit_by_},
                                           {"family", entry.family},
                                           {"label", entry.label},
                                           {"light_scale", 1.0},
                                           {"frames", options_.flicker_frames},
                                           {"accumulate_frames", n},
                                           {"estimate_delta", delta},
                                           {"truth_delta", truth_delta_},
                                           {"excess", delta - truth_delta_},
                                           {"mean_mae", error_sum / options_.flicker_frames}});
        }
        return {};
    }

    const Options& options_;
    const OutputDirs& dirs_;
    bench::Progress& progress_;
    json& results_;
    json& scene_record_;
    Scene scene_;
    SunPath path_;
    Light light_kind_;
    std::string lit_by_, light_dir_;
    std::unique_ptr<MeshBuffers> mesh_;
    std::optional<Pixels> pixels_;
    double step_ = 0; // the rectangle's motion per flicker frame
    std::vector<References> truths_;            // per light size
    std::vector<std::vector<float>> truth_frames_; // per flicker frame
    double truth_delta_ = 0;
    std::vector<Active> active_;
};

} // namespace

// arguments → scenes → GL context → for every scene and light: LightRun → results.json.
int main(int argc, char** argv) {
    if (penumbra::cli::asks_for_help(std::vector<std::string>(argv + 1, argv + argc)))
        return penumbra::cli::print_usage(usage_text);
    std::string error;
    const std::optional<Options> options = parse(argc, argv, error);
    if (!options) return penumbra::cli::fail_with_usage(error, usage_text);
    const std::optional<LoadedScenes> loaded = load_scenes(*options, &error);
    if (!loaded) return fail(error, 2);
    std::optional<HeadlessContext> context = HeadlessContext::create(&error);
    if (!context) return fail("no OpenGL 4.5 context: " + error);

    const std::vector<bench::LadderEntry> ladder = selected_ladder(*options);
    const OutputDirs dirs{options->out_dir, options->out_dir + "/cache", options->out_dir + "/images"};
    std::error_code ec;
    std::filesystem::create_directories(dirs.out, ec);
    if (ec) return fail("cannot create " + dirs.out + ": " + ec.message());
    const auto run_start = std::chrono::steady_clock::now();
    bench::Progress progress;
    plan_progress(progress, *options, loaded->scenes.size(), ladder);

    json results = results_skeleton(argc, argv, *options, *context);
    for (std::size_t i = 0; i < loaded->scenes.size(); ++i) {
        json scene_record = scene_json(options->scenes[i], loaded->scenes[i], loaded->load_ms[i]);
        for (const Light light_kind : options->lights) {
            LightRun run(*options, dirs, progress, results, scene_record, loaded->scenes[i], light_kind);
            if (std::string e = run.run(ladder); !e.empty()) return fail(e);
        }
        results["scenes"].push_back(std::move(scene_record));
    }
    results["meta"]["wall_s"] = milliseconds_since(run_start) / 1000.0;

    // All or nothing, as every other output of the project: a failed write leaves the previous
    // results.json as it was (tools/include/penumbra_tools/file_transaction.hpp).
    const std::string path = dirs.out + "/results.json";
    if (std::string e = penumbra_gen::write_file_atomically(path, results.dump(1) + "\n"); !e.empty()) return fail(e);
    std::printf("wrote %s (%zu measurements, %zu flicker runs) in %.0f s\n", path.c_str(), results["measurements"].size(),
                results["flicker"].size(), milliseconds_since(run_start) / 1000.0);
    return 0;
}
