// penumbra-vulkan-run — runs a target bundle's vulkan emission (targets/bundle/README.md) by its
// layout.json alone, under the Khronos validation layer, and compares the visibility with the
// desktop GL runtime's and with the CPU oracle's, within the oracle's bound.
//
//   penumbra-vulkan-run --bundle DIR [--epsilon E] [--min-penumbra N] [--pixels-allowed F] [--out visibility.f32]
//
// Occlusion textures: passes when every pixel satisfies |Vulkan − GL| ≤ bound + E and
// |Vulkan − oracle| ≤ bound + E (default E = 1e-4: the rounding of one 16-bit float level).
// Other techniques (shadowmap, pcf, pcss, erosion, oim: the oracle models none of them, and their
// bundles have no oracle.f32 or bound.f32): every pixel satisfies |Vulkan − GL| ≤ E, the same
// emission's GLSL on the same Mesa rasterizer and sampler code (llvmpipe / lavapipe), except in
// a fraction F of the pixels (--pixels-allowed, default 0): pcf's and pcss's per-pixel rotation
// hashes with integers (the same angle everywhere), but the rotated tap offsets round differently
// in Mesa's GLSL and SPIR-V paths, which flips depth comparisons at ties.
// Either way the GL image must have at least N penumbra pixels (0.02 < visibility < 0.98;
// default 0), so that the comparison means something, and the validation layer must report
// nothing. Exit status: 0 pass; 1 a difference beyond the bound, a validation message, or a
// failure; 2 bad arguments; 77 no Vulkan device (the test is skipped).
#include "bundle_reader.hpp"
#include <penumbra_tools/cli.hpp>
#include "layout_runner.hpp"
#include "vulkan_context.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace {

using namespace penumbra::vulkan;
using penumbra::targets::Bundle;
using penumbra::targets::read_bundle;

enum Exit { pass = 0, failed = 1, bad_input = 2, skipped = 77 };

constexpr const char* usage =
    "usage: penumbra-vulkan-run --bundle DIR [--epsilon E] [--min-penumbra N] [--pixels-allowed F] [--out visibility.f32]\n";

using penumbra::cli::fail;
using penumbra::cli::parse_number;

