// Occlusion interval maps (GPU Gems ch. 13) as text: one labelled evaluation per rise/fall pair,
// no loop, the chapter's min/max/saturate/dot; validation of the oim fields. No glslang, no GL.
#include <penumbra/penumbra.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace penumbra;

namespace {

int count(std::string_view text, std::string_view needle) {
    int n = 0;
    for (std::size_t at = text.find(needle); at != std::string_view::npos; at = text.find(needle, at + 1)) ++n;
    return n;
}

std::string first_error(const Config& config) {
    const std::vector<ConfigError> errors = validate(config);
    return errors.empty() ? std::string() : errors.front().message;
}

} // namespace

TEST_CASE("oim: the evaluation is unrolled per rise/fall pair, two fetches each") {
    for (int intervals : {4, 8, 12, 16}) {
        Config config{.technique = Technique::oim};
        config.oim.intervals = intervals;
        CAPTURE(intervals);
        REQUIRE(is_valid(config));
        const std::string snippet = emit_file(config, "penumbra_visibility.glsl").text;
        const std::size_t start = snippet.find("float penumbraVisibility(vec2 texCoord)");
        REQUIRE(start != std::string::npos);
        const std::string body = snippet.substr(start, snippet.find("\n}\n", start) - start);
        const int pairs = intervals / 4;
        CHECK(count(body, "textureLod(") == 2 * pairs);
        CHECK(count(body, "dot(inverseWidth, clamp(min(") == pairs);
        for (int p = 0; p < pairs; ++p)
            CHECK(body.find("// intervals " + std::to_string(4 * p) + " to " + std::to_string(4 * p + 3) + ": pair " +
                            std::to_string(p)) != std::string::npos);
        CHECK(count(body, "for (") + count(body, "while (") + count(body, "if (") == 0);
        CHECK(count(snippet, "uniform sampler2D penumbra_rise") == pairs);
        CHECK(count(snippet, "uniform sampler2D penumbra_fall") == pairs);
        CHECK(snippet.find("#version") == std::string::npos);
        CHECK(snippet.find("interval maps 256x256 | " + std::to_string(intervals) + " intervals") != std::string::npos);
    }
}

TEST_CASE("oim: invalid fields are rejected with their message") {
    auto with = [](auto change) {
        Config c{.technique = Technique::oim};
        change(c.oim);
        return first_error(c);
    };
    CHECK(with([](OimParams& o) { o.intervals = 6; }) ==
          "oim.intervals: 6 is not allowed; allowed: 4, 8, 12 or 16 (four intervals per RGBA rise/fall texture pair)");
    CHECK(with([](OimParams& o) { o.samples = 128; }).starts_with("oim.samples: 128 is not allowed; allowed: 256, 512"));
    CHECK(with([](OimParams& o) { o.samples = 1000; }).starts_with("oim.samples: 1000 is not allowed"));
    CHECK(with([](OimParams& o) { o.resolution = 100; }).starts_with("oim.resolution: 100 is not allowed"));
    Config es{.technique = Technique::oim, .target = Target::essl300};
    es.oim.resolution = 4096;
    CHECK(first_error(es).starts_with("oim.resolution: 4096 is larger than target 'essl300' guarantees; allowed: up to 2048"));
    // the occlusion-texture fields are not the technique's: out-of-range values there do not matter
    Config other{.technique = Technique::oim, .slices = 99};
    CHECK(first_error(other) == "");
}

TEST_CASE("oim: the layout marks the maps as baked, nearest, one rise and one fall per pair") {
    Config config{.technique = Technique::oim};
    config.oim.intervals = 12;
    const Layout layout = describe_layout(config);
    REQUIRE(layout.textures.size() == 8); // 3 pairs, the caller's texture coordinates, the visibility
    for (int i = 0; i < 6; ++i) {
        const TextureDesc& t = layout.textures[static_cast<std::size_t>(i)];
        CHECK(t.internal_format == "RGBA16F");
        CHECK(t.width == 256);
        CHECK(t.min_filter == "NEAREST");
        CHECK(t.source == "bake");
    }
    CHECK(layout.textures[6].source == "caller");
    CHECK(layout.textures[6].size == "output");
    CHECK(layout.result == "penumbra_visibility");
    CHECK(layout.passes.front().phase == "screen");
    CHECK(layout.textures[4].name == "penumbra_rise2");
    CHECK(layout.textures[5].name == "penumbra_fall2");
    REQUIRE(layout.programs.size() == 2);
    const std::string json = to_json(layout);
    CHECK(json.find("\"technique\": \"oim\"") != std::string::npos);
    CHECK(json.find("\"source\": \"bake\"") != std::string::npos);
    CHECK(json.find("\"oim\": {\"resolution\": 256, \"intervals\": 12, \"samples\": 256}") != std::string::npos);
    // the deferred program reads the G-buffer of texture coordinates after the six maps
    bool texcoords = false;
    for (const ParamDesc& p : layout.programs[1].parameters)
        if (p.name == "penumbra_texCoords") texcoords = p.binding == 6;
    CHECK(texcoords);
}
