// The glslang matrix: one table of (technique, configurations), every emitted program of every
// valid configuration compiled and linked by glslang for its target, through one check. A row
// says which configurations it covers, which of them must be valid or refused, and what else must
// hold of each emission and of the row as a whole.
#include <penumbra/generic.hpp>
#include <penumbra/penumbra.hpp>
#include <penumbra/profiles.hpp>
#include <penumbra/validation.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

using namespace penumbra;

namespace {

// What one configuration emitted: its programs (none when refused), the snippet, the refusal.
struct Emitted {
    std::vector<Program> programs;
    std::string snippet;
    std::vector<ConfigError> errors;
};

Emitted emit_all(const Config& config) {
    Result<Emission> result = emit(config);
    if (!result.value) return {{}, {}, result.errors};
    return {result.value->programs, result.value->snippet.text, {}};
}

// penumbra/generic.hpp: the one reference program of a configuration.
Emitted emit_generic_program(const Config& config) {
    Result<GenericShading> result = emit_generic(config);
    if (!result.value) return {{}, {}, result.errors};
    return {{result.value->program}, {}, {}};
}

enum class Expect { either, valid, refused };

// What a row's run found, for its own final checks.
struct RowResult {
    int valid = 0, refused = 0, programs = 0;
    int compiled = 0;                  // distinct program texts glslang compiled
    std::vector<Config> valid_configs; // in table order
};

struct Row {
    std::string name;
    std::vector<Config> configurations;
    std::function<Emitted(const Config&)> emit_programs = emit_all;
    std::function<Expect(const Config&)> expect = [](const Config&) { return Expect::either; };
    std::function<void(const Config&, const Emitted&)> check_emission = nullptr; // each valid one
    std::function<void(const Config&, const Emitted&)> check_refusal = nullptr;  // each refused one
    std::function<void(const RowResult&)> check_row = nullptr;
};

std::string name_of(const Config& c) {
    if (c.technique != Technique::occlusion) return std::string(detail::describe(c).view());
    return std::string(to_string(c.filter)) + "/" + std::string(to_string(c.fusion)) + "/" +
           std::string(to_string(c.packing)) + "/" + std::string(to_string(c.light)) + "/" +
           std::string(to_string(c.target)) + "/S" + std::to_string(c.slices) + "/R" + std::to_string(c.resolution) +
           (c.tangent_clip ? "/tangent-clip" : "") +
           (c.slice_placement == SlicePlacement::adaptive ? "/adaptive" : "");
}

// The targets glslang compiles as GLSL: every one but WGSL, whose matrix Chromium's compiler checks (ctest
// -R wgsl_matrix), HLSL, whose matrix glslang's HLSL front end checks (ctest -R hlsl_matrix), and MSL,
// which emit() refuses (emit_msl translates vulkan's SPIR-V: ctest -R msl_matrix).
std::vector<Target> glsl_targets() {
    std::vector<Target> targets;
    for (Target target : all_values<Target>())
        if (target != Target::wgsl && target != Target::hlsl && target != Target::msl) targets.push_back(target);
    return targets;
}

// --- the rows ------------------------------------------------------------------------------------

// Every filter × fusion × packing × target × light × slices × resolution.
std::vector<Config> occlusion_matrix(bool fade_both_ways) {
    std::vector<Config> configs;
    for (Filter filter : all_values<Filter>())
        for (Fusion fusion : all_values<Fusion>())
            for (Packing packing : all_values<Packing>())
                for (Target target : glsl_targets())
                    for (Light light : all_values<Light>())
                        for (bool fade : fade_both_ways ? std::vector<bool>{true, false} : std::vector<bool>{true})
                            for (int slices : {1, 4, 5, 8, 16, 32})
                                for (int resolution : {32, 256, 2048})
                                    configs.push_back({.slices = slices, .resolution = resolution, .filter = filter,
                                                       .fusion = fusion, .packing = packing, .light = light,
                                                       .self_shadow_fade = fade, .target = target});
    return configs;
}

Row occlusion_row() {
    return {.name = "occlusion",
            .configurations = occlusion_matrix(false),
            .check_refusal = [](const Config&, const Emitted& e) { REQUIRE(!e.errors.empty()); },
            .check_row = [](const RowResult& r) {
                CHECK(r.valid > 0);
                CHECK(r.refused > 0);
            }};
}

// The tangent clip changes the visibility function, the kernel and the deferred pass's inputs:
// every filter × packing × light × target with it on (four slice counts: 5 with correlated fusion, whose
// step reads each slice's kernel, 6 with extent fusion, which also reads a doubled window, 7 with clustered
// fusion, which also reads the kernel's quadrants, 16 with chained).
Row tangent_clip_row() {
    std::vector<Config> configs;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Target target : glsl_targets())
                for (Light light : all_values<Light>())
                    for (int slices : {5, 6, 7, 16})
                        configs.push_back({.slices = slices, .resolution = 256, .filter = filter,
                                           .fusion = slices == 5   ? Fusion::correlated
                                                     : slices == 6 ? Fusion::extent
                                                     : slices == 7 ? Fusion::clustered
                                                                   : Fusion::chained,
                                           .packing = packing,
                                           .light = light, .tangent_clip = true, .target = target});
    return {.name = "occlusion, tangent clip",
            .configurations = configs,
            .check_emission = [](const Config&, const Emitted& e) {
                CHECK(e.snippet.find("float penumbraVisibility(vec3 worldPos, vec3 worldNormal)") != std::string::npos);
            },
            .check_row = [](const RowResult& r) { CHECK(r.valid > 40); }};
}

