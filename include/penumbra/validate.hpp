// penumbra/validate.hpp — is a configuration something Penumbra can emit for its target?
//
//   for (const penumbra::ConfigError& e : penumbra::validate(config)) std::puts(e.message.c_str());
//
// Every message names the field, the value given and what is allowed. Nothing is clamped.
#pragma once

#include "config.hpp"
#include "detail/target_limits.hpp"
#include "detail/text.hpp"

#include <string>
#include <vector>

namespace penumbra {

// The slice counts a configuration may have, as diagnostics and --help texts say it.
inline constexpr std::string_view allowed_slices = "1 to 32, 64 or 128";

struct ConfigError {
    std::string field;   // "slices", "resolution", "filter", …
    std::string value;   // the value given, as text
    std::string message; // "<field>: <value> <what is wrong>; allowed: <what is allowed>"
};

namespace detail {

struct Problem {
    std::string_view field;
    Text value;
    Text message;
};

template <class Enum> constexpr bool in_range(Enum value) {
    return static_cast<std::size_t>(value) < EnumNames<Enum>::names.size();
}

template <class Enum> constexpr Text joined_names() {
    Text out;
    for (std::string_view name : EnumNames<Enum>::names) {
        if (!out.empty()) out += ", ";
        out += name;
    }
    return out;
}

constexpr bool is_power_of_two(int value) { return value > 0 && (value & (value - 1)) == 0; }

// Texel extent of the widest 2D texture a packing needs (the atlas puts the T tiles side by side;
// summed-area tables store R+1 exclusive prefix sums per side).
constexpr long long widest_2d_texture(const Config& config) {
    const long long tile = config.resolution + (config.filter == Filter::sat ? 1 : 0);
    return config.packing == Packing::atlas ? tile * texture_count(config) : tile;
}

// Occlusion interval maps (GPU Gems ch. 13): the fields of config.oim.
constexpr void add_oim_problems(const Config& config, std::vector<Problem>& problems) {
    auto add = [&](std::string_view field, Text value, Text message) {
        problems.push_back({field, value, cat(field, ": ", value, " ", message)});
    };
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

// A double as diagnostics print it; values no literal can hold are named, not formatted.
constexpr Text format_value(double value) {
    if (value != value) return Text("nan");
    if (value > 1e9 || value < -1e9) return Text(value > 0 ? "a number above 1e9" : "a number below -1e9");
    return format_float(value);
}

// The shadow map techniques read shadow_map, pcf, pcss or erosion, light and target; nothing else.
constexpr std::vector<Problem> shadow_map_problems(const Config& config) {
    std::vector<Problem> problems;
    auto add = [&](std::string_view field, Text value, Text message) {
        problems.push_back({field, value, cat(field, ": ", value, " ", message)});
    };
    auto int_range = [&](std::string_view field, int value, int lo, int hi, std::string_view why) {
        if (value < lo || value > hi)
            add(field, format_int(value), cat(why, "; allowed: ", format_int(lo), " to ", format_int(hi)));
    };
    // `!(lo <= v && v <= hi)` also catches NaN.
    auto real_range = [&](std::string_view field, double value, double lo, double hi, bool lo_open,
                          std::string_view units) {
        const bool above_lo = lo_open ? value > lo : value >= lo;
        if (!(above_lo && value <= hi))
            add(field, format_value(value),
                cat("is out of range; allowed: ", lo_open ? "more than " : "", format_float(lo), " to ",
                    format_float(hi), " ", units));
    };
    if (!in_range(config.light))
        add("light", format_int(static_cast<int>(config.light)), cat("is not a known value; allowed: ", joined_names<Light>()));
    if (!in_range(config.target))
        add("target", format_int(static_cast<int>(config.target)), cat("is not a known value; allowed: ", joined_names<Target>()));
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
    real_range("shadow_map.constant_bias", sm.constant_bias, 0.0, 10.0, false, "scene units");
    real_range("shadow_map.slope_bias", sm.slope_bias, 0.0, 16.0, false, "(times the depth change per texel)");
    real_range("shadow_map.normal_offset", sm.normal_offset, 0.0, 8.0, false, "shadow-map texels");

    if (config.technique == Technique::pcf) {
        const PcfParams& pcf = config.pcf;
        if (!in_range(pcf.pattern))
            add("pcf.pattern", format_int(static_cast<int>(pcf.pattern)),
                cat("is not a known value; allowed: ", joined_names<TapPattern>()));
        else if (pcf.pattern == TapPattern::grid)
            int_range("pcf.grid_size", pcf.grid_size, 1, 16, "is out of range (N gives N x N taps)");
        else
            int_range("pcf.poisson_taps", pcf.poisson_taps, 1, 64, "is out of range");
        real_range("pcf.radius", pcf.radius, 0.0, 1000.0, true, "scene units");
    }
    if (config.technique == Technique::pcss) {
        const PcssParams& pcss = config.pcss;
        int_range("pcss.blocker_samples", pcss.blocker_samples, 1, 64, "is out of range");
        int_range("pcss.filter_samples", pcss.filter_samples, 1, 128, "is out of range");
        if (pcss.max_filter_texels < 1 || pcss.max_filter_texels > sm.resolution / 2)
            add("pcss.max_filter_texels", format_int(pcss.max_filter_texels),
                cat("is a kernel the ", format_int(sm.resolution), "-texel shadow map cannot hold; allowed: 1 to ",
                    format_int(sm.resolution / 2), " (half the shadow-map resolution)"));
    }
    if (config.technique == Technique::erosion) {
        const ErosionParams& e = config.erosion;
        const int max_size = limits(config.target).max_texture_size;
        if (e.max_search_radius < 1 || e.max_search_radius > 256 || e.max_search_radius > max_size / 2)
            add("erosion.max_search_radius", format_int(e.max_search_radius),
                cat("pixels is a search beyond the image (its min-max chain needs an image of at least twice the "
                    "radius); allowed: 1 to ", format_int(max_size / 2 < 256 ? max_size / 2 : 256), " pixels"));
        real_range("erosion.edge_threshold", e.edge_threshold, 0.0, 4.0, true, "(|Laplacian| of the 0/1 hard shadow)");
        int_range("erosion.search_taps", e.search_taps, 1, 64, "is out of range");
        int_range("erosion.blur_taps", e.blur_taps, 1, 64, "is out of range");
    }
    return problems;
}

constexpr std::vector<Problem> find_problems(const Config& config) {
    std::vector<Problem> problems;
    auto add = [&](std::string_view field, Text value, Text message) {
        problems.push_back({field, value, cat(field, ": ", value, " ", message)});
    };
    auto enum_problem = [&]<class Enum>(std::string_view field, Enum value) {
        if (!in_range(value))
            add(field, format_int(static_cast<int>(value)), cat("is not a known value; allowed: ", joined_names<Enum>()));
    };
    enum_problem("technique", config.technique);
    if (!problems.empty()) return problems;
    if (uses_shadow_map(config)) return shadow_map_problems(config);
    if (config.technique == Technique::oim) {
        enum_problem("target", config.target);
        if (problems.empty()) add_oim_problems(config, problems);
        return problems;
    }

    if (config.slices < 1 || (config.slices > max_channel_slices && config.slices != 64 && config.slices != 128))
        add("slices", format_int(config.slices), cat("is out of range; allowed: ", allowed_slices));
    if (config.resolution < 32 || config.resolution > 4096 || !is_power_of_two(config.resolution))
        add("resolution", format_int(config.resolution),
            "is not allowed; allowed: a power of two from 32 to 4096 (32, 64, 128, 256, 512, 1024, 2048, 4096)");
    enum_problem("filter", config.filter);
    enum_problem("fusion", config.fusion);
    enum_problem("packing", config.packing);
    enum_problem("light", config.light);
    enum_problem("target", config.target);
    enum_problem("slice_placement", config.slice_placement);
    enum_problem("level_format", config.level_format);
    if (problems.empty() && (config.level_bound < -1 || config.level_bound > resolution_levels(config)))
        add("level_bound", format_int(config.level_bound),
            cat("is out of range; allowed: -1 (every level) or 0 to ", format_int(resolution_levels(config)),
                " (log2 of resolution ", format_int(config.resolution), ")"));
    if (!(config.tangent_clip_offset >= 0.0 && config.tangent_clip_offset <= 8.0))
        add("tangent_clip_offset", format_value(config.tangent_clip_offset), "is out of range; allowed: 0 to 8 slicing texels");
    if (!(config.fade_ramp > 0.0 && config.fade_ramp <= 4.0))
        add("fade_ramp", format_value(config.fade_ramp),
            "is out of range; allowed: more than 0 to 4 (fraction of a slice's thickness)");
    if (problems.empty() && (config.level_reduction < -1 || config.level_reduction > resolution_levels(config)))
        add("level_reduction", format_int(config.level_reduction),
            cat("is out of range; allowed: -1 (every level at full resolution) or 0 to ",
                format_int(resolution_levels(config)), " (log2 of resolution ", format_int(config.resolution), ")"));
    if (!problems.empty()) return problems; // the rules below need valid fields

    const std::string_view filter = to_string(config.filter);
    const std::string_view target = to_string(config.target);
    const TargetLimits limit = limits(config.target);
    if (config.filter == Filter::gaussian && config.light != Light::sun)
        add("filter", Text(filter),
            cat("needs light 'sun' (the Gaussian stands for the sun's disk, journal §3.5); allowed with light '",
                to_string(config.light), "': mipmap, nbuffer, sat"));
    if (config.packing == Packing::volume && (config.filter == Filter::mipmap || config.filter == Filter::sat))
        add("packing", Text("volume"),
            cat("cannot hold filter '", filter,
                "' (a volume stores equal-size filter levels as depth; mipmap levels shrink and a summed-area table "
                "has one level); allowed with this filter: atlas, array"));
    if (config.filter == Filter::sat && !limit.float32_render_filter)
        add("filter", Text("sat"),
            cat("needs renderable, filterable 32-bit float textures, which target '", target,
                "' does not guarantee; allowed filters for ", target, ": mipmap, nbuffer, gaussian"));
    const Text allowed_for_target = cat("1 to ", format_int(4 * limit.max_draw_buffers), limit.logic_op ? ", 64 or 128" : "");
    if (slices_as_bits(config) && !limit.logic_op)
        add("slices", format_int(config.slices),
            cat("needs a logical OR on the slicing target (more than 32 slices are written as bits, paper §3.7), "
                "which target '", target, "' does not have; allowed for ", target, ": ", allowed_for_target));
    else if (!slices_as_bits(config) && texture_count(config) > limit.max_draw_buffers)
        add("slices", format_int(config.slices),
            cat("needs ", format_int(texture_count(config)), " render targets (four slices each) but target '", target,
                "' guarantees ", format_int(limit.max_draw_buffers), "; allowed for ", target, ": ", allowed_for_target));
    if (slices_as_bits(config) && config.packing == Packing::volume)
        add("packing", Text("volume"),
            cat("needs ", format_int(texture_count(config)), " 3D textures for ", format_int(config.slices),
                " slices, more samplers than a shading pass is guaranteed (16); allowed with more than 32 slices: atlas, "
                "array"));
    if (widest_2d_texture(config) > limit.max_texture_size) {
        Config smaller = config;
        while (smaller.resolution > 32 && widest_2d_texture(smaller) > limit.max_texture_size) smaller.resolution /= 2;
        const bool fits = widest_2d_texture(smaller) <= limit.max_texture_size;
        add("resolution", format_int(config.resolution),
            cat("needs a ", format_int(widest_2d_texture(config)), "-texel wide ",
                config.packing == Packing::atlas ? "atlas" : "texture", " but target '", target,
                "' guarantees only ", format_int(limit.max_texture_size), " texels; allowed with ",
                format_int(config.slices), " slices and packing ", to_string(config.packing), ": ",
                fits ? cat("up to ", format_int(smaller.resolution)) : Text("none"),
                ", or fewer slices, another packing or another target"));
    }
    const int level_count = config.filter == Filter::mipmap || config.filter == Filter::sat ? 1 : max_level(config) + 1;
    if (config.packing == Packing::array && level_count * texture_count(config) > limit.max_array_layers)
        add("packing", Text("array"),
            cat("needs ", format_int(level_count * texture_count(config)), " layers but target '", target,
                "' guarantees ", format_int(limit.max_array_layers), "; allowed: atlas, or fewer slices"));
    if (config.packing == Packing::volume && config.resolution > limit.max_3d_texture_size)
        add("resolution", format_int(config.resolution),
            cat("is too large for packing 'volume': target '", target, "' guarantees 3D textures of ",
                format_int(limit.max_3d_texture_size), " texels; allowed: up to ",
                format_int(limit.max_3d_texture_size), ", or packing atlas or array"));
    return problems;
}

} // namespace detail

// True when `config` can be emitted. Usable in constant expressions.
constexpr bool is_valid(const Config& config) { return detail::find_problems(config).empty(); }

// Every problem with `config`, in field order; empty when it is valid.
inline std::vector<ConfigError> validate(const Config& config) {
    std::vector<ConfigError> errors;
    for (const detail::Problem& problem : detail::find_problems(config))
        errors.push_back({std::string(problem.field), problem.value.str(), problem.message.str()});
    return errors;
}

} // namespace penumbra
