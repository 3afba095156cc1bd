// playground/src/reference/oracle.cpp — the CPU oracle (see oracle.hpp), and its error bound.
//
// Why the GPU may differ from the oracle, per filtered lookup (all of it texture precision):
//   1. storage: filtered levels are stored rounded (level_format: RGBA8 or RGBA16F levels, RGBA8
//      mip chains, RGBA32F summed-area tables) and each level is built from the rounded previous
//      one, so a texel of level l is off by at most l units of the format's last place (1/255
//      for RGBA8, 2^-11 relative for half floats, i.e. ≤ 2^-11 for values ≤ 1). Texels whose
//      exact value is 0 or 1 are exact (a mean of zeros or of ones rounds to itself). RGBA8
//      N-buffer and Gaussian levels are modelled: the oracle rounds each level to the nearest
//      1/255 before building the next, so what is left is the GPU's fp32 sum at a rounding tie.
//   2. bilinear weights: GPUs quantize the sub-texel fraction, usually to 8 bits, so each weight is
//      off by up to δ (TexturePrecision::sub_texel, 2^-8 unless measured coarser); a bilinear fetch
//      is then off by ≤ (2δ + δ²)·(max − min of its 4 texels). The same δ applies to the volume's
//      depth: ≤ δ·|slice lo − slice hi|. The hardware's fraction between two mip levels (mipmap
//      trilinear) has its own, δ_λ (TexturePrecision::level_fraction): ≤ δ_λ·|level lo − level hi|.
//   3. fp32 coordinates: kernel centres and N-buffer anchors are computed in fp32, off by about
//      2^-20 in uv, i.e. η = R·2^-19 texels (with margin), worth η·(texel spread) per axis; the
//      level λ (log2, fp32) is off by ~2^-16, worth 2^-16·|level lo − level hi|.
//   4. summed-area tables: prefix sums are integers below 2^24, exact in fp32, but the 4 fetches
//      cancel: fraction errors cost δ·(coverage along the window's edge) per edge, fp32 rounding of
//      the interpolated sums ~16·2^-24·(largest sum); both divided by the window area.
// Each slice's bound is weighted by its fade weight and summed over the slices: every fusion
// rule is 1-Lipschitz in each q_k (|∂V/∂q_k| ≤ 1), so |ΔV| ≤ Σ_k |Δq_k|. A further 2^-16 per
// slice covers fp32 arithmetic in the fade weight and the fusion.
#include "reference/oracle.hpp"

#include <penumbra/detail/occlusion/emit_near_field.hpp>
#include <penumbra/gl/runtime.hpp>
#include <penumbra/layout.hpp>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cmath>
#include <stdexcept>

namespace penumbra::playground {

namespace {

constexpr double level_error = 1.0 / 65536.0;     // fp32 log2 and level arithmetic
constexpr double arithmetic_error = 1.0 / 65536.0; // fp32 fade weight and fusion, per slice
constexpr double fp32_epsilon = 1.0 / 16777216.0;  // 2^-24
// Gaussian levels are read at log2(side) + log2(√6/4) (detail/occlusion/emit_visibility.hpp): level l has a
// standard deviation of about 2^l/√6 texels, a disk of diameter D one of D/4.
const double gaussian_bias = std::log2(std::sqrt(6.0) / 4.0);

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

} // namespace

bool read_slice_textures(const penumbra::gl::Runtime& runtime, SliceTextures& out, std::string* error) {
    const Config& config = runtime.config();
    const int R = config.resolution;
    out.resolution = R;
    out.slices = config.slices;
    out.coverage.assign(static_cast<std::size_t>(config.slices) * R * R, 0.0f);
    for (const PassDesc& pass : runtime.emission().layout.passes) {
        if (pass.action != PassAction::draw_scene || pass.program != "slicing") continue;
        std::vector<float> rgba(static_cast<std::size_t>(4) * R * R);
        if (slices_as_bits(config)) { // paper §3.7: slice k is bit k % 32 of component k / 32 of one RGBA32UI target
            const AttachmentDesc& target = pass.outputs.at(0);
            std::vector<GLuint> bits(static_cast<std::size_t>(4) * R * R);
            glGetTextureSubImage(runtime.texture(target.texture), target.level, 0, 0, 0, R, R, 1, GL_RGBA_INTEGER,
                                 GL_UNSIGNED_INT, static_cast<GLsizei>(bits.size() * sizeof(GLuint)), bits.data());
            for (int slice = 0; slice < config.slices; ++slice)
                for (int texel = 0; texel < R * R; ++texel)
                    out.coverage[static_cast<std::size_t>(slice) * R * R + texel] =
                        static_cast<float>((bits[4 * texel + slice / 32] >> (slice % 32)) & 1u);
        }
        // Colour attachment t holds slices 4t .. 4t+3 in its channels; with the near field, the T attachments
        // after them the slices' nearest depths in the same order.
        const std::size_t T = static_cast<std::size_t>(texture_count(config));
        if (marches_near_field(config)) out.near_depth.assign(out.coverage.size(), 0.0f);
        for (std::size_t t = 0; !slices_as_bits(config) && t < pass.outputs.size(); ++t) {
            const AttachmentDesc& target = pass.outputs[t];
            const bool near = t >= T;
            std::vector<float>& plane = near ? out.near_depth : out.coverage;
            if (near && target.texture != detail::near_depth_texture) continue;
            glGetTextureSubImage(runtime.texture(target.texture), target.level, 0, 0, std::max(target.layer, 0), R, R, 1,
                                 GL_RGBA, GL_FLOAT, static_cast<GLsizei>(rgba.size() * sizeof(float)), rgba.data());
            for (int c = 0; c < 4; ++c) {
                const int slice = static_cast<int>(4 * (near ? t - T : t)) + c;
                if (slice >= config.slices) break;
                for (int texel = 0; texel < R * R; ++texel)
                    plane[static_cast<std::size_t>(slice) * R * R + texel] = rgba[4 * texel + c];
            }
        }
        if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
            if (error) *error = "GL error " + std::to_string(e) + " reading the slicing output";
            return false;
        }
        return true;
    }
    if (error) *error = "the layout has no slicing pass (draw_scene with program 'slicing')";
    return false;
}

