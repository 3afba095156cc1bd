// The WGSL target (detail/language.hpp): every module of the techniques that write WGSL has one entry
// point of its stage and nothing of GLSL; each `@binding(N) var NAME` in a module is the binding
// layout.json gives NAME (the texture at binding, its sampler at sampler_binding, a block at
// block_binding); the GLSL of the same configuration is unchanged by the target; the techniques that
// do not write WGSL are refused with a message naming those that do; the compile-time API emits it too.
// (Chromium's WGSL compiler checks the modules: ctest -R wgsl_matrix.)
#include <penumbra/penumbra.hpp>
#include <penumbra/static_glsl.hpp>

#include <doctest/doctest.h>

#include <algorithm>
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
    for (Technique technique : {Technique::shadowmap, Technique::pcf, Technique::pcss, Technique::erosion, Technique::evsm,
                                Technique::smrt, Technique::occlusion})
        for (Light light : {Light::rect, Light::sun})
            for (bool alpha : {false, true})
                out.push_back({.technique = technique, .light = light, .target = Target::wgsl, .alpha_test = alpha});
    // occlusion textures: Gaussian levels (the sun), every fusion, without the tangent clip, 32 slices
    for (Fusion fusion : all_values<Fusion>())
        out.push_back({.slices = 5, .resolution = 64, .filter = Filter::gaussian, .fusion = fusion, .light = Light::sun,
                       .tangent_clip = fusion == Fusion::chained, .target = Target::wgsl});
    out.push_back({.slices = 32, .resolution = 128, .self_shadow_fade = false, .level_reduction = -1, .target = Target::wgsl});
    // the mip chain as passes (WebGPU has no generateMipmap), with the extent fusion's second read
    out.push_back({.slices = 8, .resolution = 128, .filter = Filter::mipmap, .fusion = Fusion::extent, .target = Target::wgsl});
    // clustered fusion: the kernel's quadrants in the atlas level loop (two levels each) and through the lookup function
    out.push_back({.slices = 8, .resolution = 128, .fusion = Fusion::clustered, .target = Target::wgsl});
    out.push_back({.slices = 5, .resolution = 64, .filter = Filter::sat, .fusion = Fusion::clustered, .packing = Packing::array,
                   .target = Target::wgsl});
    // the array and volume packings: levels built in a scratch texture and copied into a layer / depth
    out.push_back({.slices = 8, .resolution = 128, .filter = Filter::mipmap, .packing = Packing::array, .target = Target::wgsl});
    out.push_back({.slices = 8, .resolution = 128, .packing = Packing::array, .target = Target::wgsl});
    // without the irradiance window (on by default: two passes of the slice loop, mixed by the irradiance),
    // the light weighed by area
    Config area{.slices = 8, .resolution = 128, .target = Target::wgsl};
    area.irradiance_window = false;
    out.push_back(area);
    // summed-area tables: RGBA32F rendered, read texel by texel and filtered by hand (WebGPU filters no 32-bit float)
    out.push_back({.slices = 8, .resolution = 128, .filter = Filter::sat, .target = Target::wgsl});
    out.push_back({.slices = 5, .resolution = 64, .filter = Filter::sat, .fusion = Fusion::extent, .packing = Packing::array,
                   .light = Light::sun, .target = Target::wgsl});
    // adaptive slice placement: the depth bins' mip chain as passes, the boundaries as float bits in R32UI
    out.push_back({.slices = 8, .resolution = 128, .slice_placement = SlicePlacement::adaptive, .target = Target::wgsl});
    out.push_back({.slices = 5, .resolution = 64, .filter = Filter::mipmap, .fusion = Fusion::extent,
                   .slice_placement = SlicePlacement::adaptive, .target = Target::wgsl, .alpha_test = true});
    out.push_back({.slices = 8, .resolution = 128, .filter = Filter::gaussian, .fusion = Fusion::extent, .packing = Packing::volume,
                   .light = Light::sun, .target = Target::wgsl});
    Config grid{.technique = Technique::pcf, .target = Target::wgsl};
    grid.pcf.pattern = TapPattern::grid;
    grid.pcf.rotate = false;
    grid.shadow_map.normal_offset = 0.0;
    out.push_back(grid);
    return out;
}

