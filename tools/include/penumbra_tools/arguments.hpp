// arguments.hpp — the command line of penumbra-gen, parsed into values; errors are values too.
#pragma once

#include "printable.hpp"
#include "technique_flags.hpp"

#include <penumbra/config.hpp>

#include <optional>
#include <string>
#include <vector>

namespace penumbra_gen {

struct Arguments {
    ConfigFlags flags;                      // the configuration fields' flags (technique_flags.hpp)
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

// The --help text: every flag, every allowed value, the defaults of Config{}.
std::string usage();

} // namespace penumbra_gen