bool read_slice_boundaries(const penumbra::gl::Runtime& runtime, std::vector<float>& out, std::string* error) {
    out.clear();
    const Config& config = runtime.config();
    if (!places_slices_adaptively(config)) return true;
    std::vector<std::uint32_t> bits(static_cast<std::size_t>(config.slices) + 1);
    glGetTextureImage(runtime.texture("penumbra_sliceBoundaries"), 0, GL_RED_INTEGER, GL_UNSIGNED_INT,
                      static_cast<GLsizei>(bits.size() * sizeof(std::uint32_t)), bits.data());
    if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
        if (error) *error = "GL error " + std::to_string(e) + " reading penumbra_sliceBoundaries";
        return false;
    }
    for (std::uint32_t b : bits) out.push_back(std::bit_cast<float>(b));
    return true;
}

Oracle::Oracle(const Config& config, const SliceFrame& frame, SliceTextures slices, std::vector<float> boundaries,
               TexturePrecision precision)
    : config_(config), precision_(precision) {
    const std::size_t R = static_cast<std::size_t>(config.resolution);
    if (slices.resolution != config.resolution || slices.slices != config.slices ||
        slices.coverage.size() != R * R * static_cast<std::size_t>(config.slices))
        throw std::invalid_argument("oracle: slice textures of " + std::to_string(slices.slices) + " slices at " +
                                    std::to_string(slices.resolution) + "², the configuration has " +
                                    std::to_string(config.slices) + " at " + std::to_string(config.resolution) + "²");
    if (marches_near_field(config) && slices.near_depth.size() != slices.coverage.size())
        throw std::invalid_argument(
            "oracle: the configuration marches the near field but the slice textures have no "
            "nearest depths (read_slice_textures reads them from penumbra_nearDepth)");
    near_depth_ = std::move(slices.near_depth);
    light_from_world_ = glm::dmat4(frame.light_from_world);
    cop_distance_ = frame.cop_distance;
    light_size_ = glm::dvec2(frame.light_size);
    const int S = config.slices;
    if (!boundaries.empty() && boundaries.size() != static_cast<std::size_t>(S) + 1)
        throw std::invalid_argument("oracle: " + std::to_string(boundaries.size()) + " slice boundaries, the configuration needs " +
                                    std::to_string(S + 1));
    // uniform: slice s holds (z0 + s·Δ, z0 + (s+1)·Δ] and every fade ramps over Δ; adaptive: the
    // boundaries, each plane's fade over the slice below it, down to a virtual plane a last slice's
    // thickness below the last one, in fp32 as the GLSL computes them (detail/occlusion/emit_visibility.hpp)
    const double z0 = frame.slice_depths.x, thickness = frame.slice_depths.y;
    thickness_ = thickness;
    for (int k = 0; k <= S; ++k) planes_.push_back(boundaries.empty() ? z0 + k * thickness : double(boundaries[k]));
    for (int s = 0; s < S; ++s) {
        if (boundaries.empty()) {
            fade_thickness_.push_back(thickness);
            continue;
        }
        const float below = s + 2 <= S ? boundaries[s + 2] : 2.0f * boundaries[S] - boundaries[S - 1];
        fade_thickness_.push_back(double(below - boundaries[s + 1]));
    }
    window_half_size_ = frame.window_half_size;
    tan_angular_radius_ = frame.tan_angular_radius;
    levels_top_ = max_level(config);
    build_levels(slices);
}

void Oracle::build_levels(const SliceTextures& slices) {
    const int R = config_.resolution, L = levels_top_;
    levels_.assign(config_.slices, {});
    prefix_.assign(config_.slices, {});
    for (int s = 0; s < config_.slices; ++s) {
        Plane base{R, R, std::vector<double>(static_cast<std::size_t>(R) * R)};
        for (int y = 0; y < R; ++y)
            for (int x = 0; x < R; ++x) base.texels[static_cast<std::size_t>(y) * R + x] = slices.at(s, x, y);
        if (config_.filter == Filter::sat) {
            // Crow 1984, exclusive: texel (X, Y) = sum of the texels x < X, y < Y.
            Plane table{R + 1, R + 1, std::vector<double>(static_cast<std::size_t>(R + 1) * (R + 1), 0.0)};
            for (int y = 1; y <= R; ++y)
                for (int x = 1; x <= R; ++x)
                    table.texels[static_cast<std::size_t>(y) * (R + 1) + x] =
                        base.at(x - 1, y - 1) + table.at(x - 1, y) + table.at(x, y - 1) - table.at(x - 1, y - 1);
            prefix_[s] = std::move(table);
            continue;
        }
        std::vector<Plane>& chain = levels_[s];
        chain.push_back(std::move(base));
        for (int l = 1; l <= L; ++l) {
            const Plane& prev = chain.back();
            Plane next;
            if (config_.filter == Filter::mipmap) {
                // a mip level: 2×2 box of the level below, half the size
                next = {prev.width / 2, prev.height / 2, {}};
                next.texels.resize(static_cast<std::size_t>(next.width) * next.height);
                for (int y = 0; y < next.height; ++y)
                    for (int x = 0; x < next.width; ++x)
                        next.texels[static_cast<std::size_t>(y) * next.width + x] =
                            0.25 * (prev.at(2 * x, 2 * y) + prev.at(2 * x + 1, 2 * y) + prev.at(2 * x, 2 * y + 1) +
                                    prev.at(2 * x + 1, 2 * y + 1));
            } else {
                // Both filters are separable (and zero padding commutes with separation): a pass
                // along x, then one along y, over taps `step` = 2^(l-1) texels apart.
                const int step = 1 << (l - 1);
                const bool nbuffer = config_.filter == Filter::nbuffer;
                auto filter_1d = [&](const Plane& in, bool along_x) {
                    Plane result{R, R, std::vector<double>(static_cast<std::size_t>(R) * R)};
                    auto tap = [&](int x, int y, int offset) { // zero outside the R×R texture
                        (along_x ? x : y) += offset;
                        return x < 0 || y < 0 || x >= R || y >= R ? 0.0 : in.at(x, y);
                    };
                    for (int y = 0; y < R; ++y)
                        for (int x = 0; x < R; ++x)
                            result.texels[static_cast<std::size_t>(y) * R + x] =
                                nbuffer ? 0.5 * (tap(x, y, 0) + tap(x, y, step)) // Décoret 2005: window anchored at x
                                        : 0.25 * (tap(x, y, -step) + 2.0 * tap(x, y, 0) + tap(x, y, step)); // à trous [1 2 1]
                    return result;
                };
                next = filter_1d(filter_1d(prev, true), false);
                // RGBA8 levels (level_format): each level is stored rounded to the nearest 1/255 and
                // the next one is built from the rounded texels, as on the GPU
                if (detail::level_format(config_) == TextureFormat::rgba8)
                    for (double& texel : next.texels) texel = std::round(texel * 255.0) / 255.0;
            }
            chain.push_back(std::move(next));
        }
        // Reduced levels (level_reduction, atlas): a level at spacing s keeps texel s·j of the
        // full-resolution one as its texel j. The GPU builds it from the previous (kept) level's
        // texels at the same level-0 positions, so it is exactly that subsample, rounding included.
        for (int l = 1; l <= L && config_.filter != Filter::mipmap; ++l) {
            const int spacing = level_spacing(config_, l);
            if (spacing == 1) continue;
            const Plane& full = chain[l];
            Plane kept{R / spacing, R / spacing, {}};
            kept.texels.resize(static_cast<std::size_t>(kept.width) * kept.height);
            for (int y = 0; y < kept.height; ++y)
                for (int x = 0; x < kept.width; ++x)
                    kept.texels[static_cast<std::size_t>(y) * kept.width + x] = full.at(spacing * x, spacing * y);
            chain[l] = std::move(kept);
        }
    }
}

