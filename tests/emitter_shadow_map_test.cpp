// Emitted text of the shadow map techniques (shadowmap, pcf, pcss): tap counts as configured, the
// tap loops unrolled, constants baked in, validation messages, technique fields independent of
// each other, compile time = run time, layout. No glslang, no GL.
#include <penumbra/penumbra.hpp>
#include <penumbra/static_glsl.hpp>
#include <penumbra/texture_memory.hpp>
#include <penumbra/uniform_values.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <regex>

using namespace penumbra;

namespace {

int count(std::string_view text, std::string_view needle) {
    int n = 0;
    for (std::size_t at = text.find(needle); at != std::string_view::npos; at = text.find(needle, at + 1)) ++n;
    return n;
}

std::string snippet_of(const Config& config) { return emit_file(config, "penumbra_visibility.glsl").text; }

// Blocker / filter settings of shipping engines: Bevy, Filament, three.js example, Godot ultra, PlayCanvas high.
constexpr std::pair<int, int> engine_pcss[] = {{8, 8}, {16, 16}, {17, 34}, {32, 32}, {32, 64}};

std::vector<Config> shadow_configs() {
    std::vector<Config> configs;
    for (Light light : all_values<Light>()) {
        configs.push_back({.technique = Technique::shadowmap, .light = light});
        for (int n : {1, 3, 4, 16})
            for (bool rotate : {false, true})
                configs.push_back({.technique = Technique::pcf, .light = light,
                                   .pcf = {.pattern = TapPattern::grid, .grid_size = n, .rotate = rotate}});
        for (int k : {1, 5, 16, 64})
            configs.push_back({.technique = Technique::pcf, .light = light,
                               .pcf = {.pattern = TapPattern::poisson, .poisson_taps = k}});
        for (auto [blockers, filters] : engine_pcss)
            for (bool rotate : {false, true})
                configs.push_back({.technique = Technique::pcss, .light = light,
                                   .pcss = {.blocker_samples = blockers, .filter_samples = filters, .rotate = rotate}});
    }
    return configs;
}

int expected_comparison_taps(const Config& c) {
    if (c.technique == Technique::pcf) return pcf_taps(c.pcf);
    if (c.technique == Technique::pcss) return c.pcss.filter_samples;
    return 1;
}

int tap_group_size(const Config& c) {
    return c.technique == Technique::pcf && c.pcf.pattern == TapPattern::grid ? c.pcf.grid_size : 4;
}

} // namespace

TEST_CASE("shadow map techniques: the text holds exactly the configured taps, unrolled, one comment per group") {
    for (const Config& config : shadow_configs()) {
        CAPTURE(std::string(detail::describe(config).view()));
        REQUIRE(is_valid(config));
        const std::string snippet = snippet_of(config);
        CHECK(count(snippet, "textureLod(penumbra_shadowMap,") == expected_comparison_taps(config));
        const int blockers = config.technique == Technique::pcss ? config.pcss.blocker_samples : 0;
        CHECK(count(snippet, "textureLod(penumbra_shadowDepth,") == blockers);
        // no loop statement anywhere in a shadow map technique's text
        for (const ShaderFile& file : emit(config).value->files()) {
            CHECK(!std::regex_search(file.text, std::regex(R"(\b(for|while|do)\s*[({])")));
        }
        const int taps = expected_comparison_taps(config), group = tap_group_size(config);
        if (config.technique == Technique::pcf && config.pcf.pattern == TapPattern::grid)
            CHECK(count(snippet, "// grid row, taps ") == (taps + group - 1) / group);
        if (config.technique == Technique::pcf && config.pcf.pattern == TapPattern::poisson)
            CHECK(count(snippet, "\n    // taps ") == (taps + 3) / 4);
        if (config.technique == Technique::pcss) {
            CHECK(count(snippet, "// filter taps ") == (taps + 3) / 4);
            CHECK(count(snippet, "// blocker taps ") == (blockers + 3) / 4);
            CHECK(snippet.find("w_p = (d_receiver - d_blocker) * w_light / d_blocker") != std::string::npos);
        }
        // the weight of each comparison tap is baked: 1/N
        if (taps > 1)
            CHECK(snippet.find(std::string("return penumbra_lit * ") +
                               std::string(detail::format_float(1.0 / taps).view()) + ";") != std::string::npos);
        CHECK(snippet.find("float penumbraVisibility(vec3 worldPos)") != std::string::npos);
        CHECK(count(snippet, "penumbra_rotation(worldPos)") == (detail::rotates(config) ? 1 : 0));
    }
}

