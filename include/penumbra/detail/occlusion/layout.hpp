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
    if (program == "slicing") return caster_param_groups(config, "PenumbraSlicing", slicing_params(config));
    if (program == "depth_bins") return caster_param_groups(config, "PenumbraPass", depth_bins_params());
    std::vector<Param> params;
    if (program == "slice_boundaries") params = slice_boundaries_params();
    if (program == "pack_atlas") params = pack_atlas_params();
    if (program == "unpack_slices") params = unpack_params();
    if (program == "nbuffer_level" || program == "gaussian_level") params = level_params(config);
    if (program == "nbuffer_levels") params = nbuffer_compute_params();
    if (program == "sat_shift") params = sat_shift_params(config);
    if (program == "sat_pass") params = sat_pass_params(config);
    return {{"PenumbraPass", std::move(params)}};
}

// Adaptive slice placement (emit_slice_placement.hpp), phase "shadow", before slicing: the depth
// bins in draws of 16 bins (four layers each), their mip chain, then the S + 1 boundaries.
inline void describe_slice_placement_passes(LayoutBuilder& b, const Config& config, const RenderState& max_blend) {
    const int D = depth_bins_resolution, layers = depth_bins / 4;
    TextureDesc& bins = b.texture("penumbra_depthBins", "2D_ARRAY", "RGBA8", D, D, layers, depth_bins_read_level + 1,
                                  "NEAREST_MIPMAP_NEAREST", "NEAREST",
                                  "adaptive slice placement: coverage of " + std::to_string(depth_bins) +
                                      " depth bins seen from the slicing camera, four per layer, mip chain");
    bins.wrap = "CLAMP_TO_EDGE";
    TextureDesc& boundaries =
        b.texture("penumbra_sliceBoundaries", "2D", "R32UI", config.slices + 1, 1, 1, 1, "NEAREST", "NEAREST",
                  "adaptive slice placement: texel k = bits of the depth of slice k's top (texel S: the last slice's "
                  "bottom), scene units; read with texelFetch and uintBitsToFloat");
    boundaries.wrap = "CLAMP_TO_EDGE";
    for (int first = 0; first < depth_bins; first += depth_bins_per_draw) {
        std::vector<AttachmentDesc> outputs;
        for (int t = 0; t < depth_bins_per_draw / 4; ++t) outputs.push_back({"penumbra_depthBins", 0, first / 4 + t});
        b.pass("depth_bins", "draw_scene", "depth_bins", {}, outputs, {{"penumbra_firstBin", first}}, D, D, max_blend);
    }
    b.pass("depth_bins_mipmaps", "generate_mipmap", "", {}, {{"penumbra_depthBins", 0, -1}}, {}, 0, 0);
    b.fullscreen("slice_boundaries", "slice_boundaries", {{"penumbra_depthBins", "penumbra_depthBins"}},
                 {"penumbra_sliceBoundaries", 0, -1}, {}, config.slices + 1, 1);
}

// The compute prefilter (prefilter_stage compute): one "dispatch" pass per group of levels of
// compute_dispatches, reading the level it starts from as a sampler and writing its levels as images.
inline void describe_compute_prefilter(LayoutBuilder& b, const Config& config) {
    const int R = config.resolution, T = texture_count(config), N = compute_group_side;
    const std::string format(level_format(config));
    for (const ComputeDispatch& d : compute_dispatches(config)) {
        const int source = d.source_level, spacing = level_spacing(config, source), tile = R / spacing;
        int same_size = 0;
        while (same_size < d.levels && level_spacing(config, source + 1 + same_size) == spacing) ++same_size;
        const int groups = (tile + N - 1) / N;
        const std::string name = "nbuffer_levels_" + std::to_string(source + 1) + "_" + std::to_string(source + d.levels);
        b.pass(name, "dispatch", "nbuffer_levels", {{"penumbra_source", atlas_level_name(source).str()}}, {},
               {{"penumbra_levels", d.levels},
                {"penumbra_step", compute_step(config, source)},
                {"penumbra_sourceTile", tile},
                {"penumbra_sameSize", same_size},
                {"penumbra_groupsPerTile", groups}},
               T * tile, tile); // the viewport: the source level's texels the workgroups cover
        PassDesc& pass = b.layout.passes.back();
        pass.dispatch = DispatchDesc{{T * groups, groups, 1}, {N, N, 1}, {"TEXTURE_FETCH", "TEXTURE_UPDATE"}};
        for (int i = 0; i < d.levels; ++i)
            pass.image_outputs.push_back({compute_image_name(i).str(), atlas_level_name(source + 1 + i).str(), 0, -1, i,
                                          format, "WRITE_ONLY"});
    }
}

