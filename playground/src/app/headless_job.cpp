// playground/src/app/headless_job.cpp
#include "app/headless_job.hpp"

#include "rendering/egl_context.hpp"
#include "app/image_io.hpp"
#include "bake/oim_scene.hpp"
#include "scenes/gltf_loader.hpp"
#include "scenes/ground_plane.hpp"
#include "scenes/obj_loader.hpp"
#include "scenes/scenes.hpp"

#include <penumbra_tools/file_transaction.hpp>
#include <penumbra_tools/printable.hpp>
#include <penumbra/config_fields.hpp>
#include <penumbra/layout.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

namespace penumbra::playground {
namespace {

// Differences beyond this saturate the false-colour error image.
constexpr float error_image_range = 0.25f;

std::string lower_extension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
    return extension;
}

// `out` with its extension replaced by `suffix`: image.png → image.reference.pfm.
std::string sibling_path(const std::string& out, const std::string& suffix) {
    std::filesystem::path path(out);
    path.replace_extension();
    return path.string() + suffix;
}

double milliseconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

nlohmann::ordered_json stats_json(const ErrorStats& s) {
    return {{"mae", s.mae}, {"rmse", s.rmse}, {"p95", s.p95}, {"signed", s.bias}, {"pixels", s.count}};
}

int fail(const std::string& message, int code = 1) {
    std::cerr << "error: " << message << "\n";
    return code;
}

} // namespace

// layout.json's "config" object (every technique's keys), so that --config metrics.json reproduces the run.
nlohmann::ordered_json config_json(const Config& c) {
    return nlohmann::ordered_json::parse(config_to_json(c)); // penumbra/config_fields.hpp
}

nlohmann::ordered_json light_json(const Scene& scene, Light light) {
    if (light == Light::sun)
        return {{"kind", "sun"},
                {"angular_diameter_degrees", scene.sun.angular_diameter * 180.0 / 3.14159265358979323846},
                {"direction", {scene.sun.direction.x, scene.sun.direction.y, scene.sun.direction.z}}};
    const RectLight& l = scene.light;
    const glm::dvec3 n = l.normal();
    return {{"kind", "rect"},
            {"width", l.width},
            {"height", l.height},
            {"center", {l.center.x, l.center.y, l.center.z}},
            {"normal", {n.x, n.y, n.z}},
            {"up", {l.v_axis.x, l.v_axis.y, l.v_axis.z}},
            {"u_axis", {l.u_axis.x, l.u_axis.y, l.u_axis.z}}};
}

nlohmann::ordered_json camera_json(const OrbitCamera& camera) {
    const glm::vec3 eye = camera.eye_position();
    return {{"position", {eye.x, eye.y, eye.z}},
            {"target", {camera.target.x, camera.target.y, camera.target.z}},
            {"fov_y_degrees", camera.fov_y_radians * 180.0 / 3.14159265358979323846},
            {"z_near", camera.z_near},
            {"z_far", camera.z_far}};
}

bool is_scene_file(const std::string& name_or_path) {
    const std::string extension = lower_extension(name_or_path);
    return extension == ".obj" || extension == ".gltf" || extension == ".glb";
}

SceneLoad load_scene(const std::string& name_or_path, bool ground) {
    if (is_scene_file(name_or_path)) {
        LoadResult loaded = lower_extension(name_or_path) == ".obj" ? load_obj_scene(name_or_path)
                                                                    : load_gltf_scene(name_or_path);
        for (const std::string& warning : loaded.warnings) std::cerr << "warning: " << warning << "\n";
        if (loaded.scene && ground) add_ground_plane(*loaded.scene);
        return {std::move(loaded.scene), std::move(loaded.error), std::move(loaded.warnings)};
    }
    if (std::optional<Scene> scene = make_scene(name_or_path)) return {std::move(scene), {}, {}};
    const std::string allowed = allowed_scene_names() + ", ";
    return {std::nullopt, "--scene: unknown scene '" + penumbra_gen::printable(name_or_path) + "'; allowed: " + allowed +
                              "or a mesh file ending in .obj (Wavefront), .gltf or .glb (glTF 2.0)",
            {}};
}

void apply_light_size(Scene& scene, Light light, double size) { scale_light_to(scene, light, size); }

double shadowed_fraction(const HeadlessResult& result) {
    std::size_t geometry = 0, shadowed = 0;
    for (std::size_t i = 0; i < result.visibility.size(); ++i) {
        if (!result.geometry[i]) continue;
        ++geometry;
        shadowed += result.visibility[i] < 0.5f;
    }
    return geometry ? static_cast<double>(shadowed) / static_cast<double>(geometry) : 0.0;
}

