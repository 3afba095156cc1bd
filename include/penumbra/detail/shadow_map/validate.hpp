// penumbra/detail/shadow_map/validate.hpp — the fields of the shadow map techniques (shadowmap,
// pcf, pcss): the map, the biases and each technique's kernel.
#pragma once

#include "../problem.hpp"
#include "../target_limits.hpp"

namespace penumbra::detail {

// The shadow map techniques read shadow_map, pcf or pcss, light and target; nothing else (erosion
// adds its own fields: erosion/validate.hpp).
constexpr std::vector<Problem> shadow_map_problems(const Config& config) {
    std::vector<Problem> problems;
    auto add = [&](std::string_view field, Text value, Text message) { add_problem(problems, field, value, message); };
    check_known(problems, "light", config.light);
    check_known(problems, "target", config.target);
    if (!problems.empty()) return problems;

    const ShadowMapParams& sm = config.shadow_map;
    const int max_size = limits(config.target).max_texture_size < 8192 ? limits(config.target).max_texture_size : 8192;
    if (sm.resolution < 32 || sm.resolution > 8192 || !is_power_of_two(sm.resolution))
        add("shadow_map.resolution", format_int(sm.resolution),
            "is not allowed; allowed: a power of two from 32 to 8192 (32, 64, 128, 256, 512, 1024, 2048, 4096, 8192)");
    else if (sm.resolution > max_size)
        add("shadow_map.resolution", format_int(sm.resolution),
            cat("is larger than target '", to_string(config.target), "' guarantees; allowed: a power of two from 32 to ",
                format_int(max_size)));
    check_real_range(problems, "shadow_map.constant_bias", sm.constant_bias, 0.0, 10.0, false, "scene units");
    check_real_range(problems, "shadow_map.slope_bias", sm.slope_bias, 0.0, 16.0, false,
                     "(times the depth change per texel)");
    check_real_range(problems, "shadow_map.normal_offset", sm.normal_offset, 0.0, 8.0, false, "shadow-map texels");

    if (config.technique == Technique::pcf) {
        const PcfParams& pcf = config.pcf;
        if (!in_range(pcf.pattern))
            check_known(problems, "pcf.pattern", pcf.pattern);
        else if (pcf.pattern == TapPattern::grid)
            check_int_range(problems, "pcf.grid_size", pcf.grid_size, 1, 16,
                            "is out of range (N gives N x N taps)");
        else
            check_int_range(problems, "pcf.poisson_taps", pcf.poisson_taps, 1, 64, "is out of range");
        check_real_range(problems, "pcf.radius", pcf.radius, 0.0, 1000.0, true, "scene units");
    }
    if (config.technique == Technique::pcss) {
        const PcssParams& pcss = config.pcss;
        check_int_range(problems, "pcss.blocker_samples", pcss.blocker_samples, 1, 64, "is out of range");
        check_int_range(problems, "pcss.filter_samples", pcss.filter_samples, 1, 128, "is out of range");
        if (pcss.max_filter_texels < 1 || pcss.max_filter_texels > sm.resolution / 2)
            add("pcss.max_filter_texels", format_int(pcss.max_filter_texels),
                cat("is a kernel the ", format_int(sm.resolution), "-texel shadow map cannot hold; allowed: 1 to ",
                    format_int(sm.resolution / 2), " (half the shadow-map resolution)"));
    }
    return problems;
}

} // namespace penumbra::detail