// Occlusion textures, phase "shadow": slicing into the slices' storage (beyond 32 slices: into bits,
// then unpack draws into that storage), then the prefilter passes.
inline void describe_occlusion_passes(LayoutBuilder& b, const Config& config) {
    // L: the highest filter level (level_bound); the summed-area table doubles over all log2(R) steps
    const int R = config.resolution, T = texture_count(config), L = max_level(config);
    const std::string level_fmt(level_format(config));
    // Storage, and where the slicing pass writes slice texture t.
    std::vector<AttachmentDesc> slicing_outputs;
    const bool sliced_into_array = config.packing == Packing::atlas || config.filter == Filter::sat;
    if (sliced_into_array) {
        b.texture("penumbra_slices", "2D_ARRAY", "RGBA8", R, R, T, 1, "NEAREST", "NEAREST",
                "slicing output: binary coverage, one layer per four slices");
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_slices", 0, t});
    }
    if (config.filter == Filter::mipmap && config.packing == Packing::atlas) {
        b.texture("penumbra_occlusionAtlas", "2D", "RGBA8", T * R, R, 1, L + 1, "LINEAR_MIPMAP_LINEAR", "LINEAR",
                "occlusion tiles side by side, mip chain");
    } else if (config.filter == Filter::mipmap) {
        b.texture("penumbra_occlusion", "2D_ARRAY", "RGBA8", R, R, T, L + 1, "LINEAR_MIPMAP_LINEAR", "LINEAR",
                "occlusion textures, mip chain");
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_occlusion", 0, t});
    } else if (config.filter == Filter::sat) {
        const bool atlas = config.packing == Packing::atlas;
        for (const char* name : {"penumbra_sat", "penumbra_satScratch"}) {
            const std::string n = atlas ? std::string(name) == "penumbra_sat" ? "penumbra_satAtlas" : name : name;
            b.texture(n, atlas ? "2D" : "2D_ARRAY", "RGBA32F", atlas ? T * (R + 1) : R + 1, R + 1, atlas ? 1 : T, 1,
                    "LINEAR", "LINEAR", n == "penumbra_satScratch" ? "summed-area ping-pong target"
                                                                   : "exclusive summed-area tables, (R+1)-texel tiles");
        }
    } else if (config.packing == Packing::atlas) {
        for (int l = 0; l <= L; ++l) {
            const int side = R / level_spacing(config, l); // reduced levels: R / 2^(l - level_reduction)
            b.texture(atlas_level_name(l).str(), "2D", level_fmt, T * side, side, 1, 1, "LINEAR", "LINEAR",
                    "filter level " + std::to_string(l) + ", tiles side by side" +
                        (side < R ? ", " + std::to_string(side) + " texels per tile (texel j: level-0 texel " +
                                        std::to_string(R / side) + " * j)"
                                  : std::string()));
        }
    } else if (config.packing == Packing::array) {
        b.texture("penumbra_levels", "2D_ARRAY", level_fmt, R, R, (L + 1) * T, 1, "LINEAR", "LINEAR",
                "filter levels, layer = level * T + texture");
        b.texture("penumbra_scratch", "2D", level_fmt, R, R, 1, 1, "NEAREST", "NEAREST",
                "level being built (a texture cannot be sampled and rendered at once)");
        for (int t = 0; t < T; ++t) slicing_outputs.push_back({"penumbra_levels", 0, t});
    } else {
        for (int t = 0; t < T; ++t) {
            b.texture(volume_name(t).str(), "3D", level_fmt, R, R, L + 1, 1, "LINEAR", "LINEAR",
                    "slices " + std::to_string(4 * t) + " to " + std::to_string(4 * t + 3) + ", levels along depth");
            slicing_outputs.push_back({volume_name(t).str(), 0, 0});
        }
        b.texture("penumbra_scratch", "2D", level_fmt, R, R, 1, 1, "NEAREST", "NEAREST",
                "level being built (a texture cannot be sampled and rendered at once)");
    }

    // layout.json's slice_map: slice k is channel k % 4 of slicing output k / 4 (emit_slicing.hpp)
    for (int k = 0; k < config.slices; ++k) {
        const AttachmentDesc& out = slicing_outputs[static_cast<std::size_t>(k / 4)];
        b.layout.slice_map.push_back({k, out.texture, out.layer, std::string(1, "rgba"[k % 4])});
    }

    RenderState max_blend; // a texel is covered when any triangle covers it: blend MAX over a cleared target
    max_blend.blend = true;
    max_blend.blend_equation = "MAX";
    max_blend.blend_src = max_blend.blend_dst = "ONE";
    max_blend.clear_color = std::array<float, 4>{0.0f, 0.0f, 0.0f, 0.0f};
    std::vector<BindingDesc> slicing_inputs;
    if (places_slices_adaptively(config)) {
        describe_slice_placement_passes(b, config, max_blend);
        slicing_inputs.push_back({"penumbra_sliceBoundaries", "penumbra_sliceBoundaries"});
    }
    if (slices_as_bits(config)) {
        // paper §3.7: every slice a bit of one RGBA32UI target, OR-ed, then unpacked into the textures
        // the slicing would otherwise write, one group of colour attachments per draw
        TextureDesc& bits = b.texture("penumbra_sliceBits", "2D", "RGBA32UI", R, R, 1, 1, "NEAREST", "NEAREST",
                                      "slicing output: bit k % 32 of component k / 32 marks slice k");
        bits.wrap = "CLAMP_TO_EDGE";
        RenderState or_bits;
        or_bits.logic_op = "OR";
        or_bits.clear_color = max_blend.clear_color;
        b.pass("slicing", "draw_scene", "slicing", slicing_inputs, {{"penumbra_sliceBits", 0, -1}}, {}, R, R, or_bits);
        const int group = unpack_group(config);
        for (int d = 0; d < unpack_draws(config); ++d) {
            const auto first = slicing_outputs.begin() + d * group;
            b.pass("unpack_slices", "fullscreen", "unpack_slices", {{"penumbra_sliceBits", "penumbra_sliceBits"}},
                   {first, first + group}, {{"penumbra_firstSlice", 4 * group * d}}, R, R);
        }
    } else {
        b.pass("slicing", "draw_scene", "slicing", slicing_inputs, slicing_outputs, {}, R, R, max_blend);
    }

    // Prefilter passes.
    const std::string level_program = config.filter == Filter::gaussian ? "gaussian_level" : "nbuffer_level";
    if (config.packing == Packing::atlas && config.filter != Filter::sat) {
        // level 0, and levels 1 to packed_level (same size) as further colour outputs
        std::vector<AttachmentDesc> packed{{config.filter == Filter::mipmap ? "penumbra_occlusionAtlas" : "penumbra_level0", 0, -1}};
        for (int l = 1; l <= packed_level(config); ++l) packed.push_back({atlas_level_name(l).str(), 0, -1});
        b.pass("pack_atlas", "fullscreen", "pack_atlas", {{"penumbra_slices", "penumbra_slices"}}, packed, {}, T * R, R);
    }
    if (config.filter == Filter::mipmap) {
        const std::string storage = config.packing == Packing::atlas ? "penumbra_occlusionAtlas" : "penumbra_occlusion";
        b.pass("mipmaps", "generate_mipmap", "", {}, {{storage, 0, -1}}, {}, 0, 0);
    } else if (config.filter == Filter::sat) {
        const bool atlas = config.packing == Packing::atlas;
        const std::string final_name = atlas ? "penumbra_satAtlas" : "penumbra_sat";
        const int w = atlas ? T * (R + 1) : R + 1;
        for (int t = 0; t < (atlas ? 1 : T); ++t) {
            const int layer = atlas ? -1 : t;
            std::vector<std::pair<std::string, int>> ints;
            if (!atlas) ints.push_back({"penumbra_sourceLayer", t});
            b.fullscreen("sat_shift", "sat_shift", {{"penumbra_slices", "penumbra_slices"}}, {final_name, 0, layer},
                       ints, w, R + 1);
            std::string from = final_name, to = "penumbra_satScratch";
            for (int vertical = 0; vertical <= 1; ++vertical)
                for (int l = 0; l <= resolution_levels(config); ++l) {
                    std::vector<std::pair<std::string, int>> pass_ints{{"penumbra_step", 1 << l},
                                                                       {"penumbra_vertical", vertical}};
                    if (!atlas) pass_ints.push_back({"penumbra_sourceLayer", t});
                    b.fullscreen("sat_pass", "sat_pass", {{"penumbra_source", from}}, {to, 0, layer}, pass_ints, w,
                               R + 1);
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
                b.fullscreen(level_program, level_program, {{"penumbra_source", atlas_level_name(l - 1).str()}},
                           {atlas_level_name(l).str(), 0, -1}, ints, T * R / spacing, R / spacing);
                continue;
            }
            for (int t = 0; t < T; ++t) {
                const bool array = config.packing == Packing::array;
                const std::string storage = array ? "penumbra_levels" : volume_name(t).str();
                b.fullscreen(level_program, level_program, {{"penumbra_source", storage}}, {"penumbra_scratch", 0, -1},
                           {step, {"penumbra_sourceLayer", array ? (l - 1) * T + t : l - 1}}, R, R);
                b.pass("copy_level", "copy", "", {{"", "penumbra_scratch", 0}}, {{storage, 0, array ? l * T + t : l}}, {},
                     R, R);
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