// More than 32 slices (paper §3.7): the slicing writes bits of one RGBA32UI target, the unpack pass
// writes the occlusion textures, and the unrolled slice or level loops grow to 64 or 128 slices.
// Every filter × packing × light × target × {64, 128}, the fusion and tangent clip rotating over the
// combinations; ES 3.0 has no logic op and must refuse, and so must the volume packing.
Row many_slices_row() {
    std::vector<Config> configs;
    int index = 0;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Target target : glsl_targets())
                for (Light light : all_values<Light>())
                    for (int slices : {64, 128}) {
                        const Fusion fusion = all_values<Fusion>()[static_cast<std::size_t>(index) % all_values<Fusion>().size()];
                        configs.push_back({.slices = slices, .resolution = 32, .filter = filter, .fusion = fusion,
                                           .packing = packing, .light = light, .leak_fix = index % 3 != 0,
                                           .self_shadow_fade = true, .tangent_clip = index % 2 == 0, .target = target});
                        ++index;
                    }
    return {.name = "occlusion, 64 and 128 slices",
            .configurations = configs,
            .expect = [](const Config& c) {
                return c.target == Target::essl300 || c.packing == Packing::volume ? Expect::refused : Expect::either;
            },
            .check_emission = [](const Config&, const Emitted& e) {
                CHECK(std::any_of(e.programs.begin(), e.programs.end(),
                                  [](const Program& p) { return p.name == "unpack_slices"; }));
            },
            .check_row = [](const RowResult& r) { CHECK(r.valid >= 48); }};
}

// Adaptive slice placement adds two programs (the depth-bin pre-pass, the boundary pass) and changes
// the slicing fragment and penumbraVisibility (boundaries read from an R32UI texture): every filter ×
// packing × light × target, with 1 slice (no inner boundary) and the fade on, and with 16 slices,
// the tangent clip on and the fade off.
Row adaptive_row() {
    std::vector<Config> configs;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Target target : glsl_targets())
                for (Light light : all_values<Light>())
                    for (bool switches : {false, true})
                        configs.push_back({.slices = switches ? 16 : 1, .resolution = 256, .filter = filter,
                                           .fusion = switches ? Fusion::chained : Fusion::probabilistic,
                                           .packing = packing, .light = light, .self_shadow_fade = !switches,
                                           .tangent_clip = switches, .slice_placement = SlicePlacement::adaptive,
                                           .target = target});
    return {.name = "occlusion, adaptive slice placement",
            .configurations = configs,
            .check_emission = [](const Config& c, const Emitted& e) {
                const auto placement = std::count_if(e.programs.begin(), e.programs.end(), [](const Program& p) {
                    return p.name == "depth_bins" || p.name == "slice_boundaries";
                });
                CHECK_MESSAGE(placement == 2, name_of(c));
            },
            .check_row = [](const RowResult& r) { CHECK(r.valid > 60); }};
}

