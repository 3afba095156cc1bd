// penumbra/config.hpp — the one value that decides every line Penumbra emits.
//
//   penumbra::Config config{.slices = 8, .resolution = 256, .filter = penumbra::Filter::sat};
//   penumbra::Config pcss{.technique = penumbra::Technique::pcss, .pcss = {.blocker_samples = 16, .filter_samples = 16}};
//
// `Config{}` is the default configuration (occlusion textures: 16 slices, 512², N-buffers,
// extent fusion, the paper's atlas packing, rectangular light, leak fix, fade and tangent clip on,
// uniform slice placement, OpenGL 4.5 core). The fusion (extent: neighbouring slices between nested
// and independent by the occluder's size and the parallax, docs/model.md §1.7.2) and the tangent clip
// are where it departs from the paper: on the built-in scenes they cut the penumbra error against a
// ray-traced, orientation-aware truth by about two thirds (docs/model.md); `fusion =
// probabilistic, tangent_clip = false` is the paper's model, whose penumbraVisibility takes no
// normal. `technique` picks the shadowing method; each technique reads only its own
// fields plus `light` and `target` (occlusion textures: slices … self_shadow_fade; shadow map
// techniques: shadow_map, and pcf or pcss), so the other fields never change its output.
// Config is a structural literal type, so it can also be a template argument
// (see penumbra/static_glsl.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace penumbra {

// How the occlusion textures are prefiltered so that one lookup returns a box mean (paper §3.2).
enum class Filter : std::uint8_t {
    mipmap,   // hardware trilinear mip chain: cheapest, dyadic windows (blocky when animated)
    nbuffer,  // N-buffers (Décoret 2005): L+1 full-resolution levels, continuous window placement
    sat,      // summed-area table, 32-bit float: exact box mean from four fetches
    gaussian, // Gaussian pyramid at full resolution (journal §3.5; sun light only)
};

// How the occlusion of several slices is combined into one visibility (paper §3.3).
enum class Fusion : std::uint8_t {
    probabilistic, // Π (1 − q_k): the paper's rule, eq. (5)
    additive,      // max(0, 1 − Σ q_k)
    maximum,       // 1 − max q_k
    average,       // Soler & Sillion: 1 − (min(1, Σ q_k) + max q_k) / 2
    chained,       // Π (1 − max(q_k, q_k+1)) / Π (1 − q_k) over inner slices: neighbours fused by maximum,
                   // slices further apart by product (the leak fix and solids make neighbours correlated)
    correlated,    // neighbours blended between nested (chained) and independent (product) by the overlap of
                   // the occluder the two kernels see, displaced by the parallax between them (docs/model.md §1.7)
    extent,        // correlated, the occluder's size from the covered area in a window twice the kernel's side
                   // (one more lookup per slice; docs/model.md §1.7.2)
    clustered,     // extent, that area shared by the occluders counted from the spread of the kernel's four
                   // quadrants: crowds and foliage (four more lookups per slice; docs/model.md §1.7.3)
};

// Whether a fusion rule reads each slice over a window twice the kernel's side as well (one filter level
// more than the widest kernel's).
constexpr bool reads_doubled_window(Fusion fusion) { return fusion == Fusion::extent || fusion == Fusion::clustered; }

// How the filtered occlusion textures are stored (paper §3.6–3.7, docs/model.md §3).
enum class Packing : std::uint8_t {
    atlas,  // one texture per filter level, the T occlusion textures side by side (paper §3.6)
    array,  // one 2D array texture, layer = level·T + t
    volume, // one 3D texture per group of four slices, depth = filter levels (paper §3.7)
};

// Where the slice boundaries lie along the light normal (paper §5, future work: slice placement).
enum class SlicePlacement : std::uint8_t {
    uniform,  // S equal slices over the scene bounds' depth range: penumbra_sliceDepths = (z0, thickness)
    adaptive, // boundaries at quantiles of the depths the geometry occupies, computed on the GPU from a
              // low-resolution depth-bin pre-pass (penumbra_sliceBoundaries); half the slices stay uniform
};

