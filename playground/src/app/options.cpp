// playground/src/app/options.cpp — penumbra-playground's command line, parsed into PlaygroundOptions.
//
// The configuration flags are exactly penumbra-gen's and go through its own parsing helpers
// (tools/include/penumbra_tools/arguments.hpp, config_file.hpp), so both tools accept and reject the same text
// with the same messages.
#include "app/options.hpp"

#include <penumbra_tools/arguments.hpp>
#include <penumbra_tools/cli.hpp>
#include <penumbra_tools/config_file.hpp>

#include "bake/oim_scene.hpp"

#include <penumbra/validate.hpp>

#include <cmath>
#include <cstdio>
#include <string_view>

namespace penumbra::playground {
namespace {

using penumbra_gen::printable;

// The playground's own flags; the configuration fields' flags are penumbra-gen's (technique_flags.hpp).
std::string flag_list() {
    return "--headless, --scene, --no-ground, --size, --light-size, --light-center, --light-normal, "
           "--light-up, "
           "--camera-position, --camera-target, --out, --visibility, --reference, --samples, "
           "--metrics, --reference-out, --error-out, --config, --watch, --frames, --screenshot, --script, "
           "--sun-time, "
           "--sun-path, --bake-cache, --help, " +
           penumbra::config_flag_list();
}

bool is_switch(std::string_view flag) {
    return flag == "--headless" || flag == "--reference" || flag == "--no-ground" || penumbra_gen::is_config_switch(flag);
}

bool takes_value(std::string_view flag) {
    if (penumbra_gen::is_config_flag(flag) || is_scene_override_flag(flag)) return true;
    for (std::string_view f : {"--scene", "--size", "--out", "--visibility", "--samples", "--metrics",
                               "--reference-out", "--error-out", "--config", "--watch", "--frames",
                               "--screenshot", "--sun-time", "--sun-path", "--bake-cache", "--script"})
        if (flag == f) return true;
    return false;
}

// An integer in [lo, hi].
std::string parse_int_in(std::string_view flag, std::string_view text, int lo, int hi, int& value) {
    const std::string allowed = std::to_string(lo) + " to " + std::to_string(hi);
    if (std::string error = cli::parse_int(flag, text, value, allowed); !error.empty()) return error;
    if (value < lo || value > hi) return std::string(flag) + ": " + printable(text) + " is out of range; allowed: " + allowed;
    return {};
}

// "WxH", each side 1 to 8192.
std::string parse_size(std::string_view text, int& width, int& height) {
    const std::size_t x = text.find('x');
    const std::string allowed = "; allowed: two integers 1 to 8192, e.g. 512x512";
    const std::string bad = "--size: '" + printable(text) + "' is not WxH" + allowed;
    if (x == std::string_view::npos) return bad;
    const std::string_view sides[2] = {text.substr(0, x), text.substr(x + 1)};
    int* values[2] = {&width, &height};
    bool out_of_range = false;
    for (int i = 0; i < 2; ++i) {
        // Digits only: a sign, spaces or a second 'x' make it not WxH; too many digits or a value
        // outside 1..8192 is out of range.
        if (sides[i].empty() || sides[i].find_first_not_of("0123456789") != std::string_view::npos) return bad;
        if (!cli::parse_number(sides[i], *values[i]) || *values[i] < 1 || *values[i] > 8192) out_of_range = true;
    }
    if (out_of_range) return "--size: " + printable(text) + " is out of range" + allowed;
    return {};
}

// Checks that need every flag: the configuration as a whole, the light size for the chosen
// light, what the headless mode requires.
std::string check(const PlaygroundOptions& o) {
    if (const std::vector<penumbra::ConfigError> errors = penumbra::validate(o.config); !errors.empty())
        return errors.front().message;
    if (o.config.target == penumbra::Target::vulkan || o.config.target == penumbra::Target::wgsl ||
        o.config.target == penumbra::Target::hlsl)
        return "--target: '" + std::string(penumbra::to_string(o.config.target)) +
               "' cannot run here, the playground renders with OpenGL; allowed: glsl330, glsl450, essl300";
    const bool sun = o.config.light == penumbra::Light::sun || o.config.technique == penumbra::Technique::oim;
    const SceneOverrides& s = o.overrides;
    if (s.light_size && sun && *s.light_size >= 90.0) {
        char shown[32];
        std::snprintf(shown, sizeof shown, "%g", *s.light_size);
        return "--light-size: " + std::string(shown) +
               " degrees is too wide for the sun; allowed: an angular diameter above 0 and below 90";
    }
    if (s.light_sides && sun)
        return "--light-size: W,H sizes the rectangle light, but the light is the sun (--light sun or "
               "--technique "
               "oim); allowed: one number, the sun's angular diameter in degrees, below 90";
    if (std::string error = check_scene_overrides(s); !error.empty()) return error;
    if (o.headless && sun && (s.light_center || s.light_normal || s.light_up))
        return std::string(s.light_center   ? "--light-center"
                           : s.light_normal ? "--light-normal"
                                            : "--light-up") +
               ": places the rectangle light, but this run's light is the sun (--light sun or --technique "
               "oim); "
               "allowed: with --light rect (the default)";
    if (!o.sun_path.empty()) {
        std::string error;
        if (!parse_sun_path(o.sun_path, &error)) return error;
    }
    if (!o.headless) return {};
    if (o.out_path.empty()) return "--out: missing; --headless needs the image to write (--out image.png)";
    if (!o.reference && !o.reference_path.empty()) return "--reference-out: needs --reference";
    if (!o.reference && !o.error_image_path.empty()) return "--error-out: needs --reference";
    return {};
}

} // namespace

ParsedOptions parse_options(const std::vector<std::string>& args) {
    if (cli::asks_for_help(args)) return {{}, true, {}};

    auto fail = [](std::string message) { return ParsedOptions{{}, false, std::move(message)}; };
    PlaygroundOptions options;
    penumbra_gen::ConfigFlags flags;
    std::optional<std::string> config_file;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string_view arg = args[i];
        std::string_view flag = arg;
        std::optional<std::string_view> inline_value; // --flag=value
        if (arg.starts_with("--"))
            if (const std::size_t eq = arg.find('='); eq != std::string_view::npos) {
                flag = arg.substr(0, eq);
                inline_value = arg.substr(eq + 1);
            }
        if (is_switch(flag)) {
            if (inline_value) return fail(std::string(flag) + ": takes no value (got '" + printable(*inline_value) + "')");
            if (flag == "--headless") options.headless = true;
            if (flag == "--reference") options.reference = true;
            if (flag == "--no-ground") options.ground = false;
            penumbra_gen::set_config_switch(flag, flags);
            continue;
        }
        if (!takes_value(flag)) {
            if (arg.starts_with("-")) return fail("unknown flag '" + printable(flag) + "'; allowed: " + flag_list());
            return fail("unexpected argument '" + printable(arg) +
                        "'; every value follows its flag (allowed flags: " + flag_list() + ")");
        }
        std::string_view value;
        if (inline_value) value = *inline_value;
        else if (i + 1 < args.size()) value = args[++i];
        else return fail(std::string(flag) + ": missing value (see --help)");

        std::string error;
        if (penumbra_gen::is_config_flag(flag)) error = penumbra_gen::parse_config_flag(flag, value, flags);
        else if (flag == "--size") error = parse_size(value, options.width, options.height);
        else if (flag == "--samples") error = parse_int_in(flag, value, 1, 1024, options.samples);
        else if (flag == "--frames") error = parse_int_in(flag, value, 0, 1000000000, options.frames);
        else if (flag == "--sun-time") {
            if (!cli::parse_number(value, options.sun_time) || !(options.sun_time >= 0.0 && options.sun_time <= 1.0))
                error = "--sun-time: '" + printable(value) + "' is not allowed; allowed: a path time from 0 to 1";
        } else if (flag == "--sun-path") {
            options.sun_path = std::string(value);
        } else if (flag == "--bake-cache") {
            options.bake_cache = std::string(value);
        } else if (is_scene_override_flag(flag)) {
            error = parse_scene_override(flag, value, options.overrides);
        } else if (value.empty())
            error = std::string(flag) + ": empty; allowed: a " + (flag == "--scene" ? "scene name or .obj, .gltf or .glb path" : "path");
        else if (flag == "--scene") options.scene = std::string(value);
        else if (flag == "--config") config_file = std::string(value);
        else if (flag == "--out") options.out_path = std::string(value);
        else if (flag == "--visibility") options.visibility_path = std::string(value);
        else if (flag == "--metrics") options.metrics_path = std::string(value);
        else if (flag == "--reference-out") options.reference_path = std::string(value);
        else if (flag == "--error-out") options.error_image_path = std::string(value);
        else if (flag == "--watch") options.watch_dir = std::string(value);
        else if (flag == "--screenshot") options.screenshot_path = std::string(value);
        else options.script_path = std::string(value); // --script
        if (!error.empty()) return fail(error);
    }

