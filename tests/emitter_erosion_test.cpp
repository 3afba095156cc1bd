// Erosion's emitted structure: tap counts in the text equal the configuration's, no loop statement
// in the unrolled passes, the min-max chain as one reduction pass per level in the layout; invalid
// erosion parameters refused with their message. (Its programs compile in matrix_test.cpp.)
#include <penumbra/penumbra.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace penumbra;

namespace {

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

std::string text_of(const Config& config, std::string_view file) { return emit_file(config, file).text; }

} // namespace

TEST_CASE("erosion: tap counts equal the configuration's, no loop statements") {
    for (ErosionParams e : {ErosionParams{}, ErosionParams{.max_search_radius = 5, .search_taps = 7, .blur_taps = 3},
                            ErosionParams{.max_search_radius = 64, .search_taps = 64, .blur_taps = 1}}) {
        const Config config{.technique = Technique::erosion, .erosion = e};
        const std::string erode = text_of(config, "penumbra_erosion_erode.frag");
        const std::string blur = text_of(config, "penumbra_erosion_blur.frag");
        CHECK(count(erode, "e = penumbra_fetch(penumbra_erosionEdges, ivec2(centre") == e.search_taps);
        CHECK(count(erode, "// search taps ") == (e.search_taps + 3) / 4);
        CHECK(count(erode, "// coarse texel (") == 9);
        CHECK(count(blur, "t = penumbra_fetch(penumbra_erosionPenumbra, ivec2(centre") == e.blur_taps);
        CHECK(count(blur, "// blur taps ") == (e.blur_taps + 3) / 4);
        CHECK(erode.find(", " + std::to_string(erosion_levels(e)) + "));") != std::string::npos);
        for (std::string_view a : {"penumbra_erosion_hard.frag", "penumbra_erosion_edges.frag", "penumbra_erosion_reduce.frag",
                           "penumbra_erosion_erode.frag", "penumbra_erosion_blur.frag"}) {
            const std::string text = text_of(config, a);
            CHECK(text.find("for (") == std::string::npos);
            CHECK(text.find("while (") == std::string::npos);
        }
        const Layout layout = describe_layout(config);
        int reductions = 0;
        for (const PassDesc& pass : layout.passes)
            if (pass.name == "erosion_reduce") {
                CHECK(pass.inputs.front().level == reductions);
                CHECK(pass.outputs.front().level == reductions + 1);
                ++reductions;
            }
        CHECK(reductions == erosion_levels(e));
    }
    CHECK(erosion_levels({.max_search_radius = 16}) == 4);
    CHECK(erosion_levels({.max_search_radius = 17}) == 5);
    CHECK(erosion_levels({.max_search_radius = 1}) == 0);
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