// How the filtered levels (N-buffers, Gaussian) are stored. Level 0 is binary coverage either way.
enum class LevelFormat : std::uint8_t {
    rgba8,   // 8-bit unsigned normalized: half the bytes of rgba16f; a window mean is rounded to 1/255 per level
    rgba16f, // half floats (11-bit mantissa)
};

// Which GPU stage builds the filter levels above the atlas packing pass (N-buffers).
enum class PrefilterStage : std::uint8_t {
    fragment, // one full-screen pass per level (every target)
    compute,  // compute dispatches (GLSL 4.50, target glsl450): a workgroup loads one tile of a level into shared
              // memory and builds several levels from it (N-buffer filter, atlas packing)
};

enum class Light : std::uint8_t {
    rect, // rectangular area light: perspective slicing from behind the light (paper §3.4)
    sun,  // light at infinity with an angular radius: orthographic slicing (journal §3.5)
};

// The shading language the emitted text is written in.
enum class Target : std::uint8_t {
    glsl330, // OpenGL 3.3 core, `#version 330 core`
    glsl450, // OpenGL 4.5 core, `#version 450 core`
    essl300, // OpenGL ES 3.0 / WebGL2, `#version 300 es`
    vulkan,  // GLSL 450 for SPIR-V: set/binding decorations, parameters in a uniform block
    wgsl,    // WGSL for WebGPU: one module per stage, bind group 0, parameters in a uniform buffer
    hlsl,    // HLSL (Shader Model 5.0/6.0 style) for Direct3D 12: cbuffers and t#/s# registers in space 0
    // Metal Shading Language 2.1: the vulkan target's SPIR-V translated by SPIRV-Cross, which this
    // header-only emitter does not link; penumbra::emit_msl (penumbra/msl.hpp) and penumbra-gen write it
    msl,
};

// The shadowing technique the emitted programs implement.
enum class Technique : std::uint8_t {
    occlusion, // occlusion textures (Eisemann & Décoret 2008): slices, prefiltered, fused
    shadowmap, // one depth map from the light, one hardware comparison tap: hard shadows
    pcf,       // percentage-closer filtering (Reeves et al. 1987): fixed kernel of comparison taps
    pcss,      // percentage-closer soft shadows (Fernando 2005): blocker search, penumbra estimate, PCF
    oim,       // occlusion interval maps (GPU Gems ch. 13): baked visibility intervals of the sun on a fixed path
    erosion,   // contact-hardening soft shadows by erosion (Klein et al.): screen-space hard shadow, edges,
               // min-max chain, variable-size erosion, penumbra-wide blur
    evsm,      // exponential variance shadow maps (Lauritzen & McCool 2008; Unity HDRP's area-light shadows):
               // moments of the exponentially warped depth, blurred over the light's size, Chebyshev bound
    smrt,      // shadow-map ray tracing (Unreal Engine 5's virtual shadow maps): per pixel, rays to points
               // spread over the light, each marched through the depth map, occluders extrapolated behind
               // silhouettes
};

// A shadow quality tier: a named preset of occlusion-texture fields (penumbra/profiles.hpp), as engines
// ship shadow quality settings.
enum class Profile : std::uint8_t {
    balanced, // the default configuration, Config{}
    large,    // lights several times the scene's default rectangle: more accurate there, at a higher cost
    fast,     // a frame budget below PCSS's: 8 slices of 128², fused by chained, the light weighed by area
};

// Where the PCF taps lie in the kernel.
enum class TapPattern : std::uint8_t {
    grid,    // N x N taps on a regular grid over the square of half-side `radius`
    poisson, // k taps of a Poisson disk (best-candidate, fixed seed) over the disk of `radius`
};

