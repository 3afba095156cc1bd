// penumbra-bench-scale — how the cost grows with the scene. Per scene (the built-in ones, mesh
// files, and with --corpus the real meshes of scripts/get_corpus.sh, e.g. the Stanford dragon at
// 48k, 200k and 871k triangles), by triangle count:
//   load:    load_scene's wall time (file parse or generation, normals, framing) and the upload to
//            the GPU (MeshBuffers, to glFinish);
//   passes:  GL_TIME_ELAPSED of every pass, medians of --runs frames after --warmup frames (llvmpipe
//            compiles a shader variant at its first draw), for the default occlusion-texture
//            configuration (Config{}) and PCSS 16/16, grouped as the layout says: passes that draw
//            the scene from the light (slicing and adaptive placement's depth bins; the shadow map's
//            depth pass), the prefilter (full-screen passes of the shadow phase) and the screen pass;
//            plus the G-buffer (the camera's own draw of the scene, the engine's cost, for scale);
//   memory:  the mesh's GPU buffers, each layout's textures, and the process's resident memory
//            after the upload and after the Embree build;
//   truth:   Embree's BVH build and the trace of the visibility and the oriented references at
//            --size with --samples² rays per pixel (what penumbra-bench-compare traces per light).
// Then, within each series of one model at several triangle counts (scenes NAME-SUFFIX: dragon-48k,
// dragon-200k, dragon-871k), the growth exponent of each measure between consecutive counts
// (log(t2/t1) / log(n2/n1): 1 is linear), flagged where it exceeds 1.15.
// On llvmpipe the milliseconds are CPU time on a shared machine: read ratios and exponents.
//
//   penumbra-bench-scale [--scenes a,b | ''] [FILE ...] [--corpus [DIR]] [--size N] [--samples N]
//                        [--runs N] [--warmup N] [--no-truth] [--json FILE]
#include "arguments.hpp"
#include "compare/frame.hpp"
#include "compare/ladder.hpp"
#include "corpus/manifest.hpp"

#include "app/headless_job.hpp"
#include "reference/ground_truth.hpp"
#include "rendering/egl_context.hpp"
#include "scenes/scenes.hpp"

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
    std::string json_path;
};

