// Occlusion interval maps: every program of the parameter matrix compiles and links with glslang.
#include <penumbra/penumbra.hpp>
#include <penumbra/validation.hpp>

#include <doctest/doctest.h>

using namespace penumbra;

TEST_CASE("oim: every interval count, resolution and target compiles and links with glslang") {
    int programs = 0, rejected = 0;
    for (Target target : all_values<Target>())
        for (int intervals : {4, 8, 12, 16})
            for (int resolution : {32, 256, 2048}) {
                Config config{.technique = Technique::oim, .target = target};
                config.oim.intervals = intervals;
                config.oim.resolution = resolution;
                if (!is_valid(config)) { // a map larger than the target guarantees
                    CHECK(validate(config).front().field == "oim.resolution");
                    ++rejected;
                    continue;
                }
                const Result<Emission> emission = emit(config);
                REQUIRE(emission.value);
                REQUIRE(emission.value->programs.size() == 2); // shading_example, shading_deferred
                for (const Program& program : emission.value->programs) {
                    ++programs;
                    const std::vector<ShaderDiagnostic> diagnostics = validate_program(program, target);
                    for (const ShaderDiagnostic& d : diagnostics) MESSAGE(format(d));
                    CHECK_MESSAGE(!has_errors(diagnostics), to_string(target), " ", intervals, " ", program.name);
                }
            }
    CHECK(programs + 2 * rejected == 4 * 4 * 3 * 2);
    CHECK(rejected == 4); // glsl330 guarantees 1024 texels: 2048 is refused for each interval count
}