TEST_CASE("shadow map techniques bake their constants: bias, radius, clamp") {
    const Config pcf{.technique = Technique::pcf,
                     .shadow_map = {.resolution = 512, .constant_bias = 0.125, .slope_bias = 2.5},
                     .pcf = {.pattern = TapPattern::grid, .grid_size = 2, .radius = 0.375, .rotate = false}};
    const std::string depth = emit_file(pcf, "penumbra_shadow_depth.frag").text;
    CHECK(depth.find("float biased = penumbra_depth + 0.125 + 2.5 * slope;") != std::string::npos);
    const std::string snippet = snippet_of(pcf);
    CHECK(snippet.find("float radius = min(0.375 * penumbra_uvPerUnit(coord.w), 0.5);") != std::string::npos);
    // a 2 x 2 grid at (+-0.5, +-0.5) of the radius
    CHECK(snippet.find("coord.xy + vec2(-0.5, -0.5) * radius") != std::string::npos);
    CHECK(snippet.find("coord.xy + vec2(0.5, 0.5) * radius") != std::string::npos);
    const Config pcss{.technique = Technique::pcss, .shadow_map = {.resolution = 2048},
                      .pcss = {.max_filter_texels = 32}};
    CHECK(snippet_of(pcss).find("vec2(0.015625));") != std::string::npos); // 32 / 2048
}

TEST_CASE("receiver-plane depth bias: every pcf and pcss tap compares against the tangent plane, only with it on") {
    for (Config config : shadow_configs()) {
        for (bool tilt : {true, false}) {
            config.shadow_map.receiver_plane_bias = tilt;
            CAPTURE(std::string(detail::describe(config).view()));
            const std::string snippet = snippet_of(config);
            const bool tilts = tilt && config.technique != Technique::shadowmap;
            CHECK(tilts_taps_to_receiver_plane(config) == tilts);
            // each comparison tap and each blocker tap adds the plane's rise over its literal offset
            const int taps = tilts ? expected_comparison_taps(config) : 0;
            const int blockers = tilts && config.technique == Technique::pcss ? config.pcss.blocker_samples : 0;
            CHECK(count(snippet, ", coord.z + dot(vec2(") == taps);
            CHECK(count(snippet, "float(d < coord.z + dot(vec2(") == blockers);
            CHECK(count(snippet, "vec2 depthSlope = ") == (tilts ? 1 : 0));
            CHECK(count(snippet, "penumbra_filteredVisibility(worldPos, vec2(0.0))") == (tilts ? 1 : 0));
            // the normal is then read (as for the normal offset): the deferred pass samples penumbra_worldNormals
            for (double offset : {0.0, 1.0}) {
                Config c = config;
                c.shadow_map.normal_offset = offset;
                const bool normal = tilts || offset > 0.0;
                CHECK(reads_receiver_normal(c) == normal);
                const std::string deferred = emit_file(c, "penumbra_deferred.frag").text;
                CHECK((deferred.find("penumbra_worldNormals") != std::string::npos) == normal);
            }
        }
    }
}

