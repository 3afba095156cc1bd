// bench/compare/options.hpp — penumbra-bench-compare's command line: the scenes, the ladder's settings,
// the lights and light sizes, the image and the runs; its --help text.
#pragma once

#include "../arguments.hpp"
#include "../corpus/manifest.hpp"
#include "ladder.hpp"

#include "app/scene_overrides.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/config.hpp>

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace penumbra::bench {

using namespace penumbra::playground;
using json = nlohmann::ordered_json;

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
    SceneOverrides overrides;        // --light-*, --camera-*: every scene's rectangle and camera
};

constexpr const char* usage_text =
    "usage: penumbra-bench-compare [--quick | --full] [--scenes a,b,...] [FILE ...] [--corpus [DIR]] "
    "[--no-ground]\n"
    "                              [--settings a,b,...] [--size N|WxH] [--samples N] [--runs N]\n"
    "                              [--lights rect,sun] [--light-scales 1,2,...] [--flicker-frames N] [--out "
    "DIR]\n"
    "                              [--light-size W[,H]] [--light-center X,Y,Z] [--light-normal X,Y,Z]\n"
    "                              [--light-up X,Y,Z] [--camera-position X,Y,Z] [--camera-target X,Y,Z]\n"
    "  (default)         every built-in scene, the standard ladder under each scene's rectangle light,\n"
    "                    light x1 x2 x4 x8 x16 x32, 128x128,\n"
    "                    32x32 rays, 7 runs, 8 flicker frames (about 30 minutes on 2 llvmpipe cores)\n"
    "  --quick           boxes only, two settings, light x1 and x4, 64x64, 8x8 rays, 4 flicker frames\n"
    "                    (a smoke test: the report states the ray count)\n"
    "  --full            the full ladder (adds 1024-texel settings and OIM 8/256), 256x256, 16 flicker "
    "frames\n"
    "  --scenes          built-in scenes, comma-separated (default all: see penumbra-playground --help;\n"
    "                    --scenes '' for none, e.g. to run only files or the corpus); the rooms (room,\n"
    "                    window, cornell) only when named\n"
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
    "  --light-size W[,H]  every scene's rectangle: W its longer side (aspect kept), W,H its width (along "
    "u)\n"
    "                    and height (along v), in scene units; --light-scales multiply it (the sun keeps its "
    "size)\n"
    "  --light-center X,Y,Z  the rectangle's centre; --light-normal X,Y,Z: the direction it faces and emits\n"
    "                    towards; --light-up X,Y,Z: its height side (v), projected onto its plane, not "
    "parallel\n"
    "                    to the normal (default: the scene light's v, else +y, else +z); as "
    "penumbra-playground\n"
    "  --camera-position X,Y,Z, --camera-target X,Y,Z  every scene's camera (either alone keeps the scene's\n"
    "                    other; not the same point). Light and camera flags are set on every scene once it "
    "is\n"
    "                    made, hold for the truth, and results.json's scene records say the light and camera "
    "used\n"
    "flags after --quick or --full override what they set.\n";

// Options from argv, or an error message (one line).
inline std::optional<Options> parse(int argc, char** argv, std::string& error) {
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
        if (std::find(std::begin(valued), std::end(valued), flag) == std::end(valued) &&
            !is_scene_override_flag(flag))
            return fail("unknown flag '" + std::string(flag) +
                        "'; allowed: --quick, --full, --scenes, --corpus, --no-ground, --settings, --size, "
                        "--samples, --runs, "
                        "--light-scales, --lights, --flicker-frames, --out, " +
                        std::string(scene_override_flag_list) + ", --help, FILE");
        if (i + 1 >= argc) return fail(std::string(flag) + ": missing value (see --help)");
        const std::string_view value = argv[++i];
        if (is_scene_override_flag(flag)) {
            if (std::string e = parse_scene_override(flag, value, o.overrides); !e.empty()) return fail(e);
        } else if (flag == "--scenes") {
            built_in.clear();
            scenes_given = true;
            for (std::string_view name : split(value)) {
                if (!make_scene(name))
                    return fail("--scenes: unknown scene '" + std::string(name) +
                                "'; allowed: " + allowed_scene_names());
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
    if (std::string e = check_scene_overrides(o.overrides); !e.empty()) return fail(e);
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

} // namespace penumbra::bench