// The depth map from the light shared by shadowmap, pcf and pcss (see penumbra/light_frame.hpp
// for its camera). Depth is stored linearly: (z - near) / (far - near), z along the light's axis.
struct ShadowMapParams {
    int resolution = 1024;         // shadow map side in texels; a power of two, 32 to 8192 (target limit)
    double constant_bias = 0.02;   // added to every occluder depth (scene units along the light axis); 0 to 10
    double slope_bias = 1.5;       // times the occluder's depth change across one shadow-map texel
                                   // (scene units per texel, from screen-space derivatives); 0 to 16
    double normal_offset = 1.0;    // receivers move along their normal by this many shadow-map texels (the
                                   // texel's size at the receiver) times sin(angle to the light) before the
                                   // lookup, as Filament and Unity do; 0 to 8. Needs the normal: the deferred
                                   // pass then reads penumbra_worldNormals (shadowmap, pcf, pcss)
    bool receiver_plane_bias = true; // pcf, pcss: every tap compares against the depth of the receiver's
                                   // tangent plane under that tap, not the receiver's own depth (Isidoro
                                   // 2006), so a wide kernel on a sloped or curved receiver does not shadow
                                   // the receiver itself. Needs the normal: the deferred pass then reads
                                   // penumbra_worldNormals

    friend constexpr bool operator==(const ShadowMapParams&, const ShadowMapParams&) = default;
};

struct PcfParams {
    TapPattern pattern = TapPattern::poisson; // where the taps lie
    int grid_size = 4;             // grid: N, giving N x N taps; 1 to 16
    int poisson_taps = 16;         // poisson: k taps; 1 to 64
    double radius = 0.1;           // kernel half-extent on the receiver (scene units); > 0, up to 1000
    bool rotate = true;            // per-pixel rotation of the pattern (hash of the world position)

    friend constexpr bool operator==(const PcfParams&, const PcfParams&) = default;
};

struct PcssParams {
    int blocker_samples = 16;      // Poisson taps of the blocker search; 1 to 64
    int filter_samples = 16;       // Poisson comparison taps of the final PCF; 1 to 128
    int max_filter_texels = 64;    // the penumbra filter's half-width is clamped to this many texels;
                                   // 1 to half the shadow-map resolution
    bool rotate = true;            // per-pixel rotation of both patterns (hash of the world position)

    friend constexpr bool operator==(const PcssParams&, const PcssParams&) = default;
};

// Occlusion interval maps (Donnelly & Demers, GPU Gems ch. 13): per texel of a unique texture
// parameterization, the times along the sun's fixed path at which it rises and sets there, baked
// offline; shading averages that visibility over the window the sun's disk covers.
struct OimParams {
    int resolution = 256; // interval-map side in texels; a power of two, 32 to 4096 (target limit)
    int intervals = 8;    // visibility intervals per texel: 4, 8, 12 or 16 (four per RGBA rise/fall pair)
    int samples = 256;    // instants along the path that the bake traces: 256, 512, 1024 or 2048 (the chapter: 256)

    friend constexpr bool operator==(const OimParams&, const OimParams&) = default;
};

// Number of RGBA rise/fall texture pairs: four intervals each.
constexpr int oim_pairs(const OimParams& oim) { return (oim.intervals + 3) / 4; }

// Erosion (Klein et al., "Contact Hardening Soft Shadows using Erosion"): every pass runs in screen
// space at the output size; distances are in output pixels.
struct ErosionParams {
    int max_search_radius = 16;    // largest penumbra half-width searched for edges (output pixels); 1 to 256
    double edge_threshold = 0.5;   // |Laplacian| of the 0/1 hard shadow that marks an edge pixel; more than 0 to 4
    int search_taps = 32;          // Poisson taps of the erosion's nearest-edge search; 1 to 64
    int blur_taps = 16;            // Poisson taps of the final blur over the penumbra's width; 1 to 64

    friend constexpr bool operator==(const ErosionParams&, const ErosionParams&) = default;
};

// Levels above 0 of the erosion's min-max edge chain: the coarsest texel spans the search radius.
constexpr int erosion_levels(const ErosionParams& erosion) {
    int levels = 0;
    while ((1 << levels) < erosion.max_search_radius) ++levels;
    return levels;
}