TEST_CASE("Poisson patterns: deterministic, in the unit disk, spread out, the same prefix for every count") {
    const std::vector<detail::Tap> taps = detail::poisson_disk(64);
    REQUIRE(taps.size() == 64);
    double nearest = 1e9;
    for (std::size_t i = 0; i < taps.size(); ++i) {
        CHECK(taps[i].x * taps[i].x + taps[i].y * taps[i].y <= 1.0 + 1e-9);
        for (std::size_t j = 0; j < i; ++j)
            nearest = std::min(nearest, std::hypot(taps[i].x - taps[j].x, taps[i].y - taps[j].y));
    }
    // best-candidate with 16 candidates keeps points apart: far above uniform random (which would be ~0.02)
    CHECK(nearest > 0.1);
    const std::vector<detail::Tap> sixteen = detail::poisson_disk(16);
    for (std::size_t i = 0; i < sixteen.size(); ++i) {
        CHECK(sixteen[i].x == taps[i].x);
        CHECK(sixteen[i].y == taps[i].y);
    }
    static_assert(detail::poisson_disk(8).size() == 8); // usable in constant expressions
}

TEST_CASE("each technique reads only its own fields") {
    // occlusion-only fields do not change a shadow map technique's programs
    for (Technique t : {Technique::shadowmap, Technique::pcf, Technique::pcss}) {
        CAPTURE(to_string(t));
        const Emission a = *emit(Config{.technique = t}).value;
        const Emission b = *emit(Config{.technique = t, .slices = 3, .resolution = 64, .filter = Filter::sat,
                                        .fusion = Fusion::maximum, .packing = Packing::array, .leak_fix = false})
                                .value;
        CHECK(a.programs == b.programs);
        CHECK(a.snippet == b.snippet);
        // an occlusion field that would be invalid does not make a shadow map configuration invalid
        CHECK(is_valid(Config{.technique = t, .slices = 40}));
    }
    // shadow map fields do not change occlusion textures
    const Emission occlusion = *emit(Config{}).value;
    const Emission other = *emit(Config{.shadow_map = {.resolution = 64}, .pcf = {.grid_size = 9},
                                        .pcss = {.blocker_samples = 3}})
                                .value;
    CHECK(occlusion.programs == other.programs);
    CHECK(occlusion.snippet == other.snippet);
    // pcf fields do not change pcss, and the other way round
    CHECK(emit(Config{.technique = Technique::pcss}).value->programs ==
          emit(Config{.technique = Technique::pcss, .pcf = {.poisson_taps = 3}}).value->programs);
    CHECK(emit(Config{.technique = Technique::pcf}).value->programs ==
          emit(Config{.technique = Technique::pcf, .pcss = {.filter_samples = 3}}).value->programs);
}

TEST_CASE("invalid shadow map configurations: each names the field, the value and what is allowed") {
    auto first_message = [](const Config& c) {
        const std::vector<ConfigError> errors = validate(c);
        REQUIRE(!errors.empty());
        return errors.front().message;
    };
    CHECK(first_message(Config{.technique = Technique::pcss, .pcss = {.blocker_samples = 0}}) ==
          "pcss.blocker_samples: 0 is out of range; allowed: 1 to 64");
    CHECK(first_message(Config{.technique = Technique::pcss, .pcss = {.filter_samples = 0}}) ==
          "pcss.filter_samples: 0 is out of range; allowed: 1 to 128");
    CHECK(first_message(Config{.technique = Technique::pcf, .pcf = {.poisson_taps = 0}}) ==
          "pcf.poisson_taps: 0 is out of range; allowed: 1 to 64");
    CHECK(first_message(Config{.technique = Technique::pcf, .pcf = {.pattern = TapPattern::grid, .grid_size = 17}}) ==
          "pcf.grid_size: 17 is out of range (N gives N x N taps); allowed: 1 to 16");
    CHECK(first_message(Config{.technique = Technique::pcss, .shadow_map = {.resolution = 256},
                               .pcss = {.max_filter_texels = 200}}) ==
          "pcss.max_filter_texels: 200 is a kernel the 256-texel shadow map cannot hold; allowed: 1 to 128 (half the "
          "shadow-map resolution)");
    CHECK(first_message(Config{.technique = Technique::shadowmap, .shadow_map = {.resolution = 1000}}) ==
          "shadow_map.resolution: 1000 is not allowed; allowed: a power of two from 32 to 8192 (32, 64, 128, 256, "
          "512, 1024, 2048, 4096, 8192)");
    CHECK(first_message(Config{.technique = Technique::pcf, .target = Target::glsl330,
                               .shadow_map = {.resolution = 2048}}) ==
          "shadow_map.resolution: 2048 is larger than target 'glsl330' guarantees; allowed: a power of two from 32 to "
          "1024");
    CHECK(first_message(Config{.technique = Technique::pcf, .shadow_map = {.constant_bias = -0.5}}) ==
          "shadow_map.constant_bias: -0.5 is out of range; allowed: 0.0 to 10.0 scene units");
    CHECK(first_message(Config{.technique = Technique::pcf, .pcf = {.radius = 0.0}}) ==
          "pcf.radius: 0.0 is out of range; allowed: more than 0.0 to 1000.0 scene units");
    CHECK(first_message(Config{.technique = Technique::pcf, .pcf = {.radius = std::nan("")}}) ==
          "pcf.radius: nan is out of range; allowed: more than 0.0 to 1000.0 scene units");
    CHECK(first_message(Config{.technique = static_cast<Technique>(9)}) ==
          "technique: 9 is not a known value; allowed: occlusion, shadowmap, pcf, pcss, oim, erosion, evsm, smrt");
    CHECK(first_message(Config{.technique = Technique::pcf, .pcf = {.pattern = static_cast<TapPattern>(5)}}) ==
          "pcf.pattern: 5 is not a known value; allowed: grid, poisson");
    // every engine setting is valid
    for (auto [blockers, filters] : engine_pcss)
        CHECK(is_valid(Config{.technique = Technique::pcss,
                              .pcss = {.blocker_samples = blockers, .filter_samples = filters}}));
}

