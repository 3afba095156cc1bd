// The WGSL target (detail/language.hpp): every module of the techniques that write WGSL has one entry
// point of its stage and nothing of GLSL; each `@binding(N) var NAME` in a module is the binding
// layout.json gives NAME (the texture at binding, its sampler at sampler_binding, a block at
// block_binding); the GLSL of the same configuration is unchanged by the target; the techniques that
// do not write WGSL are refused with a message naming those that do; the compile-time API emits it too.
// (Chromium's WGSL compiler checks the modules: ctest -R wgsl_matrix.)
#include <penumbra/penumbra.hpp>
#include <penumbra/static_glsl.hpp>

#include <doctest/doctest.h>

#include <map>
#include <regex>
#include <string>
#include <vector>

using namespace penumbra;

namespace {

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
    return n;
}

// The configurations of every technique that writes WGSL, both lights, with and without cut-out casters.
std::vector<Config> wgsl_configs() {
    std::vector<Config> out;
    for (Technique technique : {Technique::shadowmap, Technique::pcf, Technique::pcss, Technique::erosion, Technique::evsm})
        for (Light light : {Light::rect, Light::sun})
            for (bool alpha : {false, true})
                out.push_back({.technique = technique, .light = light, .target = Target::wgsl, .alpha_test = alpha});
    Config grid{.technique = Technique::pcf, .target = Target::wgsl};
    grid.pcf.pattern = TapPattern::grid;
    grid.pcf.rotate = false;
    grid.shadow_map.normal_offset = 0.0;
    out.push_back(grid);
    return out;
}

std::string label(const Config& c) {
    return std::string(to_string(c.technique)) + " " + std::string(to_string(c.light)) + (c.alpha_test ? " alpha" : "");
}

} // namespace

TEST_CASE("wgsl: every module is WGSL, with one entry point of its stage") {
    for (const Config& config : wgsl_configs()) {
        CAPTURE(label(config));
        const Result<Emission> result = emit(config);
        REQUIRE(result.errors.empty());
        for (const ShaderFile& file : result.value->files()) {
            CAPTURE(file.file_name);
            CHECK(file.file_name.ends_with(".wgsl"));
            for (const std::string glsl : {"#version", "layout(", "gl_", "\nuniform ", "texelFetch", "textureLod", "texture(",
                                     "inversesqrt", "dFdx", "void ", "precision highp", "floatBitsToUint", "uintBitsToFloat",
                                     " ? "})
                CHECK_MESSAGE(!has(file.text, glsl), "GLSL left in WGSL: ", glsl);
            if (file.file_name == "penumbra_visibility.wgsl") {
                CHECK(count(file.text, "fn main(") == 0);
                CHECK(has(file.text, "fn penumbraVisibility(worldPos: vec3f) -> f32"));
                CHECK(has(file.text, "fn penumbraVisibilityWithNormal(worldPos: vec3f, worldNormal: vec3f) -> f32"));
                continue;
            }
            CHECK(count(file.text, "fn main(") == 1);
            CHECK(count(file.text, "fn penumbra_main()") == 1);
            CHECK(count(file.text, file.stage == Stage::vertex ? "@vertex\n" : "@fragment\n") == 1);
        }
    }
}

TEST_CASE("wgsl: each module's bindings are the ones layout.json gives") {
    const std::regex declaration(R"(@group\((\d+)\) @binding\((\d+)\) var(<uniform>)? (\w+))");
    for (const Config& config : wgsl_configs()) {
        CAPTURE(label(config));
        const Result<Emission> result = emit(config);
        REQUIRE(result.errors.empty());
        const Emission& emission = *result.value;
        for (std::size_t p = 0; p < emission.programs.size(); ++p) {
            const ProgramDesc& desc = emission.layout.programs[p];
            CAPTURE(desc.name);
            // what layout.json says each binding holds: the block's buffer, a texture, or its sampler
            std::map<int, std::string> expected;
            for (const ParamDesc& param : desc.parameters) {
                CHECK(param.set == 0);
                if (param.binding >= 0) {
                    expected[param.binding] = param.name;
                    if (param.sampler_binding >= 0) expected[param.sampler_binding] = param.name + "_sampler";
                    CHECK(!param.texture_type.empty());
                } else {
                    REQUIRE(param.block_binding >= 0);
                    expected[param.block_binding] = "penumbra" + param.block.substr(8) + "Block";
                }
            }
            std::map<int, std::string> declared;
            for (const ShaderFile& stage : emission.programs[p].stages)
                for (auto it = std::sregex_iterator(stage.text.begin(), stage.text.end(), declaration);
                     it != std::sregex_iterator(); ++it) {
                    const int binding = std::stoi((*it)[2]);
                    CHECK((*it)[1] == "0");
                    // one binding, one name, whichever stage declares it
                    if (declared.count(binding)) CHECK(declared[binding] == (*it)[4].str());
                    declared[binding] = (*it)[4];
                }
            for (const auto& [binding, name] : declared) {
                CAPTURE(binding);
                CHECK(expected[binding] == name);
            }
            // and nothing layout.json binds is missing from the modules
            for (const auto& [binding, name] : expected) CHECK_MESSAGE(declared.count(binding) == 1, name);
        }
    }
}

