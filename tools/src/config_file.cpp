#include "config_file.hpp"

#include "bounded_read.hpp"

#include <nlohmann/json.hpp>
#include <penumbra/config_fields.hpp>

#include <limits>
#include <vector>

namespace penumbra_gen {
namespace {

using nlohmann::json;

std::string type_of(const json& value) {
    if (value.is_number_float()) return "a number with a fraction";
    if (value.is_number()) return "an integer";
    if (value.is_string()) return "a string";
    if (value.is_boolean()) return "a boolean";
    if (value.is_null()) return "null";
    if (value.is_array()) return "an array";
    return "an object";
}

// The value as text for a message, short and on one line.
std::string shown(const json& value) {
    return printable(value.dump(-1, ' ', true, json::error_handler_t::replace));
}

// One field's JSON value into `config`; else one line naming the key, the value and what is allowed.
std::string read_field(const penumbra::ConfigField& field, const json& value, penumbra::Config& config) {
    const std::string where = "key '" + std::string(field.key) + "'";
    const std::string allowed = penumbra::allowed_text(field);
    switch (field.kind) {
    case penumbra::FieldKind::integer: {
        if (!value.is_number_integer())
            return where + " must be an integer (" + allowed + "), got " + type_of(value) + " " + shown(value);
        // number_unsigned above INT_MAX, or number_integer outside int: no narrowing, an error.
        const bool fits =
            value.is_number_unsigned()
                ? value.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<int>::max())
                : value.get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                      value.get<std::int64_t>() <= std::numeric_limits<int>::max();
        if (!fits) return where + ": " + shown(value) + " is out of range; allowed: " + allowed;
        field.set(config, static_cast<double>(value.get<std::int64_t>()));
        return {};
    }
    case penumbra::FieldKind::real:
        if (!value.is_number())
            return where + " must be a number (" + allowed + "), got " + type_of(value) + " " + shown(value);
        field.set(config, value.get<double>());
        return {};
    case penumbra::FieldKind::boolean:
        if (!value.is_boolean()) return where + " must be true or false, got " + type_of(value) + " " + shown(value);
        field.set(config, value.get<bool>() ? 1.0 : 0.0);
        return {};
    case penumbra::FieldKind::choice: {
        if (!value.is_string())
            return where + " must be a string (one of " + allowed + "), got " + type_of(value) + " " + shown(value);
        const auto& text = value.get_ref<const std::string&>();
        for (std::size_t i = 0; i < field.names.size(); ++i)
            if (field.names[i] == text) {
                field.set(config, static_cast<double>(i));
                return {};
            }
        return where + ": '" + printable(text) + "' is not allowed; allowed: " + allowed;
    }
    }
    return {};
}

// A section's object ("shadow_map", "pcf", …): every key optional, each one a row "section.key".
std::string read_section(const std::string& section, const json& value, penumbra::Config& config) {
    const std::string keys = penumbra::config_section_keys(section);
    if (!value.is_object())
        return "key '" + section + "' must be an object with the keys " + keys + ", got " + type_of(value);
    for (const auto& [key, item] : value.items()) {
        const std::string name = section + "." + key;
        const penumbra::ConfigField* field = penumbra::find_config_field(name);
        if (!field) return "unknown key '" + printable(name) + "'; allowed keys in '" + section + "': " + keys;
        if (std::string error = read_field(*field, item, config); !error.empty()) return error;
    }
    return {};
}

// The document, built by nlohmann's own DOM builder, with the parse error kept as a value instead
// of thrown: the same messages with or without C++ exceptions (the WebAssembly emitter is built
// with -fno-exceptions, wasm/README.md).
struct DomOrError : nlohmann::detail::json_sax_dom_parser<json> {
    explicit DomOrError(json& root) : json_sax_dom_parser(root, /*allow_exceptions=*/false) {}
    int error_id = 0;  // nlohmann's exception id: 1xx parse_error, 406 a number beyond a double
    std::string error; // its what()
    template <class Exception> bool parse_error(std::size_t, const std::string&, const Exception& e) {
        error_id = e.id;
        error = e.what();
        return false;
    }
};

// nlohmann's what() without its "[json.exception.parse_error.101] " prefix, on one line, with
// the raw bytes it quotes from the file ("last read: '…'") escaped.
std::string parse_message(std::string_view text) {
    if (text.starts_with("[json.exception."))
        if (std::size_t end = text.find("] "); end != std::string_view::npos) text.remove_prefix(end + 2);
    return printable(text, 400);
}

// What a key ("slices", or "pcss.blocker_samples") allows, for the messages that cannot come from the
// value's own check; "" for no such key.
std::string allowed_for(const std::string& key) {
    const penumbra::ConfigField* field = penumbra::find_config_field(key);
    if (!field) return {};
    return field->kind == penumbra::FieldKind::choice ? "one of " + penumbra::allowed_text(*field)
                                                      : penumbra::allowed_text(*field);
}

// A second pass over a document whose number did not fit a double (nlohmann's error 406 names
// neither key nor position): which key the number belongs to, and its text.
struct KeyAtError : nlohmann::json_sax<json> {
    std::vector<std::string> keys; // per open object, its current key
    std::string found_key, token;
    bool null() override { return true; }
    bool boolean(bool) override { return true; }
    bool number_integer(number_integer_t) override { return true; }
    bool number_unsigned(number_unsigned_t) override { return true; }
    bool number_float(number_float_t, const string_t&) override { return true; }
    bool string(string_t&) override { return true; }
    bool binary(binary_t&) override { return true; }
    bool start_object(std::size_t) override {
        keys.emplace_back();
        return true;
    }
    bool key(string_t& k) override {
        keys.back() = k;
        return true;
    }
    bool end_object() override {
        keys.pop_back();
        return true;
    }
    bool start_array(std::size_t) override { return true; }
    bool end_array() override { return true; }
    bool parse_error(std::size_t, const std::string& last_token, const nlohmann::detail::exception&) override {
        token = last_token;
        // The innermost key, with its section when it has one ("pcss.filter_samples"; a layout.json's
        // "config" wrapper left out).
        for (std::size_t first = 0; first < keys.size() && found_key.empty(); ++first) {
            std::string path;
            for (std::size_t k = first; k < keys.size(); ++k) path += (path.empty() ? "" : ".") + keys[k];
            if (penumbra::find_config_field(path)) found_key = path;
        }
        if (found_key.empty() && !keys.empty()) found_key = keys.back();
        return false;
    }
};

std::string overflow_message(std::string_view text) {
    KeyAtError at;
    json::sax_parse(text.begin(), text.end(), &at, nlohmann::detail::input_format_t::json, false);
    const std::string number = printable(at.token);
    if (at.found_key.empty()) return number + " is out of range; allowed: a number of at most 1.8e308 in magnitude";
    const std::string allowed = allowed_for(at.found_key);
    if (allowed.empty())
        return "unknown key '" + printable(at.found_key) + "'; allowed keys: " + penumbra::config_key_list();
    return "key '" + printable(at.found_key) + "': " + number + " is out of range; allowed: " + allowed;
}

} // namespace

