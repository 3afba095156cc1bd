// penumbra-bench-quality — how good the model is, scene × filter × (slices, resolution): MAE, RMSE
// and p95 |error| against Embree ground truth over all geometry pixels and over penumbra pixels
// (truth or estimate < 0.98) — today's truth (the whole light) and the fair ones (the part of the
// light above the receiver's tangent plane: `oriented` visibility and `irradiance`) — and the GPU
// time of each pass (timer queries; on llvmpipe the CPU
// time of the software rasteriser, so compare ratios, not absolute values).
//
//   penumbra-bench-quality [--scenes planes,boxes] [FILE ...] [--corpus [DIR]] [--no-ground] [--filters
//   sat,nbuffer]
//                          [--configs 16x512,4x128] [--size 256x256] [--samples 16] [--repeat 1]
//                          [--light-scales 1,2,4,8,16,32] [--light-size W[,H]] [--light-center X,Y,Z]
//                          [--light-normal X,Y,Z] [--light-up X,Y,Z] [--camera-position X,Y,Z]
//                          [--camera-target X,Y,Z]
// After the rows, a summary: per variant, setting and light scale, the mean penumbra MAE and mean signed
// error (estimate − truth) against the irradiance reference first (the shaded image's relative error),
// then against the oriented one (the two disagree under large lights, docs/model.md §1.7.4), the mean
// false light and false shadow (reference/metrics.hpp), and near the terminator (pixels within 3 of where
// a surface turns away from the light's centre) the p95 of |error| and the total variation of the error
// (sawtooth and seams), the built-in scenes and the mesh files apart; with more than one light scale,
// each scene's MAE and signed error by light scale, irradiance then oriented.
#include "arguments.hpp"
#include "corpus/manifest.hpp"

#include "app/headless_job.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/config.hpp>
#include <penumbra/validate.hpp>

#include <algorithm>
#include <charconv>
#include <filesystem>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

using namespace penumbra::playground;

namespace {

using penumbra::bench::parse_number;
using penumbra::bench::split;


struct SliceSetting {
    int slices = 16, resolution = 512;
};

// A model variant: fusion rule, tangent clip and its offset, fade ramp and slice placement
// ("chained+clip+offset1+ramp0.5+adaptive").
struct Variant {
    penumbra::Fusion fusion = penumbra::Config{}.fusion;
    bool tangent_clip = penumbra::Config{}.tangent_clip;
    penumbra::SlicePlacement placement = penumbra::Config{}.slice_placement;
    double tangent_clip_offset = penumbra::Config{}.tangent_clip_offset;
    double fade_ramp = penumbra::Config{}.fade_ramp;
    bool clip_footprint = penumbra::Config{}.clip_footprint;
    bool leak_fix = penumbra::Config{}.leak_fix;
    bool solid_casters = penumbra::Config{}.solid_casters;
    bool irradiance_window = penumbra::Config{}.irradiance_window;
    bool irradiance_quadrants = penumbra::Config{}.irradiance_quadrants;
    bool near_field = penumbra::Config{}.near_field;
};

std::string variant_name(const Variant& v) {
    auto number = [](double x) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", x);
        return std::string(text);
    };
    const penumbra::Config d{};
    return std::string(penumbra::to_string(v.fusion)) + (v.tangent_clip ? "+clip" : "") +
           (v.tangent_clip && v.tangent_clip_offset != d.tangent_clip_offset
                ? "+offset" + number(v.tangent_clip_offset)
                : "") +
           (v.tangent_clip && v.clip_footprint != d.clip_footprint
                ? (v.clip_footprint ? "+footprint" : "+nofootprint")
                : "") +
           (v.fade_ramp != d.fade_ramp ? "+ramp" + number(v.fade_ramp) : "") + (v.leak_fix ? "" : "+noleak") +
           (v.placement == penumbra::SlicePlacement::adaptive ? "+adaptive" : "") +
           (v.solid_casters != d.solid_casters ? (v.solid_casters ? "+solid" : "+nosolid") : "") +
           (v.irradiance_window != d.irradiance_window ? (v.irradiance_window ? "+irradiance" : "+area")
                                                       : "") +
           (v.irradiance_quadrants != d.irradiance_quadrants
                ? (v.irradiance_quadrants ? "+quadrants" : "+noquadrants")
                : "") +
           (v.near_field != d.near_field ? (v.near_field ? "+near" : "+nonear") : "");
}

// A scene to measure: a built-in name or a mesh file, and the name its rows carry.
struct SceneInput {
    std::string name_or_path, name;
    bool file = false; // a mesh file (or the corpus): summarised apart from the built-in scenes
};

