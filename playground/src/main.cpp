// penumbra-playground — headless mode: render a scene with the generated shaders to a PNG, and
// optionally compare the visibility with Embree ground truth.
//
//   penumbra-playground --headless --scene planes --out planes.png [--size 512x512]
//       [--slices 16 --resolution 512 --filter nbuffer --packing atlas --fusion probabilistic]
//       [--light rect|sun] [--reference] [--samples 16] [--metrics metrics.json]
#include "egl_context.hpp"
#include "headless_render.hpp"
#include "image_io.hpp"
#include "scenes.hpp"

#include <penumbra/config.hpp>
#include <penumbra/validate.hpp>

#include <charconv>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <string_view>

namespace {

constexpr const char* usage_text =
    "usage: penumbra-playground --headless --scene NAME --out image.png [--size WxH] [--slices N]\n"
    "       [--resolution R] [--filter F] [--packing P] [--fusion U] [--light rect|sun] [--target T]\n"
    "       [--reference] [--samples N] [--metrics metrics.json]\n"
    "Renders a scene headless (EGL, no display): G-buffer, Penumbra passes, deferred visibility, Lambert.\n"
    "  --scene NAME      planes, boxes, tree, butterfly, terrain, crowd\n"
    "  --size WxH        image size (default 512x512)\n"
    "  configuration flags as in penumbra-gen --help\n"
    "  --reference       also ray-trace the visibility with Embree and report MAE, RMSE, p95\n"
    "  --samples N       rays per light axis for --reference (default 16)\n"
    "  --metrics FILE    write the error metrics as JSON\n"
    "The interactive window is not built yet; --headless is required.\n";

int usage_error(const std::string& message) {
    std::cerr << "error: " << message << "\n" << usage_text;
    return 2;
}

bool parse_int(std::string_view text, int& value) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size();
}

template <class Enum> bool parse_named(std::string_view text, Enum& value) {
    if (auto v = penumbra::parse_enum<Enum>(text)) {
        value = *v;
        return true;
    }
    return false;
}

std::string stats_json(const penumbra::playground::ErrorStats& s) {
    char buffer[256];
    std::snprintf(buffer, sizeof buffer, "{\"mae\": %.6f, \"rmse\": %.6f, \"p95\": %.6f, \"pixels\": %zu}", s.mae, s.rmse,
                  s.p95, s.count);
    return buffer;
}

} // namespace

int main(int argc, char** argv) {
    using namespace penumbra::playground;
    bool headless = false, reference = false;
    std::string scene_name, out_path, metrics_path;
    int width = 512, height = 512, samples = 16;
    penumbra::Config config;
    for (int i = 1; i < argc; ++i) {
        const std::string_view arg = argv[i];
        auto value = [&](std::string_view& v) {
            if (i + 1 >= argc) return false;
            v = argv[++i];
            return true;
        };
        std::string_view v;
        if (arg == "--help" || arg == "-h") {
            std::cout << usage_text;
            return 0;
        }
        if (arg == "--headless") headless = true;
        else if (arg == "--reference") reference = true;
        else if (arg == "--scene") { if (!value(v)) return usage_error("--scene needs a value"); scene_name = v; }
        else if (arg == "--out") { if (!value(v)) return usage_error("--out needs a value"); out_path = v; }
        else if (arg == "--metrics") { if (!value(v)) return usage_error("--metrics needs a value"); metrics_path = v; }
        else if (arg == "--size") {
            if (!value(v)) return usage_error("--size needs WxH");
            const std::size_t x = v.find('x');
            if (x == std::string_view::npos || !parse_int(v.substr(0, x), width) || !parse_int(v.substr(x + 1), height) ||
                width < 1 || height < 1 || width > 8192 || height > 8192)
                return usage_error("--size: expected WxH with 1..8192, got " + std::string(v));
        } else if (arg == "--slices") {
            if (!value(v) || !parse_int(v, config.slices)) return usage_error("--slices needs an integer");
        } else if (arg == "--resolution") {
            if (!value(v) || !parse_int(v, config.resolution)) return usage_error("--resolution needs an integer");
        } else if (arg == "--samples") {
            if (!value(v) || !parse_int(v, samples) || samples < 1) return usage_error("--samples needs a positive integer");
        } else if (arg == "--filter") {
            if (!value(v) || !parse_named(v, config.filter)) return usage_error("--filter: unknown value");
        } else if (arg == "--packing") {
            if (!value(v) || !parse_named(v, config.packing)) return usage_error("--packing: unknown value");
        } else if (arg == "--fusion") {
            if (!value(v) || !parse_named(v, config.fusion)) return usage_error("--fusion: unknown value");
        } else if (arg == "--light") {
            if (!value(v) || !parse_named(v, config.light)) return usage_error("--light: unknown value");
        } else if (arg == "--target") {
            if (!value(v) || !parse_named(v, config.target)) return usage_error("--target: unknown value");
        } else return usage_error("unknown argument " + std::string(arg));
    }
    if (!headless) return usage_error("only --headless is implemented in this build");
    if (scene_name.empty() || out_path.empty()) return usage_error("--scene and --out are required");
    if (const auto errors = penumbra::validate(config); !errors.empty()) return usage_error(errors.front().message);
    std::optional<Scene> scene = make_scene(scene_name);
    if (!scene) return usage_error("unknown scene " + scene_name);

    std::string error;
    auto context = HeadlessContext::create(&error);
    if (!context) {
        std::cerr << "error: no OpenGL 4.5 context: " << error << "\n";
        return 1;
    }
    HeadlessResult result;
    if (!render_headless(*scene, config, width, height, result, &error)) {
        std::cerr << "error: " << error << "\n";
        return 1;
    }
    if (!write_png_rgb(out_path, width, height, result.rgb, RowOrder::top_down, &error)) {
        std::cerr << "error: " << error << "\n";
        return 1;
    }
    std::cout << "wrote " << out_path << " (" << width << "x" << height << ", " << context->renderer() << ")\n";
    if (reference) {
        const std::vector<float> truth = reference_visibility(*scene, result, samples, config.light);
        const Metrics m = compare(result, truth);
        const std::string json = "{\n  \"scene\": \"" + scene_name + "\",\n  \"samples_per_axis\": " +
                                 std::to_string(samples) + ",\n  \"all\": " + stats_json(m.all) +
                                 ",\n  \"penumbra\": " + stats_json(m.penumbra) + "\n}\n";
        std::cout << json;
        if (!metrics_path.empty()) {
            std::ofstream file(metrics_path);
            file << json;
            if (!file) {
                std::cerr << "error: cannot write " << metrics_path << "\n";
                return 1;
            }
        }
    }
    return 0;
}