namespace {

// Every output file of the run is one transaction (tools/include/penumbra_tools/file_transaction.hpp):
// all written, or none and the directory as it was; "wrote" is printed only after it succeeded.
struct RunOutputs {
    penumbra_gen::FileChanges files;
    std::vector<std::string> wrote;

    // Adds the file when its bytes could be encoded (the encoder's error stays in its *error).
    bool add(const std::string& path, std::optional<std::string> bytes) {
        if (!bytes) return false;
        files.writes.push_back({path, std::move(*bytes)});
        return true;
    }
    // Writes them all; the message of the first failure, nothing written, or "" and the "wrote" lines.
    std::string commit() {
        if (std::string e = penumbra_gen::commit(files); !e.empty()) return e;
        for (const std::string& line : wrote) std::cout << "wrote " << line << "\n";
        return {};
    }
};

// Occlusion interval maps: unique texture coordinates, the sun at --sun-time, the bake (or its
// cache), handed to the renderer through `render_options`; nullopt and *error when it fails.
std::optional<OimSetup> bake_oim(const PlaygroundOptions& options, Scene& scene, RenderOptions& render_options,
                                 std::string* error) {
    penumbra::SunPath path;
    if (!options.sun_path.empty()) path = *parse_sun_path(options.sun_path, error);
    const std::filesystem::path cache = options.bake_cache.empty() ? default_oim_cache_dir()
                                                                    : std::filesystem::path(options.bake_cache);
    std::optional<OimSetup> oim = prepare_oim(scene, options.config, path, options.sun_time, cache, error);
    if (!oim) return std::nullopt;
    const OimBake& b = oim->cached.bake;
    std::printf("oim bake %dx%d, %d intervals, %d samples: %s %s (%.0f ms to bake, %llu rays, %zu texels merged, "
                "%.1f MiB on disk)\n",
                b.resolution, b.resolution, b.intervals, b.samples, oim->cached.from_cache ? "read" : "baked into",
                oim->cached.file.string().c_str(), b.bake_ms, static_cast<unsigned long long>(b.rays),
                b.merged_texels, static_cast<double>(oim->cached.file_bytes) / (1024.0 * 1024.0));
    if (!oim->cached.warning.empty()) std::cerr << "warning: " << oim->cached.warning << "\n";
    render_options.bake_textures = oim->textures;
    render_options.time_window = oim->time_window;
    return oim;
}

// The rendered image (--out) and, with --visibility-out, the visibility as a PFM.
bool add_render_files(RunOutputs& out, const PlaygroundOptions& options, const Scene& scene,
                      const HeadlessContext& context, const HeadlessResult& result, int width, int height,
                      std::string* error) {
    if (!out.add(options.out_path, encode_png_rgb(width, height, result.rgb, RowOrder::top_down, error))) return false;
    out.wrote.push_back(options.out_path + " (" + scene.name + ", " + std::to_string(width) + "x" +
                        std::to_string(height) + ", " + context.renderer() + ")");
    if (options.visibility_path.empty()) return true;
    if (!out.add(options.visibility_path, encode_pfm({width, height, 1, result.visibility}, error))) return false;
    out.wrote.push_back(options.visibility_path);
    return true;
}

// --metrics-out's object, without the reference's part (add_reference adds it).
nlohmann::ordered_json run_metrics(const PlaygroundOptions& options, const Scene& scene,
                                   const HeadlessContext& context, const HeadlessResult& result, int width,
                                   int height, double render_ms, const std::optional<OimSetup>& oim) {
    nlohmann::ordered_json metrics = {
        {"scene", scene.name},
        {"ground", scene.ground},
        {"renderer", context.renderer()},
        {"width", width},
        {"height", height},
        {"technique", to_string(options.config.technique)},
        {"config", config_json(options.config)},
        {"light", light_json(scene, shading_light(options.config))},
        {"camera", camera_json(scene.camera)},
        {"shadowed_fraction", shadowed_fraction(result)},
        {"render_ms", render_ms},
    };
    nlohmann::ordered_json passes = nlohmann::ordered_json::array();
    for (const penumbra::gl::PassTiming& t : result.timings) passes.push_back({{"name", t.name}, {"ms", t.milliseconds}});
    metrics["passes"] = passes;
    if (oim)
        metrics["bake"] = {{"kind", "oim"},
                           {"sun_time", options.sun_time},
                           {"from_cache", oim->cached.from_cache},
                           {"bake_ms", oim->cached.bake.bake_ms},
                           {"rays", oim->cached.bake.rays},
                           {"merged_texels", oim->cached.bake.merged_texels},
                           {"cache_file", oim->cached.file.string()},
                           {"cache_bytes", oim->cached.file_bytes}};
    metrics["timing"] = result.warm ? "warm: GPU times of a second run (the first compiles the shaders)" : "cold";
    metrics["texture_bytes"] = result.texture_bytes;
    return metrics;
}

// --reference: the ray-traced truth, its files (the three truths, error image), the printed
// comparison and metrics["reference"].
bool add_reference(RunOutputs& out, nlohmann::ordered_json& metrics, const PlaygroundOptions& options,
                   const Scene& scene, const HeadlessResult& result, int width, int height, std::string* error) {
    const auto reference_start = std::chrono::steady_clock::now();
    const References references = reference_all(scene, result, options.samples, shading_light(options.config));
    const double reference_ms = milliseconds_since(reference_start);
    const QualityMetrics q = compare_quality(result, references);
    // The headline is `irradiance`, the reference of the shaded image: an engine multiplies the
    // visibility into its own unoccluded area-light shading, so the visibility it needs weighs each
    // part of the light by the irradiance it sends. `oriented` (the visibility of the part of the light
    // above each surface's tangent plane) and the whole light's visibility follow under their names.
    const Metrics& headline = q.irradiance;
    const std::string truth_path =
        options.reference_path.empty() ? sibling_path(options.out_path, ".reference.pfm") : options.reference_path;
    const std::string error_path =
        options.error_image_path.empty() ? sibling_path(options.out_path, ".error.png") : options.error_image_path;
    // estimate − irradiance truth; NaN (green) where a pixel sees none of the light.
    std::vector<float> signed_error(references.irradiance.size());
    for (std::size_t i = 0; i < signed_error.size(); ++i)
        signed_error[i] = result.geometry[i] ? result.visibility[i] - references.irradiance[i] : 0.0f;
    // The whole-light truth at --reference-out, the fair ones beside it; the shaded image the estimate's
    // should match (the example shading of the irradiance truth) beside the output image.
    const std::string oriented_path = sibling_path(truth_path, ".oriented.pfm");
    const std::string irradiance_path = sibling_path(truth_path, ".irradiance.pfm");
    const std::string shaded_truth_path = sibling_path(options.out_path, ".reference.png");
    if (!out.add(truth_path, encode_pfm({width, height, 1, references.visibility}, error)) ||
        !out.add(oriented_path, encode_pfm({width, height, 1, references.oriented}, error)) ||
        !out.add(irradiance_path, encode_pfm({width, height, 1, references.irradiance}, error)) ||
        !out.add(error_path,
                 encode_png_rgb(width, height, signed_error_colors(signed_error, error_image_range),
                                RowOrder::top_down, error)) ||
        !out.add(shaded_truth_path,
                 encode_png_rgb(width, height, example_shading(result, references.irradiance),
                                RowOrder::top_down, error)))
        return false;
    out.wrote.push_back(truth_path + " (whole-light visibility), " + oriented_path + " (oriented), " +
                        irradiance_path + " (irradiance), " + shaded_truth_path +
                        " (the shaded image with the irradiance truth) and " + error_path +
                        " (against irradiance; red: estimate too bright, blue: too dark, saturating at ±" +
                        std::to_string(error_image_range).substr(0, 4) + ", green: sees none of the light)");
    std::printf("ground truth %dx%d rays/pixel, %.0f ms; irradiance (the shaded image's reference: the light "
                "weighed by the irradiance it sends, above each surface's tangent plane):\n"
                "  all:      MAE %.4f  RMSE %.4f  p95 %.4f  signed %+.4f  (%zu px)\n"
                "  penumbra: MAE %.4f  RMSE %.4f  p95 %.4f  signed %+.4f  (%zu px)\n",
                options.samples, options.samples, reference_ms, headline.all.mae, headline.all.rmse, headline.all.p95,
                headline.all.bias, headline.all.count, headline.penumbra.mae, headline.penumbra.rmse,
                headline.penumbra.p95, headline.penumbra.bias, headline.penumbra.count);
    auto print_other = [](const char* name, const Metrics& f) {
        std::printf(
            "  %-28s all MAE %.4f  p95 %.4f  (%zu px); penumbra MAE %.4f  RMSE %.4f  p95 %.4f  signed %+.4f  "
            "(%zu px)\n",
            name, f.all.mae, f.all.p95, f.all.count, f.penumbra.mae, f.penumbra.rmse, f.penumbra.p95,
            f.penumbra.bias, f.penumbra.count);
    };
    print_other("shaded (irradiance-weighed):", q.shaded);
    print_other("oriented:", q.oriented);
    print_other("whole-light visibility:", q.visibility);
    std::printf("  false light %.1f %% (%zu of %zu px the shading lights that get no light, estimate >= %.2f); "
                "false shadow %.1f %% (%zu of %zu px fully lit, estimate < %.2f)\n",
                100.0 * q.false_light.fraction(), q.false_light.wrong, q.false_light.pixels, false_light_estimate,
                100.0 * q.false_shadow.fraction(), q.false_shadow.wrong, q.false_shadow.pixels, false_shadow_estimate);
    auto metrics_json = [](const Metrics& f) {
        return nlohmann::ordered_json{{"all", stats_json(f.all)}, {"penumbra", stats_json(f.penumbra)}};
    };
    auto rate_json = [](const ErrorRate& r) {
        return nlohmann::ordered_json{{"fraction", r.fraction()}, {"pixels", r.wrong}, {"of", r.pixels}};
    };
    metrics["reference"] = {{"samples_per_axis", options.samples},
                            {"ms", reference_ms},
                            {"headline", "irradiance"},
                            {"all", stats_json(headline.all)},
                            {"penumbra", stats_json(headline.penumbra)},
                            {"irradiance", metrics_json(q.irradiance)},
                            // the irradiance error weighed by the light each pixel receives: the shaded
                            // image's error relative to its mean (reference/metrics.hpp)
                            {"shaded", metrics_json(q.shaded)},
                            {"oriented", metrics_json(q.oriented)},
                            {"whole_light_visibility", metrics_json(q.visibility)},
                            {"false_light", rate_json(q.false_light)},
                            {"false_shadow", rate_json(q.false_shadow)}};
    return true;
}

void print_pass_times(const HeadlessResult& result) {
    std::printf("passes (GPU ms, %s):", result.warm ? "warm" : "cold");
    for (const penumbra::gl::PassTiming& t : result.timings) std::printf(" %s %.2f", t.name.c_str(), t.milliseconds);
    std::printf("\ntexture memory: %lld bytes (%.2f MiB)\n", result.texture_bytes,
                static_cast<double>(result.texture_bytes) / (1024.0 * 1024.0));
    std::fflush(stdout);
}

} // namespace