// Texel (x, y) of a slice's level as the GPU's storage returns it: border 0 outside the texture,
// except in the atlas, where the T textures of a level sit side by side (channel = slice % 4) and
// a read past a tile's left or right edge returns the neighbouring tile's texel.
double Oracle::stored(int slice, int level, int x, int y) const {
    const Plane& plane = levels_[slice][level];
    if (y < 0 || y >= plane.height) return 0.0;
    if (x >= 0 && x < plane.width) return plane.at(x, y);
    if (config_.packing != Packing::atlas) return 0.0;
    const int tile = slice / 4 + floor_div(x, plane.width);
    const int neighbour = 4 * tile + slice % 4;
    if (tile < 0 || tile >= texture_count(config_) || neighbour >= config_.slices) return 0.0;
    return levels_[neighbour][level].at(x - floor_div(x, plane.width) * plane.width, y);
}

// How far a stored texel of `level` can be from its exact value (point 1 of the bound).
double Oracle::storage_error(int level) const {
    const TextureFormat format = config_.filter == Filter::mipmap ? TextureFormat::rgba8 : detail::level_format(config_);
    const double unit = format == TextureFormat::rgba8     ? 1.0 / 255.0
                        : format == TextureFormat::rgba16f ? 1.0 / 2048.0
                                                           : 2.0 * fp32_epsilon;
    return level * unit;
}

// GL bilinear filtering at continuous texel coordinates (texel i spans [i, i + 1)).
Oracle::Sample Oracle::bilinear(int slice, int level, glm::dvec2 coords) const {
    const double x = coords.x - 0.5, y = coords.y - 0.5;
    const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
    const double fx = x - i, fy = y - j;
    const double t[4] = {stored(slice, level, i, j), stored(slice, level, i + 1, j), stored(slice, level, i, j + 1),
                         stored(slice, level, i + 1, j + 1)};
    const double w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    Sample s;
    double storage = 0.0;
    for (int k = 0; k < 4; ++k) {
        s.value += w[k] * t[k];
        if (t[k] > 0.0 && t[k] < 1.0) storage += w[k] * storage_error(level);
    }
    const double spread = *std::max_element(t, t + 4) - *std::min_element(t, t + 4);
    const double eta = config_.resolution * std::ldexp(1.0, -19);
    const double delta = precision_.sub_texel;
    s.bound = storage + (2 * delta + delta * delta + 2 * eta) * spread;
    return s;
}

Oracle::Sample Oracle::mix_levels(const Sample& lo, const Sample& hi, double t, double fraction_error) const {
    const double difference = std::abs(hi.value - lo.value);
    return {(1 - t) * lo.value + t * hi.value,
            (1 - t) * lo.bound + t * hi.bound + (level_error + fraction_error) * difference};
}

// Bilinear interpolation of the prefix table at a corner (in texels, 0..R): exact for box-shaped
// coverage, the integral of the coverage over [0, x] × [0, y].
double Oracle::prefix(int slice, glm::dvec2 corner) const {
    const Plane& table = prefix_[slice];
    const int R = config_.resolution;
    const int i = std::min(static_cast<int>(std::floor(corner.x)), R - 1);
    const int j = std::min(static_cast<int>(std::floor(corner.y)), R - 1);
    const double fx = corner.x - i, fy = corner.y - j;
    return (1 - fx) * (1 - fy) * table.at(i, j) + fx * (1 - fy) * table.at(i + 1, j) + (1 - fx) * fy * table.at(i, j + 1) +
           fx * fy * table.at(i + 1, j + 1);
}

