// EVSM's emitted structure: blur taps in the text equal the configuration's, one line and one comment
// per tap, no loop statement; the exponents and clamps as literals; the moments stored as RGBA32F and
// filtered by the hardware, or on ES as the bits of 32-bit floats in RGBA32UI filtered by hand; the
// layout's passes and textures; the cost per pass; invalid parameters refused with their message.
// (Its programs compile in matrix_test.cpp, the ES snippet alone in matrix_snippet_test.cpp.)
#include <penumbra/cost_model.hpp>
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

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

std::string text_of(const Config& config, std::string_view file) { return emit_file(config, file).text; }

const PassDesc* find_pass(const Layout& layout, std::string_view name) {
    for (const PassDesc& pass : layout.passes)
        if (pass.name == name) return &pass;
    return nullptr;
}

} // namespace

TEST_CASE("evsm: blur taps equal the configuration's, one line and one comment each, no loop statements") {
    for (EvsmParams e : {EvsmParams{}, EvsmParams{.blur_taps = 1, .max_blur_texels = 1},
                         EvsmParams{.positive_exponent = 42.0, .negative_exponent = 0.5, .light_bleeding_reduction = 0.0,
                                    .blur_fraction = 1.0, .blur_taps = 64, .max_blur_texels = 64}}) {
        const Config config{.technique = Technique::evsm, .evsm = e};
        REQUIRE(is_valid(config));
        const std::string x = text_of(config, "penumbra_evsm_blur_x.frag");
        const std::string y = text_of(config, "penumbra_evsm_blur_y.frag");
        CHECK(count(x, "sum += penumbra_evsmSample(penumbra_evsmMoments, centre + vec2(") == e.blur_taps);
        CHECK(count(y, "sum += penumbra_evsmSample(penumbra_evsmBlurX, centre + vec2(0.0, ") == e.blur_taps);
        CHECK(count(x, "// tap ") == e.blur_taps);
        CHECK(has(x, "// tap " + std::to_string(e.blur_taps) + " of " + std::to_string(e.blur_taps) + ", at "));
        // the clamp and the fraction of the widest penumbra are literals
        CHECK(has(x, ", " + std::string(detail::format_float(e.max_blur_texels).view()) + ");"));
        CHECK(has(x, "float widest = penumbra_lightSizeUV.x * (1.0 - range.x / range.y);"));
        CHECK(has(y, "float widest = penumbra_lightSizeUV.y * (1.0 - range.x / range.y);"));
        const std::string moments = text_of(config, "penumbra_evsm_moments.frag");
        CHECK(has(moments, "return vec2(exp(" + std::string(detail::format_float(e.positive_exponent).view()) +
                               " * d), -exp(-" + std::string(detail::format_float(e.negative_exponent).view()) + " * d));"));
        const std::string snippet = emit(config).value->snippet.text;
        CHECK(has(snippet, "float penumbraVisibility(vec3 worldPos)"));
        CHECK(has(snippet, "float penumbraVisibility(vec3 worldPos, vec3 worldNormal)"));
        CHECK(has(snippet, "// light-bleeding reduction (Lauritzen 2007)") == (e.light_bleeding_reduction > 0.0));
        for (std::string_view file : {"penumbra_evsm_moments.frag", "penumbra_evsm_blur_x.frag", "penumbra_evsm_blur_y.frag"}) {
            const std::string text = text_of(config, file);
            CHECK(text.find("for (") == std::string::npos);
            CHECK(text.find("while (") == std::string::npos);
        }
        CHECK(snippet.find("for (") == std::string::npos);
    }
}

