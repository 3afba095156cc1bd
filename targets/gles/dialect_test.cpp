// penumbra-dialect-test — the older dialects on their own contexts: runs each target bundle's
// emission with LayoutRunner on the context its target names (glsl330: OpenGL 3.3 core,
// essl300: OpenGL ES 3.0; EGL surfaceless) and compares the visibility with the desktop GL
// runtime's (visibility_gl.f32) for the same scene, light and configuration. Every technique:
// occlusion textures (uniform or adaptive slice placement), shadowmap, pcf, pcss, erosion, and
// oim from a bundle with its bake (uniforms.json bake_textures).
//
//   penumbra-dialect-test BUNDLE_DIR...   (each written by penumbra-export-bundle --target glsl330|essl300)
//
// Occlusion textures: per pixel |runner − oracle| ≤ bound + q (oracle.f32, bound.f32: the CPU
// model and its texture precision bound, from the desktop run's slicing output, which the same
// llvmpipe rasterizer reproduces) and |runner − desktop| ≤ 2·bound + q (both runs are within the
// bound). The other techniques (the oracle models none of them; their bundles have no oracle.f32
// or bound.f32): per pixel |runner − desktop| ≤ 1e-4: the same shader text (the bundle's GL run
// emits the requested target) into the same result format on the same llvmpipe rasterizer and
// samplers (measured: 0 on glsl330, 6e-8 on essl300, its R8 read back two ways). q is one step
// of the layout's result format when it has 8 bits (essl300: R8), else 0. Either way the desktop image must have a shadowed pixel, or the
// comparison would prove nothing. On Mesa the contexts are capped at exactly 3.3 / ES 3.0
// (MESA_GL_VERSION_OVERRIDE / MESA_GLES_VERSION_OVERRIDE, unless already set).
// Exit status: 0 all agree, 1 a difference or a failure, 2 bad arguments.
#include <epoxy/egl.h>
#include <epoxy/gl.h>

#include <penumbra_tools/cli.hpp>
#include "bundle_reader.hpp"
#include "layout_runner.hpp"
#include "rendering/egl_context.hpp"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>
#include <vector>