// Summed-area table: exact mean of the coverage over the window, clipped to the texture (the
// outside counts as unoccluded), windows narrower than a texel widened to one texel.
Oracle::Sample Oracle::box_filtered(int slice, glm::dvec2 centre, double side) const {
    const double R = config_.resolution;
    const double width = std::max(side * R, 1.0);
    const glm::dvec2 lo = glm::clamp(centre * R - 0.5 * width, 0.0, R);
    const glm::dvec2 hi = glm::clamp(centre * R + 0.5 * width, 0.0, R);
    const double sum = prefix(slice, hi) - prefix(slice, {lo.x, hi.y}) - prefix(slice, {hi.x, lo.y}) + prefix(slice, lo);
    // Coverage along each edge of the window: what an error in that edge's sub-texel fraction costs.
    auto column = [&](double x) {
        const double i = std::min(std::floor(x), R - 1);
        return (prefix(slice, {i + 1, hi.y}) - prefix(slice, {i, hi.y})) - (prefix(slice, {i + 1, lo.y}) - prefix(slice, {i, lo.y}));
    };
    auto row = [&](double y) {
        const double j = std::min(std::floor(y), R - 1);
        return (prefix(slice, {hi.x, j + 1}) - prefix(slice, {hi.x, j})) - (prefix(slice, {lo.x, j + 1}) - prefix(slice, {lo.x, j}));
    };
    const double eta = R * std::ldexp(1.0, -19);
    const double edges = column(lo.x) + column(hi.x) + row(lo.y) + row(hi.y);
    const double largest = prefix(slice, glm::min(glm::floor(hi) + 1.0, glm::dvec2(R)));
    const double delta = precision_.sub_texel;
    const double sum_bound = (delta + eta) * edges + 4 * delta * delta + 16 * fp32_epsilon * largest;
    return {std::clamp(sum / (width * width), 0.0, 1.0), sum_bound / (width * width)};
}

Oracle::Level Oracle::level_for(double side) const {
    const double bias = config_.filter == Filter::gaussian ? gaussian_bias : 0.0;
    // windows narrower than one texel read level 0
    // (clamped to the highest level built: config.level_bound)
    const double wanted = std::log2(std::max(side * config_.resolution, 1.0)) + bias;
    return {std::clamp(wanted, 0.0, static_cast<double>(levels_top_)), wanted};
}

Oracle::Sample Oracle::filtered(int slice, glm::dvec2 centre, double side) const {
    if (config_.filter == Filter::sat) return box_filtered(slice, centre, side);
    const int L = levels_top_;
    const Level level = level_for(side);
    const int lo = static_cast<int>(std::floor(level.level));
    const double t = level.level - lo;
    Sample result = filtered_at(slice, centre, level.level, lo, t);
    result.clamped = L < resolution_levels(config_) && level.wanted > L + 1e-6;
    return result;
}

Oracle::Sample Oracle::filtered_at(int slice, glm::dvec2 centre, double level, int lo, double t) const {
    const int R = config_.resolution, L = levels_top_;
    if (config_.filter == Filter::mipmap) {
        // hardware trilinear: each level read at the same uv in its own texel grid
        auto at_level = [&](int l) { return bilinear(slice, l, centre * static_cast<double>(R >> l)); };
        return mix_levels(at_level(lo), lo < L ? at_level(lo + 1) : at_level(lo), t, precision_.level_fraction);
    }
    const bool nbuffer = config_.filter == Filter::nbuffer;
    // N-buffer anchor: a window of 2^l texels centred at c starts 2^(l-1) texels left of it
    auto anchor_shift = [&](double l) { return nbuffer ? std::exp2(l - 1.0) - 0.5 : 0.0; };
    if (config_.packing == Packing::volume) {
        // one 3D fetch: both levels at the fractional level's anchor, the next depth slice past
        // the last level is the border (0, weight t = 0 there)
        const glm::dvec2 coords = centre * static_cast<double>(R) - anchor_shift(level);
        const Sample hi = lo < L ? bilinear(slice, lo + 1, coords) : Sample{};
        return mix_levels(bilinear(slice, lo, coords), hi, t, precision_.sub_texel);
    }
    // atlas and array: each level at its own anchor, then a lerp in the shader; a reduced level
    // (spacing s) has texel j at level-0 texel s·j: its centre, level-0 coordinate s·j + s/2, stands
    // for the window (N-buffer) or blur (Gaussian) of texel s·j, centred at s·j + 1/2 + anchor
    auto at_level = [&](int l) {
        const double s = level_spacing(config_, l);
        return bilinear(slice, l, (centre * static_cast<double>(R) - anchor_shift(l) + 0.5 * (s - 1.0)) / s);
    };
    return mix_levels(at_level(lo), at_level(std::min(lo + 1, L)), t, 0.0);
}

// paper §3.4.2 fade: 0 at or below the point, a ramp over fade_ramp of the nearest slice above, then 1
// (without the fade: 1 above the point, else 0).
double Oracle::fade_weight(double z, int slice) const {
    const double plane = zeta(slice);
    return config_.self_shadow_fade ? std::clamp((z - plane) / (fade_thickness_[slice] * config_.fade_ramp), 0.0, 1.0)
                                     : (plane < z ? 1.0 : 0.0);
}

glm::dvec3 Oracle::light_point(glm::vec3 world) const {
    glm::dvec3 p = glm::dvec3(light_from_world_ * glm::dvec4(glm::dvec3(world), 1.0));
    p.z = std::max(p.z, 1e-6); // points on or behind the light plane
    return p;
}

Oracle::Kernel Oracle::kernel(glm::dvec3 p, double zeta) const {
    if (config_.light == Light::rect) {
        // docs/model.md §1.4: the rays from p to the light rectangle cut the plane in a square
        const double scale = cop_distance_ / (p.z * (cop_distance_ + zeta));
        return {0.5 + glm::dvec2(p) * (zeta * scale) / light_size_, std::max(p.z - zeta, 0.0) * scale};
    }
    // journal §3.5: orthographic slicing, the cone towards the sun grows linearly
    return {0.5 + glm::dvec2(p) / (2.0 * window_half_size_),
            std::max(p.z - zeta, 0.0) * tan_angular_radius_ / window_half_size_};
}

