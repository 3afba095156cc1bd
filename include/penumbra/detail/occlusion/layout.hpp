// penumbra/detail/occlusion/layout.hpp — the occlusion textures in the layout: their programs in
// pass order, each program's parameters, and the textures and passes of the shadow phase (slice
// placement, slicing, unpack, prefilter) before the deferred shading of the screen phase.
#pragma once

#include "emit_prefilter_compute.hpp"
#include "emit_slice_placement.hpp"
#include "emit_unpack.hpp"
#include "emit_visibility.hpp"
#include "../layout_builder.hpp"

namespace penumbra::detail {

inline std::vector<ParamGroup> occlusion_param_groups(const Config& config, std::string_view program) {
    if (program == "shading_example" || program == "shading_deferred")
        return shading_param_groups(program, visibility_params(config), deferred_params(config),
                                    example_fragment_params(), example_vertex_params());
    if (program == "slicing") {
        std::vector<ParamGroup> groups = caster_param_groups(config, "PenumbraSlicing", slicing_params(config));
        if (config.solid_casters) groups.push_back({solid_caster_block, solid_caster_params(config)});
        return groups;
    }
    if (program == "depth_bins") return caster_param_groups(config, "PenumbraPass", depth_bins_params());
    std::vector<Param> params;
    if (program == "slice_boundaries") params = slice_boundaries_params();
    if (program == "pack_atlas") params = pack_atlas_params();
    if (program == "mip_level") params = mip_level_params(config);
    if (program == "depth_bins_level") params = mip_chain_params(true);
    if (program == "unpack_slices") params = unpack_params();
    if (program == "nbuffer_level" || program == "gaussian_level") params = level_params(config);
    if (program == "nbuffer_levels") params = nbuffer_compute_params();
    if (program == "sat_shift") params = sat_shift_params(config);
    if (program == "sat_pass") params = sat_pass_params(config);
    return {{"PenumbraPass", std::move(params)}};
}

// A mip chain built by passes, where the API has no generateMipmap (WebGPU, Direct3D 12): one pass a
// level (and layer: `layers` 0 for a 2D texture) running `program`, which reads level l - 1 alone.
inline void describe_level_passes(LayoutBuilder& b, const std::string& program, const std::string& texture, int levels,
                                  int layers, int width, int height) {
    for (int l = 1; l <= levels; ++l)
        for (int t = 0; t < std::max(layers, 1); ++t) {
            std::vector<std::pair<std::string, int>> ints;
            if (layers > 0) ints.push_back({"penumbra_sourceLayer", t});
            b.pass({.name = program,
                    .program = program,
                    .inputs = {{.sampler = "penumbra_source", .texture = texture, .level = l - 1}},
                    .outputs = {{texture, l, layers > 0 ? t : -1}},
                    .int_uniforms = ints,
                    .viewport_width = std::max(width >> l, 1),
                    .viewport_height = std::max(height >> l, 1)});
        }
}

// Adaptive slice placement (emit_slice_placement.hpp), phase shadow, before slicing: the depth
// bins in draws of 16 bins (four layers each), their mip chain, then the S + 1 boundaries.
inline void describe_slice_placement_passes(LayoutBuilder& b, const Config& config, const RenderState& max_blend) {
    const int D = depth_bins_resolution, layers = depth_bins / 4;
    b.texture({.name = "penumbra_depthBins",
               .target = TextureTarget::texture_2d_array,
               .width = D,
               .height = D,
               .depth = layers,
               .mip_levels = depth_bins_read_level + 1,
               .min_filter = TextureFilter::nearest_mipmap_nearest,
               .purpose = "adaptive slice placement: coverage of " + std::to_string(depth_bins) +
                          " depth bins seen from the slicing camera, four per layer, mip chain"});
    b.texture({.name = "penumbra_sliceBoundaries",
               .format = TextureFormat::r32ui,
               .width = config.slices + 1,
               .height = 1,
               .purpose = "adaptive slice placement: texel k = bits of the depth of slice k's top (texel S: the last "
                          "slice's bottom), scene units; read with texelFetch and uintBitsToFloat"});
    for (int first = 0; first < depth_bins; first += depth_bins_per_draw) {
        std::vector<AttachmentDesc> outputs;
        for (int t = 0; t < depth_bins_per_draw / 4; ++t) outputs.push_back({"penumbra_depthBins", 0, first / 4 + t});
        b.pass({.name = "depth_bins",
                .action = PassAction::draw_scene,
                .program = "depth_bins",
                .outputs = outputs,
                .int_uniforms = {{"penumbra_firstBin", first}},
                .viewport_width = D,
                .viewport_height = D,
                .state = max_blend});
    }
    if (binds_samplers_apart(config))
        describe_level_passes(b, "depth_bins_level", "penumbra_depthBins", depth_bins_read_level, layers, D, D);
    else
        b.pass({.name = "depth_bins_mipmaps", .action = PassAction::generate_mipmap, .outputs = {{"penumbra_depthBins"}}});
    b.pass({.name = "slice_boundaries",
            .program = "slice_boundaries",
            .inputs = {{"penumbra_depthBins", "penumbra_depthBins"}},
            .outputs = {{"penumbra_sliceBoundaries"}},
            .viewport_width = config.slices + 1,
            .viewport_height = 1});
}

// The compute prefilter (prefilter_stage compute): one dispatch pass per group of levels of
// compute_dispatches, reading the level it starts from as a sampler and writing its levels as images.
inline void describe_compute_prefilter(LayoutBuilder& b, const Config& config) {
    const int R = config.resolution, T = texture_count(config), N = compute_group_side;
    for (const ComputeDispatch& d : compute_dispatches(config)) {
        const int source = d.source_level, spacing = level_spacing(config, source), tile = R / spacing;
        int same_size = 0;
        while (same_size < d.levels && level_spacing(config, source + 1 + same_size) == spacing) ++same_size;
        const int groups = (tile + N - 1) / N;
        DispatchDesc dispatch{.groups = {T * groups, groups, 1},
                              .local_size = {N, N, 1},
                              .memory_barrier = {MemoryBarrierBit::texture_fetch, MemoryBarrierBit::texture_update}};
        for (int i = 0; i < d.levels; ++i)
            dispatch.images.push_back({.image = compute_image_name(i).str(),
                                       .texture = atlas_level_name(source + 1 + i).str(),
                                       .unit = i,
                                       .access = ImageAccess::write_only});
        b.pass({.name = "nbuffer_levels_" + std::to_string(source + 1) + "_" + std::to_string(source + d.levels),
                .action = PassAction::dispatch,
                .program = "nbuffer_levels",
                .inputs = {{"penumbra_source", atlas_level_name(source).str()}},
                .int_uniforms = {{"penumbra_levels", d.levels},
                                 {"penumbra_step", compute_step(config, source)},
                                 {"penumbra_sourceTile", tile},
                                 {"penumbra_sameSize", same_size},
                                 {"penumbra_groupsPerTile", groups}},
                .viewport_width = T * tile, // the source level's texels the workgroups cover
                .viewport_height = tile,
                .dispatch = std::move(dispatch)});
    }
}

// Occlusion textures, phase shadow: slicing into the slices' storage (beyond 32 slices: into bits,
// then unpack draws into that storage), then the prefilter passes.
inline void describe_occlusion_passes(LayoutBuilder& b, const Config& config) {
    // L: the highest filter level (level_bound); the summed-area table doubles over all log2(R) steps
    const int R = config.resolution, T = texture_count(config), L = max_level(config);
    const TextureFormat level_fmt = level_format(config);
    const Wrap wrap = border_wrap(config); // the storage reads the border outside the map, where there is one
    constexpr TextureFilter linear = TextureFilter::linear;
    const std::string scratch_purpose = "level being built (a texture cannot be sampled and rendered at once)";
    // Storage, and where the slicing pass writes slice texture t.
    std::vector<AttachmentDesc> slicing_outputs;
    const bool sliced_into_array = config.packing == Packing::atlas || config.filter == Filter::sat;
    if (sliced_into_array) {
        b.texture({.name = "penumbra_slices", .target = TextureTarget::texture_2d_array, .width = R, .height = R,
                   .depth = T, .wrap = wrap, .purpose = "slicing output: binary coverage, one layer per four slices"});
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_slices", 0, t});
    }
    if (config.filter == Filter::mipmap && config.packing == Packing::atlas) {
        b.texture({.name = "penumbra_occlusionAtlas", .width = T * R, .height = R, .mip_levels = L + 1,
                   .min_filter = TextureFilter::linear_mipmap_linear, .mag_filter = linear, .wrap = wrap,
                   .purpose = "occlusion tiles side by side, mip chain"});
    } else if (config.filter == Filter::mipmap) {
        b.texture({.name = "penumbra_occlusion", .target = TextureTarget::texture_2d_array, .width = R, .height = R,
                   .depth = T, .mip_levels = L + 1, .min_filter = TextureFilter::linear_mipmap_linear,
                   .mag_filter = linear, .wrap = wrap, .purpose = "occlusion textures, mip chain"});
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_occlusion", 0, t});
    } else if (config.filter == Filter::sat) {
        const bool atlas = config.packing == Packing::atlas;
        for (const std::string name : {atlas ? "penumbra_satAtlas" : "penumbra_sat", "penumbra_satScratch"})
            b.texture({.name = name,
                       .target = atlas ? TextureTarget::texture_2d : TextureTarget::texture_2d_array,
                       .format = TextureFormat::rgba32f,
                       .width = atlas ? T * (R + 1) : R + 1,
                       .height = R + 1,
                       .depth = atlas ? 1 : T,
                       .min_filter = linear,
                       .mag_filter = linear,
                       .wrap = wrap,
                       .purpose = name == "penumbra_satScratch" ? "summed-area ping-pong target"
                                                                : "exclusive summed-area tables, (R+1)-texel tiles"});
    } else if (config.packing == Packing::atlas) {
        for (int l = 0; l <= L; ++l) {
            const int side = R / level_spacing(config, l); // reduced levels: R / 2^(l - level_reduction)
            b.texture({.name = atlas_level_name(l).str(), .format = level_fmt, .width = T * side, .height = side,
                       .min_filter = linear, .mag_filter = linear, .wrap = wrap,
                       .purpose = "filter level " + std::to_string(l) + ", tiles side by side" +
                                  (side < R ? ", " + std::to_string(side) + " texels per tile (texel j: level-0 texel " +
                                                  std::to_string(R / side) + " * j)"
                                            : std::string())});
        }
    } else if (config.packing == Packing::array) {
        b.texture({.name = "penumbra_levels", .target = TextureTarget::texture_2d_array, .format = level_fmt,
                   .width = R, .height = R, .depth = (L + 1) * T, .min_filter = linear, .mag_filter = linear,
                   .wrap = wrap, .purpose = "filter levels, layer = level * T + texture"});
        b.texture({.name = "penumbra_scratch", .format = level_fmt, .width = R, .height = R, .wrap = wrap,
                   .purpose = scratch_purpose});
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_levels", 0, t});
    } else {
        for (int t = 0; t < T; ++t) {
            b.texture({.name = volume_name(t).str(), .target = TextureTarget::texture_3d, .format = level_fmt,
                       .width = R, .height = R, .depth = L + 1, .min_filter = linear, .mag_filter = linear,
                       .wrap = wrap,
                       .purpose = "slices " + std::to_string(4 * t) + " to " + std::to_string(4 * t + 3) +
                                  ", levels along depth"});
            slicing_outputs.push_back({volume_name(t).str(), 0, 0});
        }
        b.texture({.name = "penumbra_scratch", .format = level_fmt, .width = R, .height = R, .wrap = wrap,
                   .purpose = scratch_purpose});
    }

    // layout.json's slice_map: slice k is channel k % 4 of slicing output k / 4 (emit_slicing.hpp)
    for (int k = 0; k < config.slices; ++k) {
        const AttachmentDesc& out = slicing_outputs[static_cast<std::size_t>(k / 4)];
        b.layout.slice_map.push_back({k, out.texture, out.layer});
    }

    // a texel is covered when any triangle covers it: blend MAX over a cleared target
    const RenderState max_blend{.blend = true,
                                .blend_equation = BlendEquation::max,
                                .blend_src = BlendFactor::one,
                                .blend_dst = BlendFactor::one,
                                .clear_color = std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f}};
    std::vector<BindingDesc> slicing_inputs;
    if (places_slices_adaptively(config)) {
        describe_slice_placement_passes(b, config, max_blend);
        slicing_inputs.push_back({"penumbra_sliceBoundaries", "penumbra_sliceBoundaries"});
    }
    if (slices_as_bits(config)) {
        // paper §3.7: every slice a bit of one RGBA32UI target, OR-ed, then unpacked into the textures
        // the slicing would otherwise write, one group of colour attachments per draw
        b.texture({.name = "penumbra_sliceBits", .format = TextureFormat::rgba32ui, .width = R, .height = R,
                   .purpose = "slicing output: bit k % 32 of component k / 32 marks slice k"});
        b.pass({.name = "slicing",
                .action = PassAction::draw_scene,
                .program = "slicing",
                .inputs = slicing_inputs,
                .outputs = {{"penumbra_sliceBits"}},
                .viewport_width = R,
                .viewport_height = R,
                .state = {.clear_color = max_blend.clear_color, .logic_op = LogicOp::bitwise_or}});
        const int group = unpack_group(config);
        for (int d = 0; d < unpack_draws(config); ++d) {
            const auto first = slicing_outputs.begin() + d * group;
            b.pass({.name = "unpack_slices",
                    .program = "unpack_slices",
                    .inputs = {{"penumbra_sliceBits", "penumbra_sliceBits"}},
                    .outputs = {first, first + group},
                    .int_uniforms = {{"penumbra_firstSlice", 4 * group * d}},
                    .viewport_width = R,
                    .viewport_height = R});
        }
    } else if (slicing_passes(config) > 1) {
        // WGSL: the scene once per group of colour targets (WebGPU has no logic op for bits)
        const int group = slicing_targets(config);
        for (int first = 0; first < T; first += group) {
            const auto begin = slicing_outputs.begin() + first;
            b.pass({.name = "slicing",
                    .action = PassAction::draw_scene,
                    .program = "slicing",
                    .inputs = slicing_inputs,
                    .outputs = {begin, begin + std::min(group, T - first)},
                    .int_uniforms = {{"penumbra_firstTexture", first}},
                    .viewport_width = R,
                    .viewport_height = R,
                    .state = max_blend});
        }
    } else {
        // near_field: the slices' nearest depths, the colour targets after the slices' (emit_slicing.hpp)
        std::vector<AttachmentDesc> outputs = slicing_outputs;
        if (marches_near_field(config)) {
            b.texture(
                {.name = std::string(near_depth_texture),
                 .target = TextureTarget::texture_2d_array,
                 .width = R,
                 .height = R,
                 .depth = T,
                 .min_filter = TextureFilter::nearest,
                 .mag_filter = TextureFilter::nearest,
                 .wrap = wrap,
                 .purpose =
                     "near field: per slice (channel k % 4 of layer k / 4) the depth of the surface nearest "
                     "the light within slice k, 1 - f * 254/255 with f in [0, 1] from the slice's top; 0 "
                     "where the slice is empty"});
            for (int t = 0; t < T; ++t) outputs.push_back({std::string(near_depth_texture), 0, t});
        }
        // solid_casters: the targets' texels are 0 or 1, so a logical OR marks them as MAX does, and the
        // closed casters' draws switch it to XOR (emit_slicing.hpp)
        const RenderState logic_or{.clear_color = max_blend.clear_color, .logic_op = LogicOp::bitwise_or};
        b.pass({.name = "slicing",
                .action = PassAction::draw_scene,
                .program = "slicing",
                .inputs = slicing_inputs,
                .outputs = outputs,
                .viewport_width = R,
                .viewport_height = R,
                .state = config.solid_casters ? logic_or : max_blend});
    }

