// Emitted text: structure of the specialized shading code, compile-time = run-time, validation
// messages, layout consistency. No glslang, no GL.
#include <penumbra/penumbra.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <regex>
#include <set>

using namespace penumbra;

namespace {

int count(std::string_view text, std::string_view needle) {
    int n = 0;
    for (std::size_t at = text.find(needle); at != std::string_view::npos; at = text.find(needle, at + 1)) ++n;
    return n;
}

// The body of a function in emitted text, from its signature to the closing brace at column 0.
std::string_view function_body(std::string_view text, std::string_view signature) {
    const std::size_t start = text.find(signature);
    REQUIRE(start != std::string_view::npos);
    const std::size_t end = text.find("\n}\n", start);
    REQUIRE(end != std::string_view::npos);
    return text.substr(start, end - start);
}

std::vector<Config> structure_configs() {
    std::vector<Config> configs;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (int slices : {1, 4, 5, 16, 32})
                for (Fusion fusion : all_values<Fusion>()) {
                    // half the rules with the tangent clip (the default), half with the paper's kernels
                    Config c{.slices = slices, .resolution = 512, .filter = filter, .fusion = fusion,
                             .packing = packing, .light = filter == Filter::gaussian ? Light::sun : Light::rect,
                             .tangent_clip = static_cast<int>(fusion) % 2 == 0};
                    if (is_valid(c)) configs.push_back(c);
                }
    return configs;
}

// Texture fetches one slice costs with this filter and packing (docs/model.md §3).
int fetches_per_slice(const Config& c) {
    if (c.filter == Filter::sat) return 4;
    if (c.filter == Filter::mipmap || c.packing == Packing::volume) return 1;
    return 2; // two levels and a lerp
}

} // namespace

TEST_CASE("the shading function is specialized: unrolled, swizzled, constants baked in") {
    for (const Config& config : structure_configs()) {
        CAPTURE(describe_layout(config).config.slices);
        CAPTURE(to_string(config.filter));
        CAPTURE(to_string(config.packing));
        const std::string snippet = emit_file(config, "penumbra_visibility.glsl").text;
        // with the clip, the loops live in the function both penumbraVisibility overloads call
        const std::string_view body =
            function_body(snippet, config.tangent_clip ? "\nfloat penumbra_clippedVisibility(vec3 p, vec3 penumbra_clip)"
                                                       : "\nfloat penumbraVisibility(vec3 worldPos)");
        const int S = config.slices, L = max_level(config);
        // extent fusion reads each slice once more, over a window twice the kernel's side; clustered fusion
        // also over the kernel's four quadrants
        const bool clustered = config.fusion == Fusion::clustered;
        const int lookups = config.fusion == Fusion::extent ? 2 : clustered ? 6 : 1;

        // no loop statement for the static loop; the atlas level loop keeps one bounded walk per level
        CHECK(count(body, "for (") == 0);
        const bool level_loop = config.packing == Packing::atlas &&
                                (config.filter == Filter::nbuffer || config.filter == Filter::gaussian);
        CHECK(count(body, "while (") == (level_loop ? L + 1 : 0));
        // slices are selected by rotating a one-hot vec4 and a dot product, never by a branch on the index
        CHECK(count(body, "dot(") == (level_loop ? L + 1 : S) * lookups);
        CHECK(count(body, "penumbra_i = penumbra_i.yzwx;") == (level_loop ? L + 1 : S - 1));
        // and one branch before them: a receiver outside the rectangle's slicing pyramid (docs/model.md
        // §1.2b)
        const int outside_pyramid = config.light == Light::rect && !config.tangent_clip ? 1 : 0;
        CHECK(count(body, "if (") == (level_loop ? L : 0) + outside_pyramid);
        // no sampler array, let alone a dynamically indexed one
        CHECK_FALSE(std::regex_search(snippet, std::regex(R"(uniform\s+sampler\w+\s+\w+\s*\[)")));

        if (level_loop) {
            // one comment per unrolled level, each level texture read statically
            for (int level = 0; level <= L; ++level)
                CHECK(body.find("// level " + std::to_string(level) + ":") != std::string_view::npos);
            // extent: the doubled window's level two above, where there is one (the others are read already)
            // clustered: each quadrant from the level below and this one (level 0: level 0 alone)
            CHECK(count(body, "textureLod(") ==
                  2 * L + 1 + (reads_doubled_window(config.fusion) ? L - 1 : 0) + (clustered ? 4 + 8 * L : 0));
        } else {
            // one labelled block per slice, each with its baked plane index, one filtered lookup each
            for (int s = 0; s < S; ++s) {
                CHECK(body.find("// slice " + std::to_string(s) + ":") != std::string_view::npos);
                CHECK(body.find("penumbra_sliceDepths.x + " + std::to_string(s + 1) + ".0 * penumbra_sliceDepths.y") !=
                      std::string_view::npos);
            }
            CHECK(count(body, "penumbra_filtered") == S * lookups);
            if (config.filter == Filter::sat)
                CHECK(count(function_body(snippet, "vec4 penumbra_filtered"), "penumbra_prefix(") *
                          count(function_body(snippet, "vec4 penumbra_prefix"), "textureLod(") ==
                      fetches_per_slice(config));
            else if (config.packing == Packing::volume)
                CHECK(count(function_body(snippet, "vec4 penumbra_filtered0"), "textureLod(") == 1);
            else
                CHECK(count(function_body(snippet, "vec4 penumbra_filtered"), "textureLod(") ==
                      fetches_per_slice(config));
        }
        // the resolution and level count are literals
        CHECK(snippet.find(std::to_string(config.resolution) + ".0") != std::string::npos);
        CHECK(snippet.find("uniform int") == std::string::npos);
    }
}

