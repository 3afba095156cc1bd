// The generic reference program (penumbra/generic.hpp) as text: real loops over uniforms, no
// baked constants, one text for every slice count, resolution, fusion rule and fade setting.
// No glslang, no GL.

#include <penumbra/generic.hpp>
#include <penumbra/penumbra.hpp>

#include <doctest/doctest.h>

#include <map>
#include <regex>
#include <set>

using namespace penumbra;

namespace {

int count(std::string_view text, std::string_view needle) {
    int n = 0;
    for (std::size_t at = text.find(needle); at != std::string_view::npos; at = text.find(needle, at + 1)) ++n;
    return n;
}

std::string generic_fragment(const Config& config) {
    const Result<GenericShading> result = emit_generic(config);
    REQUIRE(result.value);
    return result.value->program.stages.at(1).text;
}

std::string specialized_snippet(const Config& config) { return emit_file(config, "penumbra_visibility.glsl").text; }

// One configuration per filter × packing × light that validates.
// The targets of the generic reference, a GLSL program (emit_generic refuses wgsl and hlsl).
std::vector<Target> glsl_targets() {
    std::vector<Target> targets;
    for (Target target : all_values<Target>())
        if (target != Target::wgsl && target != Target::hlsl) targets.push_back(target);
    return targets;
}

std::vector<Config> storages(Target target = Target::glsl450) {
    std::vector<Config> configs;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Light light : all_values<Light>()) {
                const Config c{.slices = 16, .resolution = 256, .filter = filter, .packing = packing, .light = light,
                               .target = target};
                if (is_valid(c)) configs.push_back(c);
            }
    return configs;
}

// Variations the generic program must not depend on.
std::vector<Config> variations_of(const Config& base) {
    std::vector<Config> out;
    for (int slices : {1, 4, 5, 16, 32})
        for (int resolution : {32, 256, 1024})
            for (Fusion fusion : all_values<Fusion>())
                for (bool fade : {true, false}) {
                    Config c = base;
                    c.slices = slices;
                    c.resolution = resolution;
                    c.fusion = fusion;
                    c.self_shadow_fade = fade;
                    c.leak_fix = !fade;
                    if (is_valid(c)) out.push_back(c);
                }
    return out;
}

} // namespace

TEST_CASE("generic: real loops over uniform bounds, channels by index, nothing unrolled") {
    for (const Config& config : storages()) {
        CAPTURE(to_string(config.filter));
        CAPTURE(to_string(config.packing));
        CAPTURE(to_string(config.light));
        const std::string text = generic_fragment(config);
        const bool level_loop = config.packing == Packing::atlas &&
                                (config.filter == Filter::nbuffer || config.filter == Filter::gaussian);
        if (level_loop) {
            // paper Algorithm 2: a `for` over the levels, each with one walk over the slices
            CHECK(count(text, "for (int level = 0; level <= penumbra_maxLevel; ++level)") == 1);
            CHECK(count(text, "while (") == 1);
            CHECK(count(text, "penumbra_levelAtlases[index]") == 1); // one sampler array, indexed by the level
        } else {
            CHECK(count(text, "for (int s = penumbra_sliceCount - 1; s >= 0; --s)") == 1);
            CHECK(count(text, "while (") == 0);
        }
        // and the irradiance window's loop over its two windows, where it weighs the light
        CHECK(count(text, "for (") == (weighs_irradiance(config) ? 2 : 1));
        // the channel is an index, not a rotated one-hot vector
        CHECK(std::regex_search(text, std::regex(R"(\)\[s % 4\];|texel\[s % 4\];)")));
        CHECK(text.find("yzwx") == std::string::npos);
        CHECK(text.find(", penumbra_i)") == std::string::npos);
        // no labelled unrolled iteration
        CHECK(text.find("// slice ") == std::string::npos);
        CHECK(text.find("// level ") == std::string::npos);
        // every configuration value is a uniform the program declares
        for (const GenericValue& v : generic_values(config))
            CHECK(text.find("uniform " + v.type + " " + v.name + ";") != std::string::npos);
        // the specialized program for the same configuration has none of those uniforms
        const std::string specialized = specialized_snippet(config);
        CHECK(specialized.find("penumbra_sliceCount") == std::string::npos);
        CHECK(specialized.find("uniform int") == std::string::npos);
    }
}

TEST_CASE("generic: none of the constants the specialized code bakes in") {
    for (const Config& base : storages()) {
        CAPTURE(to_string(base.filter));
        CAPTURE(to_string(base.packing));
        Config config = base;
        config.slices = 12; // T = 3: 1/T is not a round number
        config.resolution = 512;
        const std::string text = generic_fragment(config);
        const std::string specialized = specialized_snippet(config);
        // as detail/occlusion/emit_visibility.hpp writes them: R, 1 / T, L
        const std::string R = "512.0", inv_T = "0.333333333333", L = "9.0";
        CHECK(specialized.find(R) != std::string::npos);
        CHECK(text.find(R) == std::string::npos);
        CHECK(text.find("512") == std::string::npos);
        CHECK(text.find(inv_T) == std::string::npos);
        CHECK(text.find(L) == std::string::npos);
        CHECK(text.find("11.0") == std::string::npos); // S - 1
        if (config.packing == Packing::atlas)
            CHECK(specialized.find(inv_T) != std::string::npos); // the atlas tile width is baked there
    }
}

