// penumbra/detail/occlusion/validate.hpp — the occlusion textures' fields, and what the target
// allows of them (render targets, texture sizes, array layers, logic op).
#pragma once

#include "../problem.hpp"
#include "../target_limits.hpp"
#include "prefilter_plan.hpp"

#include <string_view>

namespace penumbra {

// The slice counts a configuration may have, as diagnostics and --help texts say it (public:
// penumbra/validate.hpp).
inline constexpr std::string_view allowed_slices = "1 to 32, 64 or 128";

namespace detail {

// Texel extent of the widest 2D texture a packing needs (the atlas puts the T tiles side by side;
// summed-area tables store R+1 exclusive prefix sums per side).
constexpr long long widest_2d_texture(const Config& config) {
    const long long tile = config.resolution + (config.filter == Filter::sat ? 1 : 0);
    return config.packing == Packing::atlas ? tile * texture_count(config) : tile;
}

constexpr std::vector<Problem> occlusion_problems(const Config& config) {
    std::vector<Problem> problems;
    auto add = [&](std::string_view field, Text value, Text message) { add_problem(problems, field, value, message); };
    if (config.slices < 1 || (config.slices > max_channel_slices && config.slices != 64 && config.slices != 128))
        add("slices", format_int(config.slices), cat("is out of range; allowed: ", allowed_slices));
    if (config.resolution < 32 || config.resolution > 4096 || !is_power_of_two(config.resolution))
        add("resolution", format_int(config.resolution),
            "is not allowed; allowed: a power of two from 32 to 4096 (32, 64, 128, 256, 512, 1024, 2048, 4096)");
    check_known(problems, "filter", config.filter);
    check_known(problems, "fusion", config.fusion);
    check_known(problems, "packing", config.packing);
    check_known(problems, "light", config.light);
    check_known(problems, "target", config.target);
    check_known(problems, "slice_placement", config.slice_placement);
    check_known(problems, "level_format", config.level_format);
    check_known(problems, "prefilter_stage", config.prefilter_stage);
    if (problems.empty() && (config.level_bound < -1 || config.level_bound > resolution_levels(config)))
        add("level_bound", format_int(config.level_bound),
            cat("is out of range; allowed: -1 (every level) or 0 to ", format_int(resolution_levels(config)),
                " (log2 of resolution ", format_int(config.resolution), ")"));
    if (!(config.tangent_clip_offset >= 0.0 && config.tangent_clip_offset <= 8.0))
        add("tangent_clip_offset", format_value(config.tangent_clip_offset), "is out of range; allowed: 0 to 8 slicing texels");
    if (!(config.fade_ramp > 0.0 && config.fade_ramp <= 4.0))
        add("fade_ramp", format_value(config.fade_ramp),
            "is out of range; allowed: more than 0 to 4 (fraction of a slice's thickness)");
    if (problems.empty() && (config.level_reduction < -1 || config.level_reduction > resolution_levels(config)))
        add("level_reduction", format_int(config.level_reduction),
            cat("is out of range; allowed: -1 (every level at full resolution) or 0 to ",
                format_int(resolution_levels(config)), " (log2 of resolution ", format_int(config.resolution), ")"));
    if (!problems.empty()) return problems; // the rules below need valid fields

    const std::string_view filter = to_string(config.filter);
    const std::string_view target = to_string(config.target);
    const TargetLimits limit = limits(config.target);
    if (config.filter == Filter::gaussian && config.light != Light::sun)
        add("filter", Text(filter),
            cat("needs light 'sun' (the Gaussian stands for the sun's disk, journal §3.5); allowed with light '",
                to_string(config.light), "': mipmap, nbuffer, sat"));
    if (config.packing == Packing::volume && (config.filter == Filter::mipmap || config.filter == Filter::sat))
        add("packing", Text("volume"),
            cat("cannot hold filter '", filter,
                "' (a volume stores equal-size filter levels as depth; mipmap levels shrink and a summed-area table "
                "has one level); allowed with this filter: atlas, array"));
    // (WGSL reads the tables texel by texel and filters them by hand: WebGPU renders 32-bit floats)
    if (config.filter == Filter::sat && !limit.float32_render_filter && !binds_samplers_apart(config))
        add("filter", Text("sat"),
            cat("needs renderable, filterable 32-bit float textures, which target '", target,
                "' does not guarantee; allowed filters for ", target, ": mipmap, nbuffer, gaussian"));
    // (WGSL slices in several passes: slicing_passes)
    const bool many_passes = binds_samplers_apart(config); // and HLSL, which follows WGSL's passes
    const Text allowed_for_target =
        cat("1 to ", format_int(many_passes ? max_channel_slices : 4 * limit.max_draw_buffers),
            limit.logic_op || many_passes ? ", 64 or 128" : "");
    if (slices_as_bits(config) && !limit.logic_op)
        add("slices", format_int(config.slices),
            cat("needs a logical OR on the slicing target (more than 32 slices are written as bits, paper §3.7), "
                "which target '", target, "' does not have; allowed for ", target, ": ", allowed_for_target));
    else if (!slices_as_bits(config) && !many_passes && texture_count(config) > limit.max_draw_buffers)
        add("slices", format_int(config.slices),
            cat("needs ", format_int(texture_count(config)), " render targets (four slices each) but target '", target,
                "' guarantees ", format_int(limit.max_draw_buffers), "; allowed for ", target, ": ", allowed_for_target));
    if (config.solid_casters && (!limit.logic_op || config.target == Target::vulkan))
        add("solid_casters", Text("true"),
            cat("needs a logical XOR on the slicing targets, switched per draw, which ",
                choose(config.target == Target::vulkan,
                       Text("the Vulkan runner (targets/vulkan) does not do yet"),
                       cat("target '", target, "' does not have")),
                "; allowed for ", target, ": false; solid_casters with target glsl450 or glsl330"));
    if (config.near_field) {
        const bool desktop = config.target == Target::glsl450 || config.target == Target::glsl330;
        // the slices' targets and as many for their nearest depths; four slices a target
        const int near_targets = 2 * texture_count(config), most_slices = 2 * limit.max_draw_buffers;
        if (!desktop)
            add("near_field", Text("true"),
                cat("is built for desktop OpenGL only so far (target '", target,
                    "' has no emission of it yet); allowed for ", target,
                    ": false; near_field with target glsl450 or "
                    "glsl330"));
        else if (near_targets > limit.max_draw_buffers)
            add("near_field", Text("true"),
                cat("needs ", format_int(near_targets), " render targets for ", format_int(config.slices),
                    " slices (the slices and their nearest depths) but target '", target, "' guarantees ",
                    format_int(limit.max_draw_buffers), "; allowed: near_field with at most ",
                    format_int(most_slices), " slices"));
        if (config.slice_placement != SlicePlacement::uniform)
            add("near_field", Text("true"),
                Text("needs uniform slice placement; allowed: near_field with slice_placement uniform"));
        if (config.solid_casters)
            add("near_field", Text("true"),
                Text("cannot be combined with solid_casters (their logical operation would combine the "
                     "depths too); "
                     "allowed: one of near_field and solid_casters"));
    }
    if (config.slices > max_channel_slices && config.packing == Packing::volume)
        add("packing", Text("volume"),
            cat("needs ", format_int(texture_count(config)), " 3D textures for ", format_int(config.slices),
                " slices, more samplers than a shading pass is guaranteed (16); allowed with more than 32 slices: atlas, "
                "array"));
    if (widest_2d_texture(config) > limit.max_texture_size) {
        Config smaller = config;
        while (smaller.resolution > 32 && widest_2d_texture(smaller) > limit.max_texture_size) smaller.resolution /= 2;
        const bool fits = widest_2d_texture(smaller) <= limit.max_texture_size;
        add("resolution", format_int(config.resolution),
            cat("needs a ", format_int(widest_2d_texture(config)), "-texel wide ",
                config.packing == Packing::atlas ? "atlas" : "texture", " but target '", target,
                "' guarantees only ", format_int(limit.max_texture_size), " texels; allowed with ",
                format_int(config.slices), " slices and packing ", to_string(config.packing), ": ",
                fits ? cat("up to ", format_int(smaller.resolution)) : Text("none"),
                ", or fewer slices, another packing or another target"));
    }
    const int level_count = config.filter == Filter::mipmap || config.filter == Filter::sat ? 1 : max_level(config) + 1;
    if (config.packing == Packing::array && level_count * texture_count(config) > limit.max_array_layers)
        add("packing", Text("array"),
            cat("needs ", format_int(level_count * texture_count(config)), " layers but target '", target,
                "' guarantees ", format_int(limit.max_array_layers), "; allowed: atlas, or fewer slices"));
    if (config.packing == Packing::volume && config.resolution > limit.max_3d_texture_size)
        add("resolution", format_int(config.resolution),
            cat("is too large for packing 'volume': target '", target, "' guarantees 3D textures of ",
                format_int(limit.max_3d_texture_size), " texels; allowed: up to ",
                format_int(limit.max_3d_texture_size), ", or packing atlas or array"));
    if (config.prefilter_stage == PrefilterStage::compute) {
        // compute dispatches (emit_prefilter_compute.hpp): N-buffer levels in the atlas, GLSL 4.50 compute
        if (config.filter != Filter::nbuffer || config.packing != Packing::atlas)
            add("prefilter_stage", Text("compute"),
                cat("builds N-buffer levels in the atlas only, not filter '", filter, "' with packing '",
                    to_string(config.packing), "'; allowed: fragment, or compute with filter nbuffer and packing atlas"));
        else if (config.target != Target::glsl450) {
            Text why = cat("target '", target, "' does not have");
            if (config.target == Target::vulkan)
                why = Text("the Vulkan runner (targets/vulkan) does not run (it has no compute pipelines)");
            if (config.target == Target::wgsl) why = Text("the WGSL emitters do not write yet (WebGPU has them)");
            if (config.target == Target::hlsl)
                why = Text("the HLSL emitters do not write yet (Direct3D 12 has them)");
            add("prefilter_stage", Text("compute"),
                cat("needs compute shaders (OpenGL 4.3+), which ", why, "; allowed for ", target,
                    ": fragment; compute with target glsl450"));
        }
        else if (compute_source_step(config) > compute_max_step)
            add("prefilter_stage", Text("compute"),
                cat("needs level_reduction 0 to ", format_int(compute_max_level_reduction),
                    " or level_bound 1 to ", format_int(compute_max_level_reduction + 1),
                    " (one level's taps must fit a workgroup's shared tile, ", format_int(compute_group_side), " + ",
                    format_int(compute_max_step), " texels per side); with level_reduction ",
                    format_int(config.level_reduction), " and level_bound ", format_int(config.level_bound),
                    " allowed: fragment"));
    }
    return problems;
}

} // namespace detail
} // namespace penumbra