TEST_CASE("fusion rules") {
    const std::pair<Fusion, std::string> expected[] = {
        {Fusion::probabilistic, "penumbra_lit *= 1.0 - q;"},
        {Fusion::additive, "return max(0.0, 1.0 - penumbra_sum);"},
        {Fusion::maximum, "return 1.0 - penumbra_max;"},
        {Fusion::average, "return 1.0 - 0.5 * (min(1.0, penumbra_sum) + penumbra_max);"},
        {Fusion::chained, "penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);"},
        {Fusion::correlated, "penumbra_lit *= penumbra_correlatedStep(q, kernel, penumbra_prev, penumbra_prevKernel);"},
        {Fusion::extent, "penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);"},
        {Fusion::clustered, "area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z / penumbra_clusterCount(penumbra_quadrants);"},
    };
    for (const auto& [fusion, line] : expected)
        CHECK(emit_file(Config{.fusion = fusion}, "penumbra_visibility.glsl").text.find(line) != std::string::npos);
}

TEST_CASE("tangent clip: the normal is an input, each kernel is restricted, the deferred pass reads normals") {
    const Config config{.fusion = Fusion::chained, .tangent_clip = true};
    const Emission emission = *emit(config).value;
    const std::string& snippet = emission.snippet.text;
    CHECK(snippet.find("float penumbraVisibility(vec3 worldPos, vec3 worldNormal)") != std::string::npos);
    CHECK(snippet.find("vec3 penumbra_tangentClip(vec3 p, vec3 n)") != std::string::npos);
    CHECK(snippet.find("vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);") != std::string::npos);
    CHECK(snippet.find("side *= clip.z;") != std::string::npos);
    CHECK(snippet.find("// move the point 1.0 slicing texels sideways along its normal") != std::string::npos);
    CHECK(snippet.find(detail::describe(config).str()) != std::string::npos);
    for (const ShaderFile& file : emission.files())
        if (file.file_name.find("shading_deferred") != std::string::npos && file.file_name.ends_with(".frag"))
            CHECK(file.text.find("penumbraVisibility(world.xyz, normal)") != std::string::npos);
    const Layout& layout = emission.layout;
    bool normals = false;
    for (const ProgramDesc& p : layout.programs)
        for (const ParamDesc& param : p.parameters) normals |= p.name == "shading_deferred" && param.name == "penumbra_worldNormals";
    CHECK(normals);
    // and without a normal, the whole light through the same loops (weighed by the irradiance it sends a
    // receiver facing it, the default's irradiance window)
    CHECK(snippet.find("float penumbraVisibility(vec3 worldPos)\n") != std::string::npos);
    CHECK(snippet.find(
              "return penumbra_windowedVisibility(p, vec3(0.0, 0.0, 1.0), penumbra_irradianceWindow(p, "
              "vec3(0.0, 0.0, -1.0), vec3(0.0, 0.0, 1.0)));") != std::string::npos);
    CHECK(count(snippet, "// slice 0:") + count(snippet, "// level 0:") == 1); // the loops are written once
    // off: the paper's signature and no clip
    const std::string plain = emit_file(Config{.tangent_clip = false}, "penumbra_visibility.glsl").text;
    CHECK(plain.find("float penumbraVisibility(vec3 worldPos)") != std::string::npos);
    CHECK(plain.find("penumbra_tangentClip") == std::string::npos);
}

