// GPU vs the CPU oracle (docs/model.md §4, question 1), pixel by pixel: the oracle gets only the slicing pass's
// read-back level 0 and builds its own filter, so any disagreement beyond what texture precision
// explains is a bug in the emitted GLSL or in the oracle. Label "gl".
//
// The bound is per pixel (Oracle::visibility, derived in oracle.cpp): the sum over the slices of
// fade weight × (storage rounding of the filtered texels read: l/255 at mip level l in RGBA8,
// l·2^-11 at N-buffer / Gaussian level l in RGBA16F, exact for texels at 0 or 1; plus 8-bit
// sub-texel weights, 2^-8 × the spread of the texels a fetch blends, or × the coverage along a
// summed-area window's edges; the same for the weight between two mip levels; plus fp32 coordinates),
// since every fusion rule is 1-Lipschitz in each slice's occlusion. The two weights' errors are
// measured on the renderer first (texture_precision.hpp) and the bound takes them where they are
// coarser than 2^-8. On llvmpipe the measured differences stay below a third of it.
#include "oracle_agreement.hpp"
#include "texture_precision.hpp"
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "reference/oracle.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>
#include <penumbra/validate.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <cstdio>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::playground;

namespace {

std::string describe_config(const Config& c) {
    return std::string(to_string(c.light)) + " " + std::string(to_string(c.filter)) + " " +
           std::string(to_string(c.fusion)) + " " + std::string(to_string(c.packing)) + " S=" + std::to_string(c.slices) +
           " R=" + std::to_string(c.resolution) + (c.leak_fix ? "" : " leak-fix-off") +
           (c.self_shadow_fade ? "" : " fade-off") + (c.tangent_clip ? " tangent-clip" : "") +
           (c.slice_placement == SlicePlacement::adaptive ? " adaptive" : "") +
           (c.level_reduction == Config{}.level_reduction ? "" : " level-reduction " + std::to_string(c.level_reduction)) +
           (c.solid_casters ? " solid-casters" : "");
}

// Every valid light × slices {4, 16} × resolution {64, 256} × filter × packing (fusion is
// varied separately: it changes the shading program, not the textures), plus the switches the
// matrix keeps on.
std::vector<Config> oracle_matrix() {
    std::vector<Config> configs;
    for (Light light : all_values<Light>())
        for (int slices : {4, 16})
            for (int resolution : {64, 256})
                for (Filter filter : all_values<Filter>())
                    for (Packing packing : all_values<Packing>()) {
                        const Config c{.slices = slices, .resolution = resolution, .filter = filter,
                                       .packing = packing, .light = light};
                        if (is_valid(c)) configs.push_back(c);
                    }
    configs.push_back({.slices = 16, .resolution = 64, .leak_fix = false});
    configs.push_back({.slices = 16, .resolution = 64, .self_shadow_fade = false});
    configs.push_back({.slices = 16, .resolution = 256, .filter = Filter::sat, .packing = Packing::array,
                       .self_shadow_fade = false});
    // the matrix above clips to the tangent plane (the default); the paper's whole-light kernels
    configs.push_back({.slices = 16, .resolution = 256, .tangent_clip = false});
    configs.push_back({.slices = 4, .resolution = 64, .filter = Filter::sat, .packing = Packing::array, .tangent_clip = false});
    configs.push_back({.slices = 16, .resolution = 256, .filter = Filter::mipmap, .tangent_clip = false});
    configs.push_back({.slices = 16, .resolution = 256, .filter = Filter::gaussian, .packing = Packing::volume,
                       .light = Light::sun, .tangent_clip = false});
    // more than 32 slices: sliced as bits (logic op OR), unpacked, then the same filters; the oracle
    // decodes the bits, so the unpack is checked through the visibility
    configs.push_back({.slices = 64, .resolution = 64, .filter = Filter::nbuffer, .packing = Packing::atlas,
                       .light = Light::rect, .leak_fix = true, .self_shadow_fade = true, .tangent_clip = false});
    configs.push_back({.slices = 64, .resolution = 64, .filter = Filter::mipmap, .packing = Packing::array,
                       .light = Light::rect, .leak_fix = false, .self_shadow_fade = true, .tangent_clip = true});
    configs.push_back({.slices = 128, .resolution = 64, .filter = Filter::sat, .packing = Packing::array,
                       .light = Light::rect, .leak_fix = true, .self_shadow_fade = true, .tangent_clip = true});
    configs.push_back({.slices = 128, .resolution = 64, .filter = Filter::gaussian, .packing = Packing::atlas,
                       .light = Light::sun, .leak_fix = true, .self_shadow_fade = true, .tangent_clip = false});
    // adaptive slice placement (paper §5): the GPU's boundaries, read back, place the oracle's slices;
    // the level loop (atlas N-buffers), the slice loop (array, volume, summed-area table), the fade
    // off, the tangent clip and the sun
    const SlicePlacement adaptive = SlicePlacement::adaptive;
    configs.push_back({.slices = 16, .resolution = 256, .filter = Filter::nbuffer, .packing = Packing::atlas,
                       .tangent_clip = false, .slice_placement = adaptive});
    configs.push_back({.slices = 16, .resolution = 256, .filter = Filter::nbuffer, .packing = Packing::atlas,
                       .tangent_clip = true, .slice_placement = adaptive});
    configs.push_back({.slices = 16, .resolution = 64, .filter = Filter::mipmap, .packing = Packing::array,
                       .self_shadow_fade = false, .tangent_clip = false, .slice_placement = adaptive});
    configs.push_back({.slices = 4, .resolution = 64, .filter = Filter::sat, .packing = Packing::array,
                       .tangent_clip = false, .slice_placement = adaptive});
    configs.push_back({.slices = 16, .resolution = 256, .filter = Filter::gaussian, .packing = Packing::volume,
                       .light = Light::sun, .tangent_clip = true, .slice_placement = adaptive});
    // reduced atlas levels (level_reduction): the matrix runs the default; every level halved
    // (0, the most offsets and scales), one halving from level 1, and every level at full resolution
    for (int reduction : {0, 1, -1}) {
        Config c{.slices = 16, .resolution = 256, .filter = Filter::nbuffer, .packing = Packing::atlas};
        c.level_reduction = reduction;
        configs.push_back(c);
    }
    Config reduced_sun{.slices = 16, .resolution = 256, .filter = Filter::gaussian, .packing = Packing::atlas,
                       .light = Light::sun};
    reduced_sun.level_reduction = 0;
    configs.push_back(reduced_sun);
    // solid casters: the boxes fill the slices between their surfaces (logic op XOR), as channels and as
    // bits; the oracle filters and fuses what the GPU sliced, so the fill reaches it through the slices
    for (int slices : {16, 64}) {
        Config solid{.slices = slices, .resolution = slices == 16 ? 256 : 64};
        solid.solid_casters = true;
        configs.push_back(solid);
    }
    return configs;
}

struct Shard {
    std::size_t index = 0, count = 1; // index from 0
    std::string error;
};
Shard oracle_shard(const char* text) {
    if (!text || !*text) return {};
    std::size_t k = 0, n = 0;
    char end = 0;
    if (std::sscanf(text, "%zu/%zu%c", &k, &n, &end) != 2 || n == 0 || k == 0 || k > n)
        return {0, 1, std::string("PENUMBRA_ORACLE_SHARD '") + text + "': expected K/N with 1 <= K <= N, e.g. 2/3"};
    return {k - 1, n, {}};
}

// The boxes scene with a 20-degree sun: the default sun (5x the real one) casts penumbrae under 2
// texels wide at R = 256, which reach only level 0 of the filters; this one reaches the upper
// Gaussian and N-buffer levels.
std::optional<Scene> boxes_under_a_wide_sun() {
    std::optional<Scene> scene = make_scene("boxes");
    if (scene) scene->sun.angular_diameter = 0.35;
    return scene;
}

} // namespace

