// penumbra/detail/oim/validate.hpp — the fields of occlusion interval maps (config.oim) and the target.
#pragma once

#include "../problem.hpp"
#include "../target_limits.hpp"

namespace penumbra::detail {

// Occlusion interval maps (GPU Gems ch. 13): the fields of config.oim.
constexpr void add_oim_problems(const Config& config, std::vector<Problem>& problems) {
    auto add = [&](std::string_view field, Text value, Text message) { add_problem(problems, field, value, message); };
    const OimParams& o = config.oim;
    const TargetLimits limit = limits(config.target);
    if (o.resolution < 32 || o.resolution > 4096 || !is_power_of_two(o.resolution))
        add("oim.resolution", format_int(o.resolution),
            "is not allowed; allowed: a power of two from 32 to 4096 (32, 64, 128, 256, 512, 1024, 2048, 4096)");
    else if (o.resolution > limit.max_texture_size)
        add("oim.resolution", format_int(o.resolution),
            cat("is larger than target '", to_string(config.target), "' guarantees; allowed: up to ",
                format_int(limit.max_texture_size)));
    if (o.intervals != 4 && o.intervals != 8 && o.intervals != 12 && o.intervals != 16)
        add("oim.intervals", format_int(o.intervals),
            "is not allowed; allowed: 4, 8, 12 or 16 (four intervals per RGBA rise/fall texture pair)");
    if (o.samples < 256 || o.samples > 2048 || !is_power_of_two(o.samples))
        add("oim.samples", format_int(o.samples),
            "is not allowed; allowed: 256, 512, 1024 or 2048 (a power of two, so the edge times k / samples are exact "
            "in the 16-bit float maps)");
}

constexpr std::vector<Problem> oim_problems(const Config& config) {
    std::vector<Problem> problems;
    check_known(problems, "target", config.target);
    if (problems.empty()) add_oim_problems(config, problems);
    return problems;
}

} // namespace penumbra::detail
