// The slicing pass on the "planes" scene (docs/model.md §1, paper §3.4), where the expected occlusion
// textures are known exactly: each triangle, projected from the slicing camera, covers the texel
// centres inside it, in the slice of its depth (and the next one with the leak fix; the CPU's
// slicing, reference/slice_coverage.hpp). The oracle
// test builds on this output, so it is checked on its own here. Label "gl".
#include "rendering/egl_context.hpp"
#include "rendering/headless_render.hpp"
#include "reference/oracle.hpp"
#include "reference/slice_coverage.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace penumbra;
using namespace penumbra::playground;

namespace {

// The CPU's slicing (reference/slice_coverage.hpp): texels near an edge or a slice boundary may go either way.
using Expect = Coverage;

SliceCoverage expected_slices(const Mesh& mesh, const Config& config, const SliceFrame& frame, int reach) {
    return cpu_slice_coverage(mesh, config, frame, reach, /*cut=*/false);
}

// One texel's column, slice 0 (nearest the light) first, as a failure's message needs it on a renderer
// nobody here can run: the GPU's slices (1 covered, 0 empty), the CPU's (? either way), and the CPU's
// surfaces alone, without the solid fill.
std::string describe_column(const SliceTextures& gpu, const SliceCoverage& expected, const SliceCoverage& surfaces,
                            int slice, int x, int y) {
    std::string g, e, f;
    for (int k = 0; k < expected.slices; ++k) {
        g += gpu.at(k, x, y) == 1.0f ? '1' : gpu.at(k, x, y) == 0.0f ? '0' : 'x';
        e += "0?1"[static_cast<int>(expected.at(k, x, y))];
        f += "0?1"[static_cast<int>(surfaces.at(k, x, y))];
    }
    return "slice " + std::to_string(slice) + " of texel " + std::to_string(x) + "," + std::to_string(y) + ": GPU " + g +
           ", CPU " + e + ", its surfaces alone " + f;
}

} // namespace

