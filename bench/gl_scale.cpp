// penumbra-bench-scale — how the cost grows with the scene. Per scene (the built-in ones, mesh
// files, and with --corpus the real meshes of scripts/get_corpus.sh, e.g. the Stanford dragon at
// 48k, 200k and 871k triangles), by triangle count:
//   load:    load_scene's wall time (file parse or generation, normals, framing, the floor under a
//            file) and the upload to the GPU (MeshBuffers, to glFinish);
//   passes:  GL_TIME_ELAPSED of every pass after --warmup frames (llvmpipe compiles a shader variant
//            at its first draw), for the default occlusion-texture configuration (Config{}) and
//            PCSS 16/16, grouped as the layout says: passes that draw the scene from the light
//            (slicing, and adaptive placement's depth bins; the shadow map's depth pass), the
//            prefilter (full-screen passes of the shadow phase) and the screen pass; plus the
//            G-buffer (the camera's own draw of the scene, the engine's cost, for scale);
//   memory:  the mesh's GPU buffers, each layout's textures, the heap the Embree BVH holds (and the
//            resident memory it adds), and the process's peak;
//   truth:   Embree's BVH build and the trace of the visibility and the oriented references at
//            --size with --samples² rays per pixel (what penumbra-bench-compare traces per light).
// Every measure is interleaved over the scenes (round r of every scene, then round r + 1) and the
// median of --runs rounds, so that load from other processes slows every triangle count alike.
// Then, within each series of one model at several triangle counts (scenes NAME-SUFFIX: dragon-48k,
// dragon-200k, dragon-871k), the growth exponent of each measure between consecutive counts
// (log(t2/t1) / log(n2/n1): 1 is linear), flagged where it exceeds 1.15.
// On llvmpipe the milliseconds are CPU time on a shared machine: read ratios and exponents.
//
//   penumbra-bench-scale [--scenes a,b | ''] [FILE ...] [--corpus [DIR]] [--no-ground] [--size N] [--samples
//   N]
//                        [--runs N] [--warmup N] [--no-truth] [--json FILE] [--light-size W[,H]]
//                        [--light-center X,Y,Z]
//                        [--light-normal X,Y,Z] [--light-up X,Y,Z] [--camera-position X,Y,Z] [--camera-target
//                        X,Y,Z]
#include "arguments.hpp"
#include "compare/frame.hpp"
#include "compare/ladder.hpp"
#include "corpus/manifest.hpp"

#include "app/headless_job.hpp"
#include "reference/ground_truth.hpp"
#include "rendering/egl_context.hpp"
#include "scenes/scenes.hpp"

#include <penumbra_tools/file_transaction.hpp>

#include <penumbra/layout.hpp>
#include <penumbra/texture_memory.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <malloc.h>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

using namespace penumbra;
using namespace penumbra::playground;
using json = nlohmann::ordered_json;

