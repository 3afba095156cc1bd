// penumbra/detail/occlusion/technique.hpp — occlusion textures (Eisemann & Décoret 2008) as a
// descriptor: [slice placement,] slicing, [unpack,] prefilter, then the deferred shading that fuses
// the slices' filtered occlusion.
#pragma once

#include "../technique.hpp"
#include "fields.hpp"
#include "layout.hpp"
#include "validate.hpp"

namespace penumbra::detail {

inline constexpr ShaderFileSpec slicing_vert{"penumbra_slicing.vert", Stage::vertex, slicing_vertex, VertexInputs::caster};
inline constexpr ShaderFileSpec slicing_frag{"penumbra_slicing.frag", Stage::fragment, slicing_fragment};
inline constexpr ShaderFileSpec pack_atlas_frag{"penumbra_pack_atlas.frag", Stage::fragment, pack_atlas_fragment};
inline constexpr ShaderFileSpec nbuffer_level_frag{"penumbra_nbuffer_level.frag", Stage::fragment, nbuffer_level_fragment};
inline constexpr ShaderFileSpec mip_level_frag{"penumbra_mip_level.frag", Stage::fragment, mip_level_fragment};
inline constexpr ShaderFileSpec gaussian_level_frag{"penumbra_gaussian_level.frag", Stage::fragment, gaussian_level_fragment};
inline constexpr ShaderFileSpec sat_shift_frag{"penumbra_sat_shift.frag", Stage::fragment, sat_shift_fragment};
inline constexpr ShaderFileSpec sat_pass_frag{"penumbra_sat_pass.frag", Stage::fragment, sat_pass_fragment};
// more than 32 slices: the sliced bits into RGBA occlusion textures (emit_unpack.hpp)
inline constexpr ShaderFileSpec unpack_slices_frag{"penumbra_unpack_slices.frag", Stage::fragment, unpack_fragment};
// adaptive slice placement: the depth-bin pre-pass and the boundaries from it (emit_slice_placement.hpp)
inline constexpr ShaderFileSpec depth_bins_vert{"penumbra_depth_bins.vert", Stage::vertex, depth_bins_vertex,
                                                VertexInputs::caster};
inline constexpr ShaderFileSpec depth_bins_frag{"penumbra_depth_bins.frag", Stage::fragment, depth_bins_fragment};
inline constexpr ShaderFileSpec depth_bins_level_frag{"penumbra_depth_bins_level.frag", Stage::fragment,
                                                      depth_bins_level_fragment};
inline constexpr ShaderFileSpec slice_boundaries_frag{"penumbra_slice_boundaries.frag", Stage::fragment,
                                                      slice_boundaries_fragment};
// compute prefilter: N-buffer levels, several per dispatch (emit_prefilter_compute.hpp)
inline constexpr ShaderFileSpec nbuffer_levels_comp{"penumbra_nbuffer_levels.comp", Stage::compute, nbuffer_levels_compute};

// [slice placement,] slicing, [unpack,] prefilter, shading.
constexpr std::vector<ProgramPlan> occlusion_programs(const Config& config) {
    std::vector<ProgramPlan> plan;
    if (places_slices_adaptively(config)) { // paper §5: slice boundaries from the scene's depths, before slicing
        plan.push_back({"depth_bins", {depth_bins_vert, depth_bins_frag}});
        // WebGPU has no generateMipmap: the depth bins' mip chain as passes
        if (binds_samplers_apart(config))
            plan.push_back({"depth_bins_level", {fullscreen_vert, depth_bins_level_frag}});
        plan.push_back({"slice_boundaries", {fullscreen_vert, slice_boundaries_frag}});
    }
    plan.push_back({"slicing", {slicing_vert, slicing_frag}});
    if (slices_as_bits(config)) plan.push_back({"unpack_slices", {fullscreen_vert, unpack_slices_frag}});
    if (config.packing == Packing::atlas && config.filter != Filter::sat)
        plan.push_back({"pack_atlas", {fullscreen_vert, pack_atlas_frag}});
    // (the atlas packing pass writes levels 0 to packed_level; a level pass builds each one above:
    // the level program stays listed where there is none, as with level_bound 0 before)
    if (prefilters_in_compute(config)) // compute dispatches, several levels each (emit_prefilter_compute.hpp)
        plan.push_back({"nbuffer_levels", {nbuffer_levels_comp}});
    else if (config.filter == Filter::nbuffer)
        plan.push_back({"nbuffer_level", {fullscreen_vert, nbuffer_level_frag}});
    if (config.filter == Filter::gaussian) plan.push_back({"gaussian_level", {fullscreen_vert, gaussian_level_frag}});
    // WebGPU has no generateMipmap: the mip chain as passes
    if (config.filter == Filter::mipmap && binds_samplers_apart(config))
        plan.push_back({"mip_level", {fullscreen_vert, mip_level_frag}});
    if (config.filter == Filter::sat) {
        plan.push_back({"sat_shift", {fullscreen_vert, sat_shift_frag}});
        plan.push_back({"sat_pass", {fullscreen_vert, sat_pass_frag}});
    }
    plan.push_back(shading_example_program());
    plan.push_back(shading_deferred_program());
    return plan;
}

constexpr bool occlusion_reads_normal(const Config& config) { return clips_to_tangent_plane(config); }

constexpr Text occlusion_summary(const Config& config) {
    return cat("slices ", format_int(config.slices), " | resolution ", format_int(config.resolution), "x",
               format_int(config.resolution), " | filter ", to_string(config.filter), " | fusion ",
               to_string(config.fusion), " | packing ", to_string(config.packing), " | light ",
               to_string(config.light), " | leak fix ", on_off(config.leak_fix), " | fade ",
               on_off(config.self_shadow_fade),
               choose(config.self_shadow_fade && config.fade_ramp != 1.0,
                      cat(" over ", format_float(config.fade_ramp), " slice"), Text()),
               choose(clips_to_tangent_plane(config),
                      cat(" | tangent clip on, offset ", format_float(config.tangent_clip_offset), " texels",
                          choose(config.clip_footprint, " + footprint", ""),
                          choose(weighs_irradiance(config), " + irradiance window", "")),
                      Text()),
               choose(places_slices_adaptively(config), " | slice placement adaptive", ""),
               choose(prefilters_in_compute(config), " | prefilter compute", ""), " | target ",
               to_string(config.target));
}

constexpr Text occlusion_storage_note(const Config& config) {
    return cat(format_int(texture_count(config)), " RGBA occlusion texture(s), filter levels 0 to ",
               format_int(max_level(config)), ".");
}

constexpr std::vector<std::string_view> occlusion_es_samplers(const Config& config) {
    if (places_slices_adaptively(config)) return {"usampler2D"}; // penumbra_sliceBoundaries
    return {};
}

// Texels one fragment reads (penumbra/cost_model.hpp's rules): an N-buffer level 4, a Gaussian one 9;
// the atlas packing 1, or the taps of level 1 where it writes level 1 too. The shading pass is an upper
// bound: every slice above the point looks up, two bilinear fetches for N-buffer atlas and array
// levels, one trilinear for mip chains and volumes, four bilinear for summed-area tables.
inline long long occlusion_texels_per_fragment(const Config& c, const PassDesc& pass) {
    const std::string_view program = pass.program;
    if (program == "nbuffer_level" || program == "mip_level" || program == "depth_bins_level") return 4;
    if (program == "gaussian_level") return 9;
    if (program == "pack_atlas" && pass.outputs.size() > 1) return c.filter == Filter::gaussian ? 9 : 4; // + level 1
    if (program == "pack_atlas" || program == "sat_shift" || program == "unpack_slices") return 1;
    if (program == "sat_pass") return 2;
    if (program == "slice_boundaries") return 64; // the 8 x 8 cells of one depth bin (emit_slice_placement.hpp)
    if (program == "shading_deferred") {
        long long per_slice = 0;
        if (c.filter == Filter::sat) per_slice = 4 * 4;
        else if (c.filter == Filter::mipmap || c.packing == Packing::volume) per_slice = 8;
        else per_slice = 2 * 4;
        // extent fusion reads each slice once more over a window twice the kernel's side: one more level
        // in the atlas level loop, one more filtered lookup elsewhere (docs/model.md §1.7.2)
        const long long kernel_lookup = per_slice;
        if (reads_doubled_window(c.fusion)) per_slice += uses_level_loop(c) ? 4 : kernel_lookup;
        // clustered fusion reads the kernel's four quadrants too: two levels each in the level loop
        if (c.fusion == Fusion::clustered) per_slice += uses_level_loop(c) ? 4 * 2 * 4 : 4 * kernel_lookup;
        const long long boundaries = places_slices_adaptively(c) ? c.slices : 0;
        return g_buffer_texels(c) + per_slice * c.slices + boundaries;
    }
    return 1;
}

inline constexpr auto occlusion_field_rows = occlusion_fields();

constexpr TechniqueDescriptor occlusion_technique() {
    return {
        .fields = occlusion_field_rows,
        .programs = occlusion_programs,
        .visibility_snippet = visibility_snippet,
        .visibility_params = visibility_params,
        .write_visibility = write_visibility,
        .reads_normal = occlusion_reads_normal,
        .param_groups = occlusion_param_groups,
        .describe_layout = describe_occlusion_layout,
        .problems = occlusion_problems,
        .summary = occlusion_summary,
        .storage_note = occlusion_storage_note,
        .es_sampler_precision = occlusion_es_samplers,
        .texels_per_fragment = occlusion_texels_per_fragment,
        .writes_wgsl =
            true, // atlas N-buffers and Gaussian levels, up to 32 slices, uniform placement (validate.hpp)
        .writes_hlsl = true, // WGSL's passes, in HLSL through the language layer
    };
}

} // namespace penumbra::detail