// Exponential variance shadow maps: the shadow map's depth d in [0, 1] warped by e^(c+ d') and
// -e^(-c- d'), d' = 2d - 1, and the two moments of each blurred by a box whose half-width follows the
// light (detail/evsm/). Reads shadow_map's resolution and the depth pass's biases.
struct EvsmParams {
    double positive_exponent = 40.0;       // c+: more than 0 to 42 (e^(2 c) must fit a 32-bit float)
    double negative_exponent = 5.0;        // c-: more than 0 to 42
    double light_bleeding_reduction = 0.1; // Chebyshev bounds below this are shadow, the rest rescaled; 0 to < 1
    double variance_bias = 0.0001;         // least depth spread, as a fraction of the depth range; 0 to 0.01
    double blur_fraction = 0.5;            // the blur box's width over the widest penumbra the light casts across
                                           // the scene (a blocker on the near plane, a receiver on the far plane);
                                           // more than 0 to 1
    int blur_taps = 32;                    // taps per blur pass (one pass per axis); 1 to 64
    int max_blur_texels = 32;              // the blur's half-width is clamped to this many shadow-map texels;
                                           // 1 to blur_taps and to half the shadow-map resolution

    friend constexpr bool operator==(const EvsmParams&, const EvsmParams&) = default;
};

// Shadow-map ray tracing (detail/smrt/): rays from the receiver to points spread over the light, each
// marched through the shadow map's depth. Names and defaults after Unreal Engine 5's
// r.Shadow.Virtual.SMRT.* console variables (docs/techniques.md says which). Reads shadow_map's
// resolution and the depth pass's biases.
struct SmrtParams {
    int rays = 7;                          // rays per pixel (RayCountLocal); 1 to 16
    int samples = 8;                       // depth-map samples per ray (SamplesPerRayLocal); 2 to 32
    double extrapolate_max_slope = 5.0;    // largest occluder depth slope (depth per lateral scene unit) carried
                                           // past a silhouette (ExtrapolateMaxSlopeDirectional); 0 (no
                                           // extrapolation) to 50
    double max_slope_bias = 50.0;          // largest receiver slope (depth per lateral scene unit) the receiver
                                           // bias follows (MaxSlopeBiasLocal); 0 to 1000
    double texel_dither = 2.0;             // the ray's origin moves off the receiver along its normal by up to
                                           // this many shadow-map texels (TexelDitherScaleLocal); 0 to 8
    int frame = 0;                         // rotates the per-pixel pattern: frame f of a temporal accumulation;
                                           // 0 to 1023

    friend constexpr bool operator==(const SmrtParams&, const SmrtParams&) = default;
};

