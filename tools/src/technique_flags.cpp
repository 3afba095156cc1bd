#include "technique_flags.hpp"

#include "arguments.hpp"
#include "cli.hpp"

namespace penumbra_gen {

const std::string_view technique_flag_list =
    "--technique, --shadow-resolution, --shadow-bias, --shadow-slope-bias, --shadow-normal-offset, --pcf-pattern, --pcf-grid, --pcf-taps, "
    "--pcf-radius, --pcss-blockers, --pcss-filter, --pcss-max-texels, --no-rotation, --no-receiver-plane-bias, "
    "--oim-resolution, "
    "--oim-intervals, --oim-samples, --erosion-radius, --erosion-edge-threshold, --erosion-search-taps, "
    "--erosion-blur-taps";

namespace {

constexpr std::string_view value_flags[] = {"--technique",   "--shadow-resolution", "--shadow-bias",
                                            "--shadow-slope-bias", "--shadow-normal-offset", "--pcf-pattern", "--pcf-grid",
                                            "--pcf-taps",    "--pcf-radius",        "--pcss-blockers",
                                            "--pcss-filter", "--pcss-max-texels", "--oim-resolution",
                                            "--oim-intervals", "--oim-samples",
                                            "--erosion-radius", "--erosion-edge-threshold",
                                            "--erosion-search-taps", "--erosion-blur-taps"};

} // namespace

std::string parse_int(std::string_view flag, std::string_view text, std::optional<int>& slot,
                      std::string_view allowed) {
    int value = 0;
    std::string error = penumbra::cli::parse_int(flag, text, value, allowed);
    if (error.empty()) slot = value;
    return error;
}

std::string parse_real(std::string_view flag, std::string_view text, std::optional<double>& slot,
                       std::string_view allowed) {
    double value = 0.0;
    std::string error = penumbra::cli::parse_real(flag, text, value, allowed);
    if (error.empty()) slot = value;
    return error;
}

bool is_technique_switch(std::string_view flag) {
    return flag == "--no-rotation" || flag == "--no-receiver-plane-bias";
}

bool is_technique_flag(std::string_view flag) {
    for (std::string_view f : value_flags)
        if (f == flag) return true;
    return false;
}

void set_technique_switch(std::string_view flag, TechniqueFlags& flags) {
    if (flag == "--no-rotation") flags.no_rotation = true;
    if (flag == "--no-receiver-plane-bias") flags.no_receiver_plane_bias = true;
}

std::string parse_technique_flag(std::string_view flag, std::string_view value, TechniqueFlags& flags) {
    if (flag == "--technique") return parse_name(flag, value, flags.technique);
    if (flag == "--shadow-resolution")
        return parse_int(flag, value, flags.shadow_resolution, "a power of two from 32 to 8192");
    if (flag == "--shadow-bias") return parse_real(flag, value, flags.shadow_bias, "0 to 10 scene units");
    if (flag == "--shadow-slope-bias") return parse_real(flag, value, flags.shadow_slope_bias, "0 to 16");
    if (flag == "--shadow-normal-offset")
        return parse_real(flag, value, flags.shadow_normal_offset, "0 to 8 shadow-map texels");
    if (flag == "--pcf-pattern") return parse_name(flag, value, flags.pcf_pattern);
    if (flag == "--pcf-grid") return parse_int(flag, value, flags.pcf_grid, "1 to 16");
    if (flag == "--pcf-taps") return parse_int(flag, value, flags.pcf_taps, "1 to 64");
    if (flag == "--pcf-radius") return parse_real(flag, value, flags.pcf_radius, "more than 0 to 1000 scene units");
    if (flag == "--pcss-blockers") return parse_int(flag, value, flags.pcss_blockers, "1 to 64");
    if (flag == "--pcss-filter") return parse_int(flag, value, flags.pcss_filter, "1 to 128");
    if (flag == "--oim-resolution")
        return parse_int(flag, value, flags.oim_resolution, "a power of two from 32 to 4096");
    if (flag == "--oim-intervals") return parse_int(flag, value, flags.oim_intervals, "4, 8, 12 or 16");
    if (flag == "--oim-samples") return parse_int(flag, value, flags.oim_samples, "256, 512, 1024 or 2048");
    if (flag == "--erosion-radius") return parse_int(flag, value, flags.erosion_radius, "1 to 256 pixels");
    if (flag == "--erosion-edge-threshold")
        return parse_real(flag, value, flags.erosion_edge_threshold, "more than 0 to 4");
    if (flag == "--erosion-search-taps") return parse_int(flag, value, flags.erosion_search_taps, "1 to 64");
    if (flag == "--erosion-blur-taps") return parse_int(flag, value, flags.erosion_blur_taps, "1 to 64");
    return parse_int(flag, value, flags.pcss_max_texels, "1 to half the shadow-map resolution"); // --pcss-max-texels
}

penumbra::Config apply(const TechniqueFlags& flags, penumbra::Config config) {
    if (flags.technique) config.technique = *flags.technique;
    if (flags.shadow_resolution) config.shadow_map.resolution = *flags.shadow_resolution;
    if (flags.shadow_bias) config.shadow_map.constant_bias = *flags.shadow_bias;
    if (flags.shadow_slope_bias) config.shadow_map.slope_bias = *flags.shadow_slope_bias;
    if (flags.shadow_normal_offset) config.shadow_map.normal_offset = *flags.shadow_normal_offset;
    if (flags.pcf_pattern) config.pcf.pattern = *flags.pcf_pattern;
    if (flags.pcf_grid) {
        config.pcf.grid_size = *flags.pcf_grid;
        if (!flags.pcf_pattern) config.pcf.pattern = penumbra::TapPattern::grid; // --pcf-grid N means a grid
    }
    if (flags.pcf_taps) {
        config.pcf.poisson_taps = *flags.pcf_taps;
        if (!flags.pcf_pattern) config.pcf.pattern = penumbra::TapPattern::poisson;
    }
    if (flags.pcf_radius) config.pcf.radius = *flags.pcf_radius;
    if (flags.pcss_blockers) config.pcss.blocker_samples = *flags.pcss_blockers;
    if (flags.pcss_filter) config.pcss.filter_samples = *flags.pcss_filter;
    if (flags.pcss_max_texels) config.pcss.max_filter_texels = *flags.pcss_max_texels;
    if (flags.no_rotation) config.pcf.rotate = config.pcss.rotate = false;
    if (flags.no_receiver_plane_bias) config.shadow_map.receiver_plane_bias = false;
    if (flags.oim_resolution) config.oim.resolution = *flags.oim_resolution;
    if (flags.oim_intervals) config.oim.intervals = *flags.oim_intervals;
    if (flags.oim_samples) config.oim.samples = *flags.oim_samples;
    if (flags.erosion_radius) config.erosion.max_search_radius = *flags.erosion_radius;
    if (flags.erosion_edge_threshold) config.erosion.edge_threshold = *flags.erosion_edge_threshold;
    if (flags.erosion_search_taps) config.erosion.search_taps = *flags.erosion_search_taps;
    if (flags.erosion_blur_taps) config.erosion.blur_taps = *flags.erosion_blur_taps;
    return config;
}

std::string technique_usage(std::size_t column) {
    using namespace penumbra;
    const Config d{};
    auto line = [&](std::string_view flag, std::string_view text) {
        std::string out = "  " + std::string(flag);
        out.resize(std::max<std::size_t>(out.size() + 1, column), ' ');
        return out + std::string(text) + "\n";
    };
    auto real = [](double v) {
        std::string s = std::to_string(v);
        while (s.size() > 1 && s.back() == '0') s.pop_back();
        if (s.back() == '.') s.pop_back();
        return s;
    };
    std::string out;
    out += line("--technique T", "shadowing technique: " + allowed_names<Technique>() + " (default " +
                                     std::string(to_string(d.technique)) + ")");
    out += line("--shadow-resolution R", "shadowmap, pcf, pcss, erosion: shadow map side in texels, a power of two 32 to "
                                         "8192 (default " + std::to_string(d.shadow_map.resolution) + ")");
    out += line("--shadow-bias B", "constant depth bias in scene units along the light axis, 0 to 10 (default " +
                                       real(d.shadow_map.constant_bias) + ")");
    out += line("--shadow-slope-bias S", "slope bias: S times the depth change across one texel, 0 to 16 "
                                         "(default " + real(d.shadow_map.slope_bias) + ")");
    out += line("--shadow-normal-offset K", "shadowmap, pcf, pcss: receivers move along their normal by K texels times\n" +
                                                std::string(column, ' ') + "sin(angle to the light) before the lookup, 0 to 8 (default " +
                                                real(d.shadow_map.normal_offset) + ")");
    out += line("--pcf-pattern P", "pcf: tap pattern, " + allowed_names<TapPattern>() + " (default " +
                                       std::string(to_string(d.pcf.pattern)) + ")");
    out += line("--pcf-grid N", "pcf: N x N grid taps, 1 to 16 (implies --pcf-pattern grid; default " +
                                    std::to_string(d.pcf.grid_size) + ")");
    out += line("--pcf-taps K", "pcf: K Poisson taps, 1 to 64 (implies --pcf-pattern poisson; default " +
                                    std::to_string(d.pcf.poisson_taps) + ")");
    out += line("--pcf-radius X", "pcf: kernel radius on the receiver in scene units, above 0 to 1000 (default " +
                                      real(d.pcf.radius) + ")");
    out += line("--pcss-blockers N", "pcss: blocker-search samples, 1 to 64 (default " +
                                         std::to_string(d.pcss.blocker_samples) + ")");
    out += line("--pcss-filter N", "pcss: filter samples, 1 to 128 (default " +
                                       std::to_string(d.pcss.filter_samples) + ")");
    out += line("--pcss-max-texels N", "pcss: largest filter half-width in texels, 1 to resolution / 2 (default " +
                                           std::to_string(d.pcss.max_filter_texels) + ")");
    out += line("--no-rotation", "pcf, pcss: no per-pixel rotation of the tap pattern (default on)");
    out += line("--no-receiver-plane-bias", "pcf, pcss: taps compare against the receiver's own depth, not its tangent\n" +
                                                std::string(column, ' ') + "plane's depth under the tap (default on)");
    out += line("--oim-resolution R", "oim: interval-map side in texels, a power of two 32 to 4096 (default " +
                                          std::to_string(d.oim.resolution) + ")");
    out += line("--oim-intervals N", "oim: visibility intervals per texel, 4, 8, 12 or 16 (default " +
                                         std::to_string(d.oim.intervals) + ")");
    out += line("--oim-samples N", "oim: instants the bake traces along the sun's path, 256, 512, 1024 or 2048 "
                                       "(default " + std::to_string(d.oim.samples) + ")");
    out += line("--erosion-radius N", "erosion: largest penumbra half-width searched, in output pixels, 1 to 256 "
                                      "(default " + std::to_string(d.erosion.max_search_radius) + ")");
    out += line("--erosion-edge-threshold X", "erosion: |Laplacian| of the hard shadow marking an edge, above 0 to 4 "
                                              "(default " + real(d.erosion.edge_threshold) + ")");
    out += line("--erosion-search-taps N", "erosion: Poisson taps of the nearest-edge search, 1 to 64 (default " +
                                               std::to_string(d.erosion.search_taps) + ")");
    out += line("--erosion-blur-taps N", "erosion: Poisson taps of the final blur, 1 to 64 (default " +
                                             std::to_string(d.erosion.blur_taps) + ")");
    return out;
}

} // namespace penumbra_gen