TEST_CASE("oracle: GPU matches the CPU oracle within texture precision, every filter x fusion x packing") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const MeasuredTexturePrecision measured = measure_texture_precision();
    REQUIRE_MESSAGE(measured.error.empty(), measured.error);
    const TexturePrecision precision = measured.for_oracle();
    std::printf("oracle: bound with sub-texel weights off by %.2e, mip level weights by %.2e (measured %.2e, %.2e)\n",
                precision.sub_texel, precision.level_fraction, measured.sub_texel, measured.level_fraction);
    std::optional<Scene> scene = boxes_under_a_wide_sun();
    REQUIRE(scene);
    constexpr int image_size = 64;
    std::vector<Agreement> runs;
    // PENUMBRA_ORACLE_CONFIGS: only these configurations (';'-separated, named as describe_config names the
    // matrix's, with its default fusion: "rect mipmap extent array S=16 R=64 tangent-clip"). A GPU's compiler
    // may take minutes over the whole matrix; a session with little time on one runs the rows that failed.
    const char* only = std::getenv("PENUMBRA_ORACLE_CONFIGS");
    const std::string wanted = only ? std::string(";") + only + ";" : "";
    // PENUMBRA_ORACLE_SHARD=K/N: only the configurations whose index in the matrix is K-1 modulo N, so
    // that ctest runs the matrix as N parts side by side (tests/runtime/CMakeLists.txt).
    const Shard shard = oracle_shard(std::getenv("PENUMBRA_ORACLE_SHARD"));
    REQUIRE_MESSAGE(shard.error.empty(), shard.error);
    std::size_t chosen = 0, index = 0;
    for (const Config& base : oracle_matrix()) {
        if (index++ % shard.count != shard.index) continue;
        if (only && wanted.find(";" + describe_config(base) + ";") == std::string::npos) continue;
        ++chosen;
        std::optional<Oracle> oracle;
        SliceTextures oracle_input;
        for (Fusion fusion : all_values<Fusion>()) {
            Config config = base;
            config.fusion = fusion;
            GpuRun run;
            const bool rendered = render_for_oracle(*scene, config, image_size, run, &error);
            CHECK_MESSAGE(rendered, describe_config(config), ": ", error);
            if (!rendered) continue;
            // The filter does not depend on the fusion: one oracle serves the four rules, as long
            // as the slicing pass wrote the same textures (it is deterministic).
            // the runtime fitted level_bound to the light: the oracle builds the same levels
            CHECK_MESSAGE((run.config.filter == Filter::sat || run.config.level_bound >= 0), describe_config(config));
            if (!oracle) {
                oracle.emplace(run.config, run.frame, run.slices, run.boundaries, precision);
                oracle_input = std::move(run.slices);
            } else {
                CHECK_MESSAGE(run.slices.coverage == oracle_input.coverage, describe_config(config),
                              ": the slicing output changed with the fusion rule");
            }
            Agreement a = agreement(*oracle, run.result, config.fusion, describe_config(config));
            a.level_bound = run.config.level_bound;
            std::printf("oracle %-44s max %.2e mean %.2e  bound max %.2e  worst diff/bound %.3f  beyond %zu/%zu  "
                        "penumbra %zu  level bound %d (over it %zu)\n",
                        a.name.c_str(), a.max_difference, a.mean_difference, a.max_bound, a.worst_ratio,
                        a.beyond_bound, a.pixels, a.penumbra_pixels, a.level_bound, a.beyond_level_bound);
            CHECK_MESSAGE(a.beyond_level_bound == 0, a.name, ": ", a.beyond_level_bound,
                          " pixels asked for a level above the fitted level_bound ", a.level_bound);
            CHECK_MESSAGE(a.beyond_bound == 0, a.name, ": ", a.beyond_bound, " pixels beyond the bound, max |diff| ",
                          a.max_difference, "; the worst, ", a.worst);
            // (the small sun's additive penumbrae with the clip: 37 pixels of 64², measured)
            CHECK_MESSAGE(a.penumbra_pixels > 30, a.name, ": too few penumbra pixels for a meaningful comparison");
            runs.push_back(a);
        }
    }
    REQUIRE_MESSAGE(chosen > 0, "PENUMBRA_ORACLE_CONFIGS names none of the matrix's configurations: '", std::string(only),
                    "' (the names are printed by a run without it, with the fusion the matrix starts from, ",
                    to_string(Config{}.fusion), ")");
    std::sort(runs.begin(), runs.end(), [](const Agreement& x, const Agreement& y) { return x.max_difference > y.max_difference; });
    std::printf("oracle: %zu configurations (%zu of the matrix's %zu, shard %zu/%zu) on %s; largest max |GPU - oracle|:\n",
                runs.size(), chosen, index, shard.index + 1, shard.count, context->renderer().c_str());
    for (std::size_t i = 0; i < std::min<std::size_t>(5, runs.size()); ++i)
        std::printf("  %-44s max %.2e mean %.2e (bound there up to %.2e)\n", runs[i].name.c_str(), runs[i].max_difference,
                    runs[i].mean_difference, runs[i].max_bound);
}

