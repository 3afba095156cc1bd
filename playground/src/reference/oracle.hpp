// playground/src/reference/oracle.hpp — the CPU oracle: the model of docs/model.md §1–2 in double precision.
//
// Answers "does the emitted GLSL compute the model?" (docs/model.md §4, question 1). Its only GPU input is the
// slicing pass's level-0 output (binary coverage, read back); from it the oracle builds its own
// filter (mip chain, N-buffers, summed-area table or Gaussian levels), then evaluates, for a world
// point, every slice's kernel, filtered occlusion, self-shadow fade and the fusion rule. Texture
// sampling is emulated in double (bilinear / trilinear, border 0 outside a texture, atlas tiles
// side by side), following the conventions the emitter documents:
//   - N-buffer level l at a texel = mean of the 2^l window anchored there, zero outside the tile;
//     a window centred at c is read at c − (2^(l−1) − 0.5)/R; linear between levels;
//   - the volume packing reads both levels at one position (the anchor follows the fractional
//     level) and the hardware interpolates between them;
//   - summed-area table: exact box mean of the window clipped to the texture, window ≥ 1 texel;
//   - Gaussian level l = level l−1 blurred by [1 2 1]⊗[1 2 1]/16 with taps 2^(l−1) apart,
//     read at level log2(side) + log2(√6/4);
//   - atlas packing: the T textures of one level side by side, so a read past a tile's left or
//     right edge lands in the neighbouring tile (that is what the GPU does, see oracle.cpp).
//
// Each value comes with a bound on |GPU − oracle| that texture precision explains (oracle.cpp
// derives it): storage rounding of filtered levels, 8-bit sub-texel weights, fp32 coordinates.
#pragma once

#include <penumbra/config.hpp>
#include <penumbra/light_frame.hpp>

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace penumbra::gl {
class Runtime;
}

namespace penumbra::playground {

// The slicing pass's output: one R×R binary coverage plane per slice.
struct SliceTextures {
    int resolution = 0;
    int slices = 0;
    std::vector<float> coverage; // slice-major; rows from v = 0 (GL's first row) up; texel (x, y)
    // near_field: per slice the nearest depth the slicing pass kept (penumbra_nearDepth: 1 − f·254/255 from
    // the slice's top, 0 where empty), laid out as `coverage`; empty without the near field
    std::vector<float> near_depth;

    float at(int slice, int x, int y) const {
        return coverage[(static_cast<std::size_t>(slice) * resolution + y) * resolution + x];
    }
};

// Reads the level-0 render targets of the slicing pass of a runtime that has run build() (call
// it from RenderOptions::inspect), with the near field's depths where it has them; beyond 32 slices, decodes
// the bits of its RGBA32UI target (the unpack pass that follows is then checked through the filtered
// visibility). Returns false with *error set when the layout has no slicing pass or a read fails.
bool read_slice_textures(const penumbra::gl::Runtime& runtime, SliceTextures& out, std::string* error);

// Adaptive slice placement: reads the S + 1 slice boundaries (penumbra_sliceBoundaries, scene units)
// the GPU computed; leaves `out` empty when the layout places slices uniformly. Returns false with
// *error set when a read fails.
bool read_slice_boundaries(const penumbra::gl::Runtime& runtime, std::vector<float>& out, std::string* error);

// Clustered fusion (docs/model.md §1.7.3): how many occluders share a kernel's covered area, from its four
// quadrants' coverage (lower left, lower right, upper left, upper right); at least one. The double-precision
// twin of the emitted penumbra_clusterCount.
double cluster_count(glm::dvec4 quadrants);

struct OracleValue {
    double visibility = 1.0;
    double bound = 0.0; // |GPU − oracle| that texture precision explains at this point
    // a slice with weight > 0 asked for a filter level above config.level_bound (and got that level):
    // the bound was too small for this receiver (penumbra/level_bound.hpp)
    bool beyond_level_bound = false;
};

// What the renderer's texture units round, as fractions: the weight between two texels of a bilinear fetch
// (and between a volume's depth slices), and the weight between two mip levels of a trilinear fetch. GL
// leaves both to the implementation; 2^-8 is what GPUs have long used, llvmpipe included, but a renderer
// may round more coarsely or skip the blend near whole levels: the GL tests measure both
// (tests/runtime/gl/texture_precision.hpp) and pass what they find here.
struct TexturePrecision {
    double sub_texel = 1.0 / 256.0;
    double level_fraction = 1.0 / 256.0;
};

class Oracle {
public:
    // Builds the filter of `config` from `slices`. Precondition: the slices match the config's
    // slice count and resolution (the constructor checks and throws std::invalid_argument).
    // `boundaries`: the S + 1 slice boundaries of adaptive placement (read_slice_boundaries); empty:
    // the uniform slices of frame.slice_depths.
    // `precision`: what the bound assumes the texture units round.
    Oracle(const Config& config, const SliceFrame& frame, SliceTextures slices, std::vector<float> boundaries = {},
           TexturePrecision precision = {});

    OracleValue visibility(glm::vec3 world) const { return visibility(world, config_.fusion); }
    // The same with another fusion rule (the filter does not depend on it).
    OracleValue visibility(glm::vec3 world, Fusion fusion) const { return visibility(world, glm::vec3(0.0f), fusion); }
    // With tangent_clip on: `normal` is the normal of the side being lit (ignored when it is off).
    OracleValue visibility(glm::vec3 world, glm::vec3 normal, Fusion fusion) const;

