// penumbra/detail/smrt/validate.hpp — shadow-map ray tracing's fields, after those of the shadow map
// it starts from (its resolution and the depth pass's biases; the PCF/PCSS kernels are not read).
#pragma once

#include "../shadow_map/validate.hpp"

namespace penumbra::detail {

constexpr std::vector<Problem> smrt_problems(const Config& config) {
    std::vector<Problem> problems = shadow_map_problems(config);
    if (!in_range(config.light) || !in_range(config.target)) return problems;
    const SmrtParams& s = config.smrt;
    check_int_range(problems, "smrt.rays", s.rays, 1, 16, "is out of range (rays per pixel)");
    check_int_range(problems, "smrt.samples", s.samples, 2, 32, "is out of range (depth-map samples per ray)");
    check_real_range(problems, "smrt.extrapolate_max_slope", s.extrapolate_max_slope, 0.0, 50.0, false,
                     "(depth per lateral scene unit; 0: no extrapolation)");
    check_real_range(problems, "smrt.max_slope_bias", s.max_slope_bias, 0.0, 1000.0, false,
                     "(depth per lateral scene unit)");
    check_real_range(problems, "smrt.texel_dither", s.texel_dither, 0.0, 8.0, false, "shadow-map texels");
    check_int_range(problems, "smrt.frame", s.frame, 0, 1023, "is out of range (the pattern's frame index)");
    return problems;
}

} // namespace penumbra::detail
