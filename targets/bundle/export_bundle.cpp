// penumbra-export-bundle — the inputs and the expected output of one run, for a runner that is
// not the desktop GL runtime (a browser, Vulkan): the scene's triangles, the light-frame uniforms,
// the G-buffers (world positions and normals), the GL runtime's deferred visibility and slicing
// output, the CPU oracle's per-pixel value and bound, and the emission of the requested target.
// README.md in this folder documents the files.
//
//   penumbra-export-bundle --scene NAME|FILE [--no-ground] [configuration flags] [--size WxH] [--light-size
//   X] --out DIR
//
// The configuration flags are penumbra-gen's (the same parser); the GL run uses the same
// configuration (with target glsl450 when the target is vulkan, wgsl or hlsl). Exit status: 0 written,
// 1 rendering or writing failed, 2 bad arguments.
#include <penumbra_tools/arguments.hpp>
#include <penumbra_tools/cli.hpp>
#include <penumbra_tools/config_file.hpp>
#include <penumbra_tools/write_files.hpp>

#include "app/headless_job.hpp"
#include "bake/oim_scene.hpp"
#include "reference/oracle.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"

#include <penumbra/emit.hpp>
#include <penumbra/uniform_values.hpp>
#include <penumbra/validate.hpp>

#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

namespace {

using namespace penumbra;
using namespace penumbra::playground;
using penumbra_gen::printable;

enum Exit { ok = 0, failed = 1, bad_input = 2 };

struct BundleArguments {
    std::string scene;
    int width = 128, height = 128;
    std::optional<double> light_size;
    std::string out_dir;
    Config config; // the target's; the GL run uses it (with Target::glsl450 for vulkan, wgsl and hlsl)
    bool ground = true;        // --no-ground: no floor under a mesh file
    int reference_samples = 0; // --reference N: truth.f32, N×N rays per pixel (0: none)
    double sun_time = 0.5;     // --sun-time (oim)
    std::string bake_cache;    // --bake-cache DIR (oim)
    bool help = false;
};

constexpr std::string_view usage_text =
    "usage: penumbra-export-bundle --scene NAME|FILE [--no-ground] [configuration flags] [--size WxH] [--light-size X]\n"
    "                              [--reference N] [--sun-time T] [--bake-cache DIR] --out DIR\n"
    "\n"
    "Renders the scene with the desktop GL runtime (the configuration's emission; glsl450 for the vulkan\n"
    "and wgsl targets) and writes, for a foreign runner to reproduce: mesh.f32, uniforms.json, positions.f32,\n"
    "normals.f32, visibility_gl.f32, slices.f32, oracle.f32, bound.f32 (occlusion textures: the CPU oracle;\n"
    "boundaries.f32 with adaptive slice placement)\n"
    "and emission/ (penumbra-gen's files for --target); with --reference truth.f32, with --technique oim\n"
    "texcoords.f32 and the bake's textures. See targets/bundle/README.md.\n"
    "\n"
    "  --scene NAME|FILE      planes, boxes, tree, butterfly, terrain, crowd, or a mesh file: Wavefront OBJ\n"
    "                         (.obj) or glTF 2.0 (.gltf, .glb)\n"
    "  --no-ground            no floor under a mesh file (default: one, as penumbra-playground)\n"
    "  --size WxH             image size, each side 1 to 4096 (default 128x128)\n"
    "  --light-size X         the rectangle's longer side (scene units) or the sun's angular diameter (degrees)\n"
    "  --out DIR              the bundle directory (created; its emission/ is replaced)\n"
    "  --reference N          also truth.f32: the Embree ground truth (oriented), N x N rays per pixel, 1 to 64\n"
    "  --sun-time T           --technique oim: the instant of the sun's path, 0 to 1 (default 0.5)\n"
    "  --bake-cache DIR       --technique oim: where bakes are cached (default as penumbra-playground)\n"
    "  configuration flags    as penumbra-gen: every configuration field's flag (--technique, --slices, --pcss-blockers,\n"
    "                         ...) and --config FILE.json (see penumbra-gen --help)\n";

constexpr std::string_view flag_list =
    "--scene, --no-ground, --size, --light-size, --out, --reference, --sun-time, --bake-cache, --config, --help, and the "
    "configuration flags of penumbra-gen (--technique, --slices, ...)";

using penumbra::cli::parse_number;

// An integer from 1 to 4096 (an image side, rays per axis).
bool parse_positive_int(std::string_view text, int& value) { return parse_number(text, value) && value >= 1 && value <= 4096; }

// Our own flags out of `args`; the rest goes to penumbra-gen's parser.
penumbra_gen::Parsed<BundleArguments> parse(const std::vector<std::string>& args) {
    auto fail = [](std::string message) { return penumbra_gen::Parsed<BundleArguments>{{}, std::move(message)}; };
    BundleArguments out;
    std::vector<std::string> config_args;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg == "--help" || arg == "-h") {
            out.help = true;
            return {out, {}};
        }
        if (arg == "--no-ground") {
            out.ground = false;
            continue;
        }
        std::string flag = arg, value;
        bool has_value = false;
        if (const std::size_t eq = arg.find('='); arg.starts_with("--") && eq != std::string::npos) {
            flag = arg.substr(0, eq);
            value = arg.substr(eq + 1);
            has_value = true;
        }
        const bool ours = flag == "--scene" || flag == "--size" || flag == "--light-size" || flag == "--out" ||
                          flag == "--reference" || flag == "--sun-time" || flag == "--bake-cache";
        const bool configuration =
            flag == "--config" || penumbra_gen::is_config_flag(flag) || penumbra_gen::is_config_switch(flag);
        if (!ours && !configuration && flag.starts_with("-"))
            return fail("unknown flag '" + printable(flag) + "'; allowed: " + std::string(flag_list));
        if (!ours) {
            config_args.push_back(arg);
            continue;
        }
        if (!has_value) {
            if (i + 1 >= args.size()) return fail(flag + ": missing value (see --help)");
            value = args[++i];
        }
        if (flag == "--scene") {
            out.scene = value;
        } else if (flag == "--out") {
            out.out_dir = value;
        } else if (flag == "--bake-cache") {
            out.bake_cache = value;
        } else if (flag == "--reference") {
            if (!parse_positive_int(value, out.reference_samples) || out.reference_samples > 64)
                return fail("--reference: '" + printable(value) + "' is not allowed; allowed: rays per axis, 1 to 64");
        } else if (flag == "--sun-time") {
            double t = 0;
            if (!parse_number(value, t) || !(t >= 0.0 && t <= 1.0))
                return fail("--sun-time: '" + printable(value) + "' is not allowed; allowed: a number from 0 to 1");
            out.sun_time = t;
        } else if (flag == "--size") {
            const std::size_t x = value.find('x');
            if (x == std::string::npos || !parse_positive_int(std::string_view(value).substr(0, x), out.width) ||
                !parse_positive_int(std::string_view(value).substr(x + 1), out.height))
                return fail("--size: '" + printable(value) + "' is not WxH; allowed: two integers 1 to 4096, e.g. 128x128");
        } else {
            double size = 0;
            if (!parse_number(value, size) || !std::isfinite(size) || size <= 0)
                return fail("--light-size: '" + printable(value) + "' is not a positive number");
            out.light_size = size;
        }
    }
    if (out.scene.empty()) return fail("--scene: missing; allowed: a scene name or a .obj, .gltf or .glb path");
    if (out.out_dir.empty()) return fail("--out: missing; the bundle directory is required (--out DIR)");
    config_args.push_back("--out");
    config_args.push_back(out.out_dir);
    const penumbra_gen::Parsed<penumbra_gen::Arguments> gen = penumbra_gen::parse_arguments(config_args);
    if (!gen.error.empty()) return fail(gen.error);
    Config base{};
    if (gen.value->config_file) {
        const penumbra_gen::Parsed<Config> file = penumbra_gen::read_config_file(*gen.value->config_file);
        if (!file.error.empty()) return fail(file.error);
        base = *file.value;
    }
    out.config = penumbra_gen::apply(gen.value->flags, base);
    if (const std::vector<ConfigError> errors = validate(out.config); !errors.empty()) return fail(errors.front().message);
    if (out.light_size && out.config.light == Light::sun && *out.light_size >= 90.0)
        return fail("--light-size: the sun's angular diameter must be below 90 degrees");
    return {out, {}};
}

