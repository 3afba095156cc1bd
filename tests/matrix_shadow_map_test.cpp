// Every shadow map technique (shadowmap, pcf, pcss) over its parameter matrix, compiled and linked
// by glslang for the four targets.
#include <penumbra/penumbra.hpp>
#include <penumbra/validation.hpp>

#include <doctest/doctest.h>

#include <chrono>
#include <cstdio>

using namespace penumbra;

namespace {

std::vector<Config> technique_matrix() {
    std::vector<Config> configs;
    for (Target target : all_values<Target>())
        for (Light light : all_values<Light>()) {
            const Config base{.light = light, .target = target};
            auto with = [&](Config c) {
                c.light = light;
                c.target = target;
                configs.push_back(c);
            };
            with({.technique = Technique::shadowmap});
            with({.technique = Technique::shadowmap, .shadow_map = {.resolution = 32, .constant_bias = 0.0, .slope_bias = 0.0}});
            for (int n : {1, 4, 16})
                with({.technique = Technique::pcf, .pcf = {.pattern = TapPattern::grid, .grid_size = n, .rotate = n == 4}});
            for (int k : {1, 16, 64})
                with({.technique = Technique::pcf, .pcf = {.pattern = TapPattern::poisson, .poisson_taps = k, .rotate = k != 1}});
            // engine settings (Bevy, Filament, three.js, Godot ultra, PlayCanvas high) and the extremes
            for (auto [b, f] : {std::pair{8, 8}, {16, 16}, {17, 34}, {32, 32}, {32, 64}, {1, 1}, {64, 128}})
                with({.technique = Technique::pcss, .pcss = {.blocker_samples = b, .filter_samples = f, .rotate = b != 1}});
            (void)base;
        }
    return configs;
}

} // namespace

TEST_CASE("every shadow map technique's parameter matrix compiles and links with glslang on every target") {
    int programs = 0;
    const auto start = std::chrono::steady_clock::now();
    for (const Config& config : technique_matrix()) {
        const std::string name(detail::describe(config).view());
        Result<Emission> result = emit(config);
        REQUIRE_MESSAGE(result.value, name << ": " << (result.errors.empty() ? "" : result.errors[0].message));
        for (const Program& program : result.value->programs) {
            ++programs;
            const std::vector<ShaderDiagnostic> diagnostics = validate_program(program, config.target);
            if (has_errors(diagnostics)) {
                for (const ShaderDiagnostic& d : diagnostics) MESSAGE(name << ": " << format(d));
                FAIL(name << " program " << program.name << " does not compile");
            }
        }
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("shadow map matrix: %zu configurations, %d programs validated, %.1f s\n", technique_matrix().size(),
                programs, seconds);
    CHECK(programs == static_cast<int>(technique_matrix().size()) * 3);
}