TEST_CASE("slicing: planes, the occlusion textures are the analytic coverage of each slice") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const std::optional<Scene> scene = make_scene("planes");
    REQUIRE(scene);
    // Storage differs per layout (slice array, level array, volumes, mip chain): read back from each.
    const std::vector<Config> configs{
        {.slices = 4, .resolution = 128, .packing = Packing::atlas, .leak_fix = true},
        {.slices = 4, .resolution = 128, .packing = Packing::atlas, .leak_fix = false},
        {.slices = 16, .resolution = 256, .packing = Packing::volume, .leak_fix = true},
        {.slices = 16, .resolution = 64, .filter = Filter::mipmap, .packing = Packing::array, .leak_fix = false},
        {.slices = 4, .resolution = 128, .packing = Packing::array, .light = Light::sun, .leak_fix = true},
        {.slices = 16, .resolution = 128, .filter = Filter::sat, .packing = Packing::array, .light = Light::sun,
         .leak_fix = false},
        {.slices = 16, .resolution = 256, .filter = Filter::gaussian, .packing = Packing::volume, .light = Light::sun,
         .leak_fix = true},
        // more than 32 slices (paper §3.7): bits of one RGBA32UI target, decoded by read_slice_textures
        {.slices = 64, .resolution = 128, .packing = Packing::atlas, .leak_fix = true},
        {.slices = 128, .resolution = 64, .filter = Filter::mipmap, .packing = Packing::array, .light = Light::sun,
         .leak_fix = false},
    };
    for (const Config& config : configs) {
        const std::string name = std::string(to_string(config.light)) + " S=" + std::to_string(config.slices) +
                                 " R=" + std::to_string(config.resolution) + " " + std::string(to_string(config.filter)) +
                                 " " + std::string(to_string(config.packing)) + (config.leak_fix ? " leak fix" : " no leak fix");
        SliceTextures gpu;
        SliceFrame frame;
        bool read = false;
        std::size_t unpacked = 0, unpack_wrong = 0;
        RenderOptions options{.inspect = [&](const gl::Runtime& runtime) {
            read = read_slice_textures(runtime, gpu, &error);
            frame = runtime.frame();
            // the unpack draws' outputs: slice firstSlice + 4i + c in channel c of attachment i, as the bits say
            const int R = config.resolution;
            std::vector<float> rgba(static_cast<std::size_t>(4) * R * R);
            for (const PassDesc& pass : runtime.emission().layout.passes) {
                if (pass.program != "unpack_slices" || !read) continue;
                for (std::size_t i = 0; i < pass.outputs.size(); ++i) {
                    const AttachmentDesc& out = pass.outputs[i];
                    glGetTextureSubImage(runtime.texture(out.texture), out.level, 0, 0, std::max(out.layer, 0), R, R, 1,
                                         GL_RGBA, GL_FLOAT, static_cast<GLsizei>(rgba.size() * sizeof(float)), rgba.data());
                    for (int c = 0; c < 4; ++c) {
                        const int slice = pass.int_uniforms.at(0).second + 4 * static_cast<int>(i) + c;
                        for (int texel = 0; texel < R * R; ++texel)
                            unpack_wrong += rgba[4 * texel + c] != gpu.at(slice, texel % R, texel / R);
                        ++unpacked;
                    }
                }
            }
        }};
        HeadlessResult result;
        REQUIRE_MESSAGE(render_headless(*scene, config, 16, 16, result, &error, options), name, ": ", error);
        REQUIRE_MESSAGE(read, name, ": ", error);
        SliceCoverage expected = expected_slices(scene->mesh, config, frame, leak_fix_reach(config));
        // The texels where the leak fix makes a difference: they must follow the configuration.
        Config toggled = config;
        toggled.leak_fix = !config.leak_fix;
        SliceCoverage other = expected_slices(scene->mesh, config, frame, leak_fix_reach(toggled));

        const int R = config.resolution;
        std::size_t non_binary = 0, wrong = 0, covered = 0, leak_texels = 0, leak_marked = 0;
        std::vector<std::size_t> covered_per_slice(config.slices, 0);
        for (int s = 0; s < config.slices; ++s)
            for (int y = 0; y < R; ++y)
                for (int x = 0; x < R; ++x) {
                    const float g = gpu.at(s, x, y);
                    non_binary += g != 0.0f && g != 1.0f;
                    const Expect e = expected.at(s, x, y), o = other.at(s, x, y);
                    if (e == Expect::covered) ++covered_per_slice[s];
                    covered += e == Expect::covered;
                    wrong += (e == Expect::covered && g != 1.0f) || (e == Expect::empty && g != 0.0f);
                    if ((e == Expect::covered && o == Expect::empty) || (e == Expect::empty && o == Expect::covered)) {
                        ++leak_texels;
                        leak_marked += g == 1.0f;
                    }
                }
        std::printf("slicing %-44s covered texels %zu, wrong %zu, leak-fix texels %zu (marked %zu)\n", name.c_str(),
                    covered, wrong, leak_texels, leak_marked);
        CHECK_MESSAGE(non_binary == 0, name, ": slicing output must be binary");
        CHECK_MESSAGE(unpacked == (slices_as_bits(config) ? static_cast<std::size_t>(config.slices) : 0u), name,
                      ": the unpack draws wrote ", unpacked, " slices");
        CHECK_MESSAGE(unpack_wrong == 0, name, ": ", unpack_wrong, " unpacked texels differ from the sliced bits");
        CHECK_MESSAGE(wrong == 0, name, ": ", wrong, " texels disagree with the analytic coverage away from edges");
        // Four planes at four heights (ground included): under the rect light each has its own slice;
        // under the tilted sun the ground spans several slices and two occluders may share one.
        const auto occupied = std::count_if(covered_per_slice.begin(), covered_per_slice.end(), [](std::size_t n) { return n > 0; });
        CHECK_MESSAGE(occupied >= (config.light == Light::rect ? 4 : 3), name, ": only ", occupied, " slices hold geometry");
        // The occluders above the ground: the leak fix marks their footprint in the next slice too.
        CHECK_MESSAGE(leak_texels > 100, name, ": the leak fix should matter on planes");
        CHECK_MESSAGE(leak_marked == (config.leak_fix ? leak_texels : 0), name, ": leak fix ",
                      config.leak_fix ? "on, but the next slice is not marked" : "off, but the next slice is marked");
    }
}