TEST_CASE("generic: one text for every slice count, resolution, fusion rule and fade") {
    std::set<std::string> distinct_texts;
    for (Target target : glsl_targets())
        for (const Config& base : storages(target)) {
            CAPTURE(to_string(base.filter));
            CAPTURE(to_string(base.packing));
            CAPTURE(to_string(target));
            const std::vector<Config> variations = variations_of(base);
            REQUIRE(variations.size() > 10);
            const Result<GenericShading> first = emit_generic(variations.front());
            REQUIRE(first.value);
            std::set<std::string> specialized;
            for (const Config& c : variations) {
                const Result<GenericShading> other = emit_generic(c);
                REQUIRE(other.value);
                CHECK(other.value->program == first.value->program);
                CHECK(shares_generic_program(c, base));
                specialized.insert(specialized_snippet(c));
            }
            // while the specialized code is a different text for each of them
            CHECK(specialized.size() == variations.size());
            distinct_texts.insert(first.value->program.stages.at(1).text);
        }
    // and the generic text does change with what picks resources and dialect
    std::size_t storage_count = 0;
    for (Target target : glsl_targets()) storage_count += storages(target).size();
    CHECK(distinct_texts.size() == storage_count);
}

TEST_CASE("generic: the values are the configuration's") {
    const Config config{.slices = 13, .resolution = 1024, .fusion = Fusion::maximum, .self_shadow_fade = false};
    std::map<std::string, double> values;
    for (const GenericValue& v : generic_values(config)) values[v.name] = v.value;
    CHECK(values.at("penumbra_sliceCount") == 13);
    CHECK(values.at("penumbra_resolution") == 1024);
    CHECK(values.at("penumbra_maxLevel") == 10);
    CHECK(values.at("penumbra_tileCount") == 4);
    CHECK(values.at("penumbra_invTileCount") == 0.25);
    CHECK(values.at("penumbra_fusion") == static_cast<int>(Fusion::maximum));
    CHECK(values.at("penumbra_fade") == 0);
    CHECK(generic_fragment(config).find("if (penumbra_fusion == 2) return 1.0 - maximum;") != std::string::npos);
}

TEST_CASE("generic: samplers read the layout's textures, the same ones the specialized pass reads") {
    for (Target target : glsl_targets())
        for (const Config& base : storages(target))
            for (int slices : {1, 5, 16})
                for (int resolution : {32, 128}) {
                    Config config = base;
                    config.slices = slices;
                    config.resolution = resolution;
                    if (!is_valid(config)) continue;
                    CAPTURE(to_string(config.filter));
                    CAPTURE(to_string(config.packing));
                    CAPTURE(to_string(target));
                    CAPTURE(slices);
                    const Layout layout = describe_layout(config);
                    std::set<std::string> layout_textures, specialized_reads, generic_reads;
                    for (const TextureDesc& t : layout.textures) layout_textures.insert(t.name);
                    for (const PassDesc& pass : layout.passes)
                        if (pass.phase == Phase::example)
                            for (const BindingDesc& b : pass.inputs) specialized_reads.insert(b.texture);
                    std::set<int> units;
                    const std::vector<GenericSampler> samplers = generic_samplers(config);
                    for (const GenericSampler& s : samplers) {
                        if (s.texture.empty() || s.texture == "penumbra_worldPositions" ||
                            s.texture == "penumbra_worldNormals")
                            continue;
                        CHECK(layout_textures.count(s.texture) == 1);
                        generic_reads.insert(s.texture);
                        if (!detail::is_vulkan(config)) CHECK(units.insert(s.binding).second);
                    }
                    CHECK(generic_reads == specialized_reads);
                    // the G-buffer last: positions, then the tangent clip's normals
                    const bool clip = clips_to_tangent_plane(config);
                    REQUIRE(samplers.size() >= 2);
                    const GenericSampler& positions = samplers[samplers.size() - (clip ? 2 : 1)];
                    CHECK(positions.texture == "penumbra_worldPositions");
                    if (clip) CHECK(samplers.back().texture == "penumbra_worldNormals");
                    // explicit bindings in the text agree with the list
                    const std::string text = generic_fragment(config);
                    if (target == Target::glsl450)
                        CHECK(text.find("layout(binding = " + std::to_string(positions.binding) +
                                        ") uniform sampler2D penumbra_worldPositions;") != std::string::npos);
                }
}

TEST_CASE("generic: the tangent clip is part of the program text, and reads the normals") {
    const Config clipped{.fusion = Fusion::chained, .tangent_clip = true};
    const Config whole{.fusion = Fusion::chained, .tangent_clip = false};
    CHECK_FALSE(shares_generic_program(clipped, whole));
    const std::string text = generic_fragment(clipped);
    CHECK(text.find("float penumbraVisibility(vec3 worldPos, vec3 worldNormal)") != std::string::npos);
    CHECK(text.find("vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);") != std::string::npos);
    CHECK(text.find("uniform sampler2D penumbra_worldNormals;") != std::string::npos);
    CHECK(text.find("penumbra_tangentClipOffset / penumbra_resolution") != std::string::npos); // the offset is a value, over the resolution uniform
    CHECK(generic_fragment(whole).find("penumbra_worldNormals") == std::string::npos);
}

TEST_CASE("generic: adaptive slice placement is refused with a message") {
    const Result<GenericShading> result =
        emit_generic(Config{.tangent_clip = false, .slice_placement = SlicePlacement::adaptive});
    CHECK_FALSE(result.value);
    REQUIRE(result.errors.size() == 1);
    CHECK(result.errors[0].field == "slice_placement");
    CHECK(result.errors[0].message.find("allowed: uniform") != std::string::npos);
}

TEST_CASE("generic: an invalid configuration gives the validator's messages and no program") {
    const Config config{.slices = 40, .resolution = 100};
    const Result<GenericShading> result = emit_generic(config);
    CHECK_FALSE(result.value);
    REQUIRE(result.errors.size() == 2);
    CHECK(result.errors[0].message == "slices: 40 is out of range; allowed: 1 to 32, 64 or 128");
    CHECK(result.errors[1].field == "resolution");
}