// The compute prefilter (prefilter_stage compute): allowed for N-buffers in the atlas on glsl450 only,
// where one level's taps fit the shared tile (level_reduction up to 4, or every level at full
// resolution up to level 5); its program is one compute stage, glslang-compiled for GLSL 4.50, and
// the fragment level passes' program is gone. Every filter × packing × target × light × resolution ×
// level_reduction; every other combination refused on field prefilter_stage (where the fragment
// configuration itself is valid).
bool compute_prefilter_allowed(const Config& c) {
    Config fragment = c;
    fragment.prefilter_stage = PrefilterStage::fragment;
    return is_valid(fragment) && c.filter == Filter::nbuffer && c.packing == Packing::atlas &&
           c.target == Target::glsl450 && (c.level_reduction >= 0 ? std::min(c.level_reduction, max_level(c) - 1) : max_level(c) - 1) <= 4;
}

Row compute_prefilter_row() {
    std::vector<Config> configs;
    for (Filter filter : all_values<Filter>())
        for (Packing packing : all_values<Packing>())
            for (Target target : glsl_targets())
                for (Light light : all_values<Light>())
                    for (int resolution : {32, 256, 2048})
                        for (int reduction : {2, 0, 4, 5, -1}) {
                            Config c{.slices = 16, .resolution = resolution, .filter = filter, .packing = packing,
                                     .light = light, .level_reduction = reduction, .target = target,
                                     .prefilter_stage = PrefilterStage::compute};
                            configs.push_back(c);
                            if (reduction == -1 && resolution > 32) { // every level at full resolution up to level 5
                                c.level_bound = 5;
                                configs.push_back(c);
                            }
                        }
    return {.name = "occlusion, compute prefilter",
            .configurations = configs,
            .expect = [](const Config& c) { return compute_prefilter_allowed(c) ? Expect::valid : Expect::refused; },
            .check_emission = [](const Config& c, const Emitted& e) {
                const auto compute = std::find_if(e.programs.begin(), e.programs.end(),
                                                  [](const Program& p) { return p.name == "nbuffer_levels"; });
                REQUIRE_MESSAGE(compute != e.programs.end(), name_of(c));
                REQUIRE(compute->stages.size() == 1);
                CHECK(compute->stages[0].stage == Stage::compute);
                CHECK(compute->stages[0].file_name == "penumbra_nbuffer_levels.comp");
                CHECK(compute->stages[0].text.find("shared vec4 penumbra_tile[") != std::string::npos);
                CHECK(std::none_of(e.programs.begin(), e.programs.end(),
                                   [](const Program& p) { return p.name == "nbuffer_level"; }));
            },
            .check_refusal = [](const Config& c, const Emitted& e) {
                Config fragment = c;
                fragment.prefilter_stage = PrefilterStage::fragment;
                if (!is_valid(fragment)) return;
                REQUIRE_MESSAGE(!e.errors.empty(), name_of(c));
                CHECK_MESSAGE(e.errors.front().field == "prefilter_stage", name_of(c), ": ", e.errors.front().message);
            },
            .check_row = [](const RowResult& r) { CHECK(r.valid >= 10); }};
}

// The generic reference program (penumbra/generic.hpp) of the occlusion matrix, plus fade off (a
// uniform of the generic program): exactly one program per filter × packing × light × target.
Row generic_row() {
    return {.name = "occlusion, generic program",
            .configurations = occlusion_matrix(true),
            .emit_programs = emit_generic_program,
            .check_refusal = [](const Config& c, const Emitted& e) { CHECK(e.errors.size() == validate(c).size()); },
            .check_row = [](const RowResult& r) {
                CHECK(r.valid > 0);
                CHECK(r.refused > 0);
                std::set<std::tuple<Filter, Packing, Light, Target>> storages;
                for (const Config& c : r.valid_configs) storages.insert({c.filter, c.packing, c.light, c.target});
                CHECK(r.compiled == static_cast<int>(storages.size()));
            }};
}

