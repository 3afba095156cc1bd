// The whole configuration matrix, compiled and linked by glslang for its target.
#include <penumbra/penumbra.hpp>
#include <penumbra/validation.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

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

// More than 32 slices (paper §3.7): the slicing writes bits of one RGBA32UI target, the unpack pass
// writes the occlusion textures, and the unrolled slice or level loops grow to 64 or 128 slices.
// Every filter × packing × light × target × {64, 128}, the fusion and tangent clip rotating over the
// combinations; ES 3.0 has no logic op and must refuse.
TEST_CASE("64 and 128 slices compile and link with glslang where the target has a logic op") {
    int valid = 0, index = 0;
    double slowest = 0;
    std::string slowest_name;
    std::size_t largest_snippet = 0;
    const auto start = std::chrono::steady_clock::now();
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Target target : all_values<Target>())
                for (Light light : all_values<Light>())
                    for (int slices : {64, 128}) {
                        const Fusion fusion = all_values<Fusion>()[static_cast<std::size_t>(index % 5)];
                        const Config config{.slices = slices, .resolution = 32, .filter = filter, .fusion = fusion,
                                            .packing = packing, .light = light, .leak_fix = index % 3 != 0,
                                            .self_shadow_fade = true, .tangent_clip = index % 2 == 0, .target = target};
                        ++index;
                        Result<Emission> result = emit(config);
                        if (target == Target::essl300 || packing == Packing::volume) {
                            CHECK_FALSE(result.value.has_value());
                            continue;
                        }
                        if (!result.value) continue; // gaussian with a rect light
                        ++valid;
                        largest_snippet = std::max(largest_snippet, result.value->snippet.text.size());
                        bool unpacks = false;
                        for (const Program& program : result.value->programs) {
                            unpacks = unpacks || program.name == "unpack_slices";
                            const auto program_start = std::chrono::steady_clock::now();
                            const std::vector<ShaderDiagnostic> diagnostics = validate_program(program, config.target);
                            const double took =
                                std::chrono::duration<double>(std::chrono::steady_clock::now() - program_start).count();
                            if (took > slowest) slowest = took, slowest_name = name_of(config) + " " + program.name;
                            if (has_errors(diagnostics)) {
                                for (const ShaderDiagnostic& d : diagnostics) MESSAGE(name_of(config) << ": " << format(d));
                                FAIL(name_of(config) << " program " << program.name << " does not compile");
                            }
                        }
                        CHECK(unpacks);
                    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("matrix 64/128 slices: %d valid configurations, %.1f s; largest snippet %zu bytes; slowest program "
                "%.3f s (%s)\n",
                valid, seconds, largest_snippet, slowest, slowest_name.c_str());
    CHECK(valid >= 48);
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