struct Config {
    Technique technique = Technique::occlusion; // which method the programs implement
    Profile profile = Profile::balanced;    // the preset the occlusion fields started from (penumbra/profiles.hpp);
                                            // setting it through the table of fields applies that preset
    int slices = 16;                        // slices along the light normal; 1 to 32 (four per RGBA texture),
                                            // 64 or 128 (sliced as bits of one RGBA32UI target, paper §3.7)
    int resolution = 512;                   // occlusion texture side in texels; a power of two, 32 to 4096
    Filter filter = Filter::nbuffer;        // prefilter of the occlusion textures
    Fusion fusion = Fusion::extent;         // rule combining the slices' occlusion
    Packing packing = Packing::atlas;       // storage of the filtered levels
    Light light = Light::rect;              // kind of area light
    bool leak_fix = true;                   // paper §3.4.1: a fragment of slice k also marks slice k+1
                                            // (k+1 to k+S/16 beyond 16 slices: leak_fix_reach)
    bool self_shadow_fade = true;           // paper §3.4.2: fade out the slice containing the point
    bool tangent_clip = true;               // kernels cover only the part of the light above the receiver's
                                            // tangent plane (penumbraVisibility then takes the normal)
    SlicePlacement slice_placement = SlicePlacement::uniform; // slice boundaries: uniform or from the scene's depths
    LevelFormat level_format = LevelFormat::rgba8; // storage of the filtered levels (ES 3.0: always rgba8)
    int level_bound = -1;                   // highest filter level built and read (N-buffer, Gaussian, mip chain):
                                            // wider kernels read that level; -1: log2(resolution), every level.
                                            // penumbra::kernel_level_bound (level_bound.hpp) gives the one a light
                                            // and bounds need; the GL runtime fits it at set_light (grows it as
                                            // the light grows)
    double tangent_clip_offset = 1.0;       // slicing texels by which the tangent clip moves a receiver sideways along
                                            // its normal, off its own texels in the slices; 0 to 8
    bool clip_footprint = true;             // the tangent clip also moves a receiver off its own tangent plane's
                                            // footprint in the slice above it (0 on faces that face the light)
    double fade_ramp = 0.25;                // the self-shadow fade ramps over this fraction of a slice's thickness
                                            // above the plane; more than 0 to 4
    int level_reduction = 2;                // atlas of N-buffer or Gaussian levels: the levels above this one are
                                            // stored at half the resolution of the one below, level l at
                                            // R / 2^(l - level_reduction) (a window of 2^l texels is smooth at
                                            // that scale); -1: every level at R (array and volume: always)
    Target target = Target::glsl450;        // shading language of the output
    PrefilterStage prefilter_stage = PrefilterStage::fragment; // N-buffer levels above the packing pass: full-screen
                                            // passes, or compute dispatches (glsl450, nbuffer, atlas only)
    ShadowMapParams shadow_map{};           // shadowmap, pcf, pcss: the depth map from the light
    PcfParams pcf{};                        // pcf: the fixed kernel
    PcssParams pcss{};                      // pcss: blocker search and filter
    OimParams oim{};                        // oim: the interval maps (the sun's path: penumbra/sun_path.hpp)
    ErosionParams erosion{};                // erosion: edge search and blur (screen space)
    EvsmParams evsm{};                      // evsm: warp, Chebyshev bound, blur (with shadow_map's map and biases)
    SmrtParams smrt{};                      // smrt: rays, samples, extrapolation, bias (with shadow_map's map)
    bool alpha_test = false;                // cut-out casters (leaf cards, fences, grilles), every technique: the
                                            // passes that draw the casters from the light (slicing, depth bins,
                                            // shadow-map depth) discard fragments whose alpha, read from the draw's
                                            // penumbra_alphaTexture at its penumbra_uv, is below the draw's
                                            // penumbra_alphaCutoff (per-draw caller parameters; oim: its bake)
    bool solid_casters = false;             // occlusion: closed caster meshes fill the slices between their surfaces
                                            // (a volume, not its shell); the caller flags each draw closed or open
                                            // (penumbra_casterClosed) and draws the closed ones first. Desktop
                                            // OpenGL only (a logical XOR on the slicing targets)
    bool irradiance_window = true;          // occlusion: the light weighed by the irradiance it sends, not by
                                            // area: the clip's and its core's (half as wide, around the peak)
                                            // visibilities mixed by their share of the irradiance; two passes of
                                            // the slice loop (docs/model.md §1.7.5). Rect light and tangent clip;
                                            // no effect elsewhere (weighs_irradiance)
    bool irradiance_quadrants = false; // occlusion, with the irradiance window: the clip's four quadrants
                                       // fused apart as well, each weighed by the irradiance it sends
                                       // outside the core; five passes of the slice loop instead of two
                                       // (docs/model.md §1.7.6)
    bool near_field = false; // occlusion: the slicing pass also keeps, per slice and texel, the depth of
                             // the surface nearest the light in that slice, and the receiver marches
                             // rays towards the light through the slices around it, so occluders
                             // within a slice or two of it (a contact) shadow it (docs/model.md
                             // §1.7.7). Uniform placement, at most 16 slices, no solid casters

    friend constexpr bool operator==(const Config&, const Config&) = default;
};