OracleValue Oracle::near_field(glm::dvec3 p, glm::dvec3 part) const {
    using namespace penumbra::detail;
    const int R = config_.resolution, S = config_.slices, n = near_field_rays_per_axis;
    const double z0 = planes_[0], thickness = thickness_;
    // how near a texel's edge the GPU may land on either side: fp32 coordinates (η = R·2^-19 texels) or the
    // texture unit's sub-texel rounding, whichever is coarser; and fp32 depths, relative
    const double texel_edge = std::max(R * std::ldexp(1.0, -19), precision_.sub_texel), relative = 1e-5;
    int open = 0, ambiguous = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            const glm::dvec2 offset(near_field_offset(a), near_field_offset(b));
            bool blocked = false, unsure = false;
            for (int j = 0; j < near_field_steps; ++j) {
                const double zeta = p.z - near_field_height(j) * thickness;
                const double position = (zeta - z0) / thickness;
                // past the last slice: open, as the GPU says (within rounding of it, either way); above the
                // first: no stored surface lies nearer the light than the point
                const bool past = position > S;
                unsure = unsure || std::abs(position - S) < relative * std::max(1.0, std::abs(position));
                if (past || position < 0.0) continue;
                Kernel k = kernel(p, zeta);
                k.centre += glm::dvec2(part) * k.side; // tangent clip (identity when off)
                k.side *= part.z;
                const glm::dvec2 texel = (k.centre + offset * k.side) * static_cast<double>(R);
                const int slice = std::clamp(static_cast<int>(std::ceil(position)) - 1, 0, S - 1);
                const glm::dvec2 fraction = texel - glm::floor(texel);
                unsure =
                    unsure ||
                    std::min({fraction.x, 1.0 - fraction.x, fraction.y, 1.0 - fraction.y}) < texel_edge ||
                    std::abs(position - std::round(position)) < relative * std::max(1.0, std::abs(position));
                const int x = static_cast<int>(std::floor(texel.x)),
                          y = static_cast<int>(std::floor(texel.y));
                if (x < 0 || y < 0 || x >= R || y >= R) continue; // the border: empty
                const double stored = near_depth_[(static_cast<std::size_t>(slice) * R + y) * R + x];
                if (stored <= 0.5 / 255.0) continue;
                const double surface = z0 + (slice + (1.0 - stored) * 255.0 / 254.0) * thickness;
                const double limit = zeta - near_field_bias * thickness;
                unsure = unsure || std::abs(surface - limit) < relative * std::max(thickness, std::abs(zeta));
                blocked = blocked || surface < limit;
            }
            open += blocked ? 0 : 1;
            ambiguous += unsure ? 1 : 0;
        }
    const double rays = static_cast<double>(n * n);
    return {open / rays, ambiguous / rays + arithmetic_error, false};
}

std::string Oracle::describe_lookups(glm::vec3 world, glm::vec3 normal) const {
    const Receiver r = receiver(world, normal);
    const double R = config_.resolution;
    std::string out;
    for (int s = 0; s < config_.slices; ++s) {
        const double weight = fade_weight(r.point.z, s);
        if (weight == 0.0) continue;
        Kernel k = kernel(r.point, zeta(s));
        k.centre += glm::dvec2(r.clip) * k.side; // tangent clip (identity when off), as visibility() reads it
        k.side *= r.clip.z;
        const Sample filtered_here = filtered(s, k.centre, k.side);
        if (filtered_here.value <= 0.0) continue;
        char text[320];
        int length = std::snprintf(text, sizeof text, "%sslice %d: weight %.4f, kernel at %.4f,%.4f side %.4f texels, ",
                                   out.empty() ? "" : "; ", s, weight, k.centre.x * R, k.centre.y * R, k.side * R);
        if (config_.filter != Filter::sat) {
            // each level alone is the mix at t = 0
            const double level = level_for(k.side).level;
            const int lo = static_cast<int>(std::floor(level)), hi = std::min(lo + 1, levels_top_);
            length += std::snprintf(text + length, sizeof text - length, "level %.5f (level %d alone %.6f, level %d %.6f), ",
                                    level, lo, filtered_at(s, k.centre, lo, lo, 0.0).value, hi,
                                    filtered_at(s, k.centre, hi, hi, 0.0).value);
        }
        std::snprintf(text + length, sizeof text - length, "filtered %.6f +- %.2e", filtered_here.value, filtered_here.bound);
        out += text;
    }
    return out.empty() ? "no slice above it reads any occlusion" : out;
}

std::vector<double> Oracle::occlusions(glm::vec3 world) const {
    const glm::dvec3 p = light_point(world);
    std::vector<double> q(config_.slices, 0.0);
    for (int s = 0; s < config_.slices; ++s) {
        const double weight = fade_weight(p.z, s);
        if (weight == 0.0) continue;
        const Kernel k = kernel(p, zeta(s));
        q[s] = weight * filtered(s, k.centre, k.side).value;
    }
    return q;
}

