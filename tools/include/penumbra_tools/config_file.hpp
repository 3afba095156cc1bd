// config_file.hpp — a configuration from a JSON file (--config), errors as values.
//
// The keys are those of layout.json's "config" object, from the table of configuration fields
// (penumbra/config_fields.hpp): "slices", …, and the sections "shadow_map": {"resolution": …}, …; all
// optional, the rest keep the defaults of Config{}. A whole layout.json is accepted too: its "config"
// member is read.
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