PlaygroundOptions follow_asset_cuts(PlaygroundOptions options, const Scene& scene, std::string* note) {
    if (options.alpha_test_given || options.config.alpha_test || !scene.mesh.cuts()) return options;
    options.config.alpha_test = true;
    if (note)
        *note = "alpha test on: " + std::to_string(scene.mesh.cut_materials.size()) +
                " of the scene's materials cut, so they cast the shadow of their cut (--no-alpha-test: of their "
                "triangles)";
    return options;
}

// scene → context → (bake) → render → files and metrics → (reference) → one transaction.
int run_headless(const PlaygroundOptions& given) {
    SceneLoad loaded = load_scene(given.scene, given.ground);
    if (!loaded.scene) return fail(loaded.error, 2);
    Scene& scene = *loaded.scene;
    std::string cut_note;
    const PlaygroundOptions options = follow_asset_cuts(given, scene, &cut_note);
    if (!cut_note.empty()) std::printf("%s\n", cut_note.c_str());
    // --light-*, --camera-*: on the made scene, before the render, the bake and the truth (all read
    // scene.light)
    if (std::string e = apply_scene_overrides(options.overrides, scene, shading_light(options.config));
        !e.empty())
        return fail(e, 2);
    const int width = options.width > 0 ? options.width : 512;
    const int height = options.height > 0 ? options.height : 512;

    std::string error;
    std::optional<HeadlessContext> context = HeadlessContext::create(&error);
    if (!context) return fail("no OpenGL 4.5 context: " + error);
    RenderOptions render_options;
    std::optional<OimSetup> oim;
    if (options.config.technique == Technique::oim) {
        oim = bake_oim(options, scene, render_options, &error);
        if (!oim) return fail(error, 2);
    }

    HeadlessResult result;
    const auto render_start = std::chrono::steady_clock::now();
    render_options.warm_up = true; // timings of a second run: the first compiles the shaders on llvmpipe
    if (!render_headless(scene, options.config, width, height, result, &error, render_options)) return fail(error);
    const double render_ms = milliseconds_since(render_start);

    RunOutputs out;
    if (!add_render_files(out, options, scene, *context, result, width, height, &error)) return fail(error);
    nlohmann::ordered_json metrics = run_metrics(options, scene, *context, result, width, height, render_ms, oim);
    if (options.reference && !add_reference(out, metrics, options, scene, result, width, height, &error))
        return fail(error);
    print_pass_times(result);
    if (!options.metrics_path.empty()) {
        out.files.writes.push_back({options.metrics_path, metrics.dump(2) + "\n"});
        out.wrote.push_back(options.metrics_path);
    }
    if (std::string e = out.commit(); !e.empty()) return fail(e);
    return 0;
}

} // namespace penumbra::playground
