// penumbra/config_fields.hpp — the table of configuration fields: every field of penumbra::Config once
// (penumbra/config_field.hpp), and what it drives: layout.json's "config" object, the --help lines of
// the tools, the JSON Schema of that object (docs/layout.schema.json), and the table as JSON for the
// web page's panel (through the WebAssembly module).
//
//   for (const penumbra::ConfigField& f : penumbra::config_fields()) ...   // key, flag, range, help
//   std::string json = penumbra::config_to_json(config);                 // as in layout.json
//
// The fields every technique reads (technique, light, target, alpha_test) are here; each technique's
// own are in its folder, detail/<technique>/fields.hpp. A new field is one row there; a new
// technique's fields, one fields.hpp in its folder that its descriptor's `fields` names
// (detail/technique.hpp). Rows added after
// layout_version 3 set omit_default, so that the layout.json of every earlier configuration stays
// byte for byte what it was (a section whose rows all keep their defaults is left out). After a change,
// `penumbra-config-schema --write docs/layout.schema.json` regenerates the schema's "config" object.
#pragma once

#include "config_field.hpp"
#include "profiles.hpp"
#include "detail/techniques.hpp"
#include "detail/text.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {
namespace detail {

// The profile's row: setting it applies the preset (penumbra/profiles.hpp), so every way a field is set
// (a flag, a JSON key, a panel) reaches it; the readers of a whole configuration apply it again last, so that
// the fields given beside it win (apply_profile's explicit keys).
constexpr ConfigField profile_field() {
    ConfigField row = member<&Config::profile>(
        {.key = "profile",
         .flag = "--profile",
         .metavar = "P",
         .help =
             "shadow quality tier: balanced (the default), large (lights x4 and up, lower at every size: "
             "the irradiance window's quadrants, 1.3 to 1.8 times the frame) or fast (a sixth of the frame, "
             "below PCSS's: 8 slices of 128, chained, by area); the fields given beside it win",
         .detail =
             "a named preset of the occlusion fields slices, resolution, fusion, irradiance_window and "
             "irradiance_quadrants (absent means balanced, the defaults): large turns irradiance_quadrants "
             "on, for lights several times the scene's own rectangle, lower at every light size, 1.3 to 1.8 "
             "times the frame; fast takes 8 slices of 128 texels, chained fusion and the light weighed by "
             "area, for a frame budget below PCSS 16/16's, with a higher error; a key given beside it "
             "overrides the preset's value",
         .techniques = "occlusion",
         .omit_default = true});
    row.set = [](Config& c, double v) { c = apply_profile(c, detail::from_field_value<Profile>(v)); };
    return row;
}

constexpr auto common_fields() {
    return std::array{
        member<&Config::technique>({.key = "technique", .flag = "--technique", .metavar = "T",
                                    .help = "shadowing technique",
                                    .detail = "the method the programs implement; only its own fields shape the "
                                              "programs"}),
        profile_field(),
        member<&Config::light>({.key = "light", .flag = "--light", .metavar = "L", .help = "area light"}),
        member<&Config::target>({.key = "target", .flag = "--target", .metavar = "T", .help = "shading language"}),
        member<&Config::alpha_test>(
            {.key = "alpha_test", .flag = "--[no-]alpha-test",
             .help = "cut-out casters: the passes that draw casters from the light discard fragments whose alpha "
                     "(the draw's penumbra_alphaTexture at its penumbra_uv) is below its penumbra_alphaCutoff",
             .detail = "cut-out casters, every technique (absent means false): the programs that draw the casters "
                       "from the light (slicing, depth_bins, shadow_depth) take the vertex input penumbra_uv (the "
                       "caster's material texture coordinates) and the per-draw parameters penumbra_alphaTexture "
                       "and penumbra_alphaCutoff (source \"draw\"): the caller binds its own material's texture and "
                       "cutoff for each draw, and a fragment whose alpha is below the cutoff is discarded. oim: its "
                       "offline bake honours the same cut",
             .omit_default = true}),
    };
}

// Each technique descriptor's rows once (techniques that share a folder share its rows), in the
// order of the Technique values.
constexpr std::vector<std::span<const ConfigField>> technique_field_sets() {
    std::vector<std::span<const ConfigField>> sets;
    for (Technique t : all_values<Technique>()) {
        const std::span<const ConfigField> rows = technique_descriptor(t).fields;
        if (rows.empty()) continue;
        bool seen = false;
        // the same rows have the same first key (compared as text: sanitizer builds do not fold a
        // comparison of two objects' addresses in a constant expression)
        for (const std::span<const ConfigField>& s : sets) seen = seen || s.front().key == rows.front().key;
        if (!seen) sets.push_back(rows);
    }
    return sets;
}

constexpr std::size_t technique_field_count() {
    std::size_t n = 0;
    for (const std::span<const ConfigField>& s : technique_field_sets()) n += s.size();
    return n;
}

// Every row: the common fields, then each technique's (its descriptor's `fields`).
constexpr auto make_config_field_table() {
    constexpr auto common = common_fields();
    std::array<ConfigField, common.size() + technique_field_count()> out{};
    std::size_t at = 0;
    for (const ConfigField& f : common) out[at++] = f;
    for (const std::span<const ConfigField>& s : technique_field_sets())
        for (const ConfigField& f : s) out[at++] = f;
    return out;
}

inline constexpr auto config_field_table = make_config_field_table();

// layout.json's "config" keys in the order layout_version 3 writes them (top level; a section's keys
// follow the table). Frozen: keys added later follow these in table order.
inline constexpr std::array<std::string_view, 25> layout_v3_key_order{
    "technique",       "slices",       "resolution", "filter",          "fusion",     "packing",
    "light",           "leak_fix",     "self_shadow_fade", "tangent_clip", "slice_placement", "level_format",
    "level_bound",     "level_reduction", "prefilter_stage", "tangent_clip_offset", "clip_footprint", "fade_ramp",
    "target",          "shadow_map",   "pcf",        "pcss",            "oim",        "erosion",
    "alpha_test"};

// A JSON string literal of `text` (quotes and backslashes escaped; the table's texts have no control
// characters, which would become spaces).
inline std::string json_quoted(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') out += '\\';
        out += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
    }
    return out + "\"";
}