namespace {

using nlohmann::json;
using penumbra::playground::ContextRequest;
using penumbra::playground::HeadlessContext;
using penumbra::targets::Bundle;
using penumbra::targets::LayoutRunner;
namespace fs = std::filesystem;

// |runner − desktop| for the techniques without an oracle: the same text into the same format on
// the same Mesa rasterizer and sampler code differs by float rounding at most.
constexpr double no_oracle_epsilon = 1e-4;

constexpr const char* usage =
    "usage: penumbra-dialect-test BUNDLE_DIR...\n"
    "  each BUNDLE_DIR written by penumbra-export-bundle --target glsl330|essl300, any technique\n"
    "  (occlusion textures are compared with the CPU oracle and the desktop run, the others with the\n"
    "  desktop run's visibility_gl.f32; oim needs the bundle's bake, --technique oim writes it)\n";

// One line naming the configuration: the technique and what sizes it.
std::string describe(const json& c) {
    const std::string technique = c.value("technique", "occlusion"), light = c.value("light", "?");
    char text[256];
    if (technique == "occlusion") {
        std::snprintf(text, sizeof text, "occlusion %s/%s/%s/%s%s%s %d slices %d²", std::string(c["filter"]).c_str(),
                      std::string(c["packing"]).c_str(), light.c_str(), std::string(c["fusion"]).c_str(),
                      c.value("tangent_clip", false) ? " tangent-clip" : "",
                      c.value("slice_placement", "uniform") == "adaptive" ? " adaptive" : "", c["slices"].get<int>(),
                      c["resolution"].get<int>());
    } else if (technique == "oim") {
        const json o = c.value("oim", json::object());
        std::snprintf(text, sizeof text, "oim (sun of the bake) %d² bake, %d intervals", o.value("resolution", 0),
                      o.value("intervals", 0));
    } else {
        const json m = c.value("shadow_map", json::object());
        std::snprintf(text, sizeof text, "%s/%s shadow map %d²", technique.c_str(), light.c_str(), m.value("resolution", 0));
    }
    return text;
}

struct Outcome {
    bool ok = false;
    std::string line;
};

Outcome check_bundle(const fs::path& dir, std::map<std::string, HeadlessContext>& contexts) {
    auto fail = [&](const std::string& why) { return Outcome{false, "FAIL " + dir.string() + ": " + why}; };
    Bundle bundle;
    std::string error;
    if (!penumbra::targets::read_bundle(dir, bundle, &error)) return fail(error);
    const json& layout = bundle.layout;
    const std::string target = layout["config"]["target"];
    const std::string technique = layout["config"].value("technique", "occlusion");
    if (target != "glsl330" && target != "essl300")
        return fail("emission for '" + target + "'; this test runs glsl330 and essl300");

    // The context the dialect is written for.
    if (!contexts.count(target)) {
        const ContextRequest request = target == "essl300" ? ContextRequest{.es = true, .major = 3, .minor = 0}
                                                           : ContextRequest{.es = false, .major = 3, .minor = 3};
        std::optional<HeadlessContext> context = HeadlessContext::create(&error, request);
        if (!context) return fail(error);
        contexts.emplace(target, std::move(*context));
    }
    const HeadlessContext& context = contexts.at(target);
    if (!context.make_current()) return fail("eglMakeCurrent failed");

    std::map<std::string, std::string> sources;
    if (!penumbra::targets::read_emission_sources(bundle, sources, &error)) return fail(error);
    const auto start = std::chrono::steady_clock::now();
    std::unique_ptr<LayoutRunner> runner = LayoutRunner::create(layout, sources, &error, {penumbra::Phase::shadow, penumbra::Phase::screen});
    if (!runner) return fail(error);
    for (const auto& [name, value] : bundle.uniforms) runner->set_uniform(name, value);
    // Textures baked offline (oim's interval maps), once, from the bundle's files.
    for (const json& t : layout["textures"]) {
        if (t.value("source", "passes") != "bake") continue;
        const std::string name = t["name"];
        const auto texels = bundle.bake_textures.find(name);
        if (texels == bundle.bake_textures.end())
            return fail("the layout's bake texture " + name + " has no file in uniforms.json bake_textures "
                        "(penumbra-export-bundle --technique oim writes the bake with the bundle)");
        if (std::string e = runner->fill_bake(name, texels->second); !e.empty()) return fail(e);
    }

    const std::vector<float>& triangles = bundle.triangles;
    GLuint vao = 0, vbo = 0;
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(triangles.size() * sizeof(float)), triangles.data(), GL_STATIC_DRAW);
    const int position = runner->vertex_location("penumbra_position"); // layout.json's vertex_inputs
    if (position < 0) return fail("layout.json names no location for penumbra_position");
    glEnableVertexAttribArray(static_cast<GLuint>(position));
    glVertexAttribPointer(static_cast<GLuint>(position), 3, GL_FLOAT, GL_FALSE, 0, nullptr);
    glBindVertexArray(0);
    const auto draw = [&](GLuint) {
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(triangles.size() / 3));
        glBindVertexArray(0);
    };
    const int width = bundle.width, height = bundle.height;
    error = runner->run_phase(penumbra::Phase::shadow, draw, width, height);
    // Every texture the layout leaves to the caller, from the bundle's G-buffer file for it.
    for (const json& t : layout["textures"]) {
        if (!error.empty() || t.value("source", "passes") != "caller") continue;
        const std::string name = t["name"];
        const auto texels = bundle.caller_textures.find(name);
        if (texels == bundle.caller_textures.end()) {
            error = "the layout's caller texture " + name + " has no file in the bundle's caller_textures";
            break;
        }
        error = runner->fill_texture(name, width, height, texels->second.data());
    }
    if (error.empty()) error = runner->run_phase(penumbra::Phase::screen, nullptr, width, height);
    const std::vector<float> visibility = runner->read_result();
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    runner.reset();
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    if (!error.empty()) return fail(error);

    const std::vector<float>& desktop = bundle.visibility_gl;
    const bool oracle = bundle.has_oracle; // occlusion textures only
    const std::vector<float>& bound = bundle.bound;
    const std::vector<float>& model = bundle.oracle;
    if (visibility.size() != desktop.size() || (oracle && (bound.size() != desktop.size() || model.size() != desktop.size())))
        return fail("image sizes differ (runner " + std::to_string(visibility.size()) + ", desktop " +
                    std::to_string(desktop.size()) + ", bound " + std::to_string(bound.size()) + " pixels)");
    if (!oracle && technique == "occlusion") return fail("occlusion textures need the bundle's oracle.f32 and bound.f32");
    std::string result_format;
    for (const json& t : layout["textures"])
        if (t["name"] == layout["result"]) result_format = t["internal_format"];
    const double step = result_format == "R8" || result_format == "RGBA8" ? 1.0 / 255.0 : 0.0;
    double worst = 0.0, worst_model = 0.0, worst_bound = 0.0;
    int outside = 0, shadowed = 0;
    for (std::size_t i = 0; i < desktop.size(); ++i) {
        const double difference = std::abs(static_cast<double>(visibility[i]) - desktop[i]);
        worst = std::max(worst, difference);
        if (desktop[i] < 0.98f) ++shadowed;
        if (!oracle) { // NaN counts as outside
            if (!(difference <= no_oracle_epsilon)) ++outside;
            continue;
        }
        const double to_model = std::abs(static_cast<double>(visibility[i]) - model[i]);
        worst_model = std::max(worst_model, to_model);
        worst_bound = std::max(worst_bound, static_cast<double>(bound[i]));
        if (!(difference <= 2.0 * bound[i] + step + 1e-6) || !(to_model <= bound[i] + step + 1e-6)) ++outside;
    }
    char comparison[320];
    if (oracle)
        std::snprintf(comparison, sizeof comparison,
                      "max |runner − desktop| = %.3e, max |runner − oracle| = %.3e (max bound %.3e, %s result), %d shadowed "
                      "pixels, %d outside the bound (q = %.4f)",
                      worst, worst_model, worst_bound, result_format.c_str(), shadowed, outside, step);
    else
        std::snprintf(comparison, sizeof comparison,
                      "max |runner − desktop| = %.3e (no oracle for %s; %s result), %d shadowed pixels, %d beyond %.0e",
                      worst, technique.c_str(), result_format.c_str(), shadowed, outside, no_oracle_epsilon);
    char line[768];
    std::snprintf(line, sizeof line, "%s %s on %s: %s, %dx%d: %s; %.0f ms", outside || shadowed == 0 ? "FAIL" : "ok  ",
                  target.c_str(), context.version().c_str(), describe(layout["config"]).c_str(), width, height, comparison, ms);
    Outcome outcome{outside == 0 && shadowed > 0, line};
    if (shadowed == 0) outcome.line += "\n     the desktop image has no shadowed pixel: the comparison would prove nothing";
    return outcome;
}