// Correlated fusion (docs/model.md §1.7, penumbra_correlatedStep in detail/occlusion/emit_visibility.hpp): the
// light this slice (q, kernel centre and side) lets through given the one visited before.
namespace {
double correlated_step(double q, glm::dvec3 kernel, double previous, glm::dvec3 previous_kernel) {
    const glm::dvec2 parallax = glm::dvec2(kernel) - glm::dvec2(previous_kernel);
    const double grow = kernel.z - previous_kernel.z;
    const glm::dvec2 shift = glm::sqrt(parallax * parallax + glm::dvec2(grow * grow / 12.0));
    const double feature = std::sqrt(std::max(q * kernel.z * kernel.z, previous * previous_kernel.z * previous_kernel.z));
    const glm::dvec2 overlap = glm::clamp(1.0 - shift / std::max(feature, 1e-12), 0.0, 1.0);
    const double rho = overlap.x * overlap.y;
    const double both = q * previous + rho * (std::min(q, previous) - q * previous);
    return (1.0 - q - previous + both) / std::max(1.0 - previous, 1e-6);
}

// Extent fusion (docs/model.md §1.7.2, penumbra_extentStep): the same with the occluder's size from the
// covered areas (uv²) the two slices see in windows twice their kernels' sides.
double extent_step(double q, glm::dvec3 kernel, double area, double previous, glm::dvec3 previous_kernel,
                   double previous_area) {
    const glm::dvec2 parallax = glm::dvec2(kernel) - glm::dvec2(previous_kernel);
    const double grow = kernel.z - previous_kernel.z;
    const glm::dvec2 shift = glm::sqrt(parallax * parallax + glm::dvec2(grow * grow / 12.0));
    const double feature = std::sqrt(std::max(area, previous_area));
    const glm::dvec2 overlap = glm::clamp(1.0 - shift / std::max(feature, 1e-12), 0.0, 1.0);
    const double rho = overlap.x * overlap.y;
    const double both = q * previous + rho * (std::min(q, previous) - q * previous);
    return (1.0 - q - previous + both) / std::max(1.0 - previous, 1e-6);
}

// penumbra_formFactorCorner and penumbra_irradianceOf (detail/occlusion/emit_visibility.hpp): the irradiance,
// over pi, that p of unit normal n (light frame) gets from the part `part` of the light's unit square (xy centre,
// z side), the part below its tangent plane counting 0.
double form_factor_corner(glm::dvec2 a, glm::dvec3 n) {
    const glm::dvec2 s = 1.0 / glm::sqrt(1.0 + a * a);
    return -0.5 * (s.x * std::atan(a.y * s.x) * (n.x + n.z * a.x) + s.y * std::atan(a.x * s.y) * (n.y + n.z * a.y));
}
// penumbra_irradianceBetween: the same from the rectangle between the corners `lower` and `upper`.
double irradiance_between(glm::dvec3 p, glm::dvec3 n, glm::dvec2 lower, glm::dvec2 upper,
                          glm::dvec2 light_size) {
    const glm::dvec2 lo = (lower * light_size - glm::dvec2(p)) / p.z;
    const glm::dvec2 hi = (upper * light_size - glm::dvec2(p)) / p.z;
    return std::max(form_factor_corner(hi, n) - form_factor_corner({lo.x, hi.y}, n) - form_factor_corner({hi.x, lo.y}, n) +
                        form_factor_corner(lo, n),
                    0.0);
}
double irradiance_of(glm::dvec3 p, glm::dvec3 n, glm::dvec3 part, glm::dvec2 light_size) {
    return irradiance_between(p, n, glm::dvec2(part) - 0.5 * part.z, glm::dvec2(part) + 0.5 * part.z,
                              light_size);
}

// The corner (-1 or 1 per axis) of quadrant i of a square: 0 lower left, 1 lower right, 2 upper left, 3 upper
// right (quadrant_corners in detail/occlusion/emit_kernel.hpp), for clustered fusion and the clip's
// quadrants.
glm::dvec2 quadrant_corner(int i) { return {i == 1 || i == 3 ? 1.0 : -1.0, i >= 2 ? 1.0 : -1.0}; }

// irradiance_quadrants: quadrant i (0 lower left, 1 lower right, 2 upper left, 3 upper right) of the part
// `clip` (clip_quadrant in detail/occlusion/emit_tangent_clip.hpp), and the fraction of a square `part`
// inside the core.
glm::dvec3 clip_quadrant(glm::dvec3 clip, int i) {
    return {glm::dvec2(clip) + 0.25 * clip.z * quadrant_corner(i), 0.5 * clip.z};
}
struct Overlap {
    glm::dvec2 lo, hi; // the rectangle both squares cover (empty where hi <= lo on an axis)
    double fraction;   // its area over the area of `part`
};
Overlap overlap_of(glm::dvec3 part, glm::dvec3 core) {
    const glm::dvec2 lo = glm::max(glm::dvec2(part) - 0.5 * part.z, glm::dvec2(core) - 0.5 * core.z);
    const glm::dvec2 hi = glm::min(glm::dvec2(part) + 0.5 * part.z, glm::dvec2(core) + 0.5 * core.z);
    const glm::dvec2 extent = glm::max(hi - lo, glm::dvec2(0.0));
    return {lo, hi, extent.x * extent.y / std::max(part.z * part.z, 1e-12)};
}
// penumbra_ringShares: each quadrant's share of the clip's irradiance outside the core.
glm::dvec4 ring_shares(glm::dvec3 p, glm::dvec3 n, glm::dvec3 clip, glm::dvec3 core, glm::dvec2 light_size) {
    const double whole = irradiance_of(p, n, clip, light_size);
    if (whole <= 1e-12) return glm::dvec4(0.0);
    glm::dvec4 shares(0.0);
    for (int i = 0; i < 4; ++i) {
        const glm::dvec3 quadrant = clip_quadrant(clip, i);
        const Overlap o = overlap_of(quadrant, core);
        const double in_core =
            o.hi.x > o.lo.x && o.hi.y > o.lo.y ? irradiance_between(p, n, o.lo, o.hi, light_size) : 0.0;
        shares[i] = std::max(irradiance_of(p, n, quadrant, light_size) - in_core, 0.0) / whole;
    }
    return shares;
}

// penumbra_irradianceWindow: the core, half the clip's side around the weight's peak inside the clip, and the
// weight of the whole clip's visibility, which gives the core and the ring around it their share of the
// irradiance. fp32 cancels in the irradiance of a small clip (differences of four form-factor corners of order
// one), which moves the GPU's weight by about 1e-6 over that irradiance.
struct IrradianceWindow {
    glm::dvec3 core{0.0};
    double clip_weight = 1.0;  // 1: the clip alone
    double weight_error = 0.0; // |GPU − oracle| of clip_weight
};
IrradianceWindow irradiance_window(glm::dvec3 p, glm::dvec3 n, glm::dvec3 clip, glm::dvec2 light_size) {
    const double side = 0.5 * clip.z;
    // the weight's peak: the foot, moved towards the normal's side by up to z / sqrt(3) on a wall
    const double facing = std::max(-n.z, 0.0);
    const glm::dvec2 across(n);
    const glm::dvec2 peak = glm::dvec2(p) + p.z * across /
                                                std::max(2.0 * facing + std::sqrt(4.0 * facing * facing + 3.0 * glm::dot(across, across)), 1e-6);
    const glm::dvec2 centre = glm::clamp(peak / light_size, glm::dvec2(clip) - 0.5 * side, glm::dvec2(clip) + 0.5 * side);
    const double whole = irradiance_of(p, n, clip, light_size);
    const double core = irradiance_of(p, n, glm::dvec3(centre, side), light_size);
    const double ring = whole > 1e-12 ? (1.0 - core / whole) / 0.75 : 1.0;
    return {glm::dvec3(centre, side), std::clamp(ring, 0.0, 1.0),
            std::min(1.0, 2e-6 / std::max(whole, 1e-30)) + arithmetic_error};
}

} // namespace