struct Options {
    std::vector<Variant> variants{Variant{}};
    std::vector<SceneInput> scenes;
    std::vector<penumbra::Filter> filters{penumbra::Filter::mipmap, penumbra::Filter::nbuffer, penumbra::Filter::sat};
    std::vector<SliceSetting> settings{{16, 512}, {4, 128}};
    std::vector<int> level_reductions{penumbra::Config{}.level_reduction}; // --level-reductions
    std::vector<double> light_scales{1.0}; // --light-scales: multiples of each scene's rectangle
    int width = 256, height = 256, samples = 16, repeat = 3;
    bool ground = true; // --no-ground: no floor under the mesh files
    SceneOverrides
        overrides; // --light-*, --camera-*: every scene's light and camera (app/scene_overrides.hpp)
};

constexpr const char* usage_text =
    "usage: penumbra-bench-quality [--scenes a,b,...] [FILE ...] [--corpus [DIR]] [--no-ground] [--filters "
    "f,g,...]\n"
    "                              [--configs SxR,...] [--size WxH] [--samples N] [--repeat N] [--variants "
    "v,w,...]\n"
    "                              [--level-reductions N,M,...] [--light-scales X,Y,...] [--light-size "
    "W[,H]]\n"
    "                              [--light-center X,Y,Z] [--light-normal X,Y,Z] [--light-up X,Y,Z]\n"
    "                              [--camera-position X,Y,Z] [--camera-target X,Y,Z]\n"
    "  --scenes    built-in scenes (default all: planes, boxes, tree, butterfly, terrain, crowd, box, "
    "cutout; '' for none;\n"
    "              the rooms room, window, cornell only when named)\n"
    "  FILE        mesh files (what penumbra-playground --scene loads), measured after the built-in scenes\n"
    "  --corpus    every mesh of the corpus in DIR (default ~/.cache/penumbra/corpus; "
    "scripts/get_corpus.sh)\n"
    "  --no-ground no floor under the mesh files (default: each stands on one, as in penumbra-playground)\n"
    "  --filters   mipmap, nbuffer, sat (default all three; the light is each scene's rectangle)\n"
    "  --configs   slices x occlusion-texture resolution (default 16x512,4x128)\n"
    "  --size      image size (default 256x256)\n"
    "  --samples   ground-truth rays per light axis (default 16: 256 rays per pixel)\n"
    "  --repeat    render each configuration N times and keep each pass's fastest time (default 3)\n"
    "  --variants  model variants: a fusion rule, optionally +clip for the tangent clip, +offsetT for its "
    "offset\n"
    "              (slicing texels), +nofootprint / +footprint for its footprint move, +rampF for the fade's "
    "ramp\n"
    "              (fraction of a slice), +noleak for the leak fix off, +adaptive for adaptive slice "
    "placement and +solid\n"
    "              for solid casters (closed meshes fill the slices between their surfaces), +irradiance for "
    "the\n"
    "              irradiance window (the light weighed by the irradiance it sends; the default), +area for\n"
    "              the light weighed by area (--no-irradiance-window), +quadrants for the window's "
    "quadrants\n"
    "              (--irradiance-quadrants: the large profile), +near for the near field (--near-field), "
    "e.g.\n"
    "              probabilistic,chained+clip,chained+clip+offset3+nofootprint+ramp1,chained+clip+adaptive\n"
    "              (default: Config{}'s)\n"
    "  --level-reductions  level_reduction values to measure, each a row (-1: every level at full\n"
    "              resolution; default: Config{}'s); rows of another value than the default say 'rN'\n"
    "  --light-scales  multiples of each scene's default rectangle (both sides), each a row 'xK'\n"
    "              (default 1; e.g. 1,2,4,8,16,32); a summary per scale follows the rows, built-in scenes\n"
    "              and files apart: mean penumbra MAE and mean signed error (estimate - truth) of the "
    "shaded\n"
    "              image (the irradiance error weighed by the light each pixel receives), the same against\n"
    "              the irradiance reference (every pixel alike) and the oriented one, mean false light and "
    "false shadow, then near the terminator (within 3 pixels of\n"
    "              where a surface turns away from the light's centre): p95 of |error| and the error's\n"
    "              total variation (sawtooth, seams); with more than one scale, a table per scene and\n"
    "              setting: MAE / signed error by scale, shaded image, irradiance, then oriented\n"
    "  --light-size W[,H]  every scene's rectangle: W its longer side (aspect kept), W,H its width (along "
    "u)\n"
    "              and height (along v), in scene units; --light-scales multiply it\n"
    "  --light-center X,Y,Z  the rectangle's centre; --light-normal X,Y,Z: the direction it faces and emits\n"
    "              towards; --light-up X,Y,Z: its height side (v), projected onto its plane, not parallel "
    "to\n"
    "              the normal (default: the scene light's v, else +y, else +z); as penumbra-playground\n"
    "  --camera-position X,Y,Z, --camera-target X,Y,Z  every scene's camera (either alone keeps the\n"
    "              scene's other; not the same point)\n"
    "  (light and camera flags are set on every scene once it is made, and hold for the ground truth)\n";

