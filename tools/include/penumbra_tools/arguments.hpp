// arguments.hpp — the command line of penumbra-gen, parsed into values; errors are values too.
#pragma once

#include "printable.hpp"
#include "technique_flags.hpp"

#include <penumbra/config.hpp>

#include <optional>
#include <string>
#include <vector>

namespace penumbra_gen {

// Configuration fields given on the command line; they override the --config file.
struct ConfigFlags {
    std::optional<int> slices, resolution;
    std::optional<penumbra::Filter> filter;
    std::optional<penumbra::Fusion> fusion;
    std::optional<penumbra::Packing> packing;
    std::optional<penumbra::Light> light;
    std::optional<penumbra::Target> target;
    bool no_leak_fix = false;
    bool no_fade = false;
    std::optional<bool> tangent_clip; // --tangent-clip / --no-tangent-clip
    std::optional<penumbra::SlicePlacement> slice_placement; // --slice-placement
    std::optional<int> level_bound;                           // --level-bound
    std::optional<penumbra::LevelFormat> level_format;        // --level-format
    std::optional<double> tangent_clip_offset;                // --tangent-clip-offset
    bool no_clip_footprint = false;                           // --no-clip-footprint
    std::optional<double> fade_ramp;                          // --fade-ramp
    std::optional<int> level_reduction;                       // --level-reduction
    std::optional<penumbra::PrefilterStage> prefilter_stage;  // --prefilter-stage
    bool alpha_test = false;                                  // --alpha-test
    TechniqueFlags technique; // --technique and each technique's flags (technique_flags.hpp)
};

struct Arguments {
    ConfigFlags flags;
    std::optional<std::string> config_file; // --config FILE.json
    std::string out_dir;                    // --out DIR (required unless help)
    bool validate = false;                  // --validate: compile and link every program with glslang
    bool help = false;                      // --help / -h: print usage() and exit 0
};

template <class T> struct Parsed {
    std::optional<T> value; // set when error is empty
    std::string error;      // one line, without the "error: " prefix
};

// Parses argv[1..]. `--flag value` and `--flag=value` are both accepted; a later flag wins.
// --help anywhere wins over every other problem.
Parsed<Arguments> parse_arguments(const std::vector<std::string>& args);

// `config` (from the --config file, or Config{}) with the command-line flags applied.
penumbra::Config apply(const ConfigFlags& flags, penumbra::Config config);

// The --help text: every flag, every allowed value, the defaults of Config{}.
std::string usage();

// "a, b, c": the names EnumNames lists for Enum.
template <class Enum> std::string allowed_names() {
    std::string out;
    for (std::string_view name : penumbra::EnumNames<Enum>::names) {
        if (!out.empty()) out += ", ";
        out += name;
    }
    return out;
}

// One of Enum's names into `slot`, else one line: "FLAG: 'TEXT' is not allowed; allowed: a, b, c".
template <class Enum> std::string parse_name(std::string_view flag, std::string_view text, std::optional<Enum>& slot) {
    if (std::optional<Enum> value = penumbra::parse_enum<Enum>(text)) {
        slot = *value;
        return {};
    }
    return std::string(flag) + ": '" + printable(text) + "' is not allowed; allowed: " + allowed_names<Enum>();
}

} // namespace penumbra_gen