bool write_binary(const std::filesystem::path& path, const void* data, std::size_t bytes, std::string* error) {
    std::ofstream file(path, std::ios::binary);
    file.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
    if (!file) *error = "cannot write " + path.string();
    return static_cast<bool>(file);
}

template <class T> bool write_floats(const std::filesystem::path& path, const std::vector<T>& values, std::string* error) {
    return write_binary(path, values.data(), values.size() * sizeof(T), error);
}

nlohmann::ordered_json floats(const float* values, int count) {
    nlohmann::ordered_json out = nlohmann::ordered_json::array();
    for (int i = 0; i < count; ++i) out.push_back(values[i]);
    return out;
}

// Every "light" uniform the emission's programs declare, by its GLSL name (penumbra/uniform_values.hpp's
// table; matrices column-major), from the frame the GL run used ("camera" uniforms are not "light"
// ones: left out). A declared uniform without a value (an input the run did not set) is an error.
nlohmann::ordered_json uniforms_json(const UniformInputs& inputs, const Layout& layout, std::string& error) {
    auto declared = [&](std::string_view name) {
        for (const ProgramDesc& program : layout.programs)
            for (const ParamDesc& p : program.parameters)
                if (p.name == name && p.source == UniformSource::light) return true;
        return false;
    };
    nlohmann::ordered_json out = nlohmann::ordered_json::object();
    for (const UniformRule& rule : uniform_rules()) {
        if (!declared(rule.name)) continue;
        const UniformResult value = rule.value(inputs);
        if (!value) {
            error = value.error;
            return out;
        }
        std::visit(
            [&](const auto& v) {
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, int> || std::is_same_v<T, float>) out[std::string(rule.name)] = v;
                else out[std::string(rule.name)] = floats(glm::value_ptr(v), static_cast<int>(sizeof(T) / sizeof(float)));
            },
            *value);
    }
    return out;
}