TEST_CASE("wgsl: layout.json names WebGPU's formats, usages and binding types") {
    Config pcss{.technique = Technique::pcss, .target = Target::wgsl};
    const Result<Emission> result = emit(pcss);
    REQUIRE(result.errors.empty());
    const std::string json = to_json(result.value->layout);
    CHECK(has(json, R"("name": "penumbra_shadowMap")"));
    CHECK(has(json, R"("webgpu": {"format": "depth32float", "usage": ["TEXTURE_BINDING", "RENDER_ATTACHMENT"]})"));
    CHECK(has(json, R"("webgpu": {"format": "rgba32float", "usage": ["TEXTURE_BINDING", "COPY_DST"]})"));
    CHECK(has(json, R"("webgpu": {"format": "r32float", "usage": ["TEXTURE_BINDING", "RENDER_ATTACHMENT", "COPY_SRC"]})"));
    // the depth comparison and the blocker search's plain read of the same depth texture
    CHECK(has(json, R"("texture_type": "texture_depth_2d", "sample_type": "depth", "sampler_binding": 4, "sampler_type": "comparison")"));
    CHECK(has(json, R"("texture_type": "texture_depth_2d", "sample_type": "depth", "sampler_binding": 2, "sampler_type": "non-filtering")"));
    // the G-buffer is loaded texel by texel: no sampler
    CHECK(has(json, R"("texture_type": "texture_2d<f32>", "sample_type": "unfilterable-float", "sampler_binding": -1)"));
    CHECK(has(json, R"("group": 0)"));
    CHECK(!has(json, R"("set": )"));
    // the GLSL targets' layout.json is without them
    pcss.target = Target::vulkan;
    const std::string vulkan = to_json(emit(pcss).value->layout);
    CHECK(!has(vulkan, "webgpu"));
    CHECK(!has(vulkan, "sampler_binding"));
}

TEST_CASE("wgsl: EVSM stores the moments as RGBA32UI float bits and filters them by hand, as on ES") {
    const Config evsm{.technique = Technique::evsm, .target = Target::wgsl};
    const Result<Emission> result = emit(evsm);
    REQUIRE(result.errors.empty());
    const std::string deferred = emit_file(evsm, "penumbra_deferred.frag.wgsl").text;
    CHECK(has(deferred, "var penumbra_evsmMoments: texture_2d<u32>;"));
    CHECK(has(deferred, "bitcast<vec4f>(textureLoad(moments, clamp(texel, vec2i(0), vec2i(1023)), 0))"));
    CHECK(has(emit_file(evsm, "penumbra_evsm_moments.frag.wgsl").text, "penumbra_out = bitcast<vec4u>("));
}

TEST_CASE("wgsl: the techniques without WGSL are refused, naming those with it") {
    for (Technique technique : {Technique::occlusion, Technique::oim}) {
        const Config config{.technique = technique, .target = Target::wgsl};
        const std::vector<ConfigError> errors = validate(config);
        REQUIRE(errors.size() == 1);
        CHECK(errors[0].field == "target");
        CHECK(errors[0].message == "target: wgsl is not written for technique '" + std::string(to_string(technique)) +
                                       "' yet; allowed with target wgsl: technique shadowmap, pcf, pcss, erosion, evsm; "
                                       "other targets: glsl330, glsl450, essl300, vulkan");
    }
}

TEST_CASE("wgsl: the GLSL of a configuration is the same whatever the WGSL path does") {
    // The language layer must leave GLSL alone: the vulkan text keeps GLSL's main and bindings.
    for (Config config : wgsl_configs()) {
        config.target = Target::vulkan;
        CAPTURE(label(config));
        const Result<Emission> result = emit(config);
        REQUIRE(result.errors.empty());
        for (const ShaderFile& file : result.value->files()) {
            CHECK(!file.file_name.ends_with(".wgsl"));
            CHECK(!has(file.text, "var<private>"));
            CHECK(!has(file.text, "fn "));
        }
    }
}

namespace {
constexpr Config kWgslPcss{.technique = Technique::pcss, .target = Target::wgsl};
constexpr Config kWgslEvsm{.technique = Technique::evsm, .target = Target::wgsl};
} // namespace

TEST_CASE("wgsl: the compile-time API emits the same WGSL as the run-time one") {
    CHECK(static_glsl<kWgslPcss, "penumbra_deferred.frag.wgsl"> == emit_file(kWgslPcss, "penumbra_deferred.frag.wgsl").text);
    CHECK(static_glsl<kWgslPcss, "penumbra_visibility.wgsl"> == emit_file(kWgslPcss, "penumbra_visibility.wgsl").text);
    CHECK(static_glsl<kWgslEvsm, "penumbra_evsm_blur_y.frag.wgsl"> ==
          emit_file(kWgslEvsm, "penumbra_evsm_blur_y.frag.wgsl").text);
}