TEST_CASE("adaptive slice placement: boundaries counted in slicing, read per slice in penumbraVisibility") {
    for (const bool fade : {true, false}) {
        // the slice loop (array packing) and the level loop (atlas N-buffers)
        for (const Packing packing : {Packing::array, Packing::atlas}) {
            const Config config{.slices = 5, .resolution = 64, .filter = Filter::nbuffer, .fusion = Fusion::chained,
                                .packing = packing, .self_shadow_fade = fade, .tangent_clip = false,
                                .slice_placement = SlicePlacement::adaptive};
            CAPTURE(to_string(packing));
            CAPTURE(fade);
            const Emission emission = *emit(config).value;
            const std::string& snippet = emission.snippet.text;
            CHECK(snippet.find("uniform usampler2D penumbra_sliceBoundaries;") != std::string::npos);
            CHECK(snippet.find("return uintBitsToFloat(texelFetch(penumbra_sliceBoundaries, ivec2(k, 0), 0).r);") !=
                  std::string::npos);
            CHECK(snippet.find("| slice placement adaptive |") != std::string::npos);
            CHECK(snippet.find("penumbra_sliceDepths.x + ") == std::string::npos); // no uniform plane left
            CHECK((snippet.find("penumbra_weight(p.z, zeta, thickness)") != std::string::npos) == fade);
            // each plane's fade ramps over the slice below it; the last over its own thickness
            CHECK((snippet.find("float penumbra_below = 2.0 * penumbra_boundary(5) - penumbra_boundary(4);") !=
                   std::string::npos) == fade);
            CHECK((snippet.find("float thickness = penumbra_below - zeta; // the slice below the plane") !=
                   std::string::npos) == fade);
            if (packing == Packing::array) {
                CHECK(snippet.find("float zeta = penumbra_boundary(5);") != std::string::npos);
            } else { // binary search for the first slice above the point: steps 4, 2, 1 over 5 boundaries
                CHECK(snippet.find("penumbra_above += (penumbra_above + 4 <= 5 && p.z > penumbra_boundary(min("
                                   "penumbra_above + 4, 5))) ? 4 : 0;") != std::string::npos);
                CHECK(snippet.find("penumbra_above + 1 <= 5") != std::string::npos);
                CHECK(snippet.find("float zeta = penumbra_boundary(int(penumbra_k) + 1);") != std::string::npos);
            }
            const std::string slicing = emit_file(config, "penumbra_slicing.frag").text;
            CHECK(slicing.find("inner += (inner + 2 <= 4 && penumbra_depth > penumbra_boundary(min(inner + 2, 4))) ? 2 : 0;") !=
                  std::string::npos);
            CHECK(slicing.find("penumbra_boundary(5)") == std::string::npos); // inner boundaries only
            const std::string boundaries = emit_file(config, "penumbra_slice_boundaries.frag").text;
            CHECK(boundaries.find("paper §5") != std::string::npos);
            CHECK(boundaries.find("penumbra_boundary = floatBitsToUint(z);") != std::string::npos);
        }
    }
    // uniform placement keeps the uniform text
    const std::string uniform =
        emit_file(Config{.slices = 5, .resolution = 64, .packing = Packing::array, .tangent_clip = false},
                  "penumbra_visibility.glsl").text;
    CHECK(uniform.find("penumbra_sliceBoundaries") == std::string::npos);
    CHECK(uniform.find("float zeta = penumbra_sliceDepths.x + 5.0 * penumbra_sliceDepths.y;") != std::string::npos);
}

TEST_CASE("every emitted file states its configuration and carries chunk markers") {
    const Config config{.slices = 5, .resolution = 64, .filter = Filter::sat, .packing = Packing::array};
    const Emission emission = *emit(config).value;
    for (const ShaderFile& file : emission.files()) {
        CAPTURE(file.file_name);
        CHECK(file.text.find(detail::describe(config).str()) != std::string::npos);
        CHECK(file.text.find("// @penumbra:") != std::string::npos);
        if (file.file_name != "penumbra_visibility.glsl") CHECK(file.text.starts_with("#version 450 core\n"));
    }
    const std::string& text = emission.snippet.text;
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + text.find("\nfloat penumbraVisibility") + 1, '\n'));
    CHECK(chunk_at_line(text, line) == "visibility");
    CHECK(chunk_at_line(text, 1).empty());
}