// The text without its comments: what the compiler reads.
std::string code_of(const std::string& text) {
    std::string code;
    for (std::size_t at = 0; at < text.size();) {
        const std::size_t comment = text.find("//", at), end = text.find('\n', at);
        const std::size_t stop = std::min(comment, end);
        code += text.substr(at, stop == std::string::npos ? std::string::npos : stop - at);
        if (end == std::string::npos) break;
        code += '\n';
        at = end + 1;
    }
    return code;
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
                CHECK_MESSAGE(!has(code_of(file.text), glsl), "GLSL left in WGSL: ", glsl);
            if (file.file_name == "penumbra_visibility.wgsl") {
                CHECK(count(file.text, "fn main(") == 0);
                CHECK(has(file.text, "fn penumbraVisibility(worldPos: vec3f) -> f32"));
                // (occlusion textures take the normal only with the tangent clip, as in GLSL)
                if (config.technique != Technique::occlusion || config.tangent_clip)
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
    CHECK(has(json, R"("webgpu": {"format": "depth32float", "usage": ["TEXTURE_BINDING", "RENDER_ATTACHMENT", "COPY_SRC"]})"));
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

TEST_CASE("wgsl: beyond four RGBA8 targets the scene is sliced in several passes, as WebGPU's defaults allow") {
    // 32 bytes a sample across the colour attachments, RGBA8 counting 8 (no logic op for bits either)
    for (int slices : {16, 32, 64, 128}) {
        CAPTURE(slices);
        const Config config{.slices = slices, .resolution = 64, .packing = slices == 128 ? Packing::array : Packing::atlas,
                            .target = Target::wgsl};
        const Result<Emission> result = emit(config);
        REQUIRE(result.errors.empty());
        std::vector<int> firsts;
        std::size_t written = 0;
        for (const PassDesc& pass : result.value->layout.passes) {
            if (pass.name != "slicing") continue;
            CHECK(pass.outputs.size() <= 4);
            written += pass.outputs.size();
            firsts.push_back(pass.int_uniforms.empty() ? 0 : pass.int_uniforms.at(0).second);
        }
        CHECK(written == static_cast<std::size_t>(slices / 4)); // every occlusion texture, once
        CHECK(static_cast<int>(firsts.size()) == (slices + 15) / 16);
        for (std::size_t g = 0; g < firsts.size(); ++g) CHECK(firsts[g] == static_cast<int>(4 * g));
        const std::string fragment = emit_file(config, "penumbra_slicing.frag.wgsl").text;
        CHECK(has(fragment, "penumbra_firstTexture") == (slices > 16));
        CHECK(count(fragment, "@location(") == 4 + 1); // four targets, the depth varying
    }
}

TEST_CASE("wgsl: the mipmap filter builds its chain with a pass a level, each reading the level below alone") {
    // WebGPU has no generateMipmap; GL keeps it
    const Config config{.slices = 8, .resolution = 128, .filter = Filter::mipmap, .target = Target::wgsl};
    const Result<Emission> result = emit(config);
    REQUIRE(result.errors.empty());
    const Layout& layout = result.value->layout;
    std::vector<const PassDesc*> chain;
    for (const PassDesc& pass : layout.passes) {
        CHECK(pass.action != PassAction::generate_mipmap);
        if (pass.program == "mip_level") chain.push_back(&pass);
    }
    const int levels = layout.textures[1].mip_levels; // penumbra_slices, then the atlas
    REQUIRE(layout.textures[1].name == "penumbra_occlusionAtlas");
    REQUIRE(static_cast<int>(chain.size()) == levels - 1);
    for (int l = 1; l < levels; ++l) {
        const PassDesc& pass = *chain[static_cast<std::size_t>(l - 1)];
        CAPTURE(l);
        REQUIRE(pass.inputs.size() == 1);
        CHECK(pass.inputs[0].texture == "penumbra_occlusionAtlas");
        CHECK(pass.inputs[0].level == l - 1);
        REQUIRE(pass.outputs.size() == 1);
        CHECK(pass.outputs[0].level == l);
        CHECK(pass.viewport_width == (2 * 128) >> l);
        CHECK(pass.viewport_height == 128 >> l);
    }
    const std::string mip = emit_file(config, "penumbra_mip_level.frag.wgsl").text;
    CHECK(has(mip, "0.25 * (textureLoad(penumbra_source, base, 0) + textureLoad(penumbra_source, base + vec2i(1, 0), 0)"));
    CHECK(has(emit_file(config, "penumbra_visibility.wgsl").text,
              "textureSampleLevel(penumbra_occlusionAtlas, penumbra_occlusionAtlas_sampler, vec2((tile + kernel.x) * 0.5, kernel.y), kernel.w)"));
    Config gl = config;
    gl.target = Target::glsl450;
    const Result<Emission> gl_result = emit(gl);
    REQUIRE(gl_result.errors.empty());
    bool generates = false;
    for (const PassDesc& pass : gl_result.value->layout.passes) generates = generates || pass.action == PassAction::generate_mipmap;
    CHECK(generates);
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
    const Config oim{.technique = Technique::oim, .target = Target::wgsl};
    const std::vector<ConfigError> errors = validate(oim);
    REQUIRE(errors.size() == 1);
    CHECK(errors[0].field == "target");
    CHECK(errors[0].message == "target: wgsl is not written for technique 'oim' yet; allowed with target wgsl: technique "
                               "occlusion, shadowmap, pcf, pcss, erosion, evsm, smrt; other targets: glsl330, glsl450, essl300, vulkan");
}

TEST_CASE("wgsl: occlusion textures refuse what WebGPU or the WGSL emitters do not have, saying why") {
    struct Case {
        Config config;
        std::string field, message;
    };
    const std::vector<Case> cases{
    };
    for (const Case& c : cases) {
        CAPTURE(c.message);
        bool found = false;
        for (const ConfigError& e : validate(c.config)) found = found || (e.field == c.field && e.message.find(c.message) != std::string::npos);
        CHECK(found);
    }
}

TEST_CASE("wgsl: the GLSL of a configuration is the same whatever the WGSL path does") {
    // The language layer must leave GLSL alone: the vulkan text keeps GLSL's main and bindings.
    for (Config config : wgsl_configs()) {
        config.target = Target::vulkan;
        if (!is_valid(config)) continue; // 32 slices: more render targets than Vulkan guarantees
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