    // Prefilter passes.
    const std::string level_program = config.filter == Filter::gaussian ? "gaussian_level" : "nbuffer_level";
    if (config.packing == Packing::atlas && config.filter != Filter::sat) {
        // level 0, and levels 1 to packed_level (same size) as further colour outputs
        std::vector<AttachmentDesc> packed{{config.filter == Filter::mipmap ? "penumbra_occlusionAtlas" : "penumbra_level0"}};
        for (int l = 1; l <= packed_level(config); ++l) packed.push_back({atlas_level_name(l).str()});
        b.pass({.name = "pack_atlas",
                .program = "pack_atlas",
                .inputs = {{"penumbra_slices", "penumbra_slices"}},
                .outputs = packed,
                .viewport_width = T * R,
                .viewport_height = R});
    }
    if (config.filter == Filter::mipmap && binds_samplers_apart(config)) {
        const bool atlas = config.packing == Packing::atlas;
        describe_level_passes(b, "mip_level", atlas ? "penumbra_occlusionAtlas" : "penumbra_occlusion", L, atlas ? 0 : T,
                              atlas ? T * R : R, R);
    } else if (config.filter == Filter::mipmap) {
        const std::string storage = config.packing == Packing::atlas ? "penumbra_occlusionAtlas" : "penumbra_occlusion";
        b.pass({.name = "mipmaps", .action = PassAction::generate_mipmap, .outputs = {{storage}}});
    } else if (config.filter == Filter::sat) {
        const bool atlas = config.packing == Packing::atlas;
        const std::string final_name = atlas ? "penumbra_satAtlas" : "penumbra_sat";
        const int w = atlas ? T * (R + 1) : R + 1;
        for (int t = 0; t < (atlas ? 1 : T); ++t) {
            const int layer = atlas ? -1 : t;
            std::vector<std::pair<std::string, int>> ints;
            if (!atlas) ints.push_back({"penumbra_sourceLayer", t});
            b.pass({.name = "sat_shift",
                    .program = "sat_shift",
                    .inputs = {{"penumbra_slices", "penumbra_slices"}},
                    .outputs = {{final_name, 0, layer}},
                    .int_uniforms = ints,
                    .viewport_width = w,
                    .viewport_height = R + 1});
            std::string from = final_name, to = "penumbra_satScratch";
            for (int vertical = 0; vertical <= 1; ++vertical)
                for (int l = 0; l <= resolution_levels(config); ++l) {
                    std::vector<std::pair<std::string, int>> pass_ints{{"penumbra_step", 1 << l},
                                                                       {"penumbra_vertical", vertical}};
                    if (!atlas) pass_ints.push_back({"penumbra_sourceLayer", t});
                    b.pass({.name = "sat_pass",
                            .program = "sat_pass",
                            .inputs = {{"penumbra_source", from}},
                            .outputs = {{to, 0, layer}},
                            .int_uniforms = pass_ints,
                            .viewport_width = w,
                            .viewport_height = R + 1});
                    std::swap(from, to);
                }
        }
    } else if (prefilters_in_compute(config)) {
        describe_compute_prefilter(b, config);
    } else {
        for (int l = packed_level(config) + 1; l <= L; ++l) {
            const std::pair<std::string, int> step{"penumbra_step", 1 << (l - 1)};
            if (config.packing == Packing::atlas) {
                const int spacing = level_spacing(config, l), source_spacing = level_spacing(config, l - 1);
                std::vector<std::pair<std::string, int>> ints{step};
                if (reduces_levels(config)) // offsets in texels of the previous level, and its tile side
                    ints = {{"penumbra_step", (1 << (l - 1)) / source_spacing},
                            {"penumbra_sourceTile", R / source_spacing},
                            {"penumbra_scale", spacing / source_spacing}};
                b.pass({.name = level_program,
                        .program = level_program,
                        .inputs = {{"penumbra_source", atlas_level_name(l - 1).str()}},
                        .outputs = {{atlas_level_name(l).str()}},
                        .int_uniforms = ints,
                        .viewport_width = T * R / spacing,
                        .viewport_height = R / spacing});
                continue;
            }
            for (int t = 0; t < T; ++t) {
                const bool array = config.packing == Packing::array;
                const std::string storage = array ? "penumbra_levels" : volume_name(t).str();
                b.pass({.name = level_program,
                        .program = level_program,
                        .inputs = {{"penumbra_source", storage}},
                        .outputs = {{"penumbra_scratch"}},
                        .int_uniforms = {step, {"penumbra_sourceLayer", array ? (l - 1) * T + t : l - 1}},
                        .viewport_width = R,
                        .viewport_height = R});
                b.pass({.name = "copy_level",
                        .action = PassAction::copy,
                        .inputs = {{"", "penumbra_scratch", 0}},
                        .outputs = {{storage, 0, array ? l * T + t : l}},
                        .viewport_width = R,
                        .viewport_height = R});
            }
        }
    }
}

// The whole layout of the occlusion textures: the shadow phase above, then the deferred shading.
inline void describe_occlusion_layout(LayoutBuilder& b, const Config& config) {
    b.layout.textures_per_layer = texture_count(config);
    b.layout.max_level = max_level(config);
    describe_occlusion_passes(b, config);
    describe_screen_textures(b, config);
    describe_deferred_pass(b);
}

} // namespace penumbra::detail