int run(const std::vector<std::string>& args) {
    std::string bundle_dir, out_path;
    double epsilon = 1e-4, pixels_allowed = 0;
    std::size_t min_penumbra = 0;
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& flag = args[i];
        if (flag == "--help" || flag == "-h") return penumbra::cli::print_usage(usage);
        if (flag != "--bundle" && flag != "--epsilon" && flag != "--min-penumbra" && flag != "--pixels-allowed" && flag != "--out")
            return fail("unknown argument '" + flag + "'; allowed: --bundle, --epsilon, --min-penumbra, --pixels-allowed, --out",
                        bad_input);
        if (i + 1 >= args.size()) return fail(flag + ": missing value", bad_input);
        const std::string& value = args[++i];
        if (flag == "--bundle") bundle_dir = value;
        else if (flag == "--out") out_path = value;
        else if (flag == "--min-penumbra") {
            if (!parse_number(value, min_penumbra))
                return fail("--min-penumbra: '" + value + "' is not a pixel count >= 0", bad_input);
        } else if (flag == "--pixels-allowed") {
            if (!parse_number(value, pixels_allowed) || !(pixels_allowed >= 0 && pixels_allowed <= 1))
                return fail("--pixels-allowed: '" + value + "' is not a fraction from 0 to 1", bad_input);
        } else if (!parse_number(value, epsilon) || !(epsilon >= 0))
            return fail("--epsilon: '" + value + "' is not a number >= 0", bad_input);
    }
    if (bundle_dir.empty()) return fail(std::string("--bundle: missing\n") + usage, bad_input);

    Bundle bundle;
    std::string error;
    // a bundle of a technique the oracle does not model has no oracle.f32 and bound.f32 (has_oracle)
    if (!read_bundle(std::filesystem::path(bundle_dir), bundle, &error)) return fail(error);
    const bool oracle = bundle.has_oracle;
    if (oracle && pixels_allowed > 0)
        return fail("--pixels-allowed applies to bundles without an oracle.f32; this bundle has one (its bound is per pixel)",
                    bad_input);
    LayoutInputs inputs;
    inputs.layout = bundle.layout;
    inputs.emission_dir = bundle.emission_dir;
    inputs.width = bundle.width;
    inputs.height = bundle.height;
    inputs.triangles = bundle.triangles;
    inputs.uniforms = bundle.uniforms;
    inputs.caller_textures = bundle.caller_textures; // the bundle's G-buffers; the layout says which it reads
    inputs.bake_textures = bundle.bake_textures; // oim's bake (uniforms.json bake_textures)

    Context::Failure failure = Context::Failure::none;
    std::optional<Context> context = Context::create(&failure, &error);
    if (!context) {
        if (failure == Context::Failure::no_device) {
            std::cout << "skipped: " << error << '\n';
            return skipped;
        }
        return fail(error);
    }
    const auto start = std::chrono::steady_clock::now();
    LayoutOutput output;
    error = run_layout(*context, inputs, output);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const std::string device = context->properties().deviceName;
    const std::shared_ptr<const int> counter = context->message_counter();
    context.reset(); // counts what destroying the device reports too
    const int messages = *counter;
    if (!error.empty()) return fail(error);

    if (output.result.size() != bundle.visibility_gl.size())
        return fail("the result has " + std::to_string(output.result.size()) + " pixels, visibility_gl.f32 " +
                    std::to_string(bundle.visibility_gl.size()));
    // |Vulkan − GL| and |Vulkan − oracle| against the oracle's bound (0 without an oracle), pixel by pixel.
    double max_difference = 0, max_to_oracle = 0, max_bound = 0;
    std::size_t beyond = 0, beyond_oracle = 0, penumbra = 0;
    for (std::size_t i = 0; i < output.result.size(); ++i) {
        const double bound = oracle ? bundle.bound[i] : 0.0;
        const double difference = std::abs(static_cast<double>(output.result[i]) - bundle.visibility_gl[i]);
        max_difference = std::max(max_difference, difference);
        max_bound = std::max(max_bound, bound);
        beyond += !(difference <= bound + epsilon); // NaN counts as beyond
        if (oracle) {
            const double to_oracle = std::abs(static_cast<double>(output.result[i]) - bundle.oracle[i]);
            max_to_oracle = std::max(max_to_oracle, to_oracle);
            beyond_oracle += !(to_oracle <= bound + epsilon);
        }
        penumbra += bundle.visibility_gl[i] > 0.02f && bundle.visibility_gl[i] < 0.98f;
    }
    const std::string technique = bundle.layout.at("config").value("technique", "occlusion");
    if (oracle)
        std::printf("vulkan %s, %s: %zu passes, %d validation messages, %.0f ms; max |vulkan - gl| %.3g, max |vulkan - oracle| "
                    "%.3g, max bound %.3g, %zu (gl) and %zu (oracle) of %zu pixels beyond bound + %.0e, %zu penumbra pixels\n",
                    device.c_str(), technique.c_str(), output.passes.size(), messages, ms, max_difference, max_to_oracle,
                    max_bound, beyond, beyond_oracle, output.result.size(), epsilon, penumbra);
    else
        std::printf("vulkan %s, %s (no oracle): %zu passes, %d validation messages, %.0f ms; max |vulkan - gl| %.3g, "
                    "%zu of %zu pixels beyond %.0e, %zu penumbra pixels\n",
                    device.c_str(), technique.c_str(), output.passes.size(), messages, ms, max_difference, beyond,
                    output.result.size(), epsilon, penumbra);
    if (!out_path.empty()) {
        std::ofstream file(out_path, std::ios::binary);
        file.write(reinterpret_cast<const char*>(output.result.data()),
                   static_cast<std::streamsize>(output.result.size() * sizeof(float)));
        if (!file) return fail("cannot write " + out_path);
    }
    if (messages > 0) return fail(std::to_string(messages) + " validation messages (printed above)");
    if (penumbra < min_penumbra)
        return fail("only " + std::to_string(penumbra) + " penumbra pixels in the GL image; the check needs " +
                    std::to_string(min_penumbra));
    const auto allowed = static_cast<std::size_t>(pixels_allowed * static_cast<double>(output.result.size()));
    if (beyond > allowed)
        return fail(std::to_string(beyond) + " pixels differ from the GL runtime beyond " +
                    (oracle ? std::string("the oracle's bound")
                            : "--epsilon (no oracle for " + technique + "); allowed: " + std::to_string(allowed)));
    if (beyond_oracle > 0) return fail(std::to_string(beyond_oracle) + " pixels differ from the oracle beyond its bound");
    return pass;
}

} // namespace

int main(int argc, char** argv) { return penumbra::cli::run_main(argc, argv, run, failed); }