// penumbra_clusterCount in detail/occlusion/emit_visibility.hpp: the spread of the four quadrants' coverage
// and the saddle pattern's share of it.
double cluster_count(glm::dvec4 quadrants) {
    const double mean = 0.25 * (quadrants.x + quadrants.y + quadrants.z + quadrants.w);
    const glm::dvec4 deviation = quadrants - glm::dvec4(mean);
    const double spread = 0.25 * glm::dot(deviation, deviation);
    const double saddle = 0.5 * (deviation.x - deviation.y - deviation.z + deviation.w);
    const double scattered = std::min(0.75 * saddle * saddle / std::max(spread, 1e-10), 1.0);
    return std::max((1.0 + 2.0 * scattered) * mean * mean / std::max(spread, 1e-10), 1.0);
}

Oracle::Receiver Oracle::receiver(glm::vec3 world, glm::vec3 normal) const {
    Receiver r;
    glm::dvec3 p = light_point(world);
    r.unmoved = p;
    // Tangent clip (detail/occlusion/emit_visibility.hpp): the part of the light above the tangent plane, in the
    // light's unit square, cut along the axis the plane crosses most steeply; then the point
    // moves config.tangent_clip_offset slicing texels sideways along its normal.
    if (config_.tangent_clip) {
        glm::dvec3 n = glm::dmat3(light_from_world_) * glm::dvec3(normal);
        n *= 1.0 / std::sqrt(std::max(glm::dot(n, n), 1e-20));
        r.normal = n;
        const bool rect = config_.light == Light::rect;
        const glm::dvec2 slopes = glm::dvec2(n) * (rect ? light_size_ : glm::dvec2(2.0 * tan_angular_radius_));
        const double level = rect ? glm::dot(n, p) : n.z;
        auto clip_along = [&](bool x) {
            const double slope = x ? slopes.x : slopes.y;
            const double safe = slope >= 0.0 ? std::max(slope, 1e-12) : std::min(slope, -1e-12);
            const double cut = std::clamp(level / safe, -0.5, 0.5);
            const double lo = safe > 0.0 ? cut : -0.5, hi = safe > 0.0 ? 0.5 : cut;
            const double mid = 0.5 * (lo + hi);
            return x ? glm::dvec3(mid, 0.0, hi - lo) : glm::dvec3(0.0, mid, hi - lo);
        };
        r.clip = clip_along(std::abs(slopes.x) >= std::abs(slopes.y));
        // or the largest square in the corner the plane spares, where it is larger
        const double slope_sum = std::abs(slopes.x) + std::abs(slopes.y);
        const double corner = std::clamp((0.5 * slope_sum - level) / std::max(slope_sum, 1e-12), 0.0, 1.0);
        const glm::dvec3 centre_line = r.clip, corner_square(glm::sign(slopes) * (0.5 - 0.5 * corner), corner);
        if (corner > centre_line.z) r.clip = corner_square;
        // fp32 may pick the other axis where both slopes are (nearly) equal; it matters only
        // where the two cuts differ
        r.clip_ambiguous = std::abs(std::abs(slopes.x) - std::abs(slopes.y)) <= 1e-5 * std::abs(slopes.x) &&
                           glm::length(clip_along(true) - clip_along(false)) > 1e-9;
        // and either square where their sides (nearly) tie
        r.clip_ambiguous = r.clip_ambiguous || (std::abs(corner - centre_line.z) <= 1e-5 &&
                                                glm::length(corner_square - centre_line) > 1e-9);
        // clip_footprint: the receiver's own tangent plane in the slice above it, capped
        const double across = std::max(glm::length(glm::dvec2(n)), 1e-6);
        double footprint = 0.0;
        if (config_.clip_footprint) {
            const double spread =
                std::max(n.z / across + (rect ? glm::dot(glm::dvec2(p), glm::dvec2(n)) / (across * (cop_distance_ + p.z)) : 0.0),
                         0.0);
            const double cap_uv = detail::clip_footprint_cap_texels / config_.resolution;
            const double cap = rect ? std::max(light_size_.x, light_size_.y) * (cop_distance_ + p.z) / cop_distance_ * cap_uv
                                    : 2.0 * window_half_size_ * cap_uv;
            footprint = std::min(spread * (1 + leak_fix_reach(config_)) * thickness_, cap);
        }
        const double texels = config_.tangent_clip_offset / config_.resolution;
        if (rect) p += glm::dvec3(glm::dvec2(n) * light_size_ * ((cop_distance_ + p.z) / cop_distance_ * texels), 0.0);
        else p += glm::dvec3(glm::dvec2(n) * (2.0 * window_half_size_ * texels), 0.0);
        p += glm::dvec3(glm::dvec2(n) / across * footprint, 0.0);
    }
    r.point = p;
    return r;
}