// A row whose every configuration must be valid and emit `programs_each` programs.
Row all_valid_row(std::string name, std::vector<Config> configs, int programs_each) {
    const int expected = static_cast<int>(configs.size()) * programs_each;
    return {.name = std::move(name),
            .configurations = std::move(configs),
            .expect = [](const Config&) { return Expect::valid; },
            .check_row = [expected](const RowResult& r) { CHECK(r.programs == expected); }};
}

// Every shadow map technique (shadowmap, pcf, pcss) over its parameters, on every target and light.
Row shadow_map_row() {
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (Light light : all_values<Light>()) {
            auto with = [&](Config c) {
                c.light = light;
                c.target = target;
                configs.push_back(c);
            };
            with({.technique = Technique::shadowmap});
            with({.technique = Technique::shadowmap, .shadow_map = {.resolution = 32, .constant_bias = 0.0, .slope_bias = 0.0}});
            for (int n : {1, 4, 16})
                with({.technique = Technique::pcf, .pcf = {.pattern = TapPattern::grid, .grid_size = n, .rotate = n == 4}});
            for (int k : {1, 16, 64})
                with({.technique = Technique::pcf, .pcf = {.pattern = TapPattern::poisson, .poisson_taps = k, .rotate = k != 1}});
            // engine settings (Bevy, Filament, three.js, Godot ultra, PlayCanvas high) and the extremes
            for (auto [b, f] : {std::pair{8, 8}, {16, 16}, {17, 34}, {32, 32}, {32, 64}, {1, 1}, {64, 128}})
                with({.technique = Technique::pcss, .pcss = {.blocker_samples = b, .filter_samples = f, .rotate = b != 1}});
        }
    return all_valid_row("shadow map, pcf, pcss", configs, 3);
}

// Erosion over its parameters (the defaults and both extremes), on every target and light.
Row erosion_row() {
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (Light light : all_values<Light>())
            for (ErosionParams e : {ErosionParams{}, ErosionParams{.max_search_radius = 1, .search_taps = 1, .blur_taps = 1},
                                    ErosionParams{.max_search_radius = 256, .edge_threshold = 4.0, .search_taps = 64,
                                                  .blur_taps = 64}})
                configs.push_back({.technique = Technique::erosion, .light = light, .target = target, .erosion = e});
    return all_valid_row("erosion", configs, 7);
}

// EVSM over its parameters (the defaults and both extremes, a small map), on every target (ES: the
// moments as bits in RGBA32UI, filtered by hand) and light: depth, moments, blur x, blur y, example, deferred.
Row evsm_row() {
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (Light light : all_values<Light>())
            for (auto [resolution, e] : {std::pair{1024, EvsmParams{}},
                                         {32, EvsmParams{.light_bleeding_reduction = 0.0, .variance_bias = 0.0,
                                                         .blur_taps = 1, .max_blur_texels = 1}},
                                         {1024, EvsmParams{.positive_exponent = 42.0, .negative_exponent = 42.0,
                                                           .light_bleeding_reduction = 0.9, .variance_bias = 0.01,
                                                           .blur_fraction = 1.0, .blur_taps = 64, .max_blur_texels = 64}}})
                configs.push_back({.technique = Technique::evsm, .light = light, .target = target,
                                   .shadow_map = {.resolution = resolution}, .evsm = e});
    return all_valid_row("evsm", configs, 6);
}

// Shadow-map ray tracing over its parameters (Unreal's defaults, both extremes, no extrapolation, a
// later frame), on every target and light: depth, example, deferred.
Row smrt_row() {
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (Light light : all_values<Light>())
            for (auto [resolution, s] : {std::pair{1024, SmrtParams{}},
                                         {32, SmrtParams{.rays = 1, .samples = 2, .extrapolate_max_slope = 0.0,
                                                         .max_slope_bias = 0.0, .texel_dither = 0.0}},
                                         {1024, SmrtParams{.rays = 16, .samples = 32, .extrapolate_max_slope = 50.0,
                                                           .max_slope_bias = 1000.0, .texel_dither = 8.0, .frame = 1023}}})
                configs.push_back({.technique = Technique::smrt, .light = light, .target = target,
                                   .shadow_map = {.resolution = resolution}, .smrt = s});
    return all_valid_row("smrt", configs, 3);
}