TEST_CASE("slicing: one render target per four slices, the leak fix marks the next slice") {
    const std::string with_fix = emit_file(Config{.slices = 6}, "penumbra_slicing.frag").text;
    const std::string without = emit_file(Config{.slices = 6, .leak_fix = false}, "penumbra_slicing.frag").text;
    CHECK(count(with_fix, "out vec4 penumbra_occlusion") == 2);
    CHECK(with_fix.find("float next = min(k + 1.0, 5.0);") != std::string::npos);
    CHECK(without.find("next") == std::string::npos);
}

namespace {
constexpr Config kCompileTime1{.slices = 8, .resolution = 256};
constexpr Config kCompileTime2{.slices = 5, .resolution = 64, .filter = Filter::sat, .fusion = Fusion::average,
                               .packing = Packing::array, .target = Target::vulkan};
constexpr Config kCompileTime3{.slices = 4, .resolution = 128, .filter = Filter::gaussian, .packing = Packing::volume,
                               .light = Light::sun, .self_shadow_fade = false, .target = Target::essl300};
} // namespace

TEST_CASE("compile-time emission equals run-time emission") {
    CHECK(static_glsl<kCompileTime1, "penumbra_visibility.glsl"> ==
          emit_file(kCompileTime1, "penumbra_visibility.glsl").text);
    CHECK(static_glsl<kCompileTime1, "penumbra_slicing.frag"> == emit_file(kCompileTime1, "penumbra_slicing.frag").text);
    CHECK(static_glsl<kCompileTime2, "penumbra_shading.frag"> == emit_file(kCompileTime2, "penumbra_shading.frag").text);
    CHECK(static_glsl<kCompileTime2, "penumbra_sat_pass.frag"> == emit_file(kCompileTime2, "penumbra_sat_pass.frag").text);
    CHECK(static_glsl<kCompileTime3, "penumbra_deferred.frag"> == emit_file(kCompileTime3, "penumbra_deferred.frag").text);
    CHECK(static_glsl<kCompileTime3, "penumbra_gaussian_level.frag"> ==
          emit_file(kCompileTime3, "penumbra_gaussian_level.frag").text);
    static_assert(static_glsl<kCompileTime1, "penumbra_visibility.glsl">.size() > 1000);
}

