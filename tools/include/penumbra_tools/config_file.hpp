// config_file.hpp — a configuration from a JSON file (--config), errors as values.
//
// The keys are the Config field names, as in layout.json's "config" object: slices, resolution,
// filter, fusion, packing, light, leak_fix, self_shadow_fade, target; all optional, the rest keep
// the defaults of Config{}. A whole layout.json is accepted too: its "config" member is read.
#pragma once

#include "arguments.hpp"

#include <penumbra/config.hpp>

#include <string>
#include <string_view>

namespace penumbra_gen {

// The configuration in the JSON text `text`; `source` names it in error messages.
Parsed<penumbra::Config> parse_config_json(std::string_view text, std::string_view source);

// The configuration in the file at `path` (missing, unreadable or malformed: an error).
Parsed<penumbra::Config> read_config_file(const std::string& path);

} // namespace penumbra_gen