// Occlusion interval maps: every interval count, resolution and target. glsl330 guarantees 1024
// texels, so 2048 is refused for each interval count.
Row oim_row() {
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (int intervals : {4, 8, 12, 16})
            for (int resolution : {32, 256, 2048}) {
                Config config{.technique = Technique::oim, .target = target};
                config.oim.intervals = intervals;
                config.oim.resolution = resolution;
                configs.push_back(config);
            }
    return {.name = "oim",
            .configurations = configs,
            .check_emission = [](const Config&, const Emitted& e) {
                REQUIRE(e.programs.size() == 2); // shading_example, shading_deferred
            },
            .check_refusal = [](const Config&, const Emitted& e) {
                CHECK(e.errors.front().field == "oim.resolution"); // a map larger than the target guarantees
            },
            .check_row = [](const RowResult& r) {
                CHECK(r.programs + 2 * r.refused == 4 * 4 * 3 * 2);
                CHECK(r.refused == 4);
            }};
}

// Cut-out casters (alpha_test): every technique × target × light, the occlusion textures with the slices
// as channels and as bits, and with adaptive slice placement. Each program that draws the casters from
// the light (slicing, depth_bins, shadow_depth) reads penumbra_uv, penumbra_alphaTexture and
// penumbra_alphaCutoff and discards; the other programs are those of the configuration without the cut.
Row alpha_test_row() {
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (Light light : all_values<Light>()) {
            auto with = [&](Config c) {
                c.light = light;
                c.target = target;
                c.alpha_test = true;
                configs.push_back(c);
            };
            with({.resolution = 256}); // the default but for the resolution (glsl330's atlas holds 16 x 256)
            with({.slices = 5, .resolution = 64, .filter = target == Target::essl300 ? Filter::mipmap : Filter::sat,
                  .packing = Packing::array});
            with({.slices = 16, .resolution = 256, .slice_placement = SlicePlacement::adaptive});
            if (target != Target::essl300) with({.slices = 64, .resolution = 32}); // bits of an RGBA32UI target
            with({.technique = Technique::shadowmap});
            with({.technique = Technique::pcf});
            with({.technique = Technique::pcss});
            with({.technique = Technique::erosion});
            with({.technique = Technique::evsm});
            with({.technique = Technique::smrt});
            with({.technique = Technique::oim});
        }
    return {.name = "alpha test (cut-out casters)",
            .configurations = configs,
            .expect = [](const Config&) { return Expect::valid; },
            .check_emission = [](const Config& c, const Emitted& e) {
                Config solid = c;
                solid.alpha_test = false;
                const Emitted without = emit_all(solid);
                REQUIRE(without.programs.size() == e.programs.size());
                int casters = 0;
                for (std::size_t i = 0; i < e.programs.size(); ++i) {
                    const Program& p = e.programs[i];
                    const bool caster = p.name == "slicing" || p.name == "depth_bins" || p.name == "shadow_depth";
                    casters += caster;
                    const std::string vertex = p.stages.front().text, fragment = p.stages.back().text;
                    if (caster) {
                        CHECK_MESSAGE(vertex.find("in vec2 penumbra_uv;") != std::string::npos, name_of(c), " ", p.name);
                        CHECK_MESSAGE(fragment.find("uniform sampler2D penumbra_alphaTexture;") != std::string::npos,
                                      name_of(c), " ", p.name);
                        CHECK_MESSAGE(fragment.find("penumbra_alphaCutoff) discard;") != std::string::npos, name_of(c),
                                      " ", p.name);
                    } else {
                        CHECK_MESSAGE(fragment.find("penumbra_alpha") == std::string::npos, name_of(c), " ", p.name);
                    }
                }
                CHECK_MESSAGE(casters == (c.technique == Technique::oim ? 0 : places_slices_adaptively(c) ? 2 : 1),
                              name_of(c));
            },
            .check_row = [](const RowResult& r) { CHECK(r.valid == 4 * 2 * 10 + 3 * 2); }};
}