TEST_CASE("evsm: the header names the configuration; the sun's blur grows with the depth range") {
    const Config rect{.technique = Technique::evsm};
    CHECK(has(text_of(rect, "penumbra_evsm_moments.frag"),
              "// technique evsm | shadow map 1024x1024 | bias 0.02 scene units + 1.5 x slope | evsm exponents +40.0 / "
              "-5.0, light-bleeding reduction 0.1, variance bias 0.0001, blur 32 taps per axis over 0.5 of the widest "
              "penumbra, at most 32 texels, moments RGBA32F | light rect | target glsl450\n"));
    const Config sun{.technique = Technique::evsm, .light = Light::sun};
    CHECK(has(text_of(sun, "penumbra_evsm_blur_x.frag"), "float widest = penumbra_lightSizeUV.x * (range.y - range.x);"));
    // half of blur_fraction of the widest penumbra, in texels of the 1024-texel map
    CHECK(has(text_of(sun, "penumbra_evsm_blur_x.frag"), "float radius = min(widest * 256.0, 32.0);"));
}

TEST_CASE("evsm: moments in RGBA32F filtered by the hardware, on ES the bits of 32-bit floats in RGBA32UI") {
    for (Target target : all_values<Target>()) {
        // the GLSL targets: emitter_wgsl_test.cpp has WGSL's (HLSL stores WGSL's; msl is vulkan's, translated)
        if (target == Target::wgsl || target == Target::hlsl || target == Target::msl) continue;
        CAPTURE(to_string(target));
        const Config config{.technique = Technique::evsm, .target = target, .shadow_map = {.resolution = 256}};
        const bool es = target == Target::essl300;
        const Layout layout = describe_layout(config);
        const TextureDesc* moments = detail::find_texture(layout, "penumbra_evsmMoments");
        const TextureDesc* blurred = detail::find_texture(layout, "penumbra_evsmBlurX");
        REQUIRE(moments);
        REQUIRE(blurred);
        CHECK(moments->format == (es ? TextureFormat::rgba32ui : TextureFormat::rgba32f));
        CHECK(blurred->format == moments->format);
        CHECK(moments->min_filter == (es ? TextureFilter::nearest : TextureFilter::linear));
        CHECK(moments->width == 256);
        CHECK(moments->wrap == Wrap::clamp_to_edge);
        const std::string blur = text_of(config, "penumbra_evsm_blur_x.frag");
        const std::string snippet = emit(config).value->snippet.text;
        CHECK(has(blur, es ? "out uvec4 penumbra_out;" : "out vec4 penumbra_out;"));
        CHECK(has(blur, "floatBitsToUint(sum * 0.03125)") == es);
        CHECK(has(snippet, "uintBitsToFloat(texelFetch(moments, clamp(texel, ivec2(0), ivec2(255)), 0))") == es);
        CHECK(has(snippet, "return textureLod(moments, texel * 0.00390625, 0.0);") == !es);
        CHECK(has(snippet, "precision highp usampler2D;") == es);
        CHECK(has(text_of(config, "penumbra_evsm_moments.frag"), "precision highp usampler2D;") == es);
    }
}