constexpr const char* usage_text =
    "usage: penumbra-bench-scale [--scenes a,b,...] [FILE ...] [--corpus [DIR]] [--size N] [--samples N]\n"
    "                            [--runs N] [--warmup N] [--no-truth] [--json FILE]\n"
    "  --scenes    built-in scenes, comma-separated (default all; '' for none)\n"
    "  FILE        mesh files (what penumbra-playground --scene loads), named after their stem\n"
    "  --corpus    every mesh of the corpus in DIR (default ~/.cache/penumbra/corpus; scripts/get_corpus.sh)\n"
    "  --size      image side in pixels, 16 to 1024 (default 256): the screen pass and the truth's pixels\n"
    "  --samples   ground-truth rays per light axis, 1 to 128 (default 32: 32x32 rays per pixel)\n"
    "  --runs      timed frames per configuration, 1 to 100 (default 5; medians reported)\n"
    "  --warmup    untimed frames first, 1 to 10 (default 2: llvmpipe compiles at the first draw)\n"
    "  --no-truth  skip the Embree build and trace\n"
    "  --json      also write every number to FILE\n"
    "prints a table per scene, sorted by triangles, and the growth exponents between consecutive counts.\n";

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
        if (flag == "--no-truth") {
            o.truth = false;
            continue;
        }
        constexpr std::string_view valued[] = {"--scenes", "--size", "--samples", "--runs", "--warmup", "--json"};
        if (std::find(std::begin(valued), std::end(valued), flag) == std::end(valued))
            return fail("unknown flag '" + std::string(flag) + "'; allowed: --scenes, --corpus, --size, --samples, "
                        "--runs, --warmup, --no-truth, --json, --help, FILE");
        if (i + 1 >= argc) return fail(std::string(flag) + ": missing value (see --help)");
        const std::string_view value = argv[++i];
        auto number = [&](int& out, int lo, int hi) {
            return parse_number(value, out) && out >= lo && out <= hi;
        };
        if (flag == "--scenes") {
            built_in.clear();
            for (std::string_view name : split(value)) {
                if (!make_scene(name)) {
                    std::string allowed;
                    for (std::string_view n : scene_names()) allowed += (allowed.empty() ? "" : ", ") + std::string(n);
                    return fail("--scenes: unknown scene '" + std::string(name) + "'; allowed: " + allowed);
                }
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

// The passes of one frame grouped by what they are: scene draws from the light, the prefilter,
// the screen pass; each pass's median over the runs, and the scene draws per frame.
struct PassGroups {
    double scene_ms = 0, prefilter_ms = 0, screen_ms = 0;
    int scene_draws = 0; // draw_scene pass instances per frame
    json passes = json::array();
};

PassGroups group_passes(const Layout& layout, const std::vector<bench::FrameTimes>& runs) {
    std::map<std::string, std::string> action;
    for (const PassDesc& p : layout.passes) action[p.name] = p.phase == "screen" ? "screen" : p.action;
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

std::string fmt(double v) {
    char text[32];
    std::snprintf(text, sizeof text, v >= 100 ? "%.0f" : v >= 10 ? "%.1f" : "%.2f", v);
    return text;
}

int fail(const std::string& message, int code = 1) {
    std::cerr << "error: " << message << "\n";
    return code;
}

} // namespace

int main(int argc, char** argv) {
    for (int i = 1; i < argc; ++i)
        if (std::string_view(argv[i]) == "--help" || std::string_view(argv[i]) == "-h") {
            std::cout << usage_text;
            return 0;
        }
    std::string error;
    const std::optional<Options> options = parse(argc, argv, error);
    if (!options) {
        std::cerr << "error: " << error << "\n" << usage_text;
        return 2;
    }
    // Every scene is loaded (and timed) before any rendering: a bad file stops the run at once.
    struct Loaded {
        Scene scene;
        double load_ms;
        bool file;
    };
    std::vector<Loaded> scenes;
    for (const SceneInput& input : options->scenes) {
        const auto start = std::chrono::steady_clock::now();
        SceneLoad loaded = load_scene(input.name_or_path);
        if (!loaded.scene) return fail(loaded.error, 2);
        const double ms = bench::milliseconds_since(start);
        loaded.scene->name = input.name;
        scenes.push_back({std::move(*loaded.scene), ms, !make_scene(input.name_or_path).has_value()});
    }
    std::stable_sort(scenes.begin(), scenes.end(),
                     [](const Loaded& a, const Loaded& b) { return a.scene.mesh.triangle_count() < b.scene.mesh.triangle_count(); });

    std::optional<HeadlessContext> context = HeadlessContext::create(&error);
    if (!context) return fail("no OpenGL 4.5 context: " + error);
    const std::vector<Setting> techniques{{"OT default", Config{}}, {"PCSS 16/16", bench::pcss_entry(16, 16).config}};
    std::vector<std::unique_ptr<gl::Runtime>> runtimes;
    for (const Setting& t : techniques) {
        runtimes.push_back(gl::Runtime::create(t.config, &error));
        if (!runtimes.back()) return fail(t.label + ": " + error);
    }
    const int size = options->size;
    std::printf("penumbra-bench-scale: %s; image %dx%d; %d timed frames after %d warm-up; truth %s\n"
                "ms: GPU time (GL_TIME_ELAPSED) medians; on llvmpipe CPU time of a shared machine, read the ratios\n\n",
                context->renderer().c_str(), size, size, options->runs, options->warmup,
                options->truth ? (std::to_string(options->samples) + "x" + std::to_string(options->samples) + " rays per pixel").c_str()
                               : "skipped");
    std::printf("| scene | triangles | load ms | upload ms | G-buffer ms | OT scene passes ms (draws) | OT prefilter ms | "
                "OT screen ms | PCSS depth ms (draws) | PCSS screen ms | OT scene / PCSS depth | mesh MiB | OT tex MiB | "
                "PCSS tex MiB | RSS MiB | Embree build ms | trace ms (vis + oriented) | Mrays/s | Embree RSS +MiB |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");

    json results = {{"meta",
                     {{"tool", "penumbra-bench-scale"},
                      {"renderer", context->renderer()},
                      {"image", size},
                      {"runs", options->runs},
                      {"warmup", options->warmup},
                      {"truth_rays_per_axis", options->truth ? options->samples : 0}}},
                    {"scenes", json::array()}};
    for (const Loaded& item : scenes) {
        const Scene& scene = item.scene;
        const Mesh& m = scene.mesh;
        const auto upload_start = std::chrono::steady_clock::now();
        const MeshBuffers mesh(m);
        glFinish();
        const double upload_ms = bench::milliseconds_since(upload_start);
        const double mesh_mib = (m.positions.size() * sizeof(glm::vec3) * 2 + m.indices.size() * sizeof(std::uint32_t) +
                                 m.uvs.size() * sizeof(glm::vec2)) / 1048576.0;
        // The G-buffer: rendered for the pixels, then timed alone (warm) as the engine's own draw.
        std::optional<bench::Pixels> pixels = bench::render_pixels(scene, mesh, size, size, &error);
        if (!pixels) return fail(scene.name + ": " + error);
        const glm::mat4 clip = scene.camera.projection_matrix(1.0f) * scene.camera.view_matrix();
        std::vector<double> gbuffer_ms;
        for (int r = 0; r < options->warmup + options->runs; ++r) {
            glFinish();
            const auto start = std::chrono::steady_clock::now();
            pixels->gbuffer->render(mesh, clip);
            glFinish();
            if (r >= options->warmup) gbuffer_ms.push_back(bench::milliseconds_since(start));
        }

        json record = {{"name", scene.name},
                       {"file", item.file},
                       {"triangles", m.triangle_count()},
                       {"vertices", m.positions.size()},
                       {"load_ms", item.load_ms},
                       {"upload_ms", upload_ms},
                       {"gbuffer_wall_ms", bench::median(gbuffer_ms)},
                       {"mesh_mib", mesh_mib},
                       {"techniques", json::object()}};
        std::vector<PassGroups> groups;
        for (std::size_t t = 0; t < techniques.size(); ++t) {
            gl::Runtime& runtime = *runtimes[t];
            runtime.set_light(scene.light, glm::dvec3(scene.bounds_min), glm::dvec3(scene.bounds_max));
            std::vector<bench::FrameTimes> runs;
            for (int r = 0; r < options->warmup + options->runs; ++r) {
                bench::FrameTimes times;
                if (!bench::run_frame(runtime, mesh, *pixels, times, &error)) return fail(scene.name + ", " + techniques[t].label + ": " + error);
                if (r >= options->warmup) runs.push_back(std::move(times));
            }
            groups.push_back(group_passes(runtime.layout(), runs));
            std::vector<double> wall_build, wall_shading;
            for (const bench::FrameTimes& r : runs) {
                wall_build.push_back(r.wall_build_ms);
                wall_shading.push_back(r.wall_shading_ms);
            }
            const double tex_mib = static_cast<double>(penumbra::texture_bytes(runtime.layout(), size, size)) / 1048576.0;
            record["techniques"][techniques[t].label] = {{"scene_passes_ms", groups[t].scene_ms},
                                                         {"scene_draws", groups[t].scene_draws},
                                                         {"prefilter_ms", groups[t].prefilter_ms},
                                                         {"screen_ms", groups[t].screen_ms},
                                                         {"wall_light_passes_ms", bench::median(wall_build)},
                                                         {"wall_screen_ms", bench::median(wall_shading)},
                                                         {"texture_mib", tex_mib},
                                                         {"passes", groups[t].passes}};
        }
        const Resident before_truth = resident_memory();
        record["rss_mib"] = before_truth.now_mib;
        double build_ms = 0, trace_ms = 0, mrays = 0, truth_mib = 0;
        if (options->truth) {
            try {
                const auto build_start = std::chrono::steady_clock::now();
                const GroundTruth truth(m);
                build_ms = bench::milliseconds_since(build_start);
                truth_mib = resident_memory().now_mib - before_truth.now_mib;
                const HeadlessResult& f = pixels->frame;
                const glm::vec3 eye = scene.camera.eye_position();
                std::vector<glm::vec3> facing(f.normals.size(), glm::vec3(0.0f));
                std::size_t points = 0;
                for (std::size_t i = 0; i < facing.size(); ++i)
                    if (f.geometry[i]) {
                        ++points;
                        facing[i] = glm::dot(f.normals[i], eye - f.positions[i]) < 0.0f ? -f.normals[i] : f.normals[i];
                    }
                const auto trace_start = std::chrono::steady_clock::now();
                const std::vector<float> visibility = truth.visibility(f.positions, f.normals, scene.light, options->samples);
                const double visibility_ms = bench::milliseconds_since(trace_start);
                const auto oriented_start = std::chrono::steady_clock::now();
                const GroundTruth::Oriented fair = truth.oriented(f.positions, facing, scene.light, options->samples);
                const double oriented_ms = bench::milliseconds_since(oriented_start);
                trace_ms = visibility_ms + oriented_ms;
                const double rays = static_cast<double>(points) * options->samples * options->samples;
                mrays = visibility_ms > 0 ? rays / (visibility_ms * 1000.0) : 0;
                record["truth"] = {{"build_ms", build_ms},     {"visibility_trace_ms", visibility_ms},
                                   {"oriented_trace_ms", oriented_ms}, {"geometry_pixels", points},
                                   {"visibility_rays", rays},  {"visibility_mrays_per_s", mrays},
                                   {"rss_growth_mib", truth_mib}};
            } catch (const GroundTruthError& e) {
                return fail(scene.name + ": ground truth: " + e.what());
            }
        }
        record["peak_rss_mib"] = resident_memory().peak_mib;
        const PassGroups& ot = groups[0];
        const PassGroups& pcss = groups[1];
        std::printf("| %s | %zu | %s | %s | %s | %s (%d) | %s | %s | %s (%d) | %s | %.2f | %.1f | %.1f | %.1f | %.0f | %s | %s | %s | %s |\n",
                    scene.name.c_str(), m.triangle_count(), fmt(item.load_ms).c_str(), fmt(upload_ms).c_str(),
                    fmt(bench::median(gbuffer_ms)).c_str(), fmt(ot.scene_ms).c_str(), ot.scene_draws,
                    fmt(ot.prefilter_ms).c_str(), fmt(ot.screen_ms).c_str(), fmt(pcss.scene_ms).c_str(), pcss.scene_draws,
                    fmt(pcss.screen_ms).c_str(), pcss.scene_ms > 0 ? ot.scene_ms / pcss.scene_ms : 0.0, mesh_mib,
                    record["techniques"]["OT default"]["texture_mib"].get<double>(),
                    record["techniques"]["PCSS 16/16"]["texture_mib"].get<double>(), before_truth.now_mib,
                    options->truth ? fmt(build_ms).c_str() : "–", options->truth ? fmt(trace_ms).c_str() : "–",
                    options->truth ? fmt(mrays).c_str() : "–", options->truth ? fmt(truth_mib).c_str() : "–");
        std::fflush(stdout);
        results["scenes"].push_back(std::move(record));
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
        for (const auto& [prefix, steps] : series)
        for (std::size_t i = 1; i < steps.size(); ++i) {
            const json& a = *steps[i - 1];
            const json& b = *steps[i];
            const double n = b["triangles"].get<double>() / a["triangles"].get<double>();
            json row = {{"from", a["name"]}, {"to", b["name"]}, {"triangle_ratio", n}, {"exponents", json::object()}};
            std::printf("| %s | %s | %.1f |", a["name"].get<std::string>().c_str(), b["name"].get<std::string>().c_str(), n);
            for (const Measure& m : measures) {
                const double t1 = m.value(a), t2 = m.value(b);
                if (!(t1 > 0) || !(t2 > 0)) {
                    std::printf(" – |");
                    continue;
                }
                const double e = std::log(t2 / t1) / std::log(n);
                row["exponents"][m.name] = e;
                std::printf(" %.2f%s |", e, e > 1.15 ? "*" : "");
            }
            std::printf("\n");
            growth.push_back(std::move(row));
        }
    }
    results["growth"] = growth;
    if (!options->json_path.empty()) {
        const std::string tmp = options->json_path + ".tmp";
        std::ofstream file(tmp);
        file << results.dump(1) << "\n";
        file.close();
        std::error_code ec;
        if (!file || (std::filesystem::rename(tmp, options->json_path, ec), ec))
            return fail("cannot write " + options->json_path);
        std::printf("\nwrote %s\n", options->json_path.c_str());
    }
    return 0;
}
