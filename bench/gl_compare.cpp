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
//                          [--size N] [--samples N] [--runs N] [--lights rect,sun] [--light-scales 1,2,4]
//                          [--flicker-frames N]
//                          [--out DIR] [--light-size W[,H]] [--light-center X,Y,Z] [--light-normal X,Y,Z]
//                          [--light-up X,Y,Z] [--camera-position X,Y,Z] [--camera-target X,Y,Z]
//
// The parts: compare/options.hpp (the command line), compare/light_run.hpp (the measuring: one scene
// under one light), compare/report.hpp (results.json's records and the images), compare/lights.hpp
// (each measurement's light); this file loads the scenes and runs them.
#include "compare/light_run.hpp"
#include "compare/options.hpp"
#include "compare/progress.hpp"
#include "compare/report.hpp"

#include "rendering/egl_context.hpp"
#include "scenes/scenes.hpp"

#include <penumbra_tools/file_transaction.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::bench;
using namespace penumbra::playground;
using json = nlohmann::ordered_json;

namespace {

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
        // --light-*, --camera-*: before every truth and measurement (--light-scales scale the result)
        if (std::string e = apply_scene_overrides(options.overrides, *loaded.scene, Light::rect);
            !e.empty()) {
            *error = e;
            return std::nullopt;
        }
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