// Names as they appear on the command line, in JSON and in diagnostics.
template <class Enum> struct EnumNames;
template <> struct EnumNames<Technique> {
    static constexpr std::array<std::string_view, 8> names{"occlusion", "shadowmap", "pcf", "pcss", "oim",
                                                           "erosion", "evsm", "smrt"};
};
template <> struct EnumNames<TapPattern> {
    static constexpr std::array<std::string_view, 2> names{"grid", "poisson"};
};
template <> struct EnumNames<Filter> {
    static constexpr std::array<std::string_view, 4> names{"mipmap", "nbuffer", "sat", "gaussian"};
};
template <> struct EnumNames<Fusion> {
    static constexpr std::array<std::string_view, 8> names{"probabilistic", "additive", "maximum", "average",
                                                           "chained", "correlated", "extent", "clustered"};
};
template <> struct EnumNames<Packing> {
    static constexpr std::array<std::string_view, 3> names{"atlas", "array", "volume"};
};
template <> struct EnumNames<SlicePlacement> {
    static constexpr std::array<std::string_view, 2> names{"uniform", "adaptive"};
};
template <> struct EnumNames<LevelFormat> {
    static constexpr std::array<std::string_view, 2> names{"rgba8", "rgba16f"};
};
template <> struct EnumNames<PrefilterStage> {
    static constexpr std::array<std::string_view, 2> names{"fragment", "compute"};
};
template <> struct EnumNames<Light> {
    static constexpr std::array<std::string_view, 2> names{"rect", "sun"};
};
template <> struct EnumNames<Profile> {
    static constexpr std::array<std::string_view, 3> names{"balanced", "large", "fast"};
};
template <> struct EnumNames<Target> {
    static constexpr std::array<std::string_view, 7> names{"glsl330", "glsl450", "essl300", "vulkan",
                                                           "wgsl",    "hlsl",    "msl"};
};

template <class Enum> constexpr std::string_view to_string(Enum value) {
    return EnumNames<Enum>::names[static_cast<std::size_t>(value)];
}

// The enum value named `name`, or nothing when no value has that name.
template <class Enum> constexpr std::optional<Enum> parse_enum(std::string_view name) {
    const auto& names = EnumNames<Enum>::names;
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return static_cast<Enum>(i);
    return std::nullopt;
}

// Every value of an enum, for iterating over a configuration matrix.
template <class Enum> constexpr auto all_values() {
    std::array<Enum, EnumNames<Enum>::names.size()> values{};
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<Enum>(i);
    return values;
}

// True when the shadow-map techniques move the receiver along its normal before the lookup (the
// normal-offset bias): penumbraVisibility then uses the normal, and the deferred pass reads it.
constexpr bool offsets_along_normal(const Config& config) {
    return (config.technique == Technique::shadowmap || config.technique == Technique::pcf ||
            config.technique == Technique::pcss) &&
           config.shadow_map.normal_offset > 0.0;
}

// True when PCF's and PCSS's taps compare against the receiver's tangent plane (the receiver-plane
// depth bias): penumbraVisibility then uses the normal, and the deferred pass reads it.
constexpr bool tilts_taps_to_receiver_plane(const Config& config) {
    return (config.technique == Technique::pcf || config.technique == Technique::pcss) &&
           config.shadow_map.receiver_plane_bias;
}

// True when the occlusion-texture kernels are clipped to the receiver's tangent plane: the snippet
// then takes the normal, and the deferred pass reads the caller's penumbra_worldNormals.
constexpr bool clips_to_tangent_plane(const Config& config) {
    return config.technique == Technique::occlusion && config.tangent_clip;
}

// Whether the visibility weighs the light by irradiance (Config::irradiance_window): a refinement of the
// tangent clip's part of a rectangle. Under the sun every point of the light sends the same cosine, so
// there is nothing to weigh; without the clip there is no part to weigh within.
constexpr bool weighs_irradiance(const Config& config) {
    return config.irradiance_window && clips_to_tangent_plane(config) && config.light == Light::rect;
}

// Whether penumbraVisibility marches the near field through the slices' nearest depths (Config::near_field).
constexpr bool marches_near_field(const Config& config) {
    return config.technique == Technique::occlusion && config.near_field;
}

// Whether the irradiance window also fuses the clip's four quadrants apart (Config::irradiance_quadrants).
constexpr bool weighs_quadrants(const Config& config) {
    return config.irradiance_quadrants && weighs_irradiance(config);
}

// Number of comparison taps of the PCF kernel.
constexpr int pcf_taps(const PcfParams& pcf) {
    return pcf.pattern == TapPattern::grid ? pcf.grid_size * pcf.grid_size : pcf.poisson_taps;
}

