// The erosion technique over its parameter matrix, compiled and linked by glslang for the four
// targets; invalid erosion parameters rejected with their message.
#include <penumbra/penumbra.hpp>
#include <penumbra/validation.hpp>

#include <doctest/doctest.h>

using namespace penumbra;

namespace {

std::vector<Config> erosion_matrix() {
    std::vector<Config> configs;
    for (Target target : all_values<Target>())
        for (Light light : all_values<Light>()) {
            for (ErosionParams e : {ErosionParams{}, ErosionParams{.max_search_radius = 1, .search_taps = 1, .blur_taps = 1},
                                    ErosionParams{.max_search_radius = 256, .edge_threshold = 4.0, .search_taps = 64,
                                                  .blur_taps = 64}})
                configs.push_back({.technique = Technique::erosion, .light = light, .target = target, .erosion = e});
        }
    return configs;
}

} // namespace

TEST_CASE("erosion's parameter matrix compiles and links with glslang on every target") {
    int programs = 0;
    for (const Config& config : erosion_matrix()) {
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
    CHECK(programs == static_cast<int>(erosion_matrix().size()) * 7);
}

TEST_CASE("invalid erosion parameters are rejected with field, value and what is allowed") {
    auto first_error = [](ErosionParams e) {
        const std::vector<ConfigError> errors = validate(Config{.technique = Technique::erosion, .erosion = e});
        return errors.empty() ? std::string() : errors.front().message;
    };
    CHECK(first_error({.max_search_radius = 0}) ==
          "erosion.max_search_radius: 0 pixels is a search beyond the image (its min-max chain needs an image of at "
          "least twice the radius); allowed: 1 to 256 pixels");
    CHECK(first_error({.max_search_radius = 5000}).starts_with("erosion.max_search_radius: 5000 pixels is a search beyond the image"));
    CHECK(first_error({.edge_threshold = 0.0}) ==
          "erosion.edge_threshold: 0.0 is out of range; allowed: more than 0.0 to 4.0 (|Laplacian| of the 0/1 hard shadow)");
    CHECK(first_error({.search_taps = 0}) == "erosion.search_taps: 0 is out of range; allowed: 1 to 64");
    CHECK(first_error({.blur_taps = 0}) == "erosion.blur_taps: 0 is out of range; allowed: 1 to 64");
    CHECK(first_error({.blur_taps = 65}) == "erosion.blur_taps: 65 is out of range; allowed: 1 to 64");
    CHECK(first_error({}).empty());
}
