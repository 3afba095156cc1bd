#include "arguments.hpp"
#include "cli.hpp"

#include <penumbra/config_fields.hpp>

#include <string_view>

namespace penumbra_gen {
namespace {

// Every flag, for the messages: the configuration fields' flags (penumbra/config_fields.hpp), then
// penumbra-gen's own.
std::string flag_list() { return penumbra::config_flag_list() + ", --config, --validate, --out, --help"; }

} // namespace

Parsed<Arguments> parse_arguments(const std::vector<std::string>& args) {
    if (penumbra::cli::asks_for_help(args)) {
        Arguments help;
        help.help = true;
        return {help, {}};
    }

    Arguments out;
    for (std::size_t i = 0; i < args.size(); ++i) {
        std::string_view arg = args[i];
        std::string_view flag = arg;
        std::optional<std::string_view> inline_value; // --flag=value
        if (arg.starts_with("--"))
            if (std::size_t eq = arg.find('='); eq != std::string_view::npos) {
                flag = arg.substr(0, eq);
                inline_value = arg.substr(eq + 1);
            }

        // Flags without a value.
        if (flag == "--validate" || is_config_switch(flag)) {
            if (inline_value)
                return {{}, std::string(flag) + ": takes no value (got '" + printable(*inline_value) + "')"};
            if (flag == "--validate") out.validate = true;
            set_config_switch(flag, out.flags);
            continue;
        }
        if (flag != "--config" && flag != "--out" && !is_config_flag(flag)) {
            if (arg.starts_with("-"))
                return {{}, "unknown flag '" + printable(flag) + "'; allowed: " + flag_list()};
            return {{},
                    "unexpected argument '" + printable(arg) +
                        "'; every value follows its flag (allowed flags: " + flag_list() + ")"};
        }
        std::string_view value;
        if (inline_value) {
            value = *inline_value;
        } else {
            if (i + 1 >= args.size()) return {{}, std::string(flag) + ": missing value (see --help)"};
            value = args[++i];
        }

        std::string error;
        if (is_config_flag(flag))
            error = parse_config_flag(flag, value, out.flags);
        else if (value.empty())
            error = std::string(flag) + ": empty path; allowed: a file or directory path";
        else if (flag == "--config")
            out.config_file = std::string(value);
        else
            out.out_dir = std::string(value); // --out
        if (!error.empty()) return {{}, error};
    }
    if (out.out_dir.empty()) return {{}, "--out: missing; the output directory is required (--out DIR)"};
    return {out, {}};
}

std::string usage() {
    constexpr std::size_t column = 25;
    auto line = [](std::string_view flag, std::string_view text) { return penumbra::help_line(flag, text, column); };
    std::string out = "usage: penumbra-gen [configuration flags] [--config FILE.json] [--validate] --out DIR\n"
                      "\n"
                      "Writes the shaders of one Penumbra configuration (GLSL, WGSL, HLSL, or MSL translated from the\n"
                      "vulkan target's SPIR-V by SPIRV-Cross) and its layout.json into DIR.\n"
                      "\n"
                      "configuration (flags override the --config file; a technique reads the fields of every technique\n"
                      "and its own, the others never change its output):\n\n";
    out += penumbra::config_usage(column);
    out += "\ninput:\n";
    out += line("--config FILE.json",
                "read the configuration from JSON: an object with the keys of layout.json's \"config\" (" +
                    penumbra::config_key_list() +
                    "; all optional, a section such as pcss an object of its own keys), or a layout.json, whose "
                    "\"config\" object is read; a regular file of at most 1 MiB");
    out += "\noutput:\n";
    out += line("--out DIR", "directory to write into, created with its parents (required); all files or none: on a "
                             "failure the directory is left as it was. Files an earlier run listed in DIR/layout.json "
                             "that this one does not write are removed");
    out += line("--validate", "compile and link every program with glslang; on errors, print them, still write the "
                              "files (to inspect) and exit 1. Target msl is always compiled (its translation starts "
                              "from glslang's SPIR-V), with or without it");
    out += line("--help, -h", "print this help and exit");
    out += "\nA value may also be given as --flag=value.\n"
           "exit status: 0 written; 1 glslang rejected the emitted code (files written); 2 bad arguments,\n"
           "configuration or output directory (nothing written); 3 internal error\n";
    return out;
}

} // namespace penumbra_gen
