#include "technique_flags.hpp"

#include "cli.hpp"

#include <optional>

namespace penumbra_gen {
namespace {

// The value a switch sets in `field`, or nothing when `flag` is not that field's switch:
// "--no-x" false, "--x" true, "--[no-]x" both.
std::optional<double> switch_value(const penumbra::ConfigField& field, std::string_view flag) {
    if (field.kind != penumbra::FieldKind::boolean || field.flag.empty()) return std::nullopt;
    if (field.flag.starts_with("--[no-]")) {
        const std::string_view name = field.flag.substr(7);
        if (flag.starts_with("--no-") && flag.substr(5) == name) return 0.0;
        if (flag.starts_with("--") && flag.substr(2) == name) return 1.0;
        return std::nullopt;
    }
    if (flag != field.flag) return std::nullopt;
    return flag.starts_with("--no-") ? 0.0 : 1.0;
}

const penumbra::ConfigField* value_field(std::string_view flag) {
    for (const penumbra::ConfigField& f : penumbra::config_fields())
        if (f.kind != penumbra::FieldKind::boolean && f.flag == flag) return &f;
    return nullptr;
}

} // namespace

bool is_config_switch(std::string_view flag) {
    for (const penumbra::ConfigField& f : penumbra::config_fields())
        if (switch_value(f, flag)) return true;
    return false;
}

bool is_config_flag(std::string_view flag) { return value_field(flag) != nullptr; }

void set_config_switch(std::string_view flag, ConfigFlags& flags) {
    for (const penumbra::ConfigField& f : penumbra::config_fields()) // --no-rotation: pcf.rotate and pcss.rotate
        if (const std::optional<double> value = switch_value(f, flag)) flags.values.emplace_back(&f, *value);
}

std::string parse_config_flag(std::string_view flag, std::string_view text, ConfigFlags& flags) {
    const penumbra::ConfigField* field = value_field(flag);
    if (!field) return std::string(flag) + ": not a configuration flag";
    const std::string allowed = penumbra::allowed_text(*field);
    std::string error;
    double value = 0.0;
    if (field->kind == penumbra::FieldKind::integer) {
        int number = 0;
        error = penumbra::cli::parse_int(flag, text, number, allowed);
        value = number;
    } else if (field->kind == penumbra::FieldKind::real) {
        error = penumbra::cli::parse_real(flag, text, value, allowed);
    } else { // choice
        std::size_t i = 0;
        while (i < field->names.size() && field->names[i] != text) ++i;
        if (i == field->names.size())
            error = std::string(flag) + ": '" + printable(text) + "' is not allowed; allowed: " + allowed;
        value = static_cast<double>(i);
    }
    if (error.empty()) flags.values.emplace_back(field, value);
    return error;
}

penumbra::Config apply(const ConfigFlags& flags, penumbra::Config config) {
    for (const penumbra::ConfigField& f : penumbra::config_fields())
        if (f.implies)
            for (const auto& [field, value] : flags.values)
                if (field == &f) {
                    f.implies(config);
                    break;
                }
    // the values, then --profile's preset (once --light and the rest are set) on the fields no flag set, so
    // that they win over it whatever their order
    std::vector<std::string_view> given;
    for (const auto& [field, value] : flags.values) {
        given.push_back(field->key);
        if (field->key != "profile") field->set(config, value);
    }
    for (const auto& [field, value] : flags.values)
        if (field->key == "profile")
            config = penumbra::apply_profile(config, static_cast<penumbra::Profile>(static_cast<int>(value)), given);
    return config;
}

} // namespace penumbra_gen