// A number as --help and the schema write it: 16, 0.02, 1000.
inline std::string number_text(double value) {
    if (value == std::floor(value) && std::abs(value) < 1e15) return std::to_string(static_cast<long long>(value));
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

} // namespace detail

// Every configuration field, common ones first.
constexpr std::span<const ConfigField> config_fields() { return detail::config_field_table; }

// The row whose key is `key` ("pcss.blocker_samples"), or nullptr.
constexpr const ConfigField* find_config_field(std::string_view key) {
    for (const ConfigField& f : config_fields())
        if (f.key == key) return &f;
    return nullptr;
}

// "pcss" for "pcss.blocker_samples", "" for a top-level key.
constexpr std::string_view field_section(const ConfigField& field) {
    const std::size_t dot = field.key.find('.');
    return dot == std::string_view::npos ? std::string_view() : field.key.substr(0, dot);
}

// "blocker_samples" for "pcss.blocker_samples".
constexpr std::string_view field_name(const ConfigField& field) {
    const std::size_t dot = field.key.find('.');
    return dot == std::string_view::npos ? field.key : field.key.substr(dot + 1);
}

namespace detail {

// The techniques that read the field: the names in field.techniques ("pcf, pcss"), then for a shared
// row every technique whose descriptor reads its section; none for every technique.
inline std::vector<std::string_view> technique_names(const ConfigField& field) {
    std::vector<std::string_view> names;
    for (std::string_view rest = field.techniques; !rest.empty();) {
        const std::size_t comma = rest.find(", ");
        names.push_back(rest.substr(0, comma));
        rest = comma == std::string_view::npos ? std::string_view() : rest.substr(comma + 2);
    }
    if (field.shared)
        for (Technique t : all_values<Technique>())
            if (technique_descriptor(t).reads_shared_section == field_section(field) &&
                std::find(names.begin(), names.end(), to_string(t)) == names.end())
                names.push_back(to_string(t));
    return names;
}

// technique_names as one line, "pcf, pcss"; "" for every technique.
inline std::string technique_list(const ConfigField& field) {
    std::string out;
    for (std::string_view name : technique_names(field)) out += (out.empty() ? "" : ", ") + std::string(name);
    return out;
}

} // namespace detail

// True when `technique` reads the field.
inline bool reads_field(const ConfigField& field, Technique technique) {
    const std::vector<std::string_view> names = detail::technique_names(field);
    return names.empty() || std::find(names.begin(), names.end(), to_string(technique)) != names.end();
}