Parsed<penumbra::Config> parse_config_json(std::string_view text, std::string_view source) {
    const std::string where(source);
    json document;
    DomOrError builder(document);
    if (!json::sax_parse(text.begin(), text.end(), &builder)) {
        if (builder.error_id == 406) return {{}, where + ": " + overflow_message(text)}; // e.g. 1e309
        return {{}, where + ": " + parse_message(builder.error)};
    }
    if (!document.is_object())
        return {{},
                where + ": the top level must be a JSON object with the keys " + penumbra::config_key_list() +
                    ", got " + type_of(document)};
    const json* object = &document;
    if (document.contains("config")) { // a whole layout.json
        object = &document["config"];
        if (!object->is_object())
            return {{},
                    where + ": \"config\" must be an object with the keys " + penumbra::config_key_list() +
                        ", got " + type_of(*object)};
    }

    penumbra::Config config;
    std::vector<std::string_view> given; // the keys, which win over the profile's preset
    for (const auto& [key, value] : object->items()) {
        given.push_back(key);
        if (key == "profile") continue; // last, below
        std::string error;
        const penumbra::ConfigField* field = penumbra::find_config_field(key);
        if (field && penumbra::field_section(*field).empty()) // "pcss.rotate" is a key of "pcss", not of the top level
            error = read_field(*field, value, config);
        else if (!penumbra::config_section_keys(key).empty())
            error = read_section(key, value, config);
        else
            error = "unknown key '" + printable(key) + "'; allowed keys: " + penumbra::config_key_list();
        if (!error.empty()) return {{}, where + ": " + error};
    }
    // "profile": its preset, now that "light" and the rest are read, on the fields no key set (read into a
    // scratch configuration, since the row's own setter applies the preset to every field)
    if (const auto profile = object->find("profile"); profile != object->end()) {
        penumbra::Config chosen;
        if (std::string error = read_field(*penumbra::find_config_field("profile"), *profile, chosen); !error.empty())
            return {{}, where + ": " + error};
        config = penumbra::apply_profile(config, chosen.profile, given);
    }
    return {config, {}};
}

Parsed<penumbra::Config> read_config_file(const std::string& path) {
    const BoundedRead file = read_bounded_file(path, config_file_limit);
    if (!file.text) {
        if (file.problem == "no such file")
            return {{}, "--config: cannot open '" + printable(path) + "': no such file"};
        return {{}, "--config: cannot read '" + printable(path) + "': " + file.problem +
                        (file.problem.find("allowed") == std::string::npos ? "" : " (a JSON file)")};
    }
    return parse_config_json(*file.text, printable(path));
}

} // namespace penumbra_gen
