// penumbra/detail/occlusion/parameters.hpp — the uniforms and samplers of the occlusion-texture programs.
#pragma once

#include "../glsl_common.hpp"
#include "../target_limits.hpp"
#include "../uniform_params.hpp"

namespace penumbra::detail {

// Filters whose levels are full-resolution images built by a shader, one per level.
constexpr bool has_level_images(const Config& config) {
    return config.filter == Filter::nbuffer || config.filter == Filter::gaussian;
}

// Name of the texture of filter level `level` in the atlas packing.
constexpr Text atlas_level_name(int level) { return cat("penumbra_level", format_int(level)); }
constexpr Text volume_name(int texture) { return cat("penumbra_volume", format_int(texture)); }

// Samplers through which the shading pass reads the filtered occlusion (docs/model.md §3).
constexpr std::vector<Param> storage_samplers(const Config& config) {
    std::vector<Param> samplers;
    const int levels = max_level(config);
    if (config.filter == Filter::mipmap) {
        if (config.packing == Packing::atlas)
            samplers.push_back({"penumbra_occlusionAtlas", "sampler2D",
                                "occlusion tiles side by side with a full mip chain", "", "penumbra_occlusionAtlas"});
        else
            samplers.push_back({"penumbra_occlusion", "sampler2DArray",
                                "one layer per RGBA occlusion texture, full mip chain", "", "penumbra_occlusion"});
    } else if (config.filter == Filter::sat) {
        if (config.packing == Packing::atlas)
            samplers.push_back({"penumbra_satAtlas",
                                "sampler2D",
                                "exclusive summed-area tables, (R+1)-texel tiles side by side",
                                "",
                                "penumbra_satAtlas",
                                UniformSource::light,
                                {},
                                /*fetch_only=*/binds_samplers_apart(config)});
        else
            samplers.push_back({"penumbra_sat",
                                "sampler2DArray",
                                "exclusive summed-area tables, one (R+1)-texel layer per occlusion texture",
                                "",
                                "penumbra_sat",
                                UniformSource::light,
                                {},
                                /*fetch_only=*/binds_samplers_apart(config)});
    } else if (config.packing == Packing::atlas) {
        for (int level = 0; level <= levels; ++level)
            samplers.push_back({atlas_level_name(level), "sampler2D", "filter level, occlusion tiles side by side",
                                "", atlas_level_name(level)});
    } else if (config.packing == Packing::array) {
        samplers.push_back({"penumbra_levels", "sampler2DArray", "filter levels, layer = level * T + texture", "",
                            "penumbra_levels"});
    } else {
        for (int t = 0; t < texture_count(config); ++t)
            samplers.push_back({volume_name(t), "sampler3D", "four slices, filter levels along depth", "",
                                volume_name(t)});
    }
    return samplers;
}

// Adaptive slice placement: the S + 1 slice boundaries the slice_boundaries pass computed.
constexpr Param slice_boundaries_sampler() {
    return {"penumbra_sliceBoundaries", "usampler2D",
            "adaptive slice placement: texel k (of S + 1, one row) = bits of the depth of slice k's top; texel S: the "
            "last slice's bottom (uintBitsToFloat)",
            "scene units", "penumbra_sliceBoundaries"};
}

// Parameters of penumbraVisibility(): the light frame and the slices, then the storage.
// Uniform placement: the slice that holds light-frame depth `depth`, slice k holding (z0 + k·Δ, z0 + (k +
// 1)·Δ], clamped to the slices (the slicing pass files a fragment by it; the near field's rays read by it).
constexpr Text uniform_slice_of(const Config& config, std::string_view depth) {
    return cat("clamp(ceil((", depth, " - penumbra_sliceDepths.x) / penumbra_sliceDepths.y) - 1.0, 0.0, ",
               format_float(config.slices - 1), ")");
}

// near_field: the texture of the slices' nearest depths (slicing writes it, penumbraVisibility reads it).
inline constexpr std::string_view near_depth_texture = "penumbra_nearDepth";

constexpr std::vector<Param> visibility_params(const Config& config) {
    std::vector<Param> params;
    params.push_back(uniform_param(Uniform::light_from_world, config.light));
    if (config.light == Light::rect) {
        params.push_back(uniform_param(Uniform::light_size, config.light));
        params.push_back(uniform_param(Uniform::cop_distance, config.light));
    } else {
        params.push_back(uniform_param(Uniform::window_half_size, config.light));
        params.push_back(uniform_param(Uniform::tan_angular_radius, config.light));
    }
    params.push_back(uniform_param(Uniform::slice_depths, config.light));
    if (places_slices_adaptively(config)) params.push_back(slice_boundaries_sampler());
    for (Param& sampler : storage_samplers(config)) params.push_back(std::move(sampler));
    if (marches_near_field(config))
        params.push_back(
            {Text(near_depth_texture), "sampler2DArray",
             "near field: per slice the depth of its surface nearest the light, 1 - f * 254/255 from the "
             "slice's top (channel k % 4 of layer k / 4; 0: empty), nearest filtering",
             "", Text(near_depth_texture)});
    return params;
}

// The slicing pass's vertex stage (and the depth-bin pre-pass's): the slicing camera.
constexpr std::vector<Param> slicing_camera_params() {
    return {
        uniform_param(Uniform::slice_clip_from_world, Light::rect),
        uniform_param(Uniform::light_from_world, "world to light frame (z = depth along the light normal)"),
        uniform_param(Uniform::slice_depths, Light::rect),
    };
}

// Geometry passes of the slicing: one, but on WGSL one per group of the colour targets a WebGPU render
// pass may have (WebGPU has no logic op to write more slices as bits, paper §3.7).
constexpr int slicing_passes(const Config& config) {
    if (!binds_samplers_apart(config)) return 1;
    const int group = limits(config.target).max_draw_buffers;
    return (texture_count(config) + group - 1) / group;
}
constexpr int slicing_targets(const Config& config) {
    return slicing_passes(config) > 1 ? limits(config.target).max_draw_buffers : texture_count(config);
}

// The slicing pass's fragment stage: the camera's parameters and, with adaptive placement, the boundaries;
// with several slicing passes, which occlusion texture the pass's first target holds.
constexpr std::vector<Param> slicing_params(const Config& config) {
    std::vector<Param> params = slicing_camera_params();
    if (places_slices_adaptively(config)) params.push_back(slice_boundaries_sampler());
    if (slicing_passes(config) > 1)
        params.push_back({"penumbra_firstTexture", "int", "occlusion texture the pass's first colour target holds (slices "
                          "4 x it to 4 x it + 3)", "", {}, UniformSource::pass});
    return params;
}

// The depth-bin pre-pass of adaptive slice placement: the slicing camera and the first bin of the draw.
constexpr std::vector<Param> depth_bins_params() {
    std::vector<Param> params = slicing_camera_params();
    params.push_back({"penumbra_firstBin", "int", "depth bin written to channel r of the first render target", "",
                      {}, UniformSource::pass});
    return params;
}

// The pass that turns the depth bins into slice boundaries.
constexpr std::vector<Param> slice_boundaries_params() {
    return {
        uniform_param(Uniform::slice_depths, "x: depth z0 of the uniform slices' top, y: uniform slice thickness"),
        {"penumbra_depthBins", "sampler2DArray", "depth-bin coverage, four bins per layer, mip chain", "",
         "penumbra_depthBins", UniformSource::light, {}, /*fetch_only=*/true},
    };
}

// Adaptive slice placement: boundary k of the S + 1 the slice_boundaries pass wrote (k = 0: the first
// slice's top, k = S: the last slice's bottom).
constexpr void write_boundary_function(LineWriter& out, const Config& config) {
    out.chunk("slice_boundaries");
    out.comment("adaptive slice placement (paper §5): depth of boundary k, stored as the float's bits");
    out.line(signature(config, "float", "penumbra_boundary", {{"int", "k"}}));
    out.line("{");
    out.line("return ",
             uint_bits_to_float(config, "float",
                                cat(fetch(config, "penumbra_sliceBoundaries", construct(config, "ivec2", "k, 0"), "0"), ".r")),
             ";");
    out.line("}");
    out.blank();
}

// Declares int `count` = how many of boundaries 1 .. last lie above `depth` (nearer the light: depth >
// boundary). The boundaries increase, so a binary search finds it: steps of 16, 8, 4, 2, 1 boundaries,
// each taken when the boundary it reaches is still above the point, one fetch per step.
constexpr void write_boundary_search(LineWriter& out, const Config& config, std::string_view count, std::string_view depth,
                                     int last) {
    out.line(variable(config, "int", count, "0"));
    if (last < 1) return;
    int step = 1;
    while (step * 2 <= last) step *= 2;
    out.comment(cat("binary search over the increasing boundaries 1 to ", format_int(last)));
    for (; step >= 1; step /= 2)
        out.line(count, " += ",
                 conditional(config,
                             cat("(", count, " + ", format_int(step), " <= ", format_int(last), " && ", depth,
                                 " > penumbra_boundary(min(", count, " + ", format_int(step), ", ", format_int(last), ")))"),
                             format_int(step), "0"),
                 ";");
}

} // namespace penumbra::detail