OracleValue Oracle::visibility(glm::vec3 world, glm::vec3 normal, Fusion fusion) const {
    if (config_.light == Light::rect) {
        // a receiver beside the light, outside the slicing pyramid (docs/model.md §1.2b): left unshadowed;
        // within rounding of the pyramid's side the GPU may go either way
        const glm::dvec3 p = light_point(world);
        const double reach =
            std::max(std::abs(p.x) / light_size_.x, std::abs(p.y) / light_size_.y) * cop_distance_;
        const double side = 0.5 * detail::pyramid_margin * (cop_distance_ + p.z);
        if (std::abs(reach - side) < 1e-5 * side) return {1.0, 1.0, false};
        if (reach > side) return {1.0, 0.0, false};
    }
    const Receiver r = receiver(world, normal);
    const glm::dvec3 p = r.point, clip = r.clip;
    const bool clip_ambiguous = r.clip_ambiguous;
    // a receiver turned away from all of the light: none (fp32 may find a sliver of light where the
    // clip closes, or none where a sliver opens)
    const bool clip_closing = config_.tangent_clip && clip.z < 1e-5;
    if (config_.tangent_clip && clip.z <= 0.0) return {0.0, clip_closing ? 1.0 : 0.0, false};
    // irradiance window (penumbra_irradianceWindow), at the receiver before it moves: the core, half the clip's
    // side around the weight's peak, and the weight of the whole clip's visibility
    IrradianceWindow window; // the clip alone unless config.irradiance_window
    if (weighs_irradiance(config_)) window = irradiance_window(r.unmoved, r.normal, clip, light_size_);
    // the fused visibility of the part `part` of the light's unit square (penumbra_clippedVisibility)
    auto fused = [&](glm::dvec3 part) -> OracleValue {
        double lit = 1.0, sum = 0.0, maximum = 0.0, bound = 0.0, chain = 1.0, previous = 0.0, correlated = 1.0, extent = 1.0;
        glm::dvec3 previous_kernel(0.0); // centre and side of the slice visited before (correlated fusion)
        double previous_area = 0.0;      // and its covered area in the doubled window (extent fusion)
        bool beyond = false;
        for (int s = config_.slices - 1; s >= 0; --s) {
            const double weight = fade_weight(p.z, s);
            // without the fade, a point within fp32 rounding of a plane may fall on either side
            const bool ambiguous = !config_.self_shadow_fade && std::abs(p.z - zeta(s)) <= 1e-5 * std::max(1.0, p.z);
            if (weight == 0.0 && !ambiguous) continue;
            auto [centre, side] = kernel(p, zeta(s));
            centre += glm::dvec2(part) * side; // tangent clip (identity when off)
            side *= part.z;
            const Sample o = filtered(s, centre, side);
            beyond = beyond || (o.clamped && weight > 0.0);
            bound += ambiguous ? o.value + o.bound : clip_ambiguous ? 1.0 : weight * o.bound + arithmetic_error;
            const double q = weight * o.value;
            // extent and clustered fusion: the same slice over a window twice the kernel's side (only they read it)
            double area = 0.0;
            if (reads_doubled_window(fusion)) {
                const Sample wide = filtered(s, centre, 2.0 * side);
                area = weight * std::max(o.value, 4.0 * wide.value) * side * side;
                bound += weight * wide.bound;
            }
            // clustered fusion: that area shared by the occluders counted from the kernel's four quadrants
            if (fusion == Fusion::clustered) {
                glm::dvec4 quadrants(0.0);
                for (int i = 0; i < 4; ++i) {
                    const Sample quadrant =
                        filtered(s, centre + 0.25 * side * quadrant_corner(i), 0.5 * side);
                    quadrants[i] = quadrant.value;
                    bound += weight * quadrant.bound;
                }
                area /= cluster_count(quadrants);
            }
            lit *= 1.0 - q;
            sum += q;
            maximum = std::max(maximum, q);
            // chained: the neighbour visited before is nested with this slice, the others independent
            chain *= (1.0 - std::max(q, previous)) / std::max(1.0 - previous, 1e-6);
            correlated *= correlated_step(q, {centre, side}, previous, previous_kernel);
            extent *= extent_step(q, {centre, side}, area, previous, previous_kernel, previous_area);
            previous = q;
            previous_kernel = {centre, side};
            previous_area = area;
        }
        double v = lit;
        switch (fusion) {
        case Fusion::probabilistic: v = lit; break;
        case Fusion::additive: v = std::max(0.0, 1.0 - sum); break;
        case Fusion::maximum: v = 1.0 - maximum; break;
        case Fusion::average: v = 1.0 - 0.5 * (std::min(1.0, sum) + maximum); break; // Soler & Sillion
        case Fusion::chained: v = std::clamp(chain, 0.0, 1.0); break;
        case Fusion::correlated: v = std::clamp(correlated, 0.0, 1.0); break;
        case Fusion::extent:
        case Fusion::clustered: v = std::clamp(extent, 0.0, 1.0); break;
        }
        if (marches_near_field(config_)) {
            // capped by the near field's rays: min is 1-Lipschitz in both, so the larger bound holds
            const OracleValue near = near_field(p, part);
            v = std::min(v, near.visibility);
            bound = std::max(bound, near.bound);
        }
        return {v, clip_closing ? 1.0 : bound, beyond};
    };
    if (weighs_quadrants(config_)) {
        // penumbra_windowedVisibility with the quadrants: the core's visibility with the share the rings
        // leave, each quadrant's ring (its visibility less the core's part of it) with its own share
        const glm::dvec4 shares = ring_shares(r.unmoved, r.normal, clip, window.core, light_size_);
        const OracleValue core = fused(window.core);
        double v = (1.0 - (shares.x + shares.y + shares.z + shares.w)) * core.visibility;
        // fp32 moves each share by about the window's weight error, each counted at most once
        double bound = std::abs(1.0 - (shares.x + shares.y + shares.z + shares.w)) * core.bound +
                       5.0 * window.weight_error;
        bool beyond = core.beyond_level_bound;
        for (int i = 0; i < 4; ++i) {
            const glm::dvec3 quadrant = clip_quadrant(clip, i);
            const OracleValue seen = fused(quadrant);
            const double in_core = overlap_of(quadrant, window.core).fraction;
            const double outside = std::max(1.0 - in_core, 1e-6);
            v += shares[i] * std::clamp((seen.visibility - in_core * core.visibility) / outside, 0.0, 1.0);
            bound += shares[i] * (seen.bound + in_core * core.bound) / outside;
            beyond = beyond || seen.beyond_level_bound;
        }
        return {std::clamp(v, 0.0, 1.0), bound, beyond};
    }
    if (window.clip_weight >= 1.0) return fused(clip);
    // penumbra_windowedVisibility: the clip's and the core's visibilities mixed
    const double w = window.clip_weight;
    const OracleValue whole = fused(clip), core = fused(window.core);
    return {w * whole.visibility + (1.0 - w) * core.visibility,
            w * whole.bound + (1.0 - w) * core.bound + window.weight_error * std::abs(whole.visibility - core.visibility),
            whole.beyond_level_bound || core.beyond_level_bound};
}

} // namespace penumbra::playground