// The atlas's N-buffer and Gaussian levels themselves, read back texel by texel against the
// oracle's (which builds every level from the rounded one below and keeps the reduced levels'
// subsample): the packing pass that also writes level 1, the level passes at full and reduced
// resolution. RGBA16F: equal up to level 5 (N-buffer means of level l are multiples of 4^-l, exact
// in half floats up to 2^-10), then within l - 5 units of 2^-11 (the oracle does not round half
// floats). RGBA8: equal, or one unit off where the exact mean lies on a rounding tie (the GPU's fp32
// sum of rounded texels against the oracle's double; GL lets a conversion pick either neighbour). A
// tie rounded the other way carries into the next level's mean, so level l may be up to l units off
// (an NVIDIA H200: 31 and 336 texels two units off at levels 5 and 6 of every level at full
// resolution, a thousandth of their fractional texels; llvmpipe: none); the check allows l units,
// and more than one on at most a hundredth of a level's fractional texels.
TEST_CASE("oracle: the GPU's atlas filter levels equal the oracle's, texel by texel") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    std::optional<Scene> scene = boxes_under_a_wide_sun();
    REQUIRE(scene);
    std::vector<Config> configs;
    for (int reduction : {2, 0, -1}) {
        Config c{.slices = 16, .resolution = 256};
        c.level_reduction = reduction;
        configs.push_back(c);
    }
    Config half{.slices = 16, .resolution = 256};
    half.level_format = LevelFormat::rgba16f;
    configs.push_back(half);
    configs.push_back({.slices = 16, .resolution = 256, .filter = Filter::gaussian, .light = Light::sun});
    for (const Config& config : configs) {
        GpuRun run;
        std::vector<std::vector<float>> levels; // [level]: the atlas texture, RGBA, T * side x side
        RenderOptions options{.inspect = [&](const gl::Runtime& runtime) {
            read_slice_textures(runtime, run.slices, &error);
            run.frame = runtime.frame();
            run.config = runtime.config();
            for (int l = 0; l <= max_level(run.config); ++l) {
                const int side = run.config.resolution / level_spacing(run.config, l);
                std::vector<float>& texels = levels.emplace_back(std::size_t(4) * texture_count(run.config) * side * side);
                glGetTextureImage(runtime.texture("penumbra_level" + std::to_string(l)), 0, GL_RGBA, GL_FLOAT,
                                  static_cast<GLsizei>(texels.size() * sizeof(float)), texels.data());
            }
        }};
        REQUIRE_MESSAGE(render_headless(*scene, config, 64, 64, run.result, &error, options), error);
        REQUIRE(glGetError() == GL_NO_ERROR);
        const Oracle oracle(run.config, run.frame, run.slices);
        const bool rgba8 = config.level_format == LevelFormat::rgba8;
        const int T = texture_count(run.config);
        for (int l = 0; l < static_cast<int>(levels.size()); ++l) {
            const int side = run.config.resolution / level_spacing(run.config, l);
            std::size_t texels = 0, off_by_one = 0, beyond = 0, fractional = 0, carried = 0;
            for (int slice = 0; slice < run.config.slices; ++slice) {
                REQUIRE(oracle.level_side(slice, l) == side);
                const int t = slice / 4, c = slice % 4;
                for (int y = 0; y < side; ++y)
                    for (int x = 0; x < side; ++x) {
                        const double gpu = levels[l][4 * (std::size_t(y) * T * side + std::size_t(t) * side + x) + c];
                        const double expected = oracle.level_texel(slice, l, x, y);
                        const double units = std::abs(gpu - expected) * (rgba8 ? 255.0 : 2048.0);
                        ++texels;
                        fractional += expected > 0.0 && expected < 1.0;
                        off_by_one += units > 1e-3;
                        beyond += units > (rgba8 ? std::max(l, 1) : std::max(l - 5, 0)) + 1e-3;
                        carried += rgba8 && units > 1.0 + 1e-3;
                    }
            }
            std::printf("levels %-40s level %d (%d texels per side): %zu texels, %zu between 0 and 1, %zu off (%zu by more "
                        "than a unit), %zu beyond\n",
                        describe_config(config).c_str(), l, side, texels, fractional, off_by_one, carried, beyond);
            CHECK_MESSAGE(beyond == 0, describe_config(config), " level ", l, ": ", beyond, " texels off the oracle's");
            CHECK_MESSAGE(carried <= fractional / 100, describe_config(config), " level ", l, ": ", carried,
                          " texels more than a unit off the oracle's");
            // the slicing output has penumbrae: the levels above 0 have fractional texels to compare (100, or
            // an eighth of a level of fewer than 800 texels: the top one at level_reduction 0, 4 x 4 per slice)
            if (l > 0) CHECK_MESSAGE(fractional > std::min<std::size_t>(100, texels / 8), describe_config(config), " level ", l);
        }
    }
}