// What the field allows, in words: "1 to 64", "more than 0 to 4", "grid, poisson", "true or false".
inline std::string allowed_text(const ConfigField& field) {
    if (!field.allowed.empty()) return std::string(field.allowed);
    switch (field.kind) {
    case FieldKind::boolean: return "true or false";
    case FieldKind::choice: {
        std::string out;
        for (std::string_view name : field.names) out += (out.empty() ? "" : ", ") + std::string(name);
        return out;
    }
    default: break;
    }
    std::string out = field.min_exclusive ? "more than " : "";
    if (std::isfinite(field.min)) out += detail::number_text(field.min);
    if (std::isfinite(field.max)) out += (std::isfinite(field.min) ? " to " : "at most ") + detail::number_text(field.max);
    return out;
}

// The field's value in `config` as JSON: 16, 0.02, true, "nbuffer".
inline std::string field_json(const ConfigField& field, const Config& config) {
    const double v = field.get(config);
    switch (field.kind) {
    case FieldKind::integer: return std::to_string(static_cast<int>(v));
    case FieldKind::real: return detail::format_float(v).str();
    case FieldKind::boolean: return v != 0.0 ? "true" : "false";
    case FieldKind::choice: return detail::json_quoted(field.names[static_cast<std::size_t>(v)]);
    }
    return {};
}

// The field's value in `config` as --help shows it: 16, 0.02, on, nbuffer.
inline std::string field_text(const ConfigField& field, const Config& config) {
    const double v = field.get(config);
    if (field.kind == FieldKind::boolean) return v != 0.0 ? "on" : "off";
    if (field.kind == FieldKind::choice) return std::string(field.names[static_cast<std::size_t>(v)]);
    return detail::number_text(v);
}

namespace detail {

// The top-level keys of the "config" object in order (layout_v3_key_order, then new ones in table
// order); a section stands for its rows.
inline std::vector<std::string_view> config_top_keys() {
    std::vector<std::string_view> keys(layout_v3_key_order.begin(), layout_v3_key_order.end());
    for (const ConfigField& f : config_fields()) {
        const std::string_view top = field_section(f).empty() ? f.key : field_section(f);
        if (std::find(keys.begin(), keys.end(), top) == keys.end()) keys.push_back(top);
    }
    return keys;
}

} // namespace detail

// layout.json's "config" object for `config` (and the --config file format): every field, sections
// on one line each, two-space indentation after `indent`; fields marked omit_default only when not
// the default or in the selected technique's own section.
inline std::string config_to_json(const Config& config, std::string_view indent = "") {
    const Config defaults{};
    // the selected technique's own section ("evsm" of technique evsm) is always written: its layout states
    // every value its programs were specialized for
    auto written = [&](const ConfigField& f) {
        return !f.omit_default || f.get(config) != f.get(defaults) || field_section(f) == to_string(config.technique);
    };
    std::string out;
    for (std::string_view top : detail::config_top_keys()) {
        std::string value;
        if (const ConfigField* f = find_config_field(top)) {
            if (!written(*f)) continue;
            value = field_json(*f, config);
        } else {
            for (const ConfigField& f : config_fields())
                if (field_section(f) == top && written(f))
                    value += (value.empty() ? "{" : ", ") + detail::json_quoted(field_name(f)) + ": " + field_json(f, config);
            if (value.empty()) continue;
            value += "}";
        }
        out += (out.empty() ? "" : ",\n") + std::string(indent) + "  " + detail::json_quoted(top) + ": " + value;
    }
    return "{\n" + out + "\n" + std::string(indent) + "}";
}

// One --help entry: "  FLAG" padded to `column`, then `text` wrapped at `width` characters, its
// continuation lines indented to `column`.
inline std::string help_line(std::string_view flag, std::string_view text, std::size_t column, std::size_t width = 110) {
    std::string line = "  " + std::string(flag);
    line.resize(std::max(line.size() + 1, column), ' ');
    std::size_t length = line.size();
    bool first = true;
    for (std::string_view rest = text; !rest.empty();) {
        const std::size_t space = rest.find(' ');
        const std::string_view word = rest.substr(0, space);
        rest = space == std::string_view::npos ? std::string_view() : rest.substr(space + 1);
        if (!first && length + 1 + word.size() > width) {
            line += '\n';
            line.append(column, ' ');
            length = column;
        } else if (!first) {
            line += ' ';
            ++length;
        }
        line += word;
        length += word.size();
        first = false;
    }
    return line + "\n";
}