bool parse_pair(std::string_view text, int& a, int& b) {
    const std::size_t x = text.find('x');
    return x != std::string_view::npos && parse_number(text.substr(0, x), a) && parse_number(text.substr(x + 1), b);
}

// Options from argv, or an error message.
std::optional<Options> parse(int argc, char** argv, std::string& error) {
    Options o;
    for (std::string_view name : scene_names()) o.scenes.push_back({std::string(name), std::string(name)});
    std::vector<SceneInput> files;
    for (int i = 1; i < argc; ++i) {
        const std::string_view flag = argv[i];
        if (!flag.starts_with("--")) { // a mesh file, named after its stem
            files.push_back({std::string(flag), std::filesystem::path(flag).stem().string(), true});
            continue;
        }
        if (flag == "--no-ground") {
            o.ground = false;
            continue;
        }
        if (flag == "--corpus") {
            const std::optional<std::vector<penumbra::bench::CorpusMesh>> corpus =
                penumbra::bench::read_corpus(penumbra::bench::corpus_dir_argument(argc, argv, i), &error);
            if (!corpus) return std::nullopt;
            for (const penumbra::bench::CorpusMesh& m : *corpus) files.push_back({m.path, m.name, true});
            continue;
        }
        if (i + 1 >= argc) {
            error = std::string(flag) + ": missing value";
            return std::nullopt;
        }
        const std::string_view value = argv[++i];
        if (flag == "--scenes") {
            o.scenes.clear();
            for (std::string_view name : split(value)) {
                if (!make_scene(name)) {
                    error = "--scenes: unknown scene '" + std::string(name) +
                            "'; allowed: " + allowed_scene_names();
                    return std::nullopt;
                }
                o.scenes.push_back({std::string(name), std::string(name)});
            }
        } else if (flag == "--filters") {
            o.filters.clear();
            for (std::string_view name : split(value)) {
                const std::optional<penumbra::Filter> filter = penumbra::parse_enum<penumbra::Filter>(name);
                if (!filter || *filter == penumbra::Filter::gaussian) {
                    error = "--filters: '" + std::string(name) + "' is not allowed; allowed: mipmap, nbuffer, sat";
                    return std::nullopt;
                }
                o.filters.push_back(*filter);
            }
        } else if (flag == "--configs") {
            o.settings.clear();
            for (std::string_view pair : split(value)) {
                SliceSetting s;
                if (!parse_pair(pair, s.slices, s.resolution)) {
                    error = "--configs: '" + std::string(pair) + "' is not SLICESxRESOLUTION, e.g. 16x512";
                    return std::nullopt;
                }
                o.settings.push_back(s);
            }
        } else if (flag == "--variants") {
            o.variants.clear();
            for (std::string_view name : split(value)) {
                Variant v;
                v.tangent_clip = false;
                v.placement = penumbra::SlicePlacement::uniform;
                const std::vector<std::string_view> parts = split(name, '+');
                const std::optional<penumbra::Fusion> fusion =
                    parts.empty() ? std::nullopt : penumbra::parse_enum<penumbra::Fusion>(parts.front());
                if (!fusion) {
                    error = "--variants: '" + std::string(name) + "' does not start with a fusion rule; allowed: "
                            "probabilistic, additive, maximum, average, chained, correlated, extent, clustered";
                    return std::nullopt;
                }
                v.fusion = *fusion;
                for (std::size_t k = 1; k < parts.size(); ++k) { // the suffixes, in any order
                    const std::string_view part = parts[k];
                    double number = 0;
                    if (part == "clip") v.tangent_clip = true;
                    else if (part == "adaptive") v.placement = penumbra::SlicePlacement::adaptive;
                    else if (part == "footprint" || part == "nofootprint") v.clip_footprint = part == "footprint";
                    else if (part == "noleak") v.leak_fix = false;
                    else if (part == "solid" || part == "nosolid") v.solid_casters = part == "solid";
                    else if (part == "irradiance" || part == "area") v.irradiance_window = part == "irradiance";
                    else if (part == "quadrants" || part == "noquadrants")
                        v.irradiance_quadrants = part == "quadrants";
                    else if (part == "near" || part == "nonear")
                        v.near_field = part == "near";
                    else if (part.starts_with("offset") && parse_number(part.substr(6), number)) v.tangent_clip_offset = number;
                    else if (part.starts_with("ramp") && parse_number(part.substr(4), number)) v.fade_ramp = number;
                    else {
                        error = "--variants: '" + std::string(part) + "' in '" + std::string(name) +
                                "' is not allowed; allowed after the fusion rule: +clip, +adaptive, "
                                "+[no]footprint, +noleak, +[no]solid, "
                                "+irradiance / +area (the irradiance window on or off), +[no]quadrants, "
                                "+[no]near "
                                "(the near field), +offsetT "
                                "(tangent clip offset, texels), +rampF (fade ramp, fraction of a slice)";
                        return std::nullopt;
                    }
                }
                o.variants.push_back(v);
            }
        } else if (flag == "--level-reductions") {
            o.level_reductions.clear();
            for (std::string_view item : split(value)) {
                int n = 0;
                const bool negative = item.starts_with("-");
                if (negative) item.remove_prefix(1);
                if (!parse_number(item, n) || (negative && n != 1) || n > 12) {
                    error = "--level-reductions: expected -1 or 0 to 12, e.g. -1,2,3";
                    return std::nullopt;
                }
                o.level_reductions.push_back(negative ? -1 : n);
            }
        } else if (flag == "--light-scales") {
            o.light_scales.clear();
            for (std::string_view item : split(value)) {
                double scale = 0;
                if (!parse_number(item, scale) || !(scale > 0.0) || scale > 64.0) {
                    error = "--light-scales: '" + std::string(item) + "' is not allowed; allowed: numbers above 0, at most 64";
                    return std::nullopt;
                }
                o.light_scales.push_back(scale);
            }
            if (o.light_scales.empty()) {
                error = "--light-scales: empty; allowed: numbers above 0, at most 64";
                return std::nullopt;
            }
        } else if (penumbra::playground::is_scene_override_flag(flag)) {
            error = penumbra::playground::parse_scene_override(flag, value, o.overrides);
            if (!error.empty()) return std::nullopt;
        } else if (flag == "--size") {
            if (!parse_pair(value, o.width, o.height) || o.width < 1 || o.height < 1 || o.width > 4096 || o.height > 4096) {
                error = "--size: expected WxH, 1 to 4096 each";
                return std::nullopt;
            }
        } else if (flag == "--samples") {
            if (!parse_number(value, o.samples) || o.samples < 1 || o.samples > 256) {
                error = "--samples: expected 1 to 256";
                return std::nullopt;
            }
        } else if (flag == "--repeat") {
            if (!parse_number(value, o.repeat) || o.repeat < 1 || o.repeat > 100) {
                error = "--repeat: expected 1 to 100";
                return std::nullopt;
            }
        } else {
            error = "unknown flag '" + std::string(flag) +
                    "'; allowed: --scenes, --corpus, --no-ground, --filters, --configs, --size, "
                    "--samples, --repeat, --variants, --level-reductions, --light-scales, " +
                    std::string(penumbra::playground::scene_override_flag_list) + ", --help, FILE";
            return std::nullopt;
        }
    }
    o.scenes.insert(o.scenes.end(), files.begin(), files.end());
    if (error = penumbra::playground::check_scene_overrides(o.overrides); !error.empty()) return std::nullopt;
    if (o.scenes.empty()) {
        error = "no scene: give --scenes, a mesh file or --corpus";
        return std::nullopt;
    }
    return o;
}

