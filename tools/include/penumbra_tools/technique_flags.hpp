// technique_flags.hpp — the command-line flags that pick the technique and set its parameters
// (--technique, --shadow-*, --pcf-*, --pcss-*, --no-rotation, --oim-*), shared by penumbra-gen and
// penumbra-playground. Ranges are checked by penumbra::validate, so both tools give its messages.
#pragma once

#include <penumbra/config.hpp>

#include <optional>
#include <string>
#include <string_view>

namespace penumbra_gen {

struct TechniqueFlags {
    std::optional<penumbra::Technique> technique;
    std::optional<int> shadow_resolution;
    std::optional<double> shadow_bias, shadow_slope_bias, shadow_normal_offset;
    std::optional<penumbra::TapPattern> pcf_pattern;
    std::optional<int> pcf_grid, pcf_taps;
    std::optional<double> pcf_radius;
    std::optional<int> pcss_blockers, pcss_filter, pcss_max_texels;
    std::optional<int> erosion_radius, erosion_search_taps, erosion_blur_taps; // erosion
    std::optional<double> erosion_edge_threshold;
    bool no_rotation = false;
    bool no_receiver_plane_bias = false;
    std::optional<int> oim_resolution, oim_intervals, oim_samples;
};

// "--technique, --shadow-resolution, …": for the lists of allowed flags in messages.
extern const std::string_view technique_flag_list;

bool is_technique_switch(std::string_view flag); // a technique flag without a value (--no-rotation)
bool is_technique_flag(std::string_view flag);   // a technique flag that takes a value

// Sets `flag`'s value into `flags`; returns one line naming the flag, the text and what is allowed
// when the text is not a value of the right kind, else "".
std::string parse_technique_flag(std::string_view flag, std::string_view value, TechniqueFlags& flags);
void set_technique_switch(std::string_view flag, TechniqueFlags& flags);

penumbra::Config apply(const TechniqueFlags& flags, penumbra::Config config);

// Stores the integer `text` into `slot`; else returns one line naming the flag, the text and what
// is allowed (cli.hpp; ranges are penumbra::validate's).
std::string parse_int(std::string_view flag, std::string_view text, std::optional<int>& slot,
                      std::string_view allowed);

// Stores the finite number `text` into `slot`; else returns one line naming the flag, the text and
// what is allowed (ranges are penumbra::validate's).
std::string parse_real(std::string_view flag, std::string_view text, std::optional<double>& slot,
                       std::string_view allowed);

// The --help lines of these flags, the flag column padded to `column` characters.
std::string technique_usage(std::size_t column);

} // namespace penumbra_gen