// The --help lines of every field with a flag: a heading per technique group ("occlusion:"), then
// "  --flag V" padded to `column`, the help, what is allowed and the default, wrapped at `width`.
// Rows that share a switch (--no-rotation) are one line.
inline std::string config_usage(std::size_t column, std::size_t width = 110) {
    const Config d{};
    std::string out, heading;
    std::vector<std::string_view> done;
    for (const ConfigField& f : config_fields()) {
        if (f.flag.empty() || std::find(done.begin(), done.end(), f.flag) != done.end()) continue;
        done.push_back(f.flag);
        std::string techniques = detail::technique_list(f);
        for (const ConfigField& g : config_fields())
            if (&g != &f && g.flag == f.flag && !g.techniques.empty()) techniques += ", " + detail::technique_list(g);
        const std::string group = techniques.empty() ? "every technique" : techniques;
        if (group != heading) out += (out.empty() ? "" : "\n") + group + ":\n";
        heading = group;

        std::string text(f.help);
        const std::string def = field_text(f, d);
        if (f.kind == FieldKind::boolean) {
            const bool both = f.flag.starts_with("--[no-]");
            const std::string name(f.flag.substr(both ? 7 : 2));
            text += " (default " + def + "; ";
            if (both) text += f.get(d) != 0.0 ? "--no-" + name + " turns it off)" : "--" + name + " turns it on)";
            else text += std::string("this flag turns it ") + (f.flag.starts_with("--no-") ? "off)" : "on)");
        } else {
            // "help: 1 to 64", or "help; 1 to 64" after a help that has a colon of its own
            text += (f.help.find(':') == std::string_view::npos ? ": " : "; ") + allowed_text(f) + " (default " + def + ")";
        }
        out += help_line(std::string(f.flag) + (f.metavar.empty() ? "" : " " + std::string(f.metavar)), text, column, width);
    }
    return out;
}

// Every flag of the table, each once, in table order: "--technique, --light, …".
inline std::string config_flag_list() {
    std::string out;
    std::vector<std::string_view> done;
    for (const ConfigField& f : config_fields()) {
        if (f.flag.empty() || std::find(done.begin(), done.end(), f.flag) != done.end()) continue;
        done.push_back(f.flag);
        if (f.flag.starts_with("--[no-]")) {
            const std::string name(f.flag.substr(7));
            out += (out.empty() ? "" : ", ") + ("--" + name) + ", --no-" + name;
        } else {
            out += (out.empty() ? "" : ", ") + std::string(f.flag);
        }
    }
    return out;
}

// The top-level keys of the "config" object, in layout.json's order: "technique, slices, …".
inline std::string config_key_list() {
    std::string out;
    for (std::string_view key : detail::config_top_keys()) out += (out.empty() ? "" : ", ") + std::string(key);
    return out;
}

// The keys of section `section` ("pcss"): "blocker_samples, filter_samples, …".
inline std::string config_section_keys(std::string_view section) {
    std::string out;
    for (const ConfigField& f : config_fields())
        if (field_section(f) == section) out += (out.empty() ? "" : ", ") + std::string(field_name(f));
    return out;
}

namespace detail {

// The JSON Schema of one field: type or enum, range, description.
inline std::string field_schema(const ConfigField& f, const std::string& indent) {
    const std::string in = indent + "  ";
    std::vector<std::string> members;
    if (f.kind == FieldKind::choice) {
        std::string names;
        for (std::string_view n : f.names) names += (names.empty() ? "\n" : ",\n") + in + "  " + json_quoted(n);
        members.push_back("\"enum\": [" + names + "\n" + in + "]");
    } else {
        members.push_back(std::string("\"type\": ") +
                          (f.kind == FieldKind::integer ? "\"integer\"" : f.kind == FieldKind::real ? "\"number\"" : "\"boolean\""));
        if (f.kind != FieldKind::boolean) {
            if (std::isfinite(f.min))
                members.push_back((f.min_exclusive ? "\"exclusiveMinimum\": " : "\"minimum\": ") + number_text(f.min));
            if (std::isfinite(f.max)) members.push_back("\"maximum\": " + number_text(f.max));
        }
    }
    const std::string_view text = f.detail.empty() ? f.help : f.detail;
    members.push_back("\"description\": " +
                      json_quoted((f.techniques.empty() ? "" : technique_list(f) + ": ") + std::string(text)));
    std::string out = "{";
    for (std::size_t i = 0; i < members.size(); ++i) out += (i ? ",\n" : "\n") + in + members[i];
    return out + "\n" + indent + "}";
}

} // namespace detail