TEST_CASE("invalid configurations: each names the field, the value and what is allowed") {
    struct Case {
        Config config;
        std::string field;
        std::string message;
    };
    const Case cases[] = {
        {{.slices = 0}, "slices", "slices: 0 is out of range; allowed: 1 to 32, 64 or 128"},
        {{.slices = 33}, "slices", "slices: 33 is out of range; allowed: 1 to 32, 64 or 128"},
        {{.resolution = 100}, "resolution", "resolution: 100 is not allowed; allowed: a power of two from 32 to 4096"},
        {{.resolution = 8192}, "resolution", "resolution: 8192 is not allowed"},
        {{.resolution = 16}, "resolution", "resolution: 16 is not allowed"},
        {{.filter = static_cast<Filter>(9)}, "filter", "filter: 9 is not a known value; allowed: mipmap, nbuffer, sat, gaussian"},
        {{.fusion = static_cast<Fusion>(8)}, "fusion", "allowed: probabilistic, additive, maximum, average"},
        {{.packing = static_cast<Packing>(5)}, "packing", "allowed: atlas, array, volume"},
        {{.light = static_cast<Light>(2)}, "light", "allowed: rect, sun"},
        {{.target = static_cast<Target>(7)}, "target", "allowed: glsl330, glsl450, essl300, vulkan, wgsl, hlsl, msl"},
        {{.filter = Filter::gaussian}, "filter", "filter: gaussian needs light 'sun'"},
        {{.filter = Filter::sat, .packing = Packing::volume}, "packing", "packing: volume cannot hold filter 'sat'"},
        {{.filter = Filter::mipmap, .packing = Packing::volume}, "packing", "packing: volume cannot hold filter 'mipmap'"},
        {{.filter = Filter::sat, .target = Target::essl300}, "filter", "which target 'essl300' does not guarantee"},
        {{.slices = 32, .target = Target::essl300}, "slices", "guarantees 4; allowed for essl300: 1 to 16"},
        {{.slices = 20, .target = Target::vulkan}, "slices", "allowed for vulkan: 1 to 16"},
        {{.slices = 32, .resolution = 512, .target = Target::glsl330}, "resolution",
         "resolution: 512 needs a 4096-texel wide atlas but target 'glsl330' guarantees only 1024 texels"},
        {{.resolution = 2048, .packing = Packing::array, .target = Target::glsl330}, "resolution", "guarantees only 1024"},
        {{.resolution = 512, .packing = Packing::volume, .target = Target::vulkan}, "resolution",
         "is too large for packing 'volume'"},
        // more than 32 slices: bits of one target combined by a logical OR (paper §3.7)
        {{.slices = 100}, "slices", "slices: 100 is out of range; allowed: 1 to 32, 64 or 128"},
        {{.slices = 64, .resolution = 128, .target = Target::essl300}, "slices",
         "slices: 64 needs a logical OR on the slicing target (more than 32 slices are written as bits, paper §3.7), "
         "which target 'essl300' does not have; allowed for essl300: 1 to 16"},
        {{.slices = 24, .target = Target::vulkan}, "slices", "allowed for vulkan: 1 to 16, 64 or 128"},
        {{.slices = 64, .resolution = 128, .packing = Packing::volume}, "packing",
         "packing: volume needs 16 3D textures for 64 slices"},
        {{.slices = 128, .resolution = 1024, .packing = Packing::atlas, .target = Target::glsl450}, "resolution",
         "resolution: 1024 needs a 32768-texel wide atlas but target 'glsl450' guarantees only 16384 texels; allowed "
         "with 128 slices and packing atlas: up to 512, or fewer slices, another packing or another target"},
        {{.slices = 128, .resolution = 64, .filter = Filter::sat, .packing = Packing::atlas, .target = Target::glsl330},
         "resolution", "allowed with 128 slices and packing atlas: none"},
        {{.slices = 128, .resolution = 256, .packing = Packing::array, .target = Target::glsl330}, "packing",
         "packing: array needs 288 layers but target 'glsl330' guarantees 256"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.message);
        CHECK_FALSE(is_valid(c.config));
        const std::vector<ConfigError> errors = validate(c.config);
        REQUIRE_FALSE(errors.empty());
        const bool found = std::any_of(errors.begin(), errors.end(), [&](const ConfigError& e) {
            return e.field == c.field && e.message.find(c.message) != std::string::npos;
        });
        CHECK(found);
        const Result<Emission> result = emit(c.config);
        CHECK_FALSE(result.value.has_value());
    }
    CHECK(validate(Config{}).empty());
}

TEST_CASE("layout: every file, texture, program and binding referenced exists") {
    for (const Config& config : structure_configs()) {
        const Emission emission = *emit(config).value;
        const Layout& layout = emission.layout;
        std::set<std::string> textures, programs, files;
        for (const TextureDesc& t : layout.textures) textures.insert(t.name);
        for (const ProgramDesc& p : layout.programs) programs.insert(p.name);
        for (const ShaderFile& f : emission.files()) files.insert(f.file_name);
        files.insert("layout.json");
        CHECK(files == std::set<std::string>(layout.files.begin(), layout.files.end()));
        CHECK(files.size() == layout.files.size());
        for (const PassDesc& pass : layout.passes) {
            CAPTURE(pass.name);
            if (!pass.program.empty()) CHECK(programs.count(pass.program) == 1);
            for (const BindingDesc& input : pass.inputs) CHECK(textures.count(input.texture) == 1);
            for (const AttachmentDesc& output : pass.outputs) CHECK(textures.count(output.texture) == 1);
        }
        // the slicing pass writes one attachment per RGBA texture
        CHECK(layout.passes.front().outputs.size() == static_cast<std::size_t>(texture_count(config)));
        // the shading pass binds every storage sampler the snippet declares, at the binding it declares
        for (const BindingDesc& input : layout.passes.back().inputs) {
            const std::string declared = "layout(binding = " + std::to_string(input.binding) + ") uniform";
            const std::size_t at = emission.snippet.text.find(" " + input.sampler + ";");
            if (input.sampler == "penumbra_worldPositions") continue;
            REQUIRE(at != std::string::npos);
            const std::size_t line_start = emission.snippet.text.rfind('\n', at) + 1;
            CHECK(emission.snippet.text.compare(line_start, declared.size(), declared) == 0);
        }
        const std::string json = to_json(layout);
        CHECK(json.find("\"resolution\": " + std::to_string(config.resolution)) != std::string::npos);
    }
}