namespace {
constexpr Config kPcss{.technique = Technique::pcss, .light = Light::sun,
                       .pcss = {.blocker_samples = 17, .filter_samples = 34}};
constexpr Config kPcf{.technique = Technique::pcf, .target = Target::vulkan,
                      .pcf = {.pattern = TapPattern::grid, .grid_size = 3}};
} // namespace

TEST_CASE("shadow map techniques at compile time equal run time") {
    CHECK(static_glsl<kPcss, "penumbra_visibility.glsl"> == emit_file(kPcss, "penumbra_visibility.glsl").text);
    CHECK(static_glsl<kPcss, "penumbra_shadow_depth.frag"> == emit_file(kPcss, "penumbra_shadow_depth.frag").text);
    CHECK(static_glsl<kPcf, "penumbra_deferred.frag"> == emit_file(kPcf, "penumbra_deferred.frag").text);
}

TEST_CASE("shadow map layouts: a depth pass, the shading programs, every referenced texture exists") {
    for (const Config& config : shadow_configs()) {
        const Layout layout = describe_layout(config);
        REQUIRE(layout.programs.size() == 3);
        CHECK(layout.programs[0].name == "shadow_depth");
        CHECK(layout.programs[1].name == "shading_example");
        CHECK(layout.programs[2].name == "shading_deferred");
        CHECK(layout.passes.front().name == "shadow_depth");
        auto has_texture = [&](const std::string& name) {
            for (const TextureDesc& t : layout.textures)
                if (t.name == name) return true;
            return false;
        };
        for (const ProgramDesc& p : layout.programs)
            for (const ParamDesc& param : p.parameters)
                if (param.binding >= 0 && param.texture != "penumbra_worldPositions") CHECK(has_texture(param.texture));
        CHECK(layout.textures.front().format == TextureFormat::depth32f);
        CHECK(layout.textures.front().width == config.shadow_map.resolution);
        const std::string json = to_json(layout);
        CHECK(json.find("\"technique\": \"" + std::string(to_string(config.technique)) + "\"") != std::string::npos);
    }
}