namespace {

using penumbra::bench::parse_number;
using penumbra::bench::split;


struct SceneInput {
    std::string name_or_path, name;
};

struct Options {
    std::vector<SceneInput> scenes;
    int size = 256, samples = 32, runs = 5, warmup = 2;
    bool truth = true;
    bool ground = true; // --no-ground: no floor under the mesh files
    std::string json_path;
    SceneOverrides overrides; // --light-*, --camera-*: every scene's rectangle and camera
};

constexpr const char* usage_text =
    "usage: penumbra-bench-scale [--scenes a,b,...] [FILE ...] [--corpus [DIR]] [--no-ground] [--size N] "
    "[--samples N]\n"
    "                            [--runs N] [--warmup N] [--no-truth] [--json FILE] [--light-size W[,H]]\n"
    "                            [--light-center X,Y,Z] [--light-normal X,Y,Z] [--light-up X,Y,Z]\n"
    "                            [--camera-position X,Y,Z] [--camera-target X,Y,Z]\n"
    "  --scenes    built-in scenes, comma-separated (default all but the rooms room, window, cornell, which\n"
    "              run only when named; '' for none)\n"
    "  FILE        mesh files (what penumbra-playground --scene loads), named after their stem\n"
    "  --corpus    every mesh of the corpus in DIR (default ~/.cache/penumbra/corpus; "
    "scripts/get_corpus.sh)\n"
    "  --no-ground no floor under the mesh files (default: each stands on one, +2 triangles)\n"
    "  --size      image side in pixels, 16 to 1024 (default 256): the screen pass and the truth's pixels\n"
    "  --samples   ground-truth rays per light axis, 1 to 128 (default 32: 32x32 rays per pixel)\n"
    "  --runs      rounds of every measure, 1 to 100 (default 5; medians reported)\n"
    "  --warmup    untimed frames first, 1 to 10 (default 2: llvmpipe compiles at the first draw)\n"
    "  --no-truth  skip the Embree build and trace\n"
    "  --json      also write every number to FILE (each scene's record with the light and camera used)\n"
    "  --light-size W[,H]  every scene's rectangle: W its longer side (aspect kept), W,H its width (along "
    "u)\n"
    "              and height (along v), in scene units\n"
    "  --light-center X,Y,Z  the rectangle's centre; --light-normal X,Y,Z: the direction it faces and emits\n"
    "              towards; --light-up X,Y,Z: its height side (v), projected onto its plane, not parallel "
    "to\n"
    "              the normal (default: the scene light's v, else +y, else +z); as penumbra-playground\n"
    "  --camera-position X,Y,Z, --camera-target X,Y,Z  every scene's camera (either alone keeps the\n"
    "              scene's other; not the same point)\n"
    "prints a row per scene, sorted by triangles, and the growth exponents within each series of one\n"
    "model at several triangle counts (scenes named NAME-SUFFIX, e.g. dragon-48k, dragon-200k).\n";

std::optional<Options> parse(int argc, char** argv, std::string& error) {
    Options o;
    std::vector<SceneInput> built_in, files;
    for (std::string_view name : scene_names()) built_in.push_back({std::string(name), std::string(name)});
    auto fail = [&](std::string message) {
        error = std::move(message);
        return std::nullopt;
    };
    for (int i = 1; i < argc; ++i) {
        const std::string_view flag = argv[i];
        if (!flag.starts_with("--")) {
            files.push_back({std::string(flag), std::filesystem::path(flag).stem().string()});
            continue;
        }
        if (flag == "--corpus") {
            std::optional<std::vector<bench::CorpusMesh>> corpus =
                bench::read_corpus(bench::corpus_dir_argument(argc, argv, i), &error);
            if (!corpus) return std::nullopt;
            for (const bench::CorpusMesh& m : *corpus) files.push_back({m.path, m.name});
            continue;
        }
        if (flag == "--no-ground") {
            o.ground = false;
            continue;
        }
        if (flag == "--no-truth") {
            o.truth = false;
            continue;
        }
        constexpr std::string_view valued[] = {"--scenes", "--size", "--samples", "--runs", "--warmup", "--json"};
        if (std::find(std::begin(valued), std::end(valued), flag) == std::end(valued) &&
            !is_scene_override_flag(flag))
            return fail("unknown flag '" + std::string(flag) +
                        "'; allowed: --scenes, --corpus, --no-ground, --size, "
                        "--samples, --runs, --warmup, --no-truth, --json, " +
                        std::string(scene_override_flag_list) + ", --help, FILE");
        if (i + 1 >= argc) return fail(std::string(flag) + ": missing value (see --help)");
        const std::string_view value = argv[++i];
        if (is_scene_override_flag(flag)) {
            if (std::string e = parse_scene_override(flag, value, o.overrides); !e.empty()) return fail(e);
            continue;
        }
        auto number = [&](int& out, int lo, int hi) {
            return parse_number(value, out) && out >= lo && out <= hi;
        };
        if (flag == "--scenes") {
            built_in.clear();
            for (std::string_view name : split(value)) {
                if (!make_scene(name))
                    return fail("--scenes: unknown scene '" + std::string(name) +
                                "'; allowed: " + allowed_scene_names());
                built_in.push_back({std::string(name), std::string(name)});
            }
        } else if (flag == "--size") {
            if (!number(o.size, 16, 1024)) return fail("--size: '" + std::string(value) + "' is not allowed; allowed: 16 to 1024");
        } else if (flag == "--samples") {
            if (!number(o.samples, 1, 128)) return fail("--samples: '" + std::string(value) + "' is not allowed; allowed: 1 to 128");
        } else if (flag == "--runs") {
            if (!number(o.runs, 1, 100)) return fail("--runs: '" + std::string(value) + "' is not allowed; allowed: 1 to 100");
        } else if (flag == "--warmup") {
            if (!number(o.warmup, 1, 10)) return fail("--warmup: '" + std::string(value) + "' is not allowed; allowed: 1 to 10");
        } else { // --json
            if (value.empty()) return fail("--json: empty; allowed: a file path");
            o.json_path = std::string(value);
        }
    }
    o.scenes = built_in;
    o.scenes.insert(o.scenes.end(), files.begin(), files.end());
    if (std::string e = check_scene_overrides(o.overrides); !e.empty()) return fail(e);
    if (o.scenes.empty()) return fail("no scene: give --scenes, a mesh file or --corpus");
    return o;
}

// This process's resident memory (VmRSS) and its peak (VmHWM), in MiB; 0 where /proc has none.
struct Resident {
    double now_mib = 0, peak_mib = 0;
};
Resident resident_memory() {
    Resident r;
    std::ifstream status("/proc/self/status");
    std::string key;
    double kib = 0;
    while (status >> key) {
        if (key == "VmRSS:" && status >> kib) r.now_mib = kib / 1024.0;
        else if (key == "VmHWM:" && status >> kib) r.peak_mib = kib / 1024.0;
    }
    return r;
}

// Bytes allocated through malloc and in use now (glibc's mallinfo2: arena and mmapped chunks), so
// that memory a new object takes is counted even where freed memory is reused (the resident size
// then does not grow).
double heap_in_use_mib() {
    const struct mallinfo2 info = mallinfo2();
    return static_cast<double>(info.uordblks + info.hblkhd) / 1048576.0;
}

// The passes of one frame grouped by what they are: scene draws from the light, the prefilter,
// the screen pass; each pass's median over the runs, and the scene draws per frame.
struct PassGroups {
    double scene_ms = 0, prefilter_ms = 0, screen_ms = 0;
    int scene_draws = 0; // draw_scene pass instances per frame
    json passes = json::array();
};

PassGroups group_passes(const Layout& layout, const std::vector<bench::FrameTimes>& runs) {
    std::map<std::string, std::string> action;
    for (const PassDesc& p : layout.passes) action[p.name] = p.phase == Phase::screen ? "screen" : std::string(to_string(p.action));
    std::vector<int> instances;
    const auto names = bench::pass_totals(runs.front().passes, &instances);
    PassGroups g;
    for (std::size_t p = 0; p < names.size(); ++p) {
        std::vector<double> ms;
        for (const bench::FrameTimes& r : runs) ms.push_back(bench::pass_totals(r.passes)[p].second);
        const double m = bench::median(ms);
        // the deferred shading pass is timed by shade_deferred; it is named "shading" and is the last
        const std::string kind = p + 1 == names.size() ? "screen" : action.count(names[p].first) ? action[names[p].first] : "";
        const std::string group = kind == "screen" ? "screen" : kind == "draw_scene" ? "scene" : "prefilter";
        if (group == "screen") g.screen_ms += m;
        else if (group == "scene") {
            g.scene_ms += m;
            g.scene_draws += instances[p];
        } else g.prefilter_ms += m;
        g.passes.push_back({{"name", names[p].first}, {"group", group}, {"instances", instances[p]}, {"gpu_ms", m}});
    }
    return g;
}

struct Setting {
    std::string label;
    Config config;
};

std::string fmt(double v) { // 3 significant digits or so
    char text[32];
    std::snprintf(text, sizeof text, v >= 100 ? "%.0f" : v >= 10 ? "%.1f" : "%.2f", v);
    return text;
}

using penumbra::cli::fail;

} // namespace

