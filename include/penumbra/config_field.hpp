// penumbra/config_field.hpp — one row of the table of configuration fields (penumbra/config_fields.hpp):
// what one field of penumbra::Config is called in JSON and on the command line, what it holds, what it
// allows, what it means, which technique reads it, and how to reach it.
//
//   penumbra::member<&penumbra::Config::pcss, &penumbra::PcssParams::blocker_samples>(
//       {.key = "pcss.blocker_samples", .flag = "--pcss-blockers", .metavar = "N", .min = 1, .max = 64,
//        .help = "blocker-search samples", .techniques = "pcss"})
//
// Every value travels as a double: integers exactly, booleans as 0 or 1, a choice as the index of its
// name (EnumNames), so one pair of plain function pointers reaches any field and a row stays a
// literal type (the table is constexpr).
#pragma once

#include "config.hpp"

#include <limits>
#include <span>
#include <string_view>
#include <type_traits>

namespace penumbra {

enum class FieldKind : std::uint8_t {
    integer, // int
    real,    // double
    boolean, // bool
    choice,  // an enumeration: one of `names`
};

// Every member has a default, so a row names only the members it sets (designated initializers,
// without -Wmissing-field-initializers).
struct ConfigField {
    std::string_view key{};     // JSON key of layout.json's "config" and --config: "slices", or "section.key"
                                // for a nested one ("pcss.blocker_samples")
    std::string_view flag{};    // command-line flag. Booleans are switches: "--no-leak-fix" sets false,
                                // "--alpha-test" sets true, "--[no-]tangent-clip" is both. Rows may share a
                                // switch (--no-rotation: pcf.rotate and pcss.rotate)
    std::string_view metavar{}; // the value's name in --help ("--slices N"); "" for switches
    FieldKind kind = FieldKind::integer;  // set by member<>() from the member's type
    double min = -std::numeric_limits<double>::infinity(); // numbers: the range the field allows
    double max = std::numeric_limits<double>::infinity();
    bool min_exclusive = false;           // "more than min"
    bool power_of_two = false;            // integers: only powers of two in [min, max]
    std::string_view allowed{};             // what is allowed, in words, where a plain range does not say it
                                          // ("1 to 32, 64 or 128"); "" : written from min and max
    std::string_view help{};                // one line: --help, the panels
    std::string_view detail{};              // a longer description for docs/layout.schema.json ("": help)
    std::string_view section{};             // the first row of a section: the section's own description
    std::string_view techniques{};          // the techniques that read it, "pcf, pcss"; "": every technique
    bool shared = false;                  // also read by every technique whose descriptor names this row's
                                          // section in reads_shared_section (detail/technique.hpp)
    bool omit_default = false;            // layout.json writes it only when not the default (fields added
                                          // after layout_version 3, so that older layouts read as before)
    std::span<const std::string_view> names{}; // choice: the enumeration's names (EnumNames)
    double (*get)(const Config&) = nullptr;
    void (*set)(Config&, double) = nullptr;
    void (*implies)(Config&) = nullptr;   // the flag also sets this unless that field's own flag is given
                                          // (--pcf-grid N means --pcf-pattern grid)
};

namespace detail {

// config.*a.*b: the member a field names (one or two levels deep).
template <auto... path> constexpr auto& member_of(Config& config) { return (config .* ... .* path); }
template <auto... path> constexpr const auto& member_of(const Config& config) { return (config .* ... .* path); }

template <class T> constexpr double field_value(T value) {
    if constexpr (std::is_enum_v<T>) return static_cast<double>(static_cast<int>(value));
    else return static_cast<double>(value);
}
template <class T> constexpr T from_field_value(double value) {
    if constexpr (std::is_enum_v<T>) return static_cast<T>(static_cast<int>(value));
    else if constexpr (std::is_same_v<T, bool>) return value != 0.0;
    else return static_cast<T>(value);
}

} // namespace detail

// `row` with its kind, names and access filled in from the member Config.*path.
template <auto... path> constexpr ConfigField member(ConfigField row) {
    using T = std::remove_cvref_t<decltype(detail::member_of<path...>(std::declval<Config&>()))>;
    if constexpr (std::is_same_v<T, bool>) {
        row.kind = FieldKind::boolean;
        row.min = 0;
        row.max = 1;
    } else if constexpr (std::is_same_v<T, int>) {
        row.kind = FieldKind::integer;
    } else if constexpr (std::is_same_v<T, double>) {
        row.kind = FieldKind::real;
    } else {
        static_assert(std::is_enum_v<T>, "a configuration field is an int, a double, a bool or an enumeration");
        row.kind = FieldKind::choice;
        row.names = EnumNames<T>::names;
        row.min = 0;
        row.max = static_cast<double>(EnumNames<T>::names.size() - 1);
    }
    row.get = [](const Config& c) { return detail::field_value(detail::member_of<path...>(c)); };
    row.set = [](Config& c, double v) { detail::member_of<path...>(c) = detail::from_field_value<T>(v); };
    return row;
}

} // namespace penumbra