// Same pixels, same world positions (NaN on background): the reference can be reused.
bool same_gbuffer(const HeadlessResult& a, const HeadlessResult& b) {
    if (a.geometry != b.geometry) return false;
    for (std::size_t i = 0; i < a.positions.size(); ++i)
        if (a.geometry[i] && a.positions[i] != b.positions[i]) return false;
    return true;
}

// Each pass name once, in order, with the summed time of its instances (N-buffer levels, SAT
// doubling steps) and how many there were.
struct PassTotal {
    std::string name;
    int count = 0;
    double milliseconds = 0;
};

std::vector<PassTotal> pass_totals(const std::vector<penumbra::gl::PassTiming>& timings) {
    std::vector<PassTotal> totals;
    for (const penumbra::gl::PassTiming& t : timings) {
        if (totals.empty() || totals.back().name != t.name) totals.push_back({t.name, 0, 0.0});
        ++totals.back().count;
        totals.back().milliseconds += t.milliseconds;
    }
    return totals;
}

// The error near the terminator, what the eye sees of a sawtooth or a seam there: the geometry pixels
// with a fair (oriented) truth within `radius` pixels of a pair of neighbouring geometry pixels on
// which the side the light's centre lies on (the sign of n·(C − X)) changes: a surface turning away
// from the light, whatever the light's size. p95 of |estimate − truth| over them, and the total variation of the signed
// error: the mean |e_i − e_j| over horizontally and vertically adjacent pairs of them (a smooth error
// has little, a texel-aliased one much).
struct BoundaryStats {
    double p95 = 0, total_variation = 0;
    std::size_t count = 0;
};