int run(const std::vector<std::string>& args) {
    if (penumbra::cli::asks_for_help(args)) return penumbra::cli::print_usage(usage);
    if (args.empty()) return penumbra::cli::fail_with_usage("no bundle given", usage);
    for (const std::string& arg : args)
        if (arg.starts_with("-"))
            return penumbra::cli::fail_with_usage("unknown flag '" + penumbra_gen::printable(arg) + "'; allowed: --help", usage);
    // Mesa hands out its newest compatible version otherwise (4.5 core, ES 3.2).
    setenv("MESA_GL_VERSION_OVERRIDE", "3.3", 0);
    setenv("MESA_GLSL_VERSION_OVERRIDE", "330", 0);
    setenv("MESA_GLES_VERSION_OVERRIDE", "3.0", 0);
    std::map<std::string, HeadlessContext> contexts;
    bool ok = true;
    for (const std::string& dir : args) {
        Outcome outcome;
        try {
            outcome = check_bundle(dir, contexts);
        } catch (const std::exception& e) { // a layout.json without a key the runner reads
            outcome = {false, "FAIL " + dir + ": " + e.what()};
        }
        std::cout << outcome.line << std::endl;
        ok = ok && outcome.ok;
    }
    return ok ? 0 : 1;
}

} // namespace

int main(int argc, char** argv) { return penumbra::cli::run_main(argc, argv, run, 1); }