// Solid casters (solid_casters): every GLSL target × light, the slices as channels and as bits, with
// adaptive placement and with the cut. Valid on glsl450 and glsl330, refused on essl300 (no logic op) and
// vulkan (its runner does not switch the logic op per draw); only the slicing program changes.
Row solid_casters_row() {
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (Light light : all_values<Light>()) {
            auto with = [&](Config c) {
                c.light = light;
                c.target = target;
                c.solid_casters = true;
                configs.push_back(c);
            };
            with({.resolution = 256});
            with({.slices = 5, .resolution = 64, .filter = Filter::mipmap, .packing = Packing::array});
            with({.slices = 16, .resolution = 256, .slice_placement = SlicePlacement::adaptive});
            with({.slices = 64, .resolution = 32});
            Config cut{.slices = 8, .resolution = 128};
            cut.alpha_test = true;
            with(cut);
        }
    return {.name = "solid casters",
            .configurations = configs,
            .expect = [](const Config& c) {
                return c.target == Target::glsl450 || c.target == Target::glsl330 ? Expect::valid : Expect::refused;
            },
            .check_emission = [](const Config& c, const Emitted& e) {
                Config shells = c;
                shells.solid_casters = false;
                const Emitted without = emit_all(shells);
                REQUIRE(without.programs.size() == e.programs.size());
                for (std::size_t i = 0; i < e.programs.size(); ++i) {
                    const bool slicing = e.programs[i].name == "slicing";
                    const std::string fragment = e.programs[i].stages.back().text;
                    CHECK_MESSAGE((fragment.find("penumbra_casterClosed > 0.5") != std::string::npos) == slicing,
                                  name_of(c), " ", e.programs[i].name);
                    if (!slicing) CHECK_MESSAGE(fragment == without.programs[i].stages.back().text, name_of(c));
                }
            },
            .check_refusal = [](const Config& c, const Emitted& e) {
                CHECK_MESSAGE(std::any_of(e.errors.begin(), e.errors.end(),
                                          [](const ConfigError& error) { return error.field == "solid_casters"; }),
                              name_of(c));
            },
            .check_row = [](const RowResult& r) {
                CHECK(r.valid == 2 * 2 * 5);
                CHECK(r.refused == 2 * 2 * 5);
            }};
}

// The near field (near_field): every GLSL target × light, with and without the tangent clip, the irradiance
// window and its quadrants, 4 to 16 slices, the rectangle's filters and every packing. Valid on glsl450
// and glsl330, refused elsewhere (no emission of it yet); only the slicing program and the programs that
// compute the visibility change.
Row near_field_row() {
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (Light light : all_values<Light>()) {
            auto with = [&](Config c) {
                c.light = light;
                c.target = target;
                c.near_field = true;
                configs.push_back(c);
            };
            with({.resolution = 256});
            with({.resolution = 128, .irradiance_quadrants = true});
            with({.slices = 4, .resolution = 64, .tangent_clip = false});
            with({.slices = 7, .resolution = 64, .filter = Filter::mipmap, .packing = Packing::array});
            with({.slices = 8, .resolution = 64, .filter = Filter::sat, .fusion = Fusion::chained});
            with({.slices = 12, .resolution = 64, .packing = Packing::volume});
        }
    return {.name = "near field",
            .configurations = configs,
            .expect =
                [](const Config& c) {
                    return c.target == Target::glsl450 || c.target == Target::glsl330 ? Expect::valid
                                                                                      : Expect::refused;
                },
            .check_emission =
                [](const Config& c, const Emitted& e) {
                    Config without = c;
                    without.near_field = false;
                    const Emitted plain = emit_all(without);
                    REQUIRE(plain.programs.size() == e.programs.size());
                    for (std::size_t i = 0; i < e.programs.size(); ++i) {
                        const std::string fragment = e.programs[i].stages.back().text;
                        const bool marches = fragment.find("penumbra_nearField(") != std::string::npos;
                        const bool writes = fragment.find("penumbra_nearDepth0 = ") != std::string::npos;
                        CHECK_MESSAGE(writes == (e.programs[i].name == "slicing"), name_of(c), " ",
                                      e.programs[i].name);
                        if (!marches && !writes)
                            CHECK_MESSAGE(fragment == plain.programs[i].stages.back().text, name_of(c), " ",
                                          e.programs[i].name);
                    }
                },
            .check_refusal =
                [](const Config& c, const Emitted& e) {
                    CHECK_MESSAGE(
                        std::any_of(e.errors.begin(), e.errors.end(),
                                    [](const ConfigError& error) { return error.field == "near_field"; }),
                        name_of(c));
                },
            .check_row =
                [](const RowResult& r) {
                    CHECK(r.valid == 2 * 2 * 6);
                    CHECK(r.refused == 2 * 2 * 6);
                }};
}