BoundaryStats terminator_error(const HeadlessResult& result, const std::vector<float>& oriented, glm::dvec3 light_centre,
                               int radius = 3) {
    const int w = result.width, h = result.height;
    auto index = [w](int x, int y) { return static_cast<std::size_t>(y) * w + x; };
    auto facing = [&](std::size_t i) {
        return glm::dot(glm::dvec3(result.normals[i]), light_centre - glm::dvec3(result.positions[i])) > 0.0;
    };
    std::vector<unsigned char> turn(result.geometry.size(), 0); // the side changes towards the next pixel
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = index(x, y);
            if (!result.geometry[i]) continue;
            if (x + 1 < w && result.geometry[index(x + 1, y)] && facing(i) != facing(index(x + 1, y))) turn[i] = 1;
            if (y + 1 < h && result.geometry[index(x, y + 1)] && facing(i) != facing(index(x, y + 1))) turn[i] = 1;
        }
    auto dark = [&](int x, int y) { return turn[index(x, y)] != 0; };
    std::vector<unsigned char> near(result.geometry.size(), 0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = index(x, y);
            if (!result.geometry[i] || std::isnan(oriented[i])) continue;
            for (int dy = -radius; dy <= radius && !near[i]; ++dy)
                for (int dx = -radius; dx <= radius; ++dx) {
                    const int u = x + dx, v = y + dy;
                    if (u >= 0 && v >= 0 && u < w && v < h && dark(u, v)) {
                        near[i] = 1;
                        break;
                    }
                }
        }
    BoundaryStats b;
    std::vector<double> errors;
    double variation = 0;
    std::size_t pairs = 0;
    auto error = [&](std::size_t i) { return static_cast<double>(result.visibility[i]) - oriented[i]; };
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = index(x, y);
            if (!near[i]) continue;
            errors.push_back(std::abs(error(i)));
            if (x + 1 < w && near[index(x + 1, y)]) variation += std::abs(error(i) - error(index(x + 1, y))), ++pairs;
            if (y + 1 < h && near[index(x, y + 1)]) variation += std::abs(error(i) - error(index(x, y + 1))), ++pairs;
        }
    b.count = errors.size();
    if (!errors.empty()) {
        const std::size_t k = std::min(errors.size() - 1, static_cast<std::size_t>(std::ceil(0.95 * errors.size())) - 1);
        std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(k), errors.end());
        b.p95 = errors[k];
    }
    b.total_variation = pairs ? variation / pairs : 0.0;
    return b;
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
    std::vector<Scene> scenes; // every scene loaded before the first row, so a bad file stops the run at once
    for (const SceneInput& input : options->scenes) {
        SceneLoad loaded = load_scene(input.name_or_path, options->ground);
        if (!loaded.scene) {
            std::cerr << "error: " << loaded.error << "\n";
            return 2;
        }
        // --light-*, --camera-*: before the truth and every render (--light-scales scale the result)
        if (std::string e = apply_scene_overrides(options->overrides, *loaded.scene, penumbra::Light::rect);
            !e.empty()) {
            std::cerr << "error: " << e << "\n";
            return 2;
        }
        scenes.push_back(std::move(*loaded.scene));
        scenes.back().name = input.name;
    }
    // The summary: per row label without the scene (and light scale), mean fair penumbra MAE and signed error
    // against the oriented reference and against the irradiance one.
    struct Summary {
        double mae = 0, bias = 0, worst = 0, terminator_p95 = 0, terminator_variation = 0;
        double irradiance_mae = 0, irradiance_bias = 0, irradiance_worst = 0;
        double shaded_mae = 0,
               shaded_bias = 0;              // the irradiance error weighed by the light each pixel receives
        ErrorRate false_light, false_shadow; // pooled over the scenes: a scene with few dark pixels weighs little
        int count = 0;
        std::string worst_scene, irradiance_worst_scene;
    };
    std::map<std::pair<std::string, double>, Summary> summaries[2]; // [0] built-in scenes, [1] mesh files
    std::vector<std::string> summary_order;
    // Each scene's penumbra MAE and signed error by light scale against irradiance, then oriented, for the
    // per-scene table after the summary (scenes in the order measured).
    struct SceneCell {
        double shaded_mae, shaded_bias, irradiance_mae, irradiance_bias, oriented_mae, oriented_bias;
    };
    std::map<std::pair<std::string, std::string>, std::map<double, SceneCell>> per_scene;
    std::vector<std::string> scene_order;
    std::optional<HeadlessContext> context = HeadlessContext::create(&error);
    if (!context) {
        std::cerr << "error: no OpenGL 4.5 context: " << error << "\n";
        return 1;
    }
    std::printf(
        "penumbra-bench-quality: %s; image %dx%d; ground truth %dx%d rays per pixel; fastest of %d\n"
        "light: each scene's default (2x2 rectangle for the built-in scenes) unless --light-* says; filter "
        "column: filter and\n"
        "variant (fusion, +clip: tangent clip, +adaptive: adaptive slice placement, whose passes count as "
        "slicing);\n"
        "atlas, leak fix and fade on; penumbra pixels: truth or estimate < 0.98; times: GPU ms per pass\n\n",
        context->renderer().c_str(), options->width, options->height, options->samples, options->samples,
        options->repeat);
    std::printf("| scene | filter | S/R | MAE | RMSE | p95 | penumbra MAE | penumbra RMSE | penumbra p95 | "
                "penumbra px "
                "| oriented penumbra MAE | oriented p95 | irradiance penumbra MAE | irradiance p95 "
                "| slicing ms | prefilter ms | shading ms | terminator p95 | terminator TV | terminator px "
                "| false light % (px) | false shadow % (px) |\n");
    std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    std::vector<std::string> pass_lines;
    for (std::size_t scene_index = 0; scene_index < scenes.size(); ++scene_index)
    for (double light_scale : options->light_scales) {
        Scene& scene = scenes[scene_index];
        const bool file = options->scenes[scene_index].file;
        const penumbra::RectLight default_light = scene.light;
        scene.light.width *= light_scale;
        scene.light.height *= light_scale;
        const bool scaled = options->light_scales.size() > 1 || light_scale != 1.0;
        char scale_words[32];
        std::snprintf(scale_words, sizeof scale_words, " x%g", light_scale);
        const std::string scene_name = scene.name + (scaled ? scale_words : "");
        std::optional<HeadlessResult> reference_gbuffer; // the truth depends on the light: one per scale
        References truth;
        double truth_ms = 0;
        for (const SliceSetting& setting : options->settings)
            for (penumbra::Filter filter : options->filters)
            for (const Variant& variant : options->variants)
            for (int reduction : options->level_reductions) {
                penumbra::Config config{.slices = setting.slices, .resolution = setting.resolution, .filter = filter,
                                        .fusion = variant.fusion, .tangent_clip = variant.tangent_clip,
                                        .slice_placement = variant.placement};
                config.level_reduction = reduction;
                config.tangent_clip_offset = variant.tangent_clip_offset;
                config.clip_footprint = variant.clip_footprint;
                config.fade_ramp = variant.fade_ramp;
                config.leak_fix = variant.leak_fix;
                config.solid_casters = variant.solid_casters;
                config.irradiance_window = variant.irradiance_window;
                config.irradiance_quadrants = variant.irradiance_quadrants;
                config.near_field = variant.near_field;
                config.alpha_test = scene.mesh.cuts(); // cut-out casters cast as their materials cut, as the truth does
                const std::string reduced =
                    reduction == penumbra::Config{}.level_reduction ? "" : " r" + std::to_string(reduction);
                const std::string setting_label = std::string(penumbra::to_string(filter)) + " " + variant_name(variant) +
                                                  reduced + " | " + std::to_string(setting.slices) + "/" +
                                                  std::to_string(setting.resolution);
                const std::string label = scene_name + " | " + setting_label;
                if (const auto problems = penumbra::validate(config); !problems.empty()) {
                    std::printf("| %s | invalid: %s |\n", label.c_str(), problems.front().message.c_str());
                    continue;
                }
                HeadlessResult result;
                std::vector<penumbra::gl::PassTiming> fastest;
                for (int r = 0; r < options->repeat; ++r) {
                    if (!render_headless(scene, config, options->width, options->height, result, &error)) {
                        std::cerr << "error: " << label << ": " << error << "\n";
                        return 1;
                    }
                    if (fastest.empty()) fastest = result.timings;
                    for (std::size_t p = 0; p < fastest.size() && p < result.timings.size(); ++p)
                        fastest[p].milliseconds = std::min(fastest[p].milliseconds, result.timings[p].milliseconds);
                }
                if (!reference_gbuffer || !same_gbuffer(*reference_gbuffer, result)) {
                    const auto start = std::chrono::steady_clock::now();
                    truth = reference_all(scene, result, options->samples);
                    truth_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                    reference_gbuffer = result;
                }
                const QualityMetrics q = compare_quality(result, truth);
                const Metrics& m = q.visibility;
                if (std::find(summary_order.begin(), summary_order.end(), setting_label) == summary_order.end())
                    summary_order.push_back(setting_label);
                Summary& sum = summaries[file ? 1 : 0][{setting_label, light_scale}];
                if (std::find(scene_order.begin(), scene_order.end(), scene.name) == scene_order.end())
                    scene_order.push_back(scene.name);
                per_scene[{scene.name, setting_label}][light_scale] = {
                    q.shaded.penumbra.mae,      q.shaded.penumbra.bias,  q.irradiance.penumbra.mae,
                    q.irradiance.penumbra.bias, q.oriented.penumbra.mae, q.oriented.penumbra.bias};
                sum.shaded_mae += q.shaded.penumbra.mae;
                sum.shaded_bias += q.shaded.penumbra.bias;
                sum.mae += q.oriented.penumbra.mae;
                sum.bias += q.oriented.penumbra.bias;
                sum.irradiance_mae += q.irradiance.penumbra.mae;
                sum.irradiance_bias += q.irradiance.penumbra.bias;
                sum.false_light.wrong += q.false_light.wrong;
                sum.false_light.pixels += q.false_light.pixels;
                sum.false_shadow.wrong += q.false_shadow.wrong;
                sum.false_shadow.pixels += q.false_shadow.pixels;
                if (q.irradiance.penumbra.mae >= sum.irradiance_worst) {
                    sum.irradiance_worst = q.irradiance.penumbra.mae;
                    sum.irradiance_worst_scene = scene.name;
                }
                const BoundaryStats terminator = terminator_error(result, truth.oriented, scene.light.center);
                sum.terminator_p95 += terminator.p95;
                sum.terminator_variation += terminator.total_variation;
                ++sum.count;
                if (q.oriented.penumbra.mae >= sum.worst) {
                    sum.worst = q.oriented.penumbra.mae;
                    sum.worst_scene = scene.name;
                }
                const std::vector<PassTotal> totals = pass_totals(fastest);
                double slicing = 0, prefilter = 0, shading = 0;
                std::string line = label + ":";
                for (const PassTotal& t : totals) {
                    // adaptive placement's passes count as slicing: they only place its boundaries
                    if (t.name == "slicing" || t.name.starts_with("depth_bins") || t.name == "slice_boundaries")
                        slicing += t.milliseconds;
                    else if (t.name == "shading") shading += t.milliseconds;
                    else prefilter += t.milliseconds;
                    char part[96];
                    std::snprintf(part, sizeof part, " %s%s %.2f", t.name.c_str(),
                                  t.count > 1 ? ("x" + std::to_string(t.count)).c_str() : "", t.milliseconds);
                    line += part;
                }
                pass_lines.push_back(line);
                std::printf("| %s | %.4f | %.4f | %.4f | %.4f | %.4f | %.4f | %zu | %.4f | %.4f | %.4f | "
                            "%.4f | %.1f | %.1f "
                            "| %.1f | %.4f | %.4f | %zu | %.1f (%zu of %zu) | %.1f (%zu of %zu) |\n",
                            label.c_str(), m.all.mae, m.all.rmse, m.all.p95, m.penumbra.mae, m.penumbra.rmse,
                            m.penumbra.p95, m.penumbra.count, q.oriented.penumbra.mae,
                            q.oriented.penumbra.p95, q.irradiance.penumbra.mae, q.irradiance.penumbra.p95,
                            slicing, prefilter, shading, terminator.p95, terminator.total_variation,
                            terminator.count, 100.0 * q.false_light.fraction(), q.false_light.wrong,
                            q.false_light.pixels, 100.0 * q.false_shadow.fraction(), q.false_shadow.wrong,
                            q.false_shadow.pixels);
                std::fflush(stdout);
            }
        std::printf("|   (%s ground truth: %.0f ms CPU, Embree) |\n", scene_name.c_str(), truth_ms);
        scene.light = default_light;
    }
    std::printf(
        "\npenumbra error by light scale, over the scenes measured: the shaded image's first (the irradiance "
        "error weighed by the light each pixel receives), then against the irradiance reference (the "
        "shading's "
        "relative error, every pixel alike), then the oriented one (the visibility of the part of the light "
        "above "
        "the surface)\n");
    // The rest of a table's header after its first columns: a column per light scale.
    const auto print_scale_columns = [&](std::size_t first_columns) {
        for (double scale : options->light_scales) std::printf(" x%g |", scale);
        std::printf("\n|");
        for (std::size_t k = 0; k < first_columns + options->light_scales.size(); ++k) std::printf("---|");
        std::printf("\n");
    };
    // One table per group: a row per setting, a column per light scale, each cell written by `cell`.
    const auto print_by_scale = [&](int group, const auto& cell) {
        print_scale_columns(2);
        for (const std::string& label : summary_order) {
            std::printf("| %s |", label.c_str());
            for (double scale : options->light_scales) {
                const auto it = summaries[group].find({label, scale});
                if (it == summaries[group].end() || it->second.count == 0)
                    std::printf(" - |");
                else
                    cell(it->second);
            }
            std::printf("\n");
        }
    };
    for (int group = 0; group < 2; ++group) {
        if (summaries[group].empty()) continue;
        const char* group_name = group == 0 ? "built-in scenes" : "mesh files";
        std::printf("\n%s, shaded image (the irradiance error weighed by the light each pixel receives, "
                    "reference/metrics.hpp): mean penumbra MAE / mean signed error\n\n| filter | S/R |",
                    group_name);
        print_by_scale(group, [](const Summary& sum) {
            std::printf(" %.4f / %+.4f |", sum.shaded_mae / sum.count, sum.shaded_bias / sum.count);
        });
        std::printf("\n%s, irradiance (the shaded image's reference): mean penumbra MAE / mean signed error (estimate - "
                    "truth) / worst scene's MAE (scenes)\n\n| filter | S/R |",
                    group_name);
        print_by_scale(group, [](const Summary& sum) {
            std::printf(" %.4f / %+.4f / %.3f %s (%d) |", sum.irradiance_mae / sum.count, sum.irradiance_bias / sum.count,
                        sum.irradiance_worst, sum.irradiance_worst_scene.c_str(), sum.count);
        });
        std::printf("\n%s, oriented: mean penumbra MAE / mean signed error / worst scene's MAE (scenes)\n\n| filter | S/R |",
                    group_name);
        print_by_scale(group, [](const Summary& sum) {
            std::printf(" %.4f / %+.4f / %.3f %s (%d) |", sum.mae / sum.count, sum.bias / sum.count, sum.worst,
                        sum.worst_scene.c_str(), sum.count);
        });
        std::printf("\n%s: false light %% / false shadow %% (reference/metrics.hpp), the scenes' pixels pooled\n\n"
                    "| filter | S/R |",
                    group_name);
        print_by_scale(group, [](const Summary& sum) {
            std::printf(" %.1f / %.1f |", 100.0 * sum.false_light.fraction(), 100.0 * sum.false_shadow.fraction());
        });
        std::printf("\nnear the terminator (%s): mean p95 of |error| / mean total variation of the error\n\n| filter | S/R |",
                    group_name);
        print_by_scale(group, [](const Summary& sum) {
            std::printf(" %.4f / %.4f |", sum.terminator_p95 / sum.count, sum.terminator_variation / sum.count);
        });
    }
    if (options->light_scales.size() > 1) {
        std::printf("\nper scene, penumbra MAE / signed error by light scale: shaded image, irradiance, then "
                    "oriented\n\n"
                    "| scene | filter | S/R |");
        print_scale_columns(3);
        for (const std::string& scene_name : scene_order)
            for (const std::string& label : summary_order) {
                const auto row = per_scene.find({scene_name, label});
                if (row == per_scene.end()) continue;
                std::printf("| %s | %s |", scene_name.c_str(), label.c_str());
                for (double scale : options->light_scales) {
                    const auto it = row->second.find(scale);
                    if (it == row->second.end())
                        std::printf(" - |");
                    else
                        std::printf(" %.4f / %+.4f; %.4f / %+.4f; %.4f / %+.4f |", it->second.shaded_mae,
                                    it->second.shaded_bias, it->second.irradiance_mae,
                                    it->second.irradiance_bias, it->second.oriented_mae,
                                    it->second.oriented_bias);
                }
                std::printf("\n");
            }
    }
    std::printf("\nper-pass GPU ms (xN: N instances of the pass, summed):\n");
    for (const std::string& line : pass_lines) std::printf("  %s\n", line.c_str());
    return 0;
}
