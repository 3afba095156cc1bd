// penumbra/detail/evsm/fields.hpp — EVSM's configuration fields (evsm.*; its depth map: shadow_map.*,
// detail/shadow_map/fields.hpp): one row each (penumbra/config_field.hpp), read by
// penumbra/config_fields.hpp. Added after layout_version 3, so layout.json writes them only when not
// the default (omit_default): the layouts of every other configuration read as before.
#pragma once

#include "../../config_field.hpp"

#include <array>

namespace penumbra::detail {

constexpr auto evsm_fields() {
    using E = EvsmParams;
    return std::array{
        member<&Config::evsm, &E::positive_exponent>(
            {.key = "evsm.positive_exponent", .flag = "--evsm-positive-exponent", .metavar = "C", .min = 0, .max = 42,
             .min_exclusive = true, .help = "c+ of the warp e^(c+ d) of the depth (e^(2 c) must fit a 32-bit float)",
             .section = "exponential variance shadow maps: warp, Chebyshev bound and blur", .techniques = "evsm",
             .omit_default = true}),
        member<&Config::evsm, &E::negative_exponent>(
            {.key = "evsm.negative_exponent", .flag = "--evsm-negative-exponent", .metavar = "C", .min = 0, .max = 42,
             .min_exclusive = true, .help = "c- of the warp -e^(-c- d) of the depth", .techniques = "evsm",
             .omit_default = true}),
        member<&Config::evsm, &E::light_bleeding_reduction>(
            {.key = "evsm.light_bleeding_reduction", .flag = "--evsm-bleeding", .metavar = "X", .min = 0, .max = 1,
             .allowed = "0 to less than 1",
             .help = "light-bleeding reduction: Chebyshev bounds below X are shadow, the rest rescaled",
             .techniques = "evsm", .omit_default = true}),
        member<&Config::evsm, &E::variance_bias>(
            {.key = "evsm.variance_bias", .flag = "--evsm-variance-bias", .metavar = "X", .min = 0, .max = 0.01,
             .help = "least depth spread, as a fraction of the depth range", .techniques = "evsm",
             .omit_default = true}),
        member<&Config::evsm, &E::blur_fraction>(
            {.key = "evsm.blur_fraction", .flag = "--evsm-blur-fraction", .metavar = "X", .min = 0, .max = 1,
             .min_exclusive = true,
             .help = "the blur box's width over the widest penumbra the light casts across the scene",
             .techniques = "evsm", .omit_default = true}),
        member<&Config::evsm, &E::blur_taps>({.key = "evsm.blur_taps", .flag = "--evsm-blur-taps", .metavar = "N",
                                              .min = 1, .max = 64, .help = "taps per blur pass (one pass per axis)",
                                              .techniques = "evsm", .omit_default = true}),
        member<&Config::evsm, &E::max_blur_texels>(
            {.key = "evsm.max_blur_texels", .flag = "--evsm-max-blur", .metavar = "N", .min = 1, .max = 64,
             .allowed = "1 to evsm.blur_taps and half the shadow-map resolution",
             .help = "the blur's half-width is clamped to N shadow-map texels", .techniques = "evsm",
             .omit_default = true}),
    };
}

} // namespace penumbra::detail