// docs/layout.schema.json's "$defs"."config": the JSON Schema of the "config" object, generated from
// the table (two-space indentation after `indent`, as the file is written). A check keeps the file in
// step (tests/schema).
inline std::string config_schema_json(std::string_view indent = "") {
    const std::string in = std::string(indent) + "  ", in2 = in + "  ", in3 = in2 + "  ";
    std::string required, properties;
    for (std::string_view top : detail::config_top_keys()) {
        std::string schema;
        bool optional = true;
        if (const ConfigField* f = find_config_field(top)) {
            schema = detail::field_schema(*f, in2);
            optional = f->omit_default;
        } else {
            std::string keys, props, description, techniques;
            for (const ConfigField& f : config_fields()) {
                if (field_section(f) != top) continue;
                if (!f.omit_default) {
                    keys += (keys.empty() ? "\n" : ",\n") + in3 + "  " + detail::json_quoted(field_name(f));
                    optional = false;
                }
                props += (props.empty() ? "\n" : ",\n") + in3 + "  " + detail::json_quoted(field_name(f)) + ": " +
                         detail::field_schema(f, in3 + "  ");
                if (!f.section.empty()) description = f.section;
                for (std::string_view name : detail::technique_names(f)) // the union of the rows' techniques
                    if ((", " + techniques + ", ").find(", " + std::string(name) + ", ") == std::string::npos)
                        techniques += (techniques.empty() ? "" : ", ") + std::string(name);
            }
            if (props.empty()) continue;
            schema = "{\n" + in3 + "\"type\": \"object\",\n" + in3 + "\"additionalProperties\": false,\n" + in3 +
                     "\"required\": [" + keys + (keys.empty() ? "" : "\n" + in3) + "],\n" + in3 + "\"properties\": {" +
                     props + "\n" + in3 + "},\n" + in3 + "\"description\": " +
                     detail::json_quoted(techniques + ": " + description) + "\n" + in2 + "}";
        }
        if (!optional) required += (required.empty() ? "\n" : ",\n") + in2 + detail::json_quoted(top);
        properties += (properties.empty() ? "\n" : ",\n") + in2 + detail::json_quoted(top) + ": " + schema;
    }
    return "{\n" + in + "\"type\": \"object\",\n" + in + "\"additionalProperties\": false,\n" + in + "\"required\": [" +
           required + "\n" + in + "],\n" + in + "\"properties\": {" + properties + "\n" + in + "}\n" +
           std::string(indent) + "}";
}

// The table as JSON, for programs that cannot include this header (the web page's panel, through the
// WebAssembly module): [{"key", "flag", "metavar", "kind", "min", "max", "min_exclusive", "allowed",
// "help", "techniques": [...], "names": [...], "default", "optional", "profile_sets"}, …], in table order;
// "profile_sets": whether a profile sets the field (penumbra/profiles.hpp's profile_fields).
inline std::string config_fields_json() {
    const Config d{};
    std::string out = "[";
    for (const ConfigField& f : config_fields()) {
        static constexpr std::string_view kinds[] = {"integer", "real", "boolean", "choice"};
        std::string techniques, names;
        for (std::string_view t : detail::technique_names(f)) techniques += (techniques.empty() ? "" : ", ") + detail::json_quoted(t);
        for (std::string_view n : f.names) names += (names.empty() ? "" : ", ") + detail::json_quoted(n);
        auto number = [](double v) { return std::isfinite(v) ? detail::number_text(v) : std::string("null"); };
        out += std::string(out.size() > 1 ? ",\n " : "\n ") + "{\"key\": " + detail::json_quoted(f.key) +
               ", \"flag\": " + detail::json_quoted(f.flag) +
               ", \"metavar\": " + detail::json_quoted(f.metavar) +
               ", \"kind\": " + detail::json_quoted(kinds[static_cast<int>(f.kind)]) +
               ", \"min\": " + number(f.min) + ", \"max\": " + number(f.max) +
               ", \"min_exclusive\": " + (f.min_exclusive ? "true" : "false") +
               ", \"allowed\": " + detail::json_quoted(allowed_text(f)) +
               ", \"help\": " + detail::json_quoted(f.help) + ", \"techniques\": [" + techniques +
               "], \"names\": [" + names + "], \"default\": " + field_json(f, d) +
               ", \"optional\": " + (f.omit_default ? "true" : "false") +
               ", \"profile_sets\": " + (profile_sets(f.key) ? "true" : "false") + "}";
    }
    return out + "\n]";
}

} // namespace penumbra
