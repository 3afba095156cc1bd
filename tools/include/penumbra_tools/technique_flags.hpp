// technique_flags.hpp — the command-line flags of the configuration fields (--slices, --technique,
// --pcss-blockers, --no-rotation, …), one per row of the table of configuration fields
// (penumbra/config_fields.hpp), shared by penumbra-gen, penumbra-playground, penumbra-export-bundle
// and the playground's scripts. Ranges are checked by penumbra::validate, so every tool gives its
// messages.
#pragma once

#include <penumbra/config_fields.hpp>

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace penumbra_gen {

// The configuration values given on the command line, in order; they override the --config file.
struct ConfigFlags {
    std::vector<std::pair<const penumbra::ConfigField*, double>> values;
};

bool is_config_switch(std::string_view flag); // a field's flag without a value (--no-leak-fix, --alpha-test)
bool is_config_flag(std::string_view flag);   // a field's flag that takes a value (--slices)

// Sets `flag`'s value into `flags`; returns one line naming the flag, the text and what is allowed
// when the text is not a value of the right kind, else "".
std::string parse_config_flag(std::string_view flag, std::string_view value, ConfigFlags& flags);
void set_config_switch(std::string_view flag, ConfigFlags& flags);

// `config` with the flags applied: what a flag implies first (--pcf-grid: the grid pattern), then
// the values in command-line order, so that a later flag and an explicit --pcf-pattern win.
penumbra::Config apply(const ConfigFlags& flags, penumbra::Config config);

} // namespace penumbra_gen