// Adaptive slice placement (SlicePlacement::adaptive): the pre-pass sorts the geometry seen from the
// slicing camera into depth bins over the uniform slices' range, at a low resolution, four bins per
// RGBA8 channel set and 16 per draw (four render targets, what every target guarantees).
inline constexpr int depth_bins = 64;              // bins over [z0, z0 + S * thickness]
inline constexpr int depth_bins_resolution = 64;   // side of the pre-pass image (texels)
inline constexpr int depth_bins_per_draw = 16;     // four RGBA8 targets x four channels
inline constexpr int depth_bins_read_level = 3;    // mip level the boundary pass reads: 8 x 8 cells, where one
                                                   // covered texel of level 0 still rounds to a non-zero RGBA8 value
constexpr bool places_slices_adaptively(const Config& config) {
    return config.technique == Technique::occlusion && config.slice_placement == SlicePlacement::adaptive;
}

// Slices beyond its own that the leak fix marks: one per 16 slices, so that the copies reach the
// same depth whatever the slice count (paper §3.4.1 marks one; 0 with the leak fix off).
constexpr int leak_fix_reach(const Config& config) {
    if (!config.leak_fix) return 0;
    return config.slices > 16 ? config.slices / 16 : 1;
}

// Number of RGBA textures that hold the slices: four slices per texture, the last one may be partial.
constexpr int texture_count(const Config& config) { return (config.slices + 3) / 4; }

// Most slices one geometry pass writes as colour channels (eight RGBA targets, MAX blending).
inline constexpr int max_channel_slices = 32;

// True when the slicing pass writes the slices as bits of one RGBA32UI target (logical OR) and an
// unpack pass turns them into the RGBA occlusion textures (paper §3.7): slices > 32. WGSL (WebGPU has
// no logic op) draws the scene once per group of colour targets instead (occlusion's slicing_passes),
// and so does HLSL, which follows WGSL's passes (Direct3D 12's logic op is an optional feature).
constexpr bool slices_as_bits(const Config& config) {
    return config.slices > max_channel_slices && config.target != Target::wgsl &&
           config.target != Target::hlsl;
}

// log2(resolution): the levels a full filter chain has above the full-resolution one (and the
// summed-area table's doubling steps per axis, minus one).
constexpr int resolution_levels(const Config& config) {
    int levels = 0;
    for (int r = config.resolution; r > 1; r /= 2) ++levels;
    return levels;
}

// Highest filter level built and read: L = log2(resolution), or level_bound when it is set (the
// largest kernel any receiver inside the bounds can ask for; level_bound.hpp).
constexpr int max_level(const Config& config) {
    const int all = resolution_levels(config);
    return config.level_bound >= 0 && config.level_bound < all ? config.level_bound : all;
}

// True when the atlas's filter levels above config.level_reduction are stored at reduced
// resolution (N-buffer and Gaussian levels in the atlas packing; the array's layers and the
// volume's depth slices share one size).
constexpr bool reduces_levels(const Config& config) {
    return config.technique == Technique::occlusion && config.packing == Packing::atlas &&
           (config.filter == Filter::nbuffer || config.filter == Filter::gaussian) && config.level_reduction >= 0;
}

// Texels of level 0 between two neighbouring texels of filter level `level`: 1 at full resolution,
// 2^(level - level_reduction) above level_reduction (reduces_levels).
constexpr int level_spacing(const Config& config, int level) {
    if (!reduces_levels(config) || level <= config.level_reduction) return 1;
    return 1 << (level - config.level_reduction);
}

// True when compute dispatches build the N-buffer levels above the atlas packing pass
// (Config::prefilter_stage; validate() allows it for the N-buffer filter, the atlas packing and target glsl450).
constexpr bool prefilters_in_compute(const Config& config) {
    return config.technique == Technique::occlusion && config.prefilter_stage == PrefilterStage::compute;
}

// One reason a configuration cannot be emitted (penumbra::validate, emit's Result::errors).
struct ConfigError {
    std::string field;   // "slices", "resolution", "filter", …
    std::string value;   // the value given, as text
    std::string message; // "<field>: <value> <what is wrong>; allowed: <what is allowed>"
};

} // namespace penumbra
