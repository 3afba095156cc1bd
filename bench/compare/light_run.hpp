// bench/compare/light_run.hpp — the measuring: one run of the ladder over one scene under one kind of
// light (the truth, a runtime per setting, every light size timed and compared, then the flicker).
#pragma once

#include "frame.hpp"
#include "ladder.hpp"
#include "lights.hpp"
#include "progress.hpp"
#include "report.hpp"
#include "truth_cache.hpp"

#include "bake/oim_scene.hpp"
#include "rendering/gpu_scene.hpp"
#include "rendering/headless_render.hpp"

#include <penumbra/config_fields.hpp>
#include <penumbra/gl/runtime.hpp>
#include <penumbra/layout.hpp>
#include <penumbra/texture_memory.hpp>

#include <nlohmann/json.hpp>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::bench {

using namespace penumbra::playground;
using json = nlohmann::ordered_json;

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
        std::vector<double> bias, bias_oriented, bias_irradiance;
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
        cell.bias_irradiance.resize(active_.size());
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
            cell.quality[e] = compare_quality(visibility, geometry, truth.visibility, truth.oriented,
                                              truth.irradiance, truth.unoccluded);
            cell.bias[e] = penumbra_bias(visibility, geometry, truth.visibility);
            cell.bias_oriented[e] = penumbra_bias(visibility, geometry, truth.oriented);
            cell.bias_irradiance[e] = penumbra_bias(visibility, geometry, truth.irradiance);
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
                             {"oriented",
                              {{"all", stats_json(q.oriented.all)},
                               {"penumbra", stats_json(q.oriented.penumbra)},
                               {"penumbra_bias", cell.bias_oriented[e]}}},
                             {"irradiance",
                              {{"all", stats_json(q.irradiance.all)},
                               {"penumbra", stats_json(q.irradiance.penumbra)},
                               {"penumbra_bias", cell.bias_irradiance[e]}}},
                             // the irradiance error weighed by the light each pixel receives (metrics.hpp)
                             {"shaded",
                              {{"all", stats_json(q.shaded.all)},
                               {"penumbra", stats_json(q.shaded.penumbra)},
                               {"penumbra_bias", q.shaded.penumbra.bias}}}};
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

} // namespace penumbra::bench
