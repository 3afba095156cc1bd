// penumbra/detail/erosion/validate.hpp — erosion's fields, after those of the shadow map it starts from.
#pragma once

#include "../shadow_map/validate.hpp"

namespace penumbra::detail {

constexpr std::vector<Problem> erosion_problems(const Config& config) {
    std::vector<Problem> problems = shadow_map_problems(config);
    if (!in_range(config.light) || !in_range(config.target)) return problems; // the checks below need both
    const ErosionParams& e = config.erosion;
    const int max_size = limits(config.target).max_texture_size;
    if (e.max_search_radius < 1 || e.max_search_radius > 256 || e.max_search_radius > max_size / 2)
        add_problem(problems, "erosion.max_search_radius", format_int(e.max_search_radius),
                    cat("pixels is a search beyond the image (its min-max chain needs an image of at least twice "
                        "the radius); allowed: 1 to ", format_int(max_size / 2 < 256 ? max_size / 2 : 256), " pixels"));
    check_real_range(problems, "erosion.edge_threshold", e.edge_threshold, 0.0, 4.0, true,
                     "(|Laplacian| of the 0/1 hard shadow)");
    check_int_range(problems, "erosion.search_taps", e.search_taps, 1, 64, "is out of range");
    check_int_range(problems, "erosion.blur_taps", e.blur_taps, 1, 64, "is out of range");
    return problems;
}

} // namespace penumbra::detail