using penumbra::cli::fail;

int run(const std::vector<std::string>& args) {
    const penumbra_gen::Parsed<BundleArguments> parsed = parse(args);
    if (!parsed.error.empty()) return fail(parsed.error, bad_input);
    const BundleArguments& a = *parsed.value;
    if (a.help) return penumbra::cli::print_usage(usage_text);
    SceneLoad loaded = load_scene(a.scene, a.ground);
    if (!loaded.scene) return fail(loaded.error, bad_input);
    Scene& scene = *loaded.scene;
    if (a.light_size) apply_light_size(scene, shading_light(a.config), *a.light_size);
    // The GL run emits the same configuration: the desktop runtime runs every GL dialect (glsl330
    // and essl300 text inside its 4.5 context); the vulkan, wgsl and hlsl text it cannot, so those run
    // glsl450.
    Config gl_config = a.config;
    if (gl_config.target == Target::vulkan || gl_config.target == Target::wgsl ||
        gl_config.target == Target::hlsl)
        gl_config.target = Target::glsl450;

    // The GL run, and what the oracle needs from it.
    std::string error;
    std::optional<HeadlessContext> context = HeadlessContext::create(&error);
    if (!context) return fail("no OpenGL 4.5 context: " + error);
    HeadlessResult result;
    SliceTextures slices;
    std::vector<float> boundaries; // adaptive slice placement: the S + 1 boundaries the GL run computed
    SliceFrame frame;
    UniformInputs inputs;
    std::vector<float> visibility_gl; // bottom row first, as the runtime wrote it
    // The CPU oracle models occlusion textures only: the other techniques' bundles have no
    // slices.f32, oracle.f32 or bound.f32 (a runner compares them with visibility_gl.f32).
    const bool occlusion = gl_config.technique == Technique::occlusion;
    bool read = !occlusion;
    std::string read_error;
    RenderOptions options;
    options.inspect = [&](const gl::Runtime& runtime) {
        if (occlusion)
            read = read_slice_textures(runtime, slices, &read_error) &&
                   read_slice_boundaries(runtime, boundaries, &read_error); // empty for uniform placement
        frame = runtime.frame();
        inputs = runtime.uniform_inputs();
        visibility_gl = runtime.read_visibility();
    };
    // Occlusion interval maps: the scene's charts, the sun at --sun-time, the bake (or its cache).
    std::optional<OimSetup> oim;
    if (gl_config.technique == Technique::oim) {
        const std::filesystem::path cache = a.bake_cache.empty() ? default_oim_cache_dir() : std::filesystem::path(a.bake_cache);
        oim = prepare_oim(scene, gl_config, SunPath{}, a.sun_time, cache, &error);
        if (!oim) return fail(error, bad_input);
        options.bake_textures = oim->textures;
        options.time_window = oim->time_window;
    }
    if (!render_headless(scene, gl_config, a.width, a.height, result, &error, options)) return fail(error);
    if (!read) return fail(read_error);
    const std::vector<float> coverage = slices.coverage; // slices.f32: what a runner can rasterize differently
    const std::vector<float> placed = boundaries;        // boundaries.f32: adaptive placement's, from the same run
    std::optional<Oracle> oracle;
    if (occlusion) oracle.emplace(gl_config, frame, std::move(slices), std::move(boundaries));
    std::vector<float> truth;
    if (a.reference_samples > 0) truth = reference_all(scene, result, a.reference_samples, shading_light(gl_config)).oriented;

    // Bottom row first: the G-buffers the GL run shaded (background (0, 0, 0, 0)) and the bound.
    // The normal is the one of the side the camera sees, as the runtime's G-buffer holds it; the
    // oracle clips the kernels to its tangent plane where the configuration does (tangent_clip).
    const std::size_t pixels = static_cast<std::size_t>(a.width) * a.height;
    std::vector<glm::vec4> positions(pixels, glm::vec4(0.0f)), normals(pixels, glm::vec4(0.0f)),
        tex_coords(pixels, glm::vec4(0.0f));
    std::vector<float> bound(pixels, 0.0f), model(pixels, 1.0f), truth_bottom_first(truth.empty() ? 0 : pixels, 1.0f);
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const std::size_t top_first = static_cast<std::size_t>(a.height - 1 - y) * a.width + x;
            const std::size_t bottom_first = static_cast<std::size_t>(y) * a.width + x;
            if (!truth.empty()) truth_bottom_first[bottom_first] = truth[top_first];
            if (!result.geometry[top_first]) continue;
            positions[bottom_first] = glm::vec4(result.positions[top_first], 1.0f);
            normals[bottom_first] = glm::vec4(result.normals[top_first], 0.0f);
            if (!result.tex_coords.empty()) tex_coords[bottom_first] = glm::vec4(result.tex_coords[top_first], 0.0f, 1.0f);
            if (!oracle) continue;
            const OracleValue value = oracle->visibility(result.positions[top_first], result.normals[top_first], gl_config.fusion);
            bound[bottom_first] = static_cast<float>(value.bound);
            model[bottom_first] = static_cast<float>(value.visibility);
        }
    std::vector<glm::vec3> triangles;
    triangles.reserve(scene.mesh.indices.size());
    for (std::uint32_t index : scene.mesh.indices) triangles.push_back(scene.mesh.positions[index]);

    // The emission of the requested target, exactly as penumbra-gen writes it, into a fresh folder.
    Result<Emission> emitted = emit(a.config);
    if (!emitted.value) return fail(emitted.errors.front().message, bad_input);
    const std::vector<penumbra_gen::OutputFile> files = penumbra_gen::output_files(*emitted.value);
    const std::filesystem::path dir(a.out_dir), emission_dir = dir / "emission";
    std::error_code ec;
    std::filesystem::remove_all(emission_dir, ec);
    if (std::string e = penumbra_gen::write_files(emission_dir.string(), files); !e.empty()) return fail(e);
    std::string uniform_error;
    const nlohmann::ordered_json uniform_values = uniforms_json(inputs, emitted.value->layout, uniform_error);
    if (!uniform_error.empty()) return fail("uniform " + uniform_error);

    nlohmann::ordered_json uniforms = {
        {"width", a.width},
        {"height", a.height},
        {"scene", scene.name},
        {"ground", scene.ground},
        {"config", config_json(a.config)},
        {"gl_config", config_json(gl_config)},
        {"light", light_json(scene, shading_light(gl_config))},
        {"triangles", triangles.size() / 3},
        // The camera of the GL run (glm::lookAt with up +y, glm::perspective at width / height).
        {"camera",
         {{"eye", {scene.camera.eye_position().x, scene.camera.eye_position().y, scene.camera.eye_position().z}},
          {"target", {scene.camera.target.x, scene.camera.target.y, scene.camera.target.z}},
          {"up", {0.0, 1.0, 0.0}},
          {"fov_y_degrees", scene.camera.fov_y_radians * 180.0 / 3.14159265358979323846},
          {"near", scene.camera.z_near},
          {"far", scene.camera.z_far}}},
        {"renderer", context->renderer()},
        {"uniforms", uniform_values},
        {"caller_textures", {{"penumbra_worldPositions", "positions.f32"}, {"penumbra_worldNormals", "normals.f32"}}},
    };
    nlohmann::ordered_json bake = nlohmann::ordered_json::object();
    if (oim) {
        uniforms["caller_textures"]["penumbra_texCoords"] = "texcoords.f32";
        for (const auto& [name, texels] : oim->textures) {
            bake[name] = name + ".f32";
            if (!write_floats(dir / (name + ".f32"), texels, &error)) return fail(error);
        }
        uniforms["bake_textures"] = bake;
        uniforms["sun_time"] = a.sun_time;
        nlohmann::ordered_json path = nlohmann::ordered_json::array(); // the path the bake traced
        for (const SunPathPoint& p : SunPath{}.points) path.push_back({p.azimuth_degrees, p.elevation_degrees});
        uniforms["sun_path"] = path;
    }
    if (!truth.empty()) uniforms["truth"] = {{"file", "truth.f32"}, {"kind", "oriented"}, {"samples", a.reference_samples}};
    // Files of an earlier bundle in this folder that this one does not write would mislead a runner.
    for (const char* optional_file : {"slices.f32", "boundaries.f32", "oracle.f32", "bound.f32", "truth.f32", "texcoords.f32"})
        std::filesystem::remove(dir / optional_file, ec);
    std::ofstream json(dir / "uniforms.json", std::ios::binary);
    json << uniforms.dump(2) << '\n';
    if (!json) return fail("cannot write " + (dir / "uniforms.json").string());
    if (!write_floats(dir / "mesh.f32", triangles, &error) || !write_floats(dir / "positions.f32", positions, &error) ||
        !write_floats(dir / "normals.f32", normals, &error) || !write_floats(dir / "visibility_gl.f32", visibility_gl, &error))
        return fail(error);
    if (occlusion && (!write_floats(dir / "bound.f32", bound, &error) || !write_floats(dir / "oracle.f32", model, &error) ||
                      !write_floats(dir / "slices.f32", coverage, &error)))
        return fail(error);
    if (!placed.empty() && !write_floats(dir / "boundaries.f32", placed, &error)) return fail(error);
    if (oim && !write_floats(dir / "texcoords.f32", tex_coords, &error)) return fail(error);
    if (!truth.empty() && !write_floats(dir / "truth.f32", truth_bottom_first, &error)) return fail(error);
    std::cout << "penumbra-export-bundle: wrote " << a.out_dir << " (" << scene.name << ", " << a.width << "x"
              << a.height << ", " << triangles.size() / 3 << " triangles, emission for " << to_string(a.config.target)
              << ", GL on " << context->renderer() << ")\n";
    return ok;
}

} // namespace

int main(int argc, char** argv) {
    static_assert(sizeof(glm::vec3) == 12 && sizeof(glm::vec4) == 16, "tightly packed float vectors");
    return penumbra::cli::run_main(argc, argv, run, 3);
}
