// penumbra/detail/occlusion/fields.hpp — the occlusion textures' configuration fields: one row each
// (penumbra/config_field.hpp), read by penumbra/config_fields.hpp.
#pragma once

#include "../../config_field.hpp"

#include <array>

namespace penumbra::detail {

constexpr auto occlusion_fields() {
    return std::array{
        member<&Config::slices>({.key = "slices",
                                 .flag = "--slices",
                                 .metavar = "N",
                                 .min = 1,
                                 .max = 128,
                                 .allowed = "1 to 32, 64 or 128",
                                 .help = "slices along the light normal",
                                 .techniques = "occlusion"}),
        member<&Config::resolution>({.key = "resolution",
                                     .flag = "--resolution",
                                     .metavar = "R",
                                     .min = 32,
                                     .max = 4096,
                                     .power_of_two = true,
                                     .allowed = "a power of two from 32 to 4096",
                                     .help = "occlusion texture side in texels",
                                     .techniques = "occlusion"}),
        member<&Config::filter>({.key = "filter",
                                 .flag = "--filter",
                                 .metavar = "F",
                                 .help = "prefilter",
                                 .techniques = "occlusion"}),
        member<&Config::fusion>({.key = "fusion",
                                 .flag = "--fusion",
                                 .metavar = "U",
                                 .help = "slice fusion",
                                 .techniques = "occlusion"}),
        member<&Config::packing>({.key = "packing",
                                  .flag = "--packing",
                                  .metavar = "P",
                                  .help = "storage",
                                  .techniques = "occlusion"}),
        member<&Config::leak_fix>(
            {.key = "leak_fix",
             .flag = "--no-leak-fix",
             .help = "the leak fix: a fragment of slice k also marks slice k+1 (paper §3.4.1)",
             .techniques = "occlusion"}),
        member<&Config::self_shadow_fade>({.key = "self_shadow_fade",
                                           .flag = "--no-fade",
                                           .help = "the self-shadow fade of the slice containing the point "
                                                   "(paper §3.4.2)",
                                           .techniques = "occlusion"}),
        member<&Config::tangent_clip>(
            {.key = "tangent_clip",
             .flag = "--[no-]tangent-clip",
             .help =
                 "kernels cover only the light above the receiver's tangent plane; penumbraVisibility takes "
                 "the normal",
             .detail =
                 "kernels cover only the light above the receiver's tangent plane (the snippet takes the "
                 "normal; the screen pass reads penumbra_worldNormals)",
             .techniques = "occlusion"}),
        member<&Config::tangent_clip_offset>(
            {.key = "tangent_clip_offset",
             .flag = "--tangent-clip-offset",
             .metavar = "T",
             .min = 0,
             .max = 8,
             .allowed = "0 to 8 slicing texels",
             .help =
                 "slicing texels by which the tangent clip moves a receiver sideways along its normal, off "
                 "its own texels",
             .detail =
                 "with the tangent clip, slicing texels by which a receiver moves sideways along its normal "
                 "before its kernels are placed (off its own texels in the slices; each texel also moves the "
                 "kernels off occluders within a slice or two of it)",
             .techniques = "occlusion"}),
        member<&Config::clip_footprint>(
            {.key = "clip_footprint",
             .flag = "--no-clip-footprint",
             .help = "the tangent clip also moves receivers off their own footprint in the slice above them",
             .detail =
                 "with the tangent clip, a receiver also moves off its own tangent plane's footprint in the "
                 "slice above it (the plane's sideways run over the slice's content depth, with the slicing "
                 "perspective; 0 on faces that face the light, capped at 4 slicing texels)",
             .techniques = "occlusion"}),
        member<&Config::fade_ramp>(
            {.key = "fade_ramp",
             .flag = "--fade-ramp",
             .metavar = "F",
             .min = 0,
             .max = 4,
             .min_exclusive = true,
             .allowed = "more than 0 to 4 (fraction of a slice's thickness)",
             .help = "the self-shadow fade ramps over F of a slice's thickness",
             .detail =
                 "with the self-shadow fade, the fraction of a slice's thickness over which a plane's weight "
                 "ramps from 0 (at the point) to 1",
             .techniques = "occlusion"}),
        member<&Config::slice_placement>(
            {.key = "slice_placement",
             .flag = "--slice-placement",
             .metavar = "P",
             .help =
                 "slice boundaries: uniform (equal slices over the bounds) or adaptive (at the depths the "
                 "geometry occupies, computed on the GPU; paper §5)",
             .detail =
                 "uniform slices over the bounds (penumbra_sliceDepths), or adaptive (paper §5): boundaries "
                 "at the depths the geometry occupies, computed on the GPU by the depth_bins and "
                 "slice_boundaries passes into penumbra_sliceBoundaries",
             .techniques = "occlusion"}),
        member<&Config::level_bound>(
            {.key = "level_bound",
             .flag = "--level-bound",
             .metavar = "N",
             .min = -1,
             .allowed = "-1 (every level) or 0 to log2(resolution)",
             .help =
                 "highest filter level built and read: wider kernels read level N; the widest kernel of a "
                 "light and scene is 2^N texels for the N of penumbra::kernel_level_bound; -1: every level",
             .detail =
                 "highest filter level built and read (N-buffer, Gaussian, mip chain); -1: log2(resolution), "
                 "every level. The largest kernel a receiver inside the bounds can ask for follows from the "
                 "light, the bounds and the slice depths (penumbra::kernel_level_bound); the GL runtime fits "
                 "it at set_light and grows it with the light",
             .techniques = "occlusion"}),
        member<&Config::level_format>(
            {.key = "level_format",
             .flag = "--level-format",
             .metavar = "F",
             .help = "storage of the filtered levels (essl300: always rgba8)",
             .detail =
                 "storage of the filtered N-buffer / Gaussian levels: rgba8 (8-bit normalized, half the "
                 "bytes; a window mean rounded to 1/255 per level) or rgba16f (half floats); essl300 stores "
                 "rgba8 whatever this says",
             .techniques = "occlusion"}),
        member<&Config::level_reduction>(
            {.key = "level_reduction",
             .flag = "--level-reduction",
             .metavar = "N",
             .min = -1,
             .allowed = "-1 (every level at full resolution) or 0 to log2(resolution)",
             .help =
                 "atlas of N-buffer or Gaussian levels: the levels above N are stored at half the resolution "
                 "of the one below (level l at resolution / 2^(l - N)); -1: every level at full resolution",
             .detail =
                 "atlas of N-buffer or Gaussian levels: the levels above this one are stored at half the "
                 "resolution of the one below, level l at resolution / 2^(l - level_reduction) per axis (its "
                 "texture's width and height say so; texel j of a tile stands for level-0 texel "
                 "2^(l - level_reduction)·j, and the level passes' viewports are that size); -1: every level "
                 "at full resolution. The array and volume packings store every level at full resolution "
                 "whatever this says",
             .techniques = "occlusion"}),
        member<&Config::prefilter_stage>(
            {.key = "prefilter_stage",
             .flag = "--prefilter-stage",
             .metavar = "S",
             .help =
                 "what builds the N-buffer levels above the packing pass (compute: dispatches that build "
                 "several levels each in shared memory; filter nbuffer, packing atlas, target glsl450 only)",
             .detail =
                 "what builds the N-buffer levels above the atlas packing pass. fragment (the default; "
                 "absent "
                 "means fragment): one fullscreen pass per level. compute (filter nbuffer, packing atlas, "
                 "target glsl450): \"dispatch\" passes, each building several levels of one workgroup's tile "
                 "in shared memory (penumbra_nbuffer_levels.comp)",
             .techniques = "occlusion",
             .omit_default = true}),
        member<&Config::solid_casters>(
            {.key = "solid_casters",
             .flag = "--solid-casters",
             .help =
                 "closed caster meshes fill the slices between their surfaces (volumes, not shells; desktop "
                 "OpenGL)",
             .detail =
                 "closed caster meshes fill the slices between where the slicing camera's rays enter and "
                 "leave them, so a wall seen edge-on by the light still blocks the grazing rays of a large "
                 "light (absent means false). The slicing program takes the per-draw parameter "
                 "penumbra_casterClosed (source \"draw\"): 1 for a closed mesh (watertight, "
                 "counter-clockwise outward faces), drawn with a logical XOR instead of the pass's OR; 0 for "
                 "open casters (cards, planes), drawn after every closed one. Targets with a logical "
                 "operation on colour targets only (glsl450, glsl330)",
             .techniques = "occlusion",
             .omit_default = true}),
        member<&Config::irradiance_window>(
            {.key = "irradiance_window",
             .flag = "--[no-]irradiance-window",
             .help =
                 "weigh the light by the irradiance it sends the receiver, not by its area: the visibility "
                 "of the clip and of its core around the irradiance's peak, mixed (two passes of the slice "
                 "loop; rect light with the tangent clip, no effect elsewhere)",
             .detail =
                 "the visibility weighs each light point by the irradiance it sends the receiver (the "
                 "cosines at both ends over the squared distance, with the receiver's normal), as the "
                 "shading's unoccluded irradiance does, instead of by area (absent means true): the slice "
                 "loop runs for the tangent clip's part and for its core, a square half as wide around the "
                 "point of the light that sends the most, and the two visibilities are mixed so that the "
                 "core "
                 "and the ring around it carry their share of the irradiance (the rectangle's form factor, "
                 "in "
                 "closed form). Costs a second pass of the slice loop per receiver. A refinement of the "
                 "tangent clip's part of a rectangle: no effect without the clip, nor under the sun, whose "
                 "points all send the same cosine",
             .techniques = "occlusion",
             .omit_default = true}),
        member<&Config::irradiance_quadrants>(
            {.key = "irradiance_quadrants",
             .flag = "--[no-]irradiance-quadrants",
             .help = "with the irradiance window: the clip's four quadrants fused apart as well, each "
                     "weighed by the irradiance it sends outside the core (five passes of the slice "
                     "loop, not two)",
             .detail = "with the irradiance window (absent means false): the slice loop also runs for "
                       "each quadrant of the tangent clip's part, and each quadrant's part outside the "
                       "core carries its share of the irradiance, so a weight that falls across the light "
                       "(a receiver beside it, or tilted) is followed, and the slices are fused over a "
                       "quarter of the light at a time. Costs three more passes of the slice loop per "
                       "receiver; no effect without the window",
             .techniques = "occlusion",
             .omit_default = true}),
        member<&Config::near_field>(
            {.key = "near_field",
             .flag = "--[no-]near-field",
             .help = "occluders within a slice or two of the receiver (a contact) shadow it: the slicing "
                     "pass also "
                     "keeps each slice's nearest depth and rays march through the slices around the receiver",
             .detail =
                 "the slicing pass also writes, per slice and texel, the depth of the surface nearest the "
                 "light "
                 "within that slice (penumbra_nearDepth, absent means false), and penumbraVisibility marches "
                 "rays from the receiver towards the light through the two slice thicknesses above it: a ray "
                 "is blocked where it passes below a stored surface of the slice it is in. The fused "
                 "visibility is capped by the rays' (docs/model.md §1.7.7). Uniform slice placement, at most "
                 "16 slices (twice the render targets), no solid casters; glsl450 and glsl330",
             .techniques = "occlusion",
             .omit_default = true}),
    };
}

} // namespace penumbra::detail