TEST_CASE("texture memory of a layout: formats, mip chains, arrays") {
    // shadow map 1024², 32-bit depth: 4 MiB; PCSS reads the same map through two samplers, no copy
    CHECK(texture_bytes(describe_layout(Config{.technique = Technique::pcf})) == 4ll * 1024 * 1024);
    CHECK(texture_bytes(describe_layout(Config{.technique = Technique::pcss, .shadow_map = {.resolution = 512}})) ==
          4ll * 512 * 512);
    // occlusion, mipmap atlas: T·R × R RGBA8 with a full chain
    const Config mip{.slices = 4, .resolution = 64, .filter = Filter::mipmap};
    long long expected = 64ll * 64 * 4; // the slices array: one RGBA8 layer
    for (int w = 64, h = 64;; w = std::max(w / 2, 1), h = std::max(h / 2, 1)) {
        expected += 4ll * w * h;
        if (w == 1 && h == 1) break;
    }
    CHECK(texture_bytes(describe_layout(mip)) == expected);
    CHECK(bytes_per_texel(TextureFormat::rgba16f) == 8);
    CHECK(parse_enum<TextureFormat>("RGBA16F") == TextureFormat::rgba16f);
    CHECK_FALSE(parse_enum<TextureFormat>("no such format"));
}

TEST_CASE("shadow map layouts in the layout vocabulary: phases, depth attachment, compare, uniform sources") {
    for (const Config& config : shadow_configs()) {
        CAPTURE(std::string(detail::describe(config).view()));
        const Layout layout = describe_layout(config);
        CHECK(to_json(layout).find("\"technique\": \"" + std::string(to_string(config.technique))) != std::string::npos);
        const PassDesc& depth = layout.passes.front();
        CHECK(depth.phase == Phase::shadow);
        CHECK(depth.action == PassAction::draw_scene);
        REQUIRE(depth.outputs.size() == 1);
        CHECK(attachment_kind(layout, depth.outputs[0]) == AttachmentKind::depth);
        CHECK(depth.state.depth_test);
        CHECK(depth.state.depth_write);
        CHECK(depth.state.clear_depth == 1.0f);
        // one depth texture: the filter compares through its sampler, the blocker search reads it plain
        for (const TextureDesc& t : layout.textures) CHECK(t.name != "penumbra_shadowDepth");
        for (const PassDesc& pass : layout.passes) {
            CHECK(pass.action != PassAction::copy);
            for (const BindingDesc& in : pass.inputs) {
                if (in.sampler == "penumbra_shadowMap") CHECK(in.sampling.compare == CompareFunc::lequal);
                if (in.sampler == "penumbra_shadowDepth") {
                    CHECK(in.texture == "penumbra_shadowMap");
                    CHECK_FALSE(in.sampling.compare);
                    CHECK(in.sampling.min_filter == TextureFilter::nearest);
                }
            }
        }
        int screen = 0, example = 0, shadow = 0;
        for (const PassDesc& pass : layout.passes) {
            screen += pass.phase == Phase::screen;
            example += pass.phase == Phase::example;
            shadow += pass.phase == Phase::shadow;
        }
        CHECK(screen == 1);
        CHECK(example == 1);
        CHECK(shadow == 1);
        // every plain uniform has a value in the table, or is set by the pass
        for (const ProgramDesc& program : layout.programs)
            for (const ParamDesc& p : program.parameters) {
                CAPTURE(p.name);
                if (p.binding >= 0) continue;
                if (p.source == UniformSource::light || p.source == UniformSource::camera) CHECK(has_uniform_rule(p.name));
            }
    }
    // the table's shadow values come from shadow_frame
    RectLight light;
    const ShadowFrame shadow = shadow_frame(light, {-1, 0, -1}, {1, 1, 1});
    const UniformInputs in{slice_frame(light, {-1, 0, -1}, {1, 1, 1}, 4), Light::rect, std::nullopt, shadow};
    CHECK(std::get<glm::vec2>(*uniform_value("penumbra_shadowDepthRange", in)) == shadow.depth_range);
    CHECK(std::get<float>(*uniform_value("penumbra_shadowTanHalfFov", in)) == shadow.tan_half_fov);
    CHECK(std::get<glm::vec2>(*uniform_value("penumbra_lightSizeUV", in)) == shadow.light_size_uv);
    CHECK(std::get<glm::mat4>(*uniform_value("penumbra_lightFromWorld", in)) == shadow.light_from_world);
}
