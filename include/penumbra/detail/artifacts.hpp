// penumbra/detail/artifacts.hpp — every file Penumbra can emit: its name, its stage and its text.
// Which files and programs a configuration emits: detail/techniques.hpp.
#pragma once

#include "../program.hpp"
#include "occlusion/emit_prefilter.hpp"
#include "occlusion/emit_prefilter_compute.hpp"
#include "emit_shading.hpp"
#include "occlusion/emit_slice_placement.hpp"
#include "occlusion/emit_slicing.hpp"
#include "occlusion/emit_unpack.hpp"
#include "oim/emit_oim.hpp"
#include "shadow_map/emit_depth.hpp"
#include "erosion/emit_passes.hpp"

namespace penumbra {

// Every file Penumbra can emit. Which ones a configuration needs: detail::artifacts() (techniques.hpp).
enum class Artifact : std::uint8_t {
    slicing_vert,
    slicing_frag,
    fullscreen_vert,
    pack_atlas_frag,
    nbuffer_level_frag,
    gaussian_level_frag,
    sat_shift_frag,
    sat_pass_frag,
    shading_vert,
    shading_frag,
    deferred_frag,
    visibility_snippet, // penumbra_visibility.glsl, no #version: for inclusion into the engine's shaders
    shadow_depth_vert,  // shadow map techniques: the depth pass from the light
    shadow_depth_frag,
    oim_shading_vert,   // occlusion interval maps: the example pass (with texture coordinates)
    oim_shading_frag,
    oim_deferred_frag,  // occlusion interval maps: the deferred pass over a G-buffer of texture coordinates
    erosion_hard_frag,  // erosion: the screen passes (erosion/emit_passes.hpp)
    erosion_edges_frag,
    erosion_reduce_frag,
    erosion_erode_frag,
    erosion_blur_frag,
    unpack_slices_frag, // more than 32 slices: the sliced bits into RGBA occlusion textures (occlusion/emit_unpack.hpp)
    depth_bins_vert,       // adaptive slice placement: the depth-bin pre-pass (occlusion/emit_slice_placement.hpp)
    depth_bins_frag,
    slice_boundaries_frag, // adaptive slice placement: boundaries from the depth bins
    nbuffer_levels_comp,   // compute prefilter: N-buffer levels, several per dispatch (occlusion/emit_prefilter_compute.hpp)
};

constexpr std::string_view file_name(Artifact artifact) {
    switch (artifact) {
    case Artifact::slicing_vert: return "penumbra_slicing.vert";
    case Artifact::slicing_frag: return "penumbra_slicing.frag";
    case Artifact::fullscreen_vert: return "penumbra_fullscreen.vert";
    case Artifact::pack_atlas_frag: return "penumbra_pack_atlas.frag";
    case Artifact::nbuffer_level_frag: return "penumbra_nbuffer_level.frag";
    case Artifact::gaussian_level_frag: return "penumbra_gaussian_level.frag";
    case Artifact::sat_shift_frag: return "penumbra_sat_shift.frag";
    case Artifact::sat_pass_frag: return "penumbra_sat_pass.frag";
    case Artifact::shading_vert: return "penumbra_shading.vert";
    case Artifact::shading_frag: return "penumbra_shading.frag";
    case Artifact::deferred_frag: return "penumbra_deferred.frag";
    case Artifact::visibility_snippet: return "penumbra_visibility.glsl";
    case Artifact::shadow_depth_vert: return "penumbra_shadow_depth.vert";
    case Artifact::shadow_depth_frag: return "penumbra_shadow_depth.frag";
    case Artifact::oim_shading_vert: return "penumbra_oim_shading.vert";
    case Artifact::oim_shading_frag: return "penumbra_oim_shading.frag";
    case Artifact::oim_deferred_frag: return "penumbra_oim_deferred.frag";
    case Artifact::erosion_hard_frag: return "penumbra_erosion_hard.frag";
    case Artifact::erosion_edges_frag: return "penumbra_erosion_edges.frag";
    case Artifact::erosion_reduce_frag: return "penumbra_erosion_reduce.frag";
    case Artifact::erosion_erode_frag: return "penumbra_erosion_erode.frag";
    case Artifact::erosion_blur_frag: return "penumbra_erosion_blur.frag";
    case Artifact::unpack_slices_frag: return "penumbra_unpack_slices.frag";
    case Artifact::depth_bins_vert: return "penumbra_depth_bins.vert";
    case Artifact::depth_bins_frag: return "penumbra_depth_bins.frag";
    case Artifact::slice_boundaries_frag: return "penumbra_slice_boundaries.frag";
    case Artifact::nbuffer_levels_comp: return "penumbra_nbuffer_levels.comp";
    }
    return "";
}

constexpr Stage artifact_stage(Artifact artifact) {
    switch (artifact) {
    case Artifact::slicing_vert:
    case Artifact::depth_bins_vert:
    case Artifact::shadow_depth_vert:
    case Artifact::fullscreen_vert:
    case Artifact::shading_vert:
    case Artifact::oim_shading_vert: return Stage::vertex;
    case Artifact::nbuffer_levels_comp: return Stage::compute;
    default: return Stage::fragment;
    }
}

namespace detail {

// The text of one artifact. Pure function of the configuration; `config` must be valid.
constexpr Text artifact_text(const Config& config, Artifact artifact) {
    switch (artifact) {
    case Artifact::slicing_vert: return slicing_vertex(config);
    case Artifact::slicing_frag: return slicing_fragment(config);
    case Artifact::fullscreen_vert: return fullscreen_vertex(config);
    case Artifact::pack_atlas_frag: return pack_atlas_fragment(config);
    case Artifact::nbuffer_level_frag: return nbuffer_level_fragment(config);
    case Artifact::gaussian_level_frag: return gaussian_level_fragment(config);
    case Artifact::sat_shift_frag: return sat_shift_fragment(config);
    case Artifact::sat_pass_frag: return sat_pass_fragment(config);
    case Artifact::shading_vert: return example_vertex(config);
    case Artifact::shading_frag: return example_fragment(config);
    case Artifact::deferred_frag: return deferred_fragment(config);
    case Artifact::visibility_snippet: return technique_visibility_snippet(config);
    case Artifact::shadow_depth_vert: return shadow_depth_vertex(config);
    case Artifact::shadow_depth_frag: return shadow_depth_fragment(config);
    case Artifact::oim_shading_vert: return oim_example_vertex(config);
    case Artifact::oim_shading_frag: return oim_example_fragment(config);
    case Artifact::oim_deferred_frag: return oim_deferred_fragment(config);
    case Artifact::erosion_hard_frag: return erosion_fragment(config, "erosion_hard");
    case Artifact::erosion_edges_frag: return erosion_fragment(config, "erosion_edges");
    case Artifact::erosion_reduce_frag: return erosion_fragment(config, "erosion_reduce");
    case Artifact::erosion_erode_frag: return erosion_fragment(config, "erosion_erode");
    case Artifact::erosion_blur_frag: return erosion_fragment(config, "erosion_blur");
    case Artifact::unpack_slices_frag: return unpack_fragment(config);
    case Artifact::depth_bins_vert: return depth_bins_vertex(config);
    case Artifact::depth_bins_frag: return depth_bins_fragment(config);
    case Artifact::slice_boundaries_frag: return slice_boundaries_fragment(config);
    case Artifact::nbuffer_levels_comp: return nbuffer_levels_compute(config);
    }
    return {};
}

// A program of a configuration: its name (as layout.json and the passes call it) and stage files.
struct ProgramPlan {
    std::string_view name;
    std::vector<Artifact> stages;
};

} // namespace detail
} // namespace penumbra