// Adaptive slice placement (paper §5): on the "planes" scene the geometry occupies four depths only
// (the ground and three horizontal occluders), so the boundaries the GPU computes from its depth bins
// must crowd there: half the depth weight goes to the few occupied bins, the other half keeps every
// slice at most twice the uniform thickness. The ends stay the bounds' range.
TEST_CASE("adaptive slice placement: the GPU's boundaries gather at the depths the geometry occupies") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    std::optional<Scene> scene = make_scene("planes");
    REQUIRE(scene);
    for (const bool tangent_clip : {false, true}) {
        const Config config{.slices = 16, .resolution = 128, .filter = Filter::nbuffer, .fusion = Fusion::chained,
                            .packing = Packing::atlas, .tangent_clip = tangent_clip,
                            .slice_placement = SlicePlacement::adaptive};
        std::vector<float> boundaries;
        SliceFrame frame;
        bool read = false;
        RenderOptions options{.inspect = [&](const gl::Runtime& runtime) {
            read = read_slice_boundaries(runtime, boundaries, &error);
            frame = runtime.frame();
        }};
        HeadlessResult result;
        REQUIRE_MESSAGE(render_headless(*scene, config, 64, 64, result, &error, options), error);
        REQUIRE_MESSAGE(read, error);
        REQUIRE(boundaries.size() == 17);
        const double z0 = frame.slice_depths.x, thickness = frame.slice_depths.y, bin = 16 * thickness / depth_bins;
        CHECK(boundaries.front() == doctest::Approx(z0).epsilon(1e-6));
        CHECK(boundaries.back() == doctest::Approx(z0 + 16 * thickness).epsilon(1e-6));
        for (int k = 0; k < 16; ++k) {
            CHECK_MESSAGE(boundaries[k + 1] > boundaries[k], "boundary ", k + 1, " is not below boundary ", k);
            CHECK_MESSAGE(boundaries[k + 1] - boundaries[k] <= 2.0 * thickness * (1 + 1e-4), "slice ", k, " is ",
                          (boundaries[k + 1] - boundaries[k]) / thickness, " uniform thicknesses thick");
        }
        // every occupied depth (each plane's light-frame z) has at least two boundaries within a bin's
        // width of it; the uniform slices put at most one there
        const glm::dmat4 light_from_world(frame.light_from_world);
        std::vector<double> depths{(light_from_world * glm::dvec4(0.0, 0.0, 0.0, 1.0)).z};
        for (float h : planes_occluder_heights) depths.push_back((light_from_world * glm::dvec4(0.0, h, 0.0, 1.0)).z);
        for (double depth : depths) {
            int near = 0;
            for (float b : boundaries) near += std::abs(b - depth) <= bin;
            CHECK_MESSAGE(near >= 2, "only ", near, " boundaries within a bin of depth ", depth);
            CHECK(2 * bin < thickness); // the uniform slices are thicker than the window
        }
    }
}

// solid_casters: on "boxes" (closed boxes, some floating, on an open ground) a closed part fills the slices
// between where the slicing camera's rays enter and leave it, as the CPU's parity says; the ground is
// marked as a surface. Without solid_casters the same texels hold only the boxes' tops and bottoms.
TEST_CASE("slicing: solid casters fill the slices between a closed mesh's surfaces") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    const std::optional<Scene> scene = make_scene("boxes");
    REQUIRE(scene);
    const std::vector<Config> configs{
        {.slices = 16, .resolution = 128, .packing = Packing::atlas},
        {.slices = 8, .resolution = 128, .packing = Packing::array, .light = Light::sun, .leak_fix = false},
        // more than 32 slices: the XOR on the bits of one RGBA32UI target
        {.slices = 64, .resolution = 64, .packing = Packing::atlas},
    };
    for (Config config : configs) {
        config.solid_casters = true;
        const std::string name = std::string(to_string(config.light)) + " S=" + std::to_string(config.slices) + " " +
                                 std::string(to_string(config.packing));
        SliceTextures gpu;
        SliceFrame frame;
        bool read = false;
        RenderOptions options{.inspect = [&](const gl::Runtime& runtime) {
            read = read_slice_textures(runtime, gpu, &error);
            frame = runtime.frame();
        }};
        HeadlessResult result;
        REQUIRE_MESSAGE(render_headless(*scene, config, 16, 16, result, &error, options), name, ": ", error);
        REQUIRE_MESSAGE(read, name, ": ", error);
        const SliceCoverage expected = expected_slices(scene->mesh, config, frame, leak_fix_reach(config));
        Config shells = config;
        shells.solid_casters = false;
        const SliceCoverage surfaces = expected_slices(scene->mesh, shells, frame, leak_fix_reach(config));
        const int R = config.resolution;
        std::size_t wrong = 0, filled = 0, filled_marked = 0;
        std::string first_wrong;
        for (int s = 0; s < config.slices; ++s)
            for (int y = 0; y < R; ++y)
                for (int x = 0; x < R; ++x) {
                    const float g = gpu.at(s, x, y);
                    const Expect e = expected.at(s, x, y);
                    const bool bad = (e == Expect::covered && g != 1.0f) || (e == Expect::empty && g != 0.0f);
                    if (bad && wrong++ == 0) first_wrong = describe_column(gpu, expected, surfaces, s, x, y);
                    if (e == Expect::covered && surfaces.at(s, x, y) == Expect::empty) {
                        ++filled;
                        filled_marked += g == 1.0f;
                    }
                }
        std::printf("solid slicing %-24s texels filled inside the boxes %zu (marked %zu), wrong %zu\n", name.c_str(),
                    filled, filled_marked, wrong);
        CHECK_MESSAGE(wrong == 0, name, ": ", wrong, " texels disagree with the CPU's parity away from edges; the first, ",
                      first_wrong);
        CHECK_MESSAGE(filled > 100, name, ": only ", filled,
                      " texels inside the boxes, the fill should matter on boxes");
        CHECK_MESSAGE(filled_marked == filled, name, ": ", filled - filled_marked, " texels inside the boxes not marked");
    }
}