TEST_CASE("evsm: the layout runs depth, moments, blur x, blur y from the light, then the deferred shading") {
    const Config config{.technique = Technique::evsm, .shadow_map = {.resolution = 512}};
    const Layout layout = describe_layout(config);
    std::vector<std::string> names;
    for (const PassDesc& pass : layout.passes) names.push_back(pass.name + ":" + std::string(to_string(pass.phase)));
    CHECK(names == std::vector<std::string>{"shadow_depth:shadow", "evsm_moments:shadow", "evsm_blur_x:shadow",
                                            "evsm_blur_y:shadow", "shading:screen", "shading_example:example"});
    const PassDesc* moments = find_pass(layout, "evsm_moments");
    const PassDesc* x = find_pass(layout, "evsm_blur_x");
    const PassDesc* y = find_pass(layout, "evsm_blur_y");
    REQUIRE((moments && x && y));
    CHECK(moments->inputs.at(0).texture == "penumbra_shadowMap");
    CHECK(moments->inputs.at(0).sampling.min_filter == TextureFilter::nearest);
    CHECK(moments->outputs.at(0).texture == "penumbra_evsmMoments");
    CHECK(x->inputs.at(0).texture == "penumbra_evsmMoments");
    CHECK(x->outputs.at(0).texture == "penumbra_evsmBlurX");
    CHECK(y->inputs.at(0).texture == "penumbra_evsmBlurX");
    CHECK(y->outputs.at(0).texture == "penumbra_evsmMoments");
    CHECK(x->viewport_width == 512);
    CHECK(y->viewport_height == 512);
    // the blur passes read the light's size and the depth range, computed from the shadow frame
    int computed = 0;
    for (const ProgramDesc& program : layout.programs)
        if (program.name == "evsm_blur_x")
            for (const ParamDesc& p : program.parameters)
                computed += (p.name == "penumbra_lightSizeUV" || p.name == "penumbra_shadowDepthRange") &&
                            p.source == UniformSource::light && !p.compute.empty();
    CHECK(computed == 2);
    // the cost model: a blur tap is one bilinear footprint, the lookup one more after the G-buffer
    const CostModel cost = cost_model(layout, 64, 32);
    for (const PassCost& pass : cost.passes) {
        if (pass.name == "evsm_blur_x") CHECK(pass.texel_fetches == 512LL * 512 * 4 * 32);
        if (pass.name == "evsm_moments") CHECK(pass.texel_fetches == 512LL * 512);
        if (pass.name == "shading") CHECK(pass.texel_fetches == 64LL * 32 * (1 + 4));
    }
}

TEST_CASE("invalid evsm parameters are rejected with field, value and what is allowed") {
    auto first_error = [](EvsmParams e, int resolution = 1024) {
        const std::vector<ConfigError> errors =
            validate(Config{.technique = Technique::evsm, .shadow_map = {.resolution = resolution}, .evsm = e});
        return errors.empty() ? std::string() : errors.front().message;
    };
    CHECK(first_error({}).empty());
    CHECK(first_error({.positive_exponent = 43.0}) ==
          "evsm.positive_exponent: 43.0 is out of range; allowed: more than 0.0 to 42.0 (e^(2 c) must fit a 32-bit float)");
    CHECK(first_error({.negative_exponent = 0.0}) ==
          "evsm.negative_exponent: 0.0 is out of range; allowed: more than 0.0 to 42.0 (e^(2 c) must fit a 32-bit float)");
    CHECK(first_error({.light_bleeding_reduction = 1.0}) ==
          "evsm.light_bleeding_reduction: 1.0 is out of range; allowed: 0.0 to less than 1.0 (the Chebyshev bound cut "
          "off as shadow)");
    CHECK(first_error({.variance_bias = -1.0}) ==
          "evsm.variance_bias: -1.0 is out of range; allowed: 0.0 to 0.01 (of the depth range)");
    CHECK(first_error({.blur_fraction = 0.0}) ==
          "evsm.blur_fraction: 0.0 is out of range; allowed: more than 0.0 to 1.0 (of the widest penumbra)");
    CHECK(first_error({.blur_taps = 65, .max_blur_texels = 8}) ==
          "evsm.blur_taps: 65 is out of range (taps per blur pass); allowed: 1 to 64");
    CHECK(first_error({.blur_taps = 8, .max_blur_texels = 9}) ==
          "evsm.max_blur_texels: 9 texels leaves gaps of more than 2 texels between 8 blur taps; allowed: 1 to "
          "evsm.blur_taps (8), or raise evsm.blur_taps");
    CHECK(first_error({.blur_taps = 32, .max_blur_texels = 17}, 32) ==
          "evsm.max_blur_texels: 17 texels is a blur the 32-texel shadow map cannot hold; allowed: 1 to 16 (half the "
          "shadow-map resolution)");
    // a bad map size is named once, not again through the blur's clamp
    CHECK(validate(Config{.technique = Technique::evsm, .shadow_map = {.resolution = 100}}).size() == 1);
    // ES 3.0 guarantees 2048 texels: the map (and the moments) no larger
    CHECK(validate(Config{.technique = Technique::evsm, .target = Target::essl300, .shadow_map = {.resolution = 4096}})
              .front()
              .field == "shadow_map.resolution");
}
