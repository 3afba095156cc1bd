// penumbra/detail/evsm/validate.hpp — EVSM's fields, after those of the shadow map it starts from
// (its resolution and the depth pass's biases; the PCF/PCSS kernels and the normal offset are not read).
#pragma once

#include "../shadow_map/validate.hpp"
#include "parameters.hpp"

namespace penumbra::detail {

constexpr std::vector<Problem> evsm_problems(const Config& config) {
    std::vector<Problem> problems = shadow_map_problems(config);
    if (!in_range(config.light) || !in_range(config.target)) return problems;
    bool map_size_known = true; // the blur's clamp is checked against a valid map size only
    for (const Problem& p : problems) map_size_known = map_size_known && p.field != "shadow_map.resolution";
    const EvsmParams& e = config.evsm;
    check_real_range(problems, "evsm.positive_exponent", e.positive_exponent, 0.0, evsm_max_exponent, true,
                     "(e^(2 c) must fit a 32-bit float)");
    check_real_range(problems, "evsm.negative_exponent", e.negative_exponent, 0.0, evsm_max_exponent, true,
                     "(e^(2 c) must fit a 32-bit float)");
    if (!(e.light_bleeding_reduction >= 0.0 && e.light_bleeding_reduction < 1.0))
        add_problem(problems, "evsm.light_bleeding_reduction", format_value(e.light_bleeding_reduction),
                    "is out of range; allowed: 0.0 to less than 1.0 (the Chebyshev bound cut off as shadow)");
    check_real_range(problems, "evsm.variance_bias", e.variance_bias, 0.0, 0.01, false, "(of the depth range)");
    check_real_range(problems, "evsm.blur_fraction", e.blur_fraction, 0.0, 1.0, true, "(of the widest penumbra)");
    check_int_range(problems, "evsm.blur_taps", e.blur_taps, 1, 64, "is out of range (taps per blur pass)");
    const int R = config.shadow_map.resolution;
    if (!map_size_known) return problems;
    if (e.max_blur_texels < 1 || e.max_blur_texels > R / 2)
        add_problem(problems, "evsm.max_blur_texels", format_int(e.max_blur_texels),
                    cat("texels is a blur the ", format_int(R), "-texel shadow map cannot hold; allowed: 1 to ",
                        format_int(R / 2), " (half the shadow-map resolution)"));
    else if (e.blur_taps >= 1 && e.max_blur_texels > e.blur_taps)
        add_problem(problems, "evsm.max_blur_texels", format_int(e.max_blur_texels),
                    cat("texels leaves gaps of more than 2 texels between ", format_int(e.blur_taps),
                        " blur taps; allowed: 1 to evsm.blur_taps (", format_int(e.blur_taps),
                        "), or raise evsm.blur_taps"));
    return problems;
}

} // namespace penumbra::detail