    penumbra::Config base;
    if (config_file) {
        penumbra_gen::Parsed<penumbra::Config> read = penumbra_gen::read_config_file(*config_file);
        if (!read.error.empty()) return fail(read.error);
        base = *read.value;
    }
    options.config = penumbra_gen::apply(flags, base);
    options.alpha_test_given = base.alpha_test;
    for (const auto& [field, value] : flags.values) options.alpha_test_given |= field->key == "alpha_test";
    if (std::string error = check(options); !error.empty()) return fail(error);
    return {options, false, {}};
}

std::string usage() {
    auto line = [](std::string_view flag, std::string_view text) {
        std::string out = "  " + std::string(flag);
        out.resize(std::max<std::size_t>(out.size() + 1, 24), ' ');
        return out + std::string(text) + "\n";
    };
    std::string out =
        "usage: penumbra-playground --headless --scene NAME|FILE [--no-ground] [configuration flags] [--size "
        "WxH]\n"
        "           [light and camera flags] --out image.png [--visibility vis.pfm] [--reference] [--samples "
        "N]\n"
        "           [--metrics metrics.json] [--reference-out truth.pfm] [--error-out error.png]\n"
        "           [--sun-time T] [--sun-path AZ:EL,...] [--bake-cache DIR]  (--technique oim)\n"
        "       penumbra-playground [--scene NAME|FILE] [--no-ground] [configuration flags] [--size WxH]\n"
        "           [light and camera flags]\n"
        "           [--watch DIR] [--frames N] [--screenshot FILE] [--script FILE]\n"
        "\n"
        "With --headless: renders the scene without a display (EGL; Mesa llvmpipe or a GPU) with the "
        "shaders\n"
        "Penumbra emits for the configuration, writes the shaded image and, with --reference, compares the\n"
        "visibility with an Embree ray-traced ground truth. Without --headless: the interactive window.\n"
        "\n"
        "light and camera flags: [--light-size W[,H]] [--light-center X,Y,Z] [--light-normal X,Y,Z]\n"
        "           [--light-up X,Y,Z] [--camera-position X,Y,Z] [--camera-target X,Y,Z]\n"
        "\n"
        "scene, light and camera:\n";
    out += line("--scene NAME|FILE",
                "planes, boxes, tree, butterfly, terrain, crowd, box, cutout (default boxes);\n"
                "                        rooms: room, window, cornell; or\n"
                "                        a mesh file: Wavefront OBJ (.obj) or glTF 2.0 (.gltf with "
                "its buffers, .glb); a regular\n"
                "                        file of at most 256 MiB, coordinates finite and within "
                "±1e9. glTF: every triangle\n"
                "                        primitive of the default scene, node transforms applied; "
                "points, lines, sparse\n"
                "                        accessors and primitives whose .bin is missing are "
                "skipped with a warning;\n"
                "                        Draco (KHR_draco_mesh_compression) and meshopt "
                "(EXT_meshopt_compression,\n"
                "                        KHR_mesh_quantization) compressed geometry is decoded");
    out += line("--no-ground", "no floor under a mesh file (default: a square receiver twice the footprint,\n"
                               "                        just below the lowest point; the light and camera are "
                               "framed from the bounds\n"
                               "                        with it; metrics.json says \"ground\")");
    out += line("--size WxH", "image size, 1 to 8192 per side (default 512x512 headless, 1280x720 window)");
    out += scene_override_usage(24);
    out += "\nconfiguration (as penumbra-gen; flags override the --config file; --target vulkan, wgsl and "
           "hlsl cannot\n"
           "run here, the playground renders with OpenGL):\n\n";
    out += penumbra::config_usage(24);
    out += "  (--alpha-test here, on by default when the scene's materials cut (--no-alpha-test: off): materials\n"
           "  that cut cast the shadow of their texture's alpha, not of their\n"
           "  triangles: glTF alphaMode MASK (baseColorFactor.a x baseColorTexture.a below alphaCutoff, default\n"
           "  0.5), BLEND cast as a cut-out at 0.5, OBJ map_d (or map_Kd's alpha) at 0.5; the oim bake cuts the\n"
           "  same. The Embree truth and the receivers are cut either way: cut-out pixels are not surfaces)\n";
    out += "\ninput:\n";
    out += line("--config FILE.json", "configuration from JSON (the keys of Config, or a layout.json); a regular\n"
                                      "                        file of at most 1 MiB");
    out += "\noim (occlusion interval maps: the sun on a fixed path, baked with Embree, cached on disk):\n";
    out += line("--sun-time T", "path time of the rendered instant, 0 (first point) to 1 (last) (default 0.5)");
    out += line("--sun-path AZ:EL,...", "the path: azimuth:elevation points in degrees, evenly spaced in time\n"
                                        "                        (azimuth clockwise from north, -z; east +x; default "
                                        "100:10,180:50,260:10)");
    out += line("--bake-cache DIR", "where bakes are cached (default $PENUMBRA_CACHE_DIR/oim, else\n"
                                    "                        $XDG_CACHE_HOME/penumbra/oim, else ~/.cache/penumbra/oim)");
    out += "\nheadless output:\n";
    out += line("--out FILE.png", "the shaded image (required with --headless)");
    out += line("--visibility FILE.pfm", "the estimated visibility, one float per pixel (1 on background)");
    out += line("--reference",
                "also ray-trace the ground truth (Embree) and report MAE, RMSE, p95 |error| and the\n"
                "                        mean signed error (+ too bright, - too dark) over all geometry "
                "pixels and over\n"
                "                        penumbra pixels (truth or estimate < 0.98), and the false "
                "light and false shadow.\n"
                "                        The headline (printed first, metrics.json reference.all and "
                ".penumbra, the error\n"
                "                        PNG) is irradiance, the shaded image's reference: the light "
                "weighed by the\n"
                "                        irradiance it sends, above each surface's tangent plane; "
                "oriented (its visibility\n"
                "                        unweighed) and the whole light's visibility follow. Writes "
                "the three truths as\n"
                "                        PFM, a false-colour error PNG (red: too bright, blue: too "
                "dark, green: sees\n"
                "                        none of the light) and <out stem>.reference.png, the shaded "
                "image with the\n"
                "                        irradiance truth in place of the estimate");
    out += line("--samples N", "ground-truth rays per light axis, N×N per pixel: 1 to 1024 (default 32)");
    out += line("--reference-out FILE", "where the whole-light truth goes (default <out stem>.reference.pfm next to\n"
                                        "                        --out); the others beside it, "
                                        "<stem>.oriented.pfm and <stem>.irradiance.pfm");
    out += line("--error-out FILE", "where the error image goes (default <out stem>.error.png next to --out)");
    out += line("--metrics FILE.json", "scene, renderer, configuration, sizes, the GPU time of each pass in ms and,\n"
                                       "                        with --reference, the error statistics");
    out += "\nwindow:\n";
    out += line("--watch DIR", "write the emitted shaders to DIR and reload them when edited (default "
                               "playground-shaders)");
    out += line("--frames N", "quit after N frames (default 0: run until closed)");
    out += line("--screenshot FILE", "write the last frame as PNG");
    out += line("--script FILE",
                "run the actions in FILE, one a line (set, light, light_size, camera, wait,\n"
                "                        screenshot, readback, ...: docs/playground.md); a "
                "regular file of at most 1 MiB;\n"
                "                        wait N: 0 to 1000000 frames, wait_reload S and wait_truth S: "
                "0 to 600 seconds");
    out += line("--help, -h", "print this help and exit");
    out += "\nA value may also be given as --flag=value. A headless run's files (image, PFMs, error image,\n"
           "metrics) are one transaction: all are written or none, and an existing file keeps its old contents\n"
           "(a failed write leaves no partial file and prints no \"wrote\"); shader files the window watches are\n"
           "read up to 1 MiB.\n"
           "exit status: 0 done; 1 rendering or writing failed (no OpenGL 4.5, GL error, unwritable file);\n"
           "2 bad arguments, configuration, scene name, mesh file (OBJ, glTF) or script\n";
    return out;
}

} // namespace penumbra::playground
