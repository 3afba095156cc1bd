// penumbra/detail/shadow_map/fields.hpp — the configuration fields of the shadow-map techniques: the
// depth map (shadow_map.*, shared with erosion), PCF's kernel (pcf.*) and PCSS's search and filter
// (pcss.*); one row each (penumbra/config_field.hpp), read by penumbra/config_fields.hpp.
#pragma once

#include "../../config_field.hpp"

#include <array>

namespace penumbra::detail {

// shadow_map.* (the depth map of shadowmap, pcf, pcss and erosion), then pcf.*, then pcss.*.
constexpr auto shadow_map_fields() {
    using S = ShadowMapParams;
    using P = PcfParams;
    using Q = PcssParams;
    return std::array{
        member<&Config::shadow_map, &S::resolution>(
            {.key = "shadow_map.resolution", .flag = "--shadow-resolution", .metavar = "R", .min = 32, .max = 8192,
             .power_of_two = true, .allowed = "a power of two from 32 to 8192", .help = "shadow map side in texels",
             .section = "the depth map from the light", .techniques = "shadowmap, pcf, pcss", .shared = true}),
        member<&Config::shadow_map, &S::constant_bias>(
            {.key = "shadow_map.constant_bias", .flag = "--shadow-bias", .metavar = "B", .min = 0, .max = 10,
             .allowed = "0 to 10 scene units", .help = "constant depth bias along the light axis",
             .techniques = "shadowmap, pcf, pcss", .shared = true}),
        member<&Config::shadow_map, &S::slope_bias>(
            {.key = "shadow_map.slope_bias", .flag = "--shadow-slope-bias", .metavar = "S", .min = 0, .max = 16,
             .help = "slope bias: S times the depth change across one texel",
             .techniques = "shadowmap, pcf, pcss", .shared = true}),
        member<&Config::shadow_map, &S::normal_offset>(
            {.key = "shadow_map.normal_offset", .flag = "--shadow-normal-offset", .metavar = "K", .min = 0, .max = 8,
             .allowed = "0 to 8 shadow-map texels",
             .help = "receivers move along their normal by K texels times sin(angle to the light) before the lookup",
             .detail = "the receiver moves along its normal by this many shadow-map texels (their size at the "
                       "receiver) times sin(angle to the light) before the lookup; more than 0: penumbraVisibility "
                       "uses the normal and the screen pass reads penumbra_worldNormals",
             .techniques = "shadowmap, pcf, pcss"}),
        member<&Config::shadow_map, &S::receiver_plane_bias>(
            {.key = "shadow_map.receiver_plane_bias", .flag = "--no-receiver-plane-bias",
             .help = "taps compare against the depth of the receiver's tangent plane under the tap, not the "
                     "receiver's own depth",
             .detail = "every tap (blocker search and filter) compares against the depth of the receiver's tangent "
                       "plane under that tap instead of the receiver's own depth (receiver-plane depth bias); true: "
                       "penumbraVisibility uses the normal and the screen pass reads penumbra_worldNormals",
             .techniques = "pcf, pcss"}),
        // pcf: the fixed kernel
        member<&Config::pcf, &P::pattern>({.key = "pcf.pattern", .flag = "--pcf-pattern", .metavar = "P",
                                           .help = "tap pattern", .section = "the fixed kernel", .techniques = "pcf"}),
        member<&Config::pcf, &P::grid_size>(
            {.key = "pcf.grid_size", .flag = "--pcf-grid", .metavar = "N", .min = 1, .max = 16,
             .help = "N x N grid taps (implies --pcf-pattern grid)", .techniques = "pcf",
             .implies = [](Config& c) { c.pcf.pattern = TapPattern::grid; }}),
        member<&Config::pcf, &P::poisson_taps>(
            {.key = "pcf.poisson_taps", .flag = "--pcf-taps", .metavar = "K", .min = 1, .max = 64,
             .help = "K Poisson taps (implies --pcf-pattern poisson)", .techniques = "pcf",
             .implies = [](Config& c) { c.pcf.pattern = TapPattern::poisson; }}),
        member<&Config::pcf, &P::radius>({.key = "pcf.radius", .flag = "--pcf-radius", .metavar = "X", .min = 0,
                                          .max = 1000, .min_exclusive = true,
                                          .allowed = "more than 0 to 1000 scene units",
                                          .help = "kernel radius on the receiver", .techniques = "pcf"}),
        member<&Config::pcf, &P::rotate>({.key = "pcf.rotate", .flag = "--no-rotation",
                                          .help = "per-pixel rotation of the tap pattern", .techniques = "pcf"}),
        // pcss: blocker search and filter
        member<&Config::pcss, &Q::blocker_samples>(
            {.key = "pcss.blocker_samples", .flag = "--pcss-blockers", .metavar = "N", .min = 1, .max = 64,
             .help = "blocker-search samples", .section = "blocker search and filter", .techniques = "pcss"}),
        member<&Config::pcss, &Q::filter_samples>({.key = "pcss.filter_samples", .flag = "--pcss-filter",
                                                   .metavar = "N", .min = 1, .max = 128, .help = "filter samples",
                                                   .techniques = "pcss"}),
        member<&Config::pcss, &Q::max_filter_texels>(
            {.key = "pcss.max_filter_texels", .flag = "--pcss-max-texels", .metavar = "N", .min = 1,
             .allowed = "1 to half the shadow-map resolution", .help = "largest filter half-width in texels",
             .techniques = "pcss"}),
        member<&Config::pcss, &Q::rotate>({.key = "pcss.rotate", .flag = "--no-rotation",
                                           .help = "per-pixel rotation of the tap pattern", .techniques = "pcss"}),
    };
}

} // namespace penumbra::detail
