// The generic reference program (penumbra/generic.hpp) for every valid configuration of the
// matrix, compiled and linked by glslang for its target.
#include <penumbra/generic.hpp>
#include <penumbra/validation.hpp>

#include <doctest/doctest.h>

#include <chrono>
#include <cstdio>
#include <map>
#include <set>
#include <tuple>

using namespace penumbra;

namespace {

// The matrix of matrix_test.cpp, plus fade off (a uniform of the generic program).
constexpr int generic_matrix_slices[] = {1, 4, 5, 8, 16, 32};
constexpr int generic_matrix_resolutions[] = {32, 256, 2048};

template <class Visit> void for_each_generic_configuration(Visit visit) {
    for (Filter filter : all_values<Filter>())
        for (Fusion fusion : all_values<Fusion>())
            for (Packing packing : all_values<Packing>())
                for (Target target : all_values<Target>())
                    for (Light light : all_values<Light>())
                        for (bool fade : {true, false})
                            for (int slices : generic_matrix_slices)
                                for (int resolution : generic_matrix_resolutions)
                                    visit(Config{.slices = slices, .resolution = resolution, .filter = filter,
                                                 .fusion = fusion, .packing = packing, .light = light,
                                                 .self_shadow_fade = fade, .target = target});
}

} // namespace

TEST_CASE("the generic program of every valid configuration of the matrix compiles and links with glslang") {
    // Configurations that share a program text (same filter, packing, light, target) are compiled
    // once: the text is what glslang sees, so a second compile would prove nothing new.
    std::map<std::string, bool> compiled; // program text -> compiled without errors
    std::set<std::tuple<Filter, Packing, Light, Target>> storages;
    int valid = 0, rejected = 0;
    const auto start = std::chrono::steady_clock::now();
    for_each_generic_configuration([&](const Config& config) {
        const Result<GenericShading> result = emit_generic(config);
        if (!result.value) {
            ++rejected;
            CHECK(result.errors.size() == validate(config).size());
            return;
        }
        ++valid;
        storages.insert({config.filter, config.packing, config.light, config.target});
        const Program& program = result.value->program;
        const std::string key = program.stages.at(0).text + program.stages.at(1).text;
        if (compiled.count(key)) return;
        const std::vector<ShaderDiagnostic> diagnostics = validate_program(program, config.target);
        compiled[key] = !has_errors(diagnostics);
        if (has_errors(diagnostics)) {
            for (const ShaderDiagnostic& d : diagnostics) MESSAGE(format(d));
            FAIL(to_string(config.filter) << "/" << to_string(config.packing) << "/" << to_string(config.light) << "/"
                                          << to_string(config.target) << ": the generic program does not compile");
        }
    });
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("generic matrix: %d valid configurations served by %zu distinct programs, %d rejected, %.1f s\n", valid,
                compiled.size(), rejected, seconds);
    CHECK(valid > 0);
    CHECK(rejected > 0);
    // exactly one program per filter × packing × light × target that has a valid configuration
    CHECK(compiled.size() == storages.size());
}