// The irradiance window (irradiance_window): every GLSL target × light, with and without the tangent clip.
// Valid everywhere: under the rectangle with the clip only the programs that compute the visibility
// change, and they weigh it by the irradiance window; under the sun or without the clip it has no effect
// (every file is the text it is without it).
Row irradiance_window_row() {
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (Light light : all_values<Light>())
            for (bool clip : {true, false}) {
                auto with = [&](Config c) {
                    c.light = light;
                    c.target = target;
                    c.tangent_clip = clip;
                    c.irradiance_window = true;
                    configs.push_back(c);
                };
                with({.resolution = 256});
                with({.slices = 5, .resolution = 64, .filter = Filter::mipmap, .fusion = Fusion::clustered,
                      .packing = Packing::array});
                Config quadrants{.resolution = 256};
                quadrants.irradiance_quadrants = true; // its quadrants too (no effect without the window)
                with(quadrants);
            }
    return {
        .name = "irradiance window",
        .configurations = configs,
        .expect = [](const Config&) { return Expect::valid; },
        .check_emission =
            [](const Config& c, const Emitted& e) {
                Config whole = c;
                whole.irradiance_window = false;
                const Emitted without = emit_all(whole);
                REQUIRE(without.programs.size() == e.programs.size());
                if (!weighs_irradiance(c)) {
                    for (std::size_t i = 0; i < e.programs.size(); ++i)
                        for (std::size_t s = 0; s < e.programs[i].stages.size(); ++s)
                            CHECK_MESSAGE(e.programs[i].stages[s].text == without.programs[i].stages[s].text,
                                          name_of(c), " ", e.programs[i].name);
                    return;
                }
                // the header's configuration line names the window in every program
                auto body = [](std::string text) {
                    const std::size_t line = text.find(" | target ");
                    if (line != std::string::npos) text.erase(text.rfind('\n', line), text.find('\n', line) - text.rfind('\n', line));
                    return text;
                };
                int windowed = 0;
                for (std::size_t i = 0; i < e.programs.size(); ++i) {
                    const std::string fragment = e.programs[i].stages.back().text;
                    const bool calls = fragment.find("penumbra_irradianceWindow(p, n, penumbra_clip)") != std::string::npos;
                    windowed += calls;
                    if (!calls)
                        CHECK_MESSAGE(body(fragment) == body(without.programs[i].stages.back().text), name_of(c), " ",
                                      e.programs[i].name);
                }
                CHECK_MESSAGE(windowed >= 1, name_of(c));
                // the quadrants' shares where they are asked for, and only there
                for (const auto& program : e.programs) {
                    const std::string& fragment = program.stages.back().text;
                    if (fragment.find("penumbra_irradianceWindow(p, n, penumbra_clip)") == std::string::npos)
                        continue;
                    CHECK_MESSAGE(
                        (fragment.find("penumbra_ringShares(p, n, penumbra_clip, penumbra_window.xyz)") !=
                         std::string::npos) == c.irradiance_quadrants,
                        name_of(c), " ", program.name);
                }
            },
        .check_row = [](const RowResult& r) { CHECK(r.valid == 4 * 2 * 2 * 3); }};
}

