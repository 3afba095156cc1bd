// bench/compare/ladder.hpp — what penumbra-bench-compare renders: every technique as a plain
// penumbra::Config at a ladder of quality settings, from the fastest to the best.
//
// A technique is just a Config: the benchmark runs each one through the same generic path (the
// GL runtime executes any layout), and the only technique-specific code here is naming and which
// light a setting can run under (refusal).
#pragma once

#include <penumbra/config.hpp>
#include <penumbra/profiles.hpp>
#include <penumbra/validate.hpp>

#include <string>
#include <vector>

namespace penumbra::bench {

struct LadderEntry {
    std::string family;  // the technique's name: "occlusion", "paper", "shadowmap", "pcf", "pcss", "erosion", "evsm",
                         // "smrt", "smrt-temporal", "oim" (tables group by it)
    std::string label;   // short, unique name: "OT nbuffer 16/512"
    Config config;
    bool representative; // also in the flicker measurement and the image montage
    int accumulate = 0;  // a temporal variant: the mean of this many frames, frame f rendered with config.smrt.frame
                         // = f mod accumulate (a pattern turned per frame), reprojection-free (a static camera);
                         // its time is one frame's. 0: one frame
};

enum class LadderSet { quick, standard, full };

// Occlusion textures, paper §3: slices × resolution × prefilter.
inline LadderEntry occlusion_entry(Filter filter, int slices, int resolution, bool representative = false) {
    const Config config{.slices = slices, .resolution = resolution, .filter = filter};
    return {"occlusion",
            "OT " + std::string(to_string(filter)) + " " + std::to_string(slices) + "/" + std::to_string(resolution),
            config, representative};
}

// An occlusion-texture setting whose atlas levels above `level_reduction` (Config's default: 2) are
// stored at reduced resolution ("r1": from level 2 on). Cheaper light passes, and the reduced levels'
// bilinear reads blur small kernels: better under small lights, slightly worse under large ones (the
// note of issue 22 gives the figures), so the ladder offers both.
inline LadderEntry reduced_from_entry(Filter filter, int slices, int resolution, int level_reduction) {
    LadderEntry entry = occlusion_entry(filter, slices, resolution);
    entry.config.level_reduction = level_reduction;
    entry.label += " r" + std::to_string(level_reduction);
    return entry;
}

// The paper's own model at the default size: probabilistic fusion (eq. 5) and whole-light kernels,
// in its own family so that the tables show how far the default (extent fusion, tangent clip)
// moved from it and never pick it as "occlusion textures".
inline LadderEntry paper_entry(int slices, int resolution) {
    Config config{.slices = slices, .resolution = resolution, .filter = Filter::nbuffer};
    config.fusion = Fusion::probabilistic;
    config.tangent_clip = false;
    return {"paper", "paper nbuffer " + std::to_string(slices) + "/" + std::to_string(resolution), config, false};
}

// The default before extent fusion (docs/model.md §1.7.2): chained fusion, neighbouring slices by
// maximum. Its own family, so that the tables show it beside the default and never pick it.
inline LadderEntry chained_entry(int slices, int resolution) {
    Config config{.slices = slices, .resolution = resolution, .filter = Filter::nbuffer};
    config.fusion = Fusion::chained;
    return {"chained-fusion", "OT nbuffer " + std::to_string(slices) + "/" + std::to_string(resolution) + " chained",
            config, false};
}

// Solid casters (docs/model.md §1.3b): closed meshes fill the slices between their surfaces. Desktop
// OpenGL only, so its own family: the tables show it beside the default and never pick it.
inline LadderEntry solid_casters_entry(Filter filter, int slices, int resolution) {
    LadderEntry entry = occlusion_entry(filter, slices, resolution);
    entry.config.solid_casters = true;
    entry.family = "solid-casters";
    entry.label += " solid";
    return entry;
}

// Clustered fusion (docs/model.md §1.7.3): the occluders counted from the kernel's quadrants, for crowds and
// foliage. Four more lookups per slice: its own family, so that the tables show it beside the default and
// never pick it.
inline LadderEntry clustered_entry(int slices, int resolution) {
    LadderEntry entry = occlusion_entry(Filter::nbuffer, slices, resolution);
    entry.config.fusion = Fusion::clustered;
    entry.family = "clustered-fusion";
    entry.label += " clustered";
    return entry;
}

// A profile as it ships (penumbra/profiles.hpp, docs/model.md §1.11): `large` (the irradiance window's
// quadrants, five passes of the slice loop instead of two) or `fast` (8 slices of 128², chained, by area). In
// the occlusion family: a tier a user picks, so the equal-time tables may pick it where it fits the budget.
inline LadderEntry profile_entry(Profile profile) {
    const Config preset = apply_profile({}, profile);
    LadderEntry entry = occlusion_entry(preset.filter, preset.slices, preset.resolution);
    entry.config = preset;
    entry.label += " " + std::string(to_string(profile));
    return entry;
}

// The light weighed by area, without the irradiance window (docs/model.md §1.7.5) the default has: one
// pass of the slice loop, the default before the window. Its own family, so that the tables show it beside
// the default and never pick it.
inline LadderEntry area_entry(int slices, int resolution) {
    LadderEntry entry = occlusion_entry(Filter::nbuffer, slices, resolution);
    entry.config.irradiance_window = false;
    entry.family = "area-weighted";
    entry.label += " area";
    return entry;
}

// A budget occlusion-texture setting that weighs the light by area (--no-irradiance-window): one pass of the
// slice loop instead of the window's two, for the frame budgets of the cheapest shadow maps (on llvmpipe the
// window makes the shading pass about 1.5 times as long). In the occlusion family: a setting a user picks for
// its cost, where area_entry stands for the default before the window.
inline LadderEntry budget_area_entry(Filter filter, int slices, int resolution) {
    LadderEntry entry = occlusion_entry(filter, slices, resolution);
    entry.config.irradiance_window = false;
    entry.label += " area";
    return entry;
}

// The cheapest budget: weighed by area and fused by `chained` (docs/model.md §1.7), one lookup a slice where
// `extent` takes two (the doubled window); on llvmpipe the frame is 0.62 times the area-weighted setting's.
// In the occlusion family, like budget_area_entry: a setting a user picks for its cost.
inline LadderEntry budget_chained_entry(Filter filter, int slices, int resolution) {
    LadderEntry entry = budget_area_entry(filter, slices, resolution);
    entry.config.fusion = Fusion::chained;
    entry.label += " chained";
    return entry;
}

// The default before it built only the levels its kernels reach, in RGBA8, at reduced resolution:
// every level, RGBA16F, at full resolution (85 MiB at 16/512). Its own family, so that the tables show it beside the default and never pick it.
inline LadderEntry every_level_entry(int slices, int resolution) {
    Config config{.slices = slices, .resolution = resolution, .filter = Filter::nbuffer};
    config.level_format = LevelFormat::rgba16f;
    config.level_bound = resolution_levels(config); // set: the runtime does not fit it
    config.level_reduction = -1;                    // every level at full resolution
    return {"every-level",
            "OT nbuffer " + std::to_string(slices) + "/" + std::to_string(resolution) + " every level RGBA16F", config,
            false};
}

// The default before it stored the atlas's levels above level_reduction at reduced resolution:
// every level it builds at R² (28 to 40 MiB at 16/512, with the levels the light needs). Its own
// family, like every-level.
inline LadderEntry full_levels_entry(int slices, int resolution) {
    Config config{.slices = slices, .resolution = resolution, .filter = Filter::nbuffer};
    config.level_reduction = -1;
    return {"full-levels",
            "OT nbuffer " + std::to_string(slices) + "/" + std::to_string(resolution) + " full-resolution levels", config,
            false};
}

// The default with its N-buffer levels above the packing pass built by compute dispatches
// (prefilter_stage compute, glsl450) instead of one fragment pass per level: its own family, so that
// the tables show it beside the default and never pick it as "occlusion".
inline LadderEntry compute_prefilter_entry(int slices, int resolution) {
    Config config{.slices = slices, .resolution = resolution, .filter = Filter::nbuffer};
    config.prefilter_stage = PrefilterStage::compute;
    return {"compute-prefilter", "OT nbuffer " + std::to_string(slices) + "/" + std::to_string(resolution) + " compute",
            config, false};
}

// The shadow-map family (penumbra/config.hpp: shadowmap, pcf, pcss), one depth map of 1024².
inline LadderEntry shadow_map_entry(Technique technique, std::string label, bool representative,
                                    PcfParams pcf = {}, PcssParams pcss = {}) {
    const Config config{.technique = technique, .shadow_map = {.resolution = 1024}, .pcf = pcf, .pcss = pcss};
    return {std::string(to_string(technique)), std::move(label), config, representative};
}

// PCSS at the sample counts shipping engines use: blocker search / filter taps.
inline LadderEntry pcss_entry(int blocker_samples, int filter_samples, bool representative = false) {
    return shadow_map_entry(Technique::pcss,
                            "PCSS " + std::to_string(blocker_samples) + "/" + std::to_string(filter_samples),
                            representative, {}, {.blocker_samples = blocker_samples, .filter_samples = filter_samples});
}

// PCSS 16/16 with the depth pass's constant and slope-scaled bias only, without the normal offset and
// the receiver-plane depth bias (as Fernando 2005 wrote it, and as it was here before them): its own
// family, so that the tables show what the engines' biases buy and never pick it as PCSS.
inline LadderEntry pcss_depth_bias_only_entry() {
    LadderEntry entry = pcss_entry(16, 16);
    entry.config.shadow_map.normal_offset = 0.0;
    entry.config.shadow_map.receiver_plane_bias = false;
    entry.family = "pcss-depth-bias-only";
    entry.label = "PCSS 16/16 depth bias only";
    return entry;
}

// Erosion (Klein et al.) at its default parameters, from a hard shadow map of 1024² like the others.
inline LadderEntry erosion_entry() {
    Config config{.technique = Technique::erosion, .shadow_map = {.resolution = 1024}};
    return {"erosion", "erosion r" + std::to_string(config.erosion.max_search_radius), config, true};
}

// Exponential variance shadow maps (Unity HDRP's area-light shadows): taps per blur pass (the blur's
// clamp as many texels; its half-width follows the light) / the depth map's resolution. Its moments
// are blurred over the whole map, so the map's size is its cost: 512², half the others'.
inline LadderEntry evsm_entry(int blur_taps, int resolution, bool representative = false) {
    Config config{.technique = Technique::evsm, .shadow_map = {.resolution = resolution}};
    config.evsm.blur_taps = config.evsm.max_blur_texels = blur_taps;
    return {"evsm", "EVSM " + std::to_string(blur_taps) + "/" + std::to_string(resolution), config, representative};
}

// Shadow-map ray tracing (Unreal Engine 5's virtual shadow maps): rays per pixel / samples per ray, on
// a depth map of 1024² like the other shadow-map techniques. Unreal's default is 7/8.
inline LadderEntry smrt_entry(int rays, int samples, bool representative = false) {
    Config config{.technique = Technique::smrt, .shadow_map = {.resolution = 1024}};
    config.smrt.rays = rays;
    config.smrt.samples = samples;
    return {"smrt", "SMRT " + std::to_string(rays) + "/" + std::to_string(samples), config, representative};
}

// The same with temporal accumulation over `frames` frames (each its own turn of the pattern), as
// Unreal smooths SMRT's noise with its temporal pass: its own family, so the tables show both.
inline LadderEntry smrt_temporal_entry(int rays, int samples, int frames, bool representative = false) {
    LadderEntry entry = smrt_entry(rays, samples, representative);
    entry.family = "smrt-temporal";
    entry.label += " TAA" + std::to_string(frames);
    entry.accumulate = frames;
    return entry;
}

// Occlusion interval maps (sun only): intervals/resolution of the baked maps, the fewest samples
// along the path (256). Small by default: the bake is a precomputation of minutes at the default
// 256² on two cores.
inline LadderEntry oim_entry(int intervals, int resolution, bool representative = false) {
    Config config{.technique = Technique::oim};
    config.oim = {.resolution = resolution, .intervals = intervals, .samples = 256};
    return {"oim", "OIM " + std::to_string(intervals) + "/" + std::to_string(resolution), config, representative};
}

// Why `entry` cannot run under `light`, or empty when it can: occlusion interval maps follow the sun
// along its path; every other setting whatever validation refuses for that light.
inline std::string refusal(const LadderEntry& entry, Light light) {
    if (entry.config.technique == Technique::oim && light == Light::rect)
        return "occlusion interval maps are baked for the sun along its path; they have no rectangle-light form";
    Config config = entry.config;
    config.light = light;
    const std::vector<ConfigError> errors = validate(config);
    return errors.empty() ? std::string() : errors.front().message;
}

// The entries of one set, cheapest settings first within each filter.
inline std::vector<LadderEntry> technique_ladder(LadderSet set) {
    if (set == LadderSet::quick) return {occlusion_entry(Filter::nbuffer, 8, 256, true), pcss_entry(16, 16, true)};
    // one setting a line: a table read from the cheapest down
    // clang-format off
    std::vector<LadderEntry> ladder{
        occlusion_entry(Filter::mipmap, 4, 128, true),
        budget_area_entry(Filter::mipmap, 4, 128),
        budget_chained_entry(Filter::mipmap, 4, 128),
        occlusion_entry(Filter::mipmap, 8, 256),
        occlusion_entry(Filter::mipmap, 16, 512),
        occlusion_entry(Filter::mipmap, 8, 128),
        occlusion_entry(Filter::nbuffer, 4, 128),
        budget_area_entry(Filter::nbuffer, 4, 128),
        budget_chained_entry(Filter::nbuffer, 4, 128),
        occlusion_entry(Filter::nbuffer, 8, 128),
        budget_area_entry(Filter::nbuffer, 8, 128),
        profile_entry(Profile::fast),
        reduced_from_entry(Filter::nbuffer, 8, 128, 1),
        occlusion_entry(Filter::nbuffer, 8, 256),
        reduced_from_entry(Filter::nbuffer, 8, 256, 1),
        budget_area_entry(Filter::nbuffer, 8, 256),
        occlusion_entry(Filter::nbuffer, 16, 256),
        occlusion_entry(Filter::nbuffer, 16, 512, true), // the default configuration
        chained_entry(16, 512),
        solid_casters_entry(Filter::nbuffer, 8, 256),
        solid_casters_entry(Filter::nbuffer, 16, 512),
        clustered_entry(8, 256),
        clustered_entry(16, 512),
        profile_entry(Profile::large),
        area_entry(16, 512),
        every_level_entry(16, 512),
        full_levels_entry(16, 512),
        compute_prefilter_entry(16, 512),
        paper_entry(16, 512),
        occlusion_entry(Filter::nbuffer, 32, 512),
        occlusion_entry(Filter::sat, 8, 256),
        occlusion_entry(Filter::sat, 16, 512, true),
        shadow_map_entry(Technique::shadowmap, "hard shadow map", true),
        // PCF's kernel is fixed in scene units at the receiver: it does not follow the light.
        shadow_map_entry(Technique::pcf, "PCF 16 r0.1", true, {.poisson_taps = 16, .radius = 0.1}),
        shadow_map_entry(Technique::pcf, "PCF 32 r0.3", false, {.poisson_taps = 32, .radius = 0.3}),
        pcss_entry(8, 8),          // Bevy
        pcss_entry(16, 16, true), // Filament; the reference of the report's ratios
        pcss_depth_bias_only_entry(),
        pcss_entry(32, 32),        // Godot ultra
        pcss_entry(32, 64, true), // PlayCanvas high
        erosion_entry(),
        evsm_entry(16, 512, true), // HDRP's area-light shadows
        evsm_entry(32, 512),       // twice the blur for larger lights
        smrt_entry(2, 8),          // the cheap end of the cost-quality front
        smrt_entry(4, 8),
        smrt_entry(7, 8),          // Unreal's defaults (RayCount, SamplesPerRay)
        smrt_entry(8, 16, true),
        smrt_temporal_entry(4, 8, 8, true), // the cheap rays, smoothed over 8 frames
        smrt_temporal_entry(8, 16, 8),
        oim_entry(8, 128, true),   // the sun only (refusal); baked once per scene into --out's cache/oim
    };
    // clang-format on
    if (set == LadderSet::full) {
        ladder.push_back(occlusion_entry(Filter::sat, 32, 512)); // about 4x the time of sat 16/512 on llvmpipe
        ladder.push_back(occlusion_entry(Filter::mipmap, 32, 1024));
        ladder.push_back(occlusion_entry(Filter::nbuffer, 32, 1024));
        ladder.push_back(occlusion_entry(Filter::sat, 32, 1024));
        ladder.push_back(oim_entry(8, 256)); // OimParams' defaults
    }
    return ladder;
}

} // namespace penumbra::bench
