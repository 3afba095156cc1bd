// The whole configuration matrix, compiled and linked by glslang for its target.
#include <penumbra/penumbra.hpp>
#include <penumbra/validation.hpp>

#include <doctest/doctest.h>

#include <chrono>
#include <cstdio>

using namespace penumbra;

namespace {

constexpr int matrix_slices[] = {1, 4, 5, 8, 16, 32};
constexpr int matrix_resolutions[] = {32, 256, 2048};

template <class Visit> void for_each_configuration(Visit visit) {
    for (Filter filter : all_values<Filter>())
        for (Fusion fusion : all_values<Fusion>())
            for (Packing packing : all_values<Packing>())
                for (Target target : all_values<Target>())
                    for (Light light : all_values<Light>())
                        for (int slices : matrix_slices)
                            for (int resolution : matrix_resolutions)
                                visit(Config{.slices = slices, .resolution = resolution, .filter = filter,
                                             .fusion = fusion, .packing = packing, .light = light,
                                             .target = target});
}

std::string name_of(const Config& c) {
    return std::string(to_string(c.filter)) + "/" + std::string(to_string(c.fusion)) + "/" +
           std::string(to_string(c.packing)) + "/" + std::string(to_string(c.light)) + "/" +
           std::string(to_string(c.target)) + "/S" + std::to_string(c.slices) + "/R" + std::to_string(c.resolution);
}

} // namespace

TEST_CASE("every valid configuration of the matrix compiles and links with glslang") {
    int valid = 0, rejected = 0, programs = 0;
    const auto start = std::chrono::steady_clock::now();
    for_each_configuration([&](const Config& config) {
        Result<Emission> result = emit(config);
        if (!result.value) {
            ++rejected;
            REQUIRE(!result.errors.empty());
            return;
        }
        ++valid;
        for (const Program& program : result.value->programs) {
            ++programs;
            const std::vector<ShaderDiagnostic> diagnostics = validate_program(program, config.target);
            if (has_errors(diagnostics)) {
                for (const ShaderDiagnostic& d : diagnostics) MESSAGE(name_of(config) << ": " << format(d));
                FAIL(name_of(config) << " program " << program.name << " does not compile");
            }
        }
    });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("matrix: %d valid configurations (%d programs) validated, %d rejected, %.1f s\n", valid, programs,
                rejected, seconds);
    CHECK(valid > 0);
    CHECK(rejected > 0);
}


// The tangent clip changes the visibility function, the kernel and the deferred pass's inputs:
// every filter × packing × light × target with it on (chained fusion, two slice counts).
TEST_CASE("the tangent clip compiles and links with glslang for every filter, packing, light and target") {
    int valid = 0;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Target target : all_values<Target>())
                for (Light light : all_values<Light>())
                    for (int slices : {5, 16}) {
                        const Config config{.slices = slices, .resolution = 256, .filter = filter,
                                            .fusion = Fusion::chained, .packing = packing, .light = light,
                                            .tangent_clip = true, .target = target};
                        Result<Emission> result = emit(config);
                        if (!result.value) continue;
                        ++valid;
                        CHECK(result.value->snippet.text.find("float penumbraVisibility(vec3 worldPos, vec3 worldNormal)") !=
                              std::string::npos);
                        for (const Program& program : result.value->programs) {
                            const std::vector<ShaderDiagnostic> diagnostics = validate_program(program, config.target);
                            if (has_errors(diagnostics)) {
                                for (const ShaderDiagnostic& d : diagnostics) MESSAGE(name_of(config) << ": " << format(d));
                                FAIL(name_of(config) << " tangent clip: program " << program.name << " does not compile");
                            }
                        }
                    }
    CHECK(valid > 40);
}

// Adaptive slice placement adds two programs (the depth-bin pre-pass, the boundary pass) and changes
// the slicing fragment and penumbraVisibility (boundaries read from an R32UI texture): every filter ×
// packing × light × target, with 1 slice (no inner boundary) and the fade on, and with 16 slices,
// the tangent clip on and the fade off.
TEST_CASE("adaptive slice placement compiles and links with glslang for every filter, packing, light and target") {
    int valid = 0;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Target target : all_values<Target>())
                for (Light light : all_values<Light>())
                    for (bool switches : {false, true}) {
                        const Config config{.slices = switches ? 16 : 1, .resolution = 256, .filter = filter,
                                            .fusion = switches ? Fusion::chained : Fusion::probabilistic,
                                            .packing = packing, .light = light, .self_shadow_fade = !switches,
                                            .tangent_clip = switches, .slice_placement = SlicePlacement::adaptive,
                                            .target = target};
                        Result<Emission> result = emit(config);
                        if (!result.value) continue;
                        ++valid;
                        int placement_programs = 0;
                        for (const Program& program : result.value->programs) {
                            placement_programs += program.name == "depth_bins" || program.name == "slice_boundaries";
                            const std::vector<ShaderDiagnostic> diagnostics = validate_program(program, config.target);
                            if (has_errors(diagnostics)) {
                                for (const ShaderDiagnostic& d : diagnostics) MESSAGE(name_of(config) << ": " << format(d));
                                FAIL(name_of(config) << " adaptive placement: program " << program.name
                                                     << " does not compile");
                            }
                        }
                        CHECK_MESSAGE(placement_programs == 2, name_of(config));
                    }
    CHECK(valid > 60);
}
