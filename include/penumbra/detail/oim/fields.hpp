// penumbra/detail/oim/fields.hpp — the occlusion interval maps' configuration fields (oim.*): one row
// each (penumbra/config_field.hpp), read by penumbra/config_fields.hpp.
#pragma once

#include "../../config_field.hpp"

#include <array>

namespace penumbra::detail {

constexpr auto oim_fields() {
    using O = OimParams;
    return std::array{
        member<&Config::oim, &O::resolution>(
            {.key = "oim.resolution", .flag = "--oim-resolution", .metavar = "R", .min = 32, .max = 4096,
             .power_of_two = true, .allowed = "a power of two from 32 to 4096", .help = "interval-map side in texels",
             .section = "the baked interval maps", .techniques = "oim"}),
        member<&Config::oim, &O::intervals>({.key = "oim.intervals", .flag = "--oim-intervals", .metavar = "N",
                                             .min = 4, .max = 16, .allowed = "4, 8, 12 or 16",
                                             .help = "visibility intervals per texel", .techniques = "oim"}),
        member<&Config::oim, &O::samples>({.key = "oim.samples", .flag = "--oim-samples", .metavar = "N", .min = 256,
                                           .max = 2048, .power_of_two = true, .allowed = "256, 512, 1024 or 2048",
                                           .help = "instants the bake traces along the sun's path",
                                           .techniques = "oim"}),
    };
}

} // namespace penumbra::detail
