// The ES 3.00 snippet stands alone: `#version 300 es` followed by penumbra_visibility.glsl and
// nothing else compiles (it declares its own default precisions). glslang, no GL.
#include <penumbra/penumbra.hpp>
#include <penumbra/validation.hpp>

#include <doctest/doctest.h>

#include <sstream>
#include <string>

using namespace penumbra;

namespace {

// Parses `text` as an ES fragment shader (compile only: the snippet has no main); the info log on failure.
std::string compile_fragment(const std::string& text) {
    detail::ensure_glslang_initialized();
    glslang::TShader shader(EShLangFragment);
    const char* source = text.c_str();
    shader.setStrings(&source, 1);
    shader.setEnvInput(glslang::EShSourceGlsl, EShLangFragment, glslang::EShClientNone, 0);
    shader.setEnvTarget(glslang::EShTargetNone, glslang::EShTargetLanguageVersion(0));
    if (shader.parse(GetDefaultResources(), 300, EEsProfile, false, false, EShMsgDefault)) return {};
    const std::string log = shader.getInfoLog();
    return log.empty() ? "compilation failed" : log;
}

std::string without_precision(const std::string& text) {
    std::istringstream in(text);
    std::string out, line;
    while (std::getline(in, line))
        if (!line.starts_with("precision ")) out += line + '\n';
    return out;
}

} // namespace

TEST_CASE("essl300 snippet: #version 300 es + penumbra_visibility.glsl alone compiles") {
    int configs = 0;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Light light : all_values<Light>()) {
                const Config config{.slices = 6, .resolution = 64, .filter = filter, .packing = packing,
                                    .light = light, .target = Target::essl300};
                if (!is_valid(config)) continue;
                ++configs;
                CAPTURE(to_string(filter));
                CAPTURE(to_string(packing));
                CAPTURE(to_string(light));
                const std::string snippet = emit_file(config, "penumbra_visibility.glsl").text;
                CHECK(snippet.find("precision highp float;") != std::string::npos);
                const std::string alone = compile_fragment("#version 300 es\n" + snippet);
                CHECK_MESSAGE(alone.empty(), alone);
                // the check can fail: without its precision statements ES rejects the same text
                CHECK_FALSE(compile_fragment("#version 300 es\n" + without_precision(snippet)).empty());
            }
    CHECK(configs >= 12);
}

// EVSM's ES snippet reads the moments through usampler2D (the bits of 32-bit floats), which has no
// default precision: the snippet declares it.
TEST_CASE("essl300 snippet of evsm: #version 300 es + penumbra_visibility.glsl alone compiles") {
    for (Light light : all_values<Light>()) {
        const Config config{.technique = Technique::evsm, .light = light, .target = Target::essl300,
                            .shadow_map = {.resolution = 256}};
        REQUIRE(is_valid(config));
        const std::string snippet = emit(config).value->snippet.text;
        const std::string alone = compile_fragment("#version 300 es\n" + snippet);
        CHECK_MESSAGE(alone.empty(), alone);
        CHECK_FALSE(compile_fragment("#version 300 es\n" + without_precision(snippet)).empty());
    }
}