// The profiles (penumbra/profiles.hpp): every GLSL target × light, at 256² (OpenGL 3.3 guarantees a
// 1024-texel atlas, too narrow for the default 512² with 16 slices). Each preset is valid everywhere;
// `balanced` is the default configuration itself (there at 256², given explicitly), `large` its own preset
// (the irradiance window's quadrants, the default fusion), `fast` its own (8 slices of 128², chained, by
// area).
Row profiles_row() {
    static constexpr std::array<std::string_view, 1> resolution_given{"resolution"};
    static constexpr std::span<const std::string_view> no_keys{};
    std::vector<Config> configs;
    for (Target target : glsl_targets())
        for (Light light : all_values<Light>())
            for (Profile profile : all_values<Profile>())
                configs.push_back(apply_profile({.resolution = 256, .light = light, .target = target},
                                                profile,
                                                profile == Profile::fast ? no_keys : resolution_given));
    return {.name = "profiles",
            .configurations = configs,
            .expect = [](const Config&) { return Expect::valid; },
            .check_emission =
                [](const Config& c, const Emitted&) {
                    const Config plain{.resolution = 256, .light = c.light, .target = c.target};
                    if (c.profile == Profile::balanced) {
                        CHECK_MESSAGE(c == plain, name_of(c));
                        return;
                    }
                    if (c.profile == Profile::fast) {
                        CHECK(c.slices == 8);
                        CHECK(c.resolution == 128);
                        CHECK(c.fusion == Fusion::chained);
                        CHECK_FALSE(c.irradiance_window);
                        CHECK_FALSE(c.irradiance_quadrants);
                        return;
                    }
                    CHECK(c.slices == plain.slices);
                    CHECK(c.fusion == plain.fusion);
                    CHECK(c.irradiance_window);
                    CHECK(c.irradiance_quadrants);
                },
            .check_row = [](const RowResult& r) { CHECK(r.valid == 4 * 2 * 3); }};
}

// --- the one check -------------------------------------------------------------------------------

// Emits every configuration of `row` and compiles and links each program with glslang for its
// target. A program text seen before (same stages, same text, same target) is not compiled again:
// glslang sees only the text, so a second compile would prove nothing new.
RowResult run_row(const Row& row) {
    RowResult r;
    std::set<std::string> compiled;
    for (const Config& config : row.configurations) {
        const Emitted emitted = row.emit_programs(config);
        const Expect expect = row.expect(config);
        if (emitted.programs.empty()) {
            CHECK_MESSAGE(expect != Expect::valid,
                          name_of(config) << ": " << (emitted.errors.empty() ? "" : emitted.errors[0].message));
            ++r.refused;
            if (row.check_refusal) row.check_refusal(config, emitted);
            continue;
        }
        CHECK_MESSAGE(expect != Expect::refused, name_of(config) << " should be refused");
        ++r.valid;
        r.valid_configs.push_back(config);
        if (row.check_emission) row.check_emission(config, emitted);
        for (const Program& program : emitted.programs) {
            ++r.programs;
            std::string key = std::to_string(static_cast<int>(config.target));
            for (const auto& stage : program.stages) key += "\n//" + stage.file_name + "\n" + stage.text;
            if (!compiled.insert(key).second) continue;
            const std::vector<ShaderDiagnostic> diagnostics = validate_program(program, config.target);
            if (has_errors(diagnostics)) {
                for (const ShaderDiagnostic& d : diagnostics) MESSAGE(name_of(config) << ": " << format(d));
                FAIL(name_of(config) << " program " << program.name << " does not compile");
            }
        }
    }
    r.compiled = static_cast<int>(compiled.size());
    return r;
}

} // namespace

TEST_CASE("the glslang matrix: every program of every valid configuration of each technique compiles and links") {
    const Row rows[] = {occlusion_row(),
                        tangent_clip_row(),
                        many_slices_row(),
                        adaptive_row(),
                        compute_prefilter_row(),
                        generic_row(),
                        shadow_map_row(),
                        erosion_row(),
                        evsm_row(),
                        smrt_row(),
                        oim_row(),
                        alpha_test_row(),
                        solid_casters_row(),
                        irradiance_window_row(),
                        near_field_row(),
                        profiles_row()};
    int configurations = 0, programs = 0, compiled = 0;
    for (const Row& row : rows) {
        CAPTURE(row.name);
        const auto start = std::chrono::steady_clock::now();
        const RowResult r = run_row(row);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("glslang matrix, %s: %zu configurations (%d valid, %d refused), %d programs (%d distinct "
                    "compiled), %.1f s\n",
                    row.name.c_str(), row.configurations.size(), r.valid, r.refused, r.programs, r.compiled, seconds);
        if (row.check_row) row.check_row(r);
        configurations += static_cast<int>(row.configurations.size());
        programs += r.programs;
        compiled += r.compiled;
    }
    std::printf("glslang matrix: %d configurations, %d programs, %d distinct compiled\n", configurations, programs,
                compiled);
}