    // Every slice's faded occlusion q_k = w_k · o_k at a world point, slice 0 (nearest the light)
    // first: what the fusion rules combine. For diagnostics and studies of new rules.
    std::vector<double> occlusions(glm::vec3 world) const;
    // The lookups visibility(world, normal, ·) makes, slice by slice as text: the weight, the kernel's centre
    // and side in texels after the tangent clip (its part of the light; the irradiance window's core is not
    // listed), and for the level filters the level λ and the values of levels ⌊λ⌋ and ⌊λ⌋ + 1 alone; slices
    // with nothing to read are left out. For the failure messages of tests on renderers nobody here can run.
    std::string describe_lookups(glm::vec3 world, glm::vec3 normal) const;

    // Filtered occlusion of one slice for a kernel (centre in uv, side in uv), with its bound;
    // exposed for diagnostics and for the exact-answer tests.
    struct Sample {
        double value = 0.0;
        double bound = 0.0;
        bool clamped = false; // the kernel's level was above the highest built one (level_bound)
    };
    Sample filtered(int slice, glm::dvec2 centre, double side) const;

    // Texel (x, y) of one slice's filter level as the oracle stores it (mip chains and reduced
    // levels at their own size, level_side texels per side), for the tests that compare the GPU's
    // levels texel by texel. Not for summed-area tables.
    double level_texel(int slice, int level, int x, int y) const { return levels_[slice][level].at(x, y); }
    int level_side(int slice, int level) const { return levels_[slice][level].width; }

private:
    struct Plane {
        int width = 0, height = 0;
        std::vector<double> texels;
        double at(int x, int y) const { return texels[static_cast<std::size_t>(y) * width + x]; }
    };

    // The kernel square on the plane at depth zeta for the light-frame point p: centre and side in
    // the slice texture's uv (before the tangent clip).
    struct Kernel {
        glm::dvec2 centre;
        double side = 0;
    };
    // A world point in the light frame, kept in front of the light plane.
    glm::dvec3 light_point(glm::vec3 world) const;
    // A receiver as the lookups see it (the tangent clip, detail/occlusion/emit_visibility.hpp): the point
    // moved off its own texels, the part of the light's unit square above its tangent plane (centre, side; the
    // whole square when the clip is off), whether fp32 may cut along the other axis, and the point before the
    // move and the normal in the light frame, which the irradiance window weighs.
    struct Receiver {
        glm::dvec3 point{0.0};
        glm::dvec3 clip{0.0, 0.0, 1.0};
        bool clip_ambiguous = false;
        glm::dvec3 unmoved{0.0}, normal{0.0};
    };
    Receiver receiver(glm::vec3 world, glm::vec3 normal) const;
    Kernel kernel(glm::dvec3 p, double zeta) const;
    // near_field (penumbra_nearField, detail/occlusion/emit_near_field.hpp): the fraction of the rays from p
    // towards the part `part` of the light that no stored surface within the reach blocks; the bound counts
    // the rays whose verdict fp32 may turn (a point on a texel's edge, a slice's plane, or a surface's
    // depth).
    OracleValue near_field(glm::dvec3 p, glm::dvec3 part) const;
    // The filter level a window of `side` (uv) reads, clamped to the levels built, and the unclamped one.
    struct Level {
        double level = 0, wanted = 0;
    };
    Level level_for(double side) const;
    double zeta(int slice) const { return planes_[slice + 1]; } // the slice's bottom plane
    double fade_weight(double z, int slice) const;

    void build_levels(const SliceTextures& slices);
    double stored(int slice, int level, int x, int y) const;
    double storage_error(int level) const;
    Sample bilinear(int slice, int level, glm::dvec2 texel_coords) const;
    Sample filtered_at(int slice, glm::dvec2 centre, double level, int lo, double t) const;
    // `fraction_error`: how far the hardware's weight t may be off (0 for a mix in the shader)
    Sample mix_levels(const Sample& lo, const Sample& hi, double t, double fraction_error) const;
    Sample box_filtered(int slice, glm::dvec2 centre, double side) const;
    double prefix(int slice, glm::dvec2 corner) const;

    Config config_;
    TexturePrecision precision_;
    glm::dmat4 light_from_world_{1.0};
    double cop_distance_ = 0, window_half_size_ = 0, tan_angular_radius_ = 0;
    glm::dvec2 light_size_{0.0};
    std::vector<double> planes_;         // the S + 1 slice boundaries: slice s holds depths (planes_[s], planes_[s + 1]]
    std::vector<double> fade_thickness_; // [slice]: the depth over which its plane's fade ramps
    double thickness_ = 0;               // penumbra_sliceDepths.y: the uniform slices' thickness
    int levels_top_ = 0;                      // L: log2(R), or config.level_bound when set
    std::vector<std::vector<Plane>> levels_;  // [slice][level]: mip chain, N-buffer or Gaussian levels
    std::vector<Plane> prefix_;               // [slice]: (R+1)² table, texel (X, Y) = sum over x < X, y < Y
    std::vector<float> near_depth_;           // near_field: SliceTextures::near_depth
};

} // namespace penumbra::playground
