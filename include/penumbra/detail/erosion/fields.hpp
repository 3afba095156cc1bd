// penumbra/detail/erosion/fields.hpp — the erosion's configuration fields (erosion.*; its depth map:
// shadow_map.*, detail/shadow_map/fields.hpp): one row each (penumbra/config_field.hpp), read by
// penumbra/config_fields.hpp.
#pragma once

#include "../../config_field.hpp"

#include <array>

namespace penumbra::detail {

constexpr auto erosion_fields() {
    using E = ErosionParams;
    return std::array{
        member<&Config::erosion, &E::max_search_radius>(
            {.key = "erosion.max_search_radius", .flag = "--erosion-radius", .metavar = "N", .min = 1, .max = 256,
             .allowed = "1 to 256 pixels", .help = "largest penumbra half-width searched in output pixels",
             .section = "edge search and blur, in output pixels", .techniques = "erosion"}),
        member<&Config::erosion, &E::edge_threshold>(
            {.key = "erosion.edge_threshold", .flag = "--erosion-edge-threshold", .metavar = "X", .min = 0, .max = 4,
             .min_exclusive = true, .help = "|Laplacian| of the hard shadow marking an edge", .techniques = "erosion"}),
        member<&Config::erosion, &E::search_taps>({.key = "erosion.search_taps", .flag = "--erosion-search-taps",
                                                   .metavar = "N", .min = 1, .max = 64,
                                                   .help = "Poisson taps of the nearest-edge search",
                                                   .techniques = "erosion"}),
        member<&Config::erosion, &E::blur_taps>({.key = "erosion.blur_taps", .flag = "--erosion-blur-taps",
                                                 .metavar = "N", .min = 1, .max = 64,
                                                 .help = "Poisson taps of the final blur", .techniques = "erosion"}),
    };
}

} // namespace penumbra::detail
