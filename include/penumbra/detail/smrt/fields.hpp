// penumbra/detail/smrt/fields.hpp — shadow-map ray tracing's configuration fields (smrt.*; its depth
// map: shadow_map.*, detail/shadow_map/fields.hpp): one row each (penumbra/config_field.hpp), read by
// penumbra/config_fields.hpp. Added after layout_version 3, so layout.json writes them only when not
// the default (omit_default) or when the technique is smrt.
#pragma once

#include "../../config_field.hpp"

#include <array>

namespace penumbra::detail {

constexpr auto smrt_fields() {
    using S = SmrtParams;
    return std::array{
        member<&Config::smrt, &S::rays>({.key = "smrt.rays", .flag = "--smrt-rays", .metavar = "N", .min = 1, .max = 16,
                                         .help = "rays per pixel, to points spread over the light",
                                         .section = "shadow-map ray tracing: rays, march, extrapolation, bias",
                                         .techniques = "smrt", .omit_default = true}),
        member<&Config::smrt, &S::samples>({.key = "smrt.samples", .flag = "--smrt-samples", .metavar = "N", .min = 2,
                                            .max = 32, .help = "depth-map samples per ray (the step grows along it)",
                                            .techniques = "smrt", .omit_default = true}),
        member<&Config::smrt, &S::extrapolate_max_slope>(
            {.key = "smrt.extrapolate_max_slope", .flag = "--smrt-extrapolate-slope", .metavar = "X", .min = 0,
             .max = 50,
             .help = "largest occluder depth slope carried past a silhouette (depth per lateral scene unit); 0: no "
                     "extrapolation",
             .techniques = "smrt", .omit_default = true}),
        member<&Config::smrt, &S::max_slope_bias>(
            {.key = "smrt.max_slope_bias", .flag = "--smrt-max-slope-bias", .metavar = "X", .min = 0, .max = 1000,
             .help = "largest receiver slope the receiver bias follows (depth per lateral scene unit)",
             .techniques = "smrt", .omit_default = true}),
        member<&Config::smrt, &S::texel_dither>(
            {.key = "smrt.texel_dither", .flag = "--smrt-texel-dither", .metavar = "K", .min = 0, .max = 8,
             .allowed = "0 to 8 shadow-map texels",
             .help = "rays start off the receiver along its normal by up to K texels, per pixel at random",
             .techniques = "smrt", .omit_default = true}),
        member<&Config::smrt, &S::frame>(
            {.key = "smrt.frame", .flag = "--smrt-frame", .metavar = "F", .min = 0, .max = 1023,
             .help = "frame index that rotates the per-pixel pattern (temporal accumulation of frames 0 to N-1)",
             .techniques = "smrt", .omit_default = true}),
    };
}

} // namespace penumbra::detail