int main(int argc, char** argv) {
    if (penumbra::cli::asks_for_help(std::vector<std::string>(argv + 1, argv + argc)))
        return penumbra::cli::print_usage(usage_text);
    std::string error;
    const std::optional<Options> options = parse(argc, argv, error);
    if (!options) return penumbra::cli::fail_with_usage(error, usage_text);
    // Every measurement is interleaved over the scenes (round r of every scene, then round r + 1),
    // so that load from other processes on a shared machine slows every triangle count alike and
    // the ratios and exponents survive it. Medians of the rounds.
    // Loading: the first round keeps the scenes (a bad file stops the run before any rendering).
    struct Item {
        SceneInput input;
        Scene scene;
        bool file = false;
        std::vector<double> load_ms, upload_ms, gbuffer_ms, build_ms;
        std::unique_ptr<MeshBuffers> mesh;
        std::optional<bench::Pixels> pixels;
        std::vector<std::vector<bench::FrameTimes>> runs; // per technique
    };
    // The context first: it must outlive every GL object the items hold.
    std::optional<HeadlessContext> context = HeadlessContext::create(&error);
    if (!context) return fail("no OpenGL 4.5 context: " + error);
    std::vector<Item> items;
    for (const SceneInput& input : options->scenes) {
        const auto start = std::chrono::steady_clock::now();
        SceneLoad loaded = load_scene(input.name_or_path, options->ground);
        if (!loaded.scene) return fail(loaded.error, 2);
        Item item;
        item.load_ms.push_back(bench::milliseconds_since(start));
        item.input = input;
        item.scene = std::move(*loaded.scene);
        item.scene.name = input.name;
        // --light-*, --camera-*: before every frame and the truth
        if (std::string e = apply_scene_overrides(options->overrides, item.scene, Light::rect); !e.empty())
            return fail(e, 2);
        item.file = !make_scene(input.name_or_path).has_value();
        items.push_back(std::move(item));
    }
    std::stable_sort(items.begin(), items.end(),
                     [](const Item& a, const Item& b) { return a.scene.mesh.triangle_count() < b.scene.mesh.triangle_count(); });
    for (int r = 1; r < options->runs; ++r)
        for (Item& item : items) {
            const auto start = std::chrono::steady_clock::now();
            const SceneLoad again = load_scene(item.input.name_or_path, options->ground);
            item.load_ms.push_back(bench::milliseconds_since(start));
        }

    const std::vector<Setting> techniques{{"OT default", Config{}}, {"PCSS 16/16", bench::pcss_entry(16, 16).config}};
    std::vector<std::unique_ptr<gl::Runtime>> runtimes;
    for (const Setting& t : techniques) {
        runtimes.push_back(gl::Runtime::create(t.config, &error));
        if (!runtimes.back()) return fail(t.label + ": " + error);
    }
    const int size = options->size;
    std::fprintf(stderr, "scale: %zu scenes, %d rounds of loads, uploads and frames%s\n", items.size(), options->runs,
                 options->truth ? ", then the Embree builds and one trace each" : "");

    // Uploads: the first keeps the buffers; the later rounds make and free a copy.
    for (Item& item : items) {
        const auto start = std::chrono::steady_clock::now();
        item.mesh = std::make_unique<MeshBuffers>(item.scene.mesh);
        glFinish();
        item.upload_ms.push_back(bench::milliseconds_since(start));
        item.pixels = bench::render_pixels(item.scene, *item.mesh, size, size, &error);
        if (!item.pixels) return fail(item.scene.name + ": " + error);
        item.runs.resize(techniques.size());
    }
    for (int r = 1; r < options->runs; ++r)
        for (Item& item : items) {
            const auto start = std::chrono::steady_clock::now();
            { const MeshBuffers copy(item.scene.mesh); glFinish(); }
            item.upload_ms.push_back(bench::milliseconds_since(start));
        }
    // Frames: warm-up rounds, then timed rounds of every scene × technique, and the G-buffer draw.
    for (int r = 0; r < options->warmup + options->runs; ++r) {
        std::fprintf(stderr, "scale: %s round %d\n", r < options->warmup ? "warm-up" : "timed", r + 1);
        for (Item& item : items) {
            const Scene& scene = item.scene;
            glFinish();
            const auto start = std::chrono::steady_clock::now();
            item.pixels->gbuffer->render(*item.mesh, scene.camera.projection_matrix(1.0f) * scene.camera.view_matrix());
            glFinish();
            if (r >= options->warmup) item.gbuffer_ms.push_back(bench::milliseconds_since(start));
            for (std::size_t t = 0; t < techniques.size(); ++t) {
                runtimes[t]->set_light(scene.light, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
                bench::FrameTimes times;
                if (!bench::run_frame(*runtimes[t], *item.mesh, *item.pixels, times, &error))
                    return fail(scene.name + ", " + techniques[t].label + ": " + error);
                if (r >= options->warmup) item.runs[t].push_back(std::move(times));
            }
        }
    }

    json results = {{"meta",
                     {{"tool", "penumbra-bench-scale"},
                      {"renderer", context->renderer()},
                      {"image", size},
                      {"runs", options->runs},
                      {"warmup", options->warmup},
                      {"truth_rays_per_axis", options->truth ? options->samples : 0}}},
                    {"scenes", json::array()}};
    std::vector<json> records;
    for (Item& item : items) {
        const Mesh& m = item.scene.mesh;
        const double mesh_mib = static_cast<double>(m.positions.size() * sizeof(glm::vec3) * 2 +
                                                    m.indices.size() * sizeof(std::uint32_t) + m.uvs.size() * sizeof(glm::vec2)) /
                                1048576.0;
        json record = {{"name", item.scene.name},
                       {"file", item.file},
                       {"ground", item.scene.ground},
                       {"light", light_json(item.scene, Light::rect)},
                       {"camera", camera_json(item.scene.camera)},
                       {"triangles", m.triangle_count()},
                       {"vertices", m.positions.size()},
                       {"load_ms", bench::median(item.load_ms)},
                       {"upload_ms", bench::median(item.upload_ms)},
                       {"upload_first_ms", item.upload_ms.front()},
                       {"gbuffer_wall_ms", bench::median(item.gbuffer_ms)},
                       {"mesh_mib", mesh_mib},
                       {"techniques", json::object()}};
        for (std::size_t t = 0; t < techniques.size(); ++t) {
            const PassGroups g = group_passes(runtimes[t]->layout(), item.runs[t]);
            std::vector<double> wall_build, wall_shading;
            for (const bench::FrameTimes& f : item.runs[t]) {
                wall_build.push_back(f.wall_build_ms);
                wall_shading.push_back(f.wall_shading_ms);
            }
            record["techniques"][techniques[t].label] = {
                {"scene_passes_ms", g.scene_ms},
                {"scene_draws", g.scene_draws},
                {"prefilter_ms", g.prefilter_ms},
                {"screen_ms", g.screen_ms},
                {"wall_light_passes_ms", bench::median(wall_build)},
                {"wall_screen_ms", bench::median(wall_shading)},
                {"texture_mib", static_cast<double>(penumbra::texture_bytes(runtimes[t]->layout(), size, size)) / 1048576.0},
                {"passes", g.passes}};
        }
        records.push_back(std::move(record));
    }
    // The truth: rounds of Embree builds (each freed before the next; the first round also measures
    // the resident memory the BVH adds), then one trace per scene of both references.
    if (options->truth) {
        try {
            for (int r = 0; r < options->runs; ++r)
                for (std::size_t i = 0; i < items.size(); ++i) {
                    std::fprintf(stderr, "scale: Embree build round %d, %s\n", r + 1, items[i].scene.name.c_str());
                    const double before = resident_memory().now_mib, heap_before = heap_in_use_mib();
                    const auto start = std::chrono::steady_clock::now();
                    const GroundTruth truth(items[i].scene.mesh);
                    items[i].build_ms.push_back(bench::milliseconds_since(start));
                    if (r == 0) {
                        records[i]["truth"]["rss_growth_mib"] = resident_memory().now_mib - before;
                        records[i]["truth"]["heap_mib"] = heap_in_use_mib() - heap_before;
                    }
                }
            for (std::size_t i = 0; i < items.size(); ++i) {
                const Item& item = items[i];
                std::fprintf(stderr, "scale: trace, %s\n", item.scene.name.c_str());
                const GroundTruth truth(item.scene.mesh);
                const HeadlessResult& f = item.pixels->frame;
                const glm::vec3 eye = item.scene.camera.eye_position();
                std::vector<glm::vec3> facing(f.normals.size(), glm::vec3(0.0f));
                std::size_t points = 0;
                for (std::size_t k = 0; k < facing.size(); ++k)
                    if (f.geometry[k]) {
                        ++points;
                        facing[k] = glm::dot(f.normals[k], eye - f.positions[k]) < 0.0f ? -f.normals[k] : f.normals[k];
                    }
                const auto trace_start = std::chrono::steady_clock::now();
                const std::vector<float> visibility = truth.visibility(f.positions, f.normals, item.scene.light, options->samples);
                const double visibility_ms = bench::milliseconds_since(trace_start);
                const auto oriented_start = std::chrono::steady_clock::now();
                const GroundTruth::Oriented fair = truth.oriented(f.positions, facing, item.scene.light, options->samples);
                const double oriented_ms = bench::milliseconds_since(oriented_start);
                const double rays = static_cast<double>(points) * options->samples * options->samples;
                json& t = records[i]["truth"];
                t["build_ms"] = bench::median(item.build_ms);
                t["visibility_trace_ms"] = visibility_ms;
                t["oriented_trace_ms"] = oriented_ms;
                t["geometry_pixels"] = points;
                t["visibility_rays"] = rays;
                t["visibility_mrays_per_s"] = visibility_ms > 0 ? rays / (visibility_ms * 1000.0) : 0.0;
            }
        } catch (const GroundTruthError& e) {
            return fail("ground truth: " + std::string(e.what()));
        }
    }
    results["meta"]["peak_rss_mib"] = resident_memory().peak_mib;

    std::printf("penumbra-bench-scale: %s; image %dx%d; medians of %d interleaved rounds after %d warm-up; truth %s\n"
                "ms: GPU time (GL_TIME_ELAPSED) of the passes, wall clock of load, upload, G-buffer and Embree; on\n"
                "llvmpipe CPU time of a shared machine: read the ratios; peak resident memory %.0f MiB\n\n",
                context->renderer().c_str(), size, size, options->runs, options->warmup,
                options->truth ? (std::to_string(options->samples) + "x" + std::to_string(options->samples) + " rays per pixel").c_str()
                               : "skipped",
                results["meta"]["peak_rss_mib"].get<double>());
    std::printf("| scene | triangles | load ms | upload ms | G-buffer ms | OT scene passes ms (draws) | OT prefilter ms | "
                "OT screen ms | PCSS depth ms (draws) | PCSS screen ms | OT scene / PCSS depth | mesh MiB | OT tex MiB | "
                "PCSS tex MiB | Embree build ms | Embree heap MiB (RSS +MiB) | trace ms (vis + oriented) | Mrays/s |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const json& r : records) {
        const json& ot = r["techniques"]["OT default"];
        const json& pcss = r["techniques"]["PCSS 16/16"];
        const bool truth = r.contains("truth");
        const double ot_scene = ot["scene_passes_ms"], pcss_scene = pcss["scene_passes_ms"];
        std::printf("| %s | %zu | %s | %s | %s | %s (%d) | %s | %s | %s (%d) | %s | %.2f | %.1f | %.1f | %.1f | %s | %s | %s | %s |\n",
                    r["name"].get<std::string>().c_str(), r["triangles"].get<std::size_t>(), fmt(r["load_ms"]).c_str(),
                    fmt(r["upload_ms"]).c_str(), fmt(r["gbuffer_wall_ms"]).c_str(), fmt(ot_scene).c_str(),
                    ot["scene_draws"].get<int>(), fmt(ot["prefilter_ms"]).c_str(), fmt(ot["screen_ms"]).c_str(),
                    fmt(pcss_scene).c_str(), pcss["scene_draws"].get<int>(), fmt(pcss["screen_ms"]).c_str(),
                    pcss_scene > 0 ? ot_scene / pcss_scene : 0.0, r["mesh_mib"].get<double>(), ot["texture_mib"].get<double>(),
                    pcss["texture_mib"].get<double>(), truth ? fmt(r["truth"]["build_ms"]).c_str() : "–",
                    truth ? (fmt(r["truth"]["heap_mib"]) + " (" + fmt(r["truth"]["rss_growth_mib"]) + ")").c_str() : "–",
                    truth ? fmt(r["truth"]["visibility_trace_ms"].get<double>() + r["truth"]["oriented_trace_ms"].get<double>()).c_str() : "–",
                    truth ? fmt(r["truth"]["visibility_mrays_per_s"]).c_str() : "–");
        results["scenes"].push_back(r);
    }

    // Growth within a series: scenes named NAME-SUFFIX with the same NAME (the corpus's dragon-48k,
    // dragon-200k, dragon-871k: one model at three decimations), between consecutive triangle
    // counts: log(t2 / t1) / log(n2 / n1). Different scenes are not compared: their shadows cover
    // different areas, and the fill rate, not the triangle count, sets the time of small scenes.
    struct Measure {
        std::string name;
        std::function<double(const json&)> value;
    };
    auto technique = [](const char* label, const char* key) {
        return [=](const json& s) { return s["techniques"][label][key].get<double>(); };
    };
    std::vector<Measure> measures{
        {"load", [](const json& s) { return s["load_ms"].get<double>(); }},
        {"upload", [](const json& s) { return s["upload_ms"].get<double>(); }},
        {"G-buffer", [](const json& s) { return s["gbuffer_wall_ms"].get<double>(); }},
        {"OT scene passes", technique("OT default", "scene_passes_ms")},
        {"OT prefilter", technique("OT default", "prefilter_ms")},
        {"OT screen", technique("OT default", "screen_ms")},
        {"PCSS depth", technique("PCSS 16/16", "scene_passes_ms")},
        {"PCSS screen", technique("PCSS 16/16", "screen_ms")},
    };
    if (options->truth) {
        measures.push_back({"Embree build", [](const json& s) { return s["truth"]["build_ms"].get<double>(); }});
        measures.push_back({"Embree trace", [](const json& s) {
                                return s["truth"]["visibility_trace_ms"].get<double>() + s["truth"]["oriented_trace_ms"].get<double>();
                            }});
    }
    std::map<std::string, std::vector<const json*>> series; // sorted by triangles already
    for (const json& s : results["scenes"]) {
        const std::string name = s["name"];
        if (const std::size_t dash = name.rfind('-'); dash != std::string::npos && dash > 0)
            series[name.substr(0, dash)].push_back(&s);
    }
    json growth = json::array();
    std::erase_if(series, [](const auto& entry) { return entry.second.size() < 2; });
    if (!series.empty()) {
        std::printf("\ngrowth exponent within each series, between consecutive triangle counts (1 = linear, 0 = constant;\n"
                    "* above 1.15: worse than linear):\n\n");
        std::printf("| from | to | triangles x |");
        for (const Measure& m : measures) std::printf(" %s |", m.name.c_str());
        std::printf("\n|---|---|---|");
        for (std::size_t i = 0; i < measures.size(); ++i) std::printf("---|");
        std::printf("\n");
        auto row = [&](const json& a, const json& b) {
            const double n = b["triangles"].get<double>() / a["triangles"].get<double>();
            json r = {{"from", a["name"]}, {"to", b["name"]}, {"triangle_ratio", n}, {"exponents", json::object()}};
            std::printf("| %s | %s | %.1f |", a["name"].get<std::string>().c_str(), b["name"].get<std::string>().c_str(), n);
            for (const Measure& m : measures) {
                const double t1 = m.value(a), t2 = m.value(b);
                if (!(t1 > 0) || !(t2 > 0)) {
                    std::printf(" – |");
                    continue;
                }
                const double e = std::log(t2 / t1) / std::log(n);
                r["exponents"][m.name] = e;
                std::printf(" %.2f%s |", e, e > 1.15 ? "*" : "");
            }
            std::printf("\n");
            growth.push_back(std::move(r));
        };
        // each step, then the whole series (first to last: the steadiest estimate)
        for (const auto& [prefix, steps] : series) {
            for (std::size_t i = 1; i < steps.size(); ++i) row(*steps[i - 1], *steps[i]);
            if (steps.size() > 2) row(*steps.front(), *steps.back());
        }
    }
    results["growth"] = growth;
    if (!options->json_path.empty()) {
        // all or nothing, as every other output (tools/include/penumbra_tools/file_transaction.hpp)
        if (std::string e = penumbra_gen::write_file_atomically(options->json_path, results.dump(1) + "\n"); !e.empty())
            return fail(e);
        std::printf("\nwrote %s\n", options->json_path.c_str());
    }
    return 0;
}
