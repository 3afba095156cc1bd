#include "config_file.hpp"

#include "bounded_read.hpp"

#include <nlohmann/json.hpp>
#include <penumbra/validate.hpp>

#include <limits>
#include <vector>

namespace penumbra_gen {
namespace {

using nlohmann::json;

constexpr std::string_view key_list =
    "slices, resolution, filter, fusion, packing, light, leak_fix, self_shadow_fade, tangent_clip, slice_placement, "
    "level_format, level_bound, level_reduction, prefilter_stage, tangent_clip_offset, clip_footprint, fade_ramp, target, "
    "technique, shadow_map, pcf, pcss, oim, erosion, alpha_test";

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

Parsed<int> read_int(std::string_view key, const json& value, std::string_view allowed) {
    const std::string where = "key '" + std::string(key) + "'";
    if (!value.is_number_integer())
        return {{},
                where + " must be an integer (" + std::string(allowed) + "), got " + type_of(value) + " " +
                    shown(value)};
    // number_unsigned above INT_MAX, or number_integer outside int: no narrowing, an error.
    const bool fits =
        value.is_number_unsigned()
            ? value.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<int>::max())
            : value.get<std::int64_t>() >= std::numeric_limits<int>::min() &&
                  value.get<std::int64_t>() <= std::numeric_limits<int>::max();
    if (!fits)
        return {{}, where + ": " + shown(value) + " is out of range; allowed: " + std::string(allowed)};
    return {static_cast<int>(value.get<std::int64_t>()), {}};
}

Parsed<bool> read_bool(std::string_view key, const json& value) {
    if (!value.is_boolean())
        return {{},
                "key '" + std::string(key) + "' must be true or false, got " + type_of(value) + " " +
                    shown(value)};
    return {value.get<bool>(), {}};
}

template <class Enum> Parsed<Enum> read_enum(std::string_view key, const json& value) {
    const std::string where = "key '" + std::string(key) + "'";
    if (!value.is_string())
        return {{},
                where + " must be a string (one of " + allowed_names<Enum>() + "), got " + type_of(value) +
                    " " + shown(value)};
    const auto& text = value.get_ref<const std::string&>();
    if (std::optional<Enum> parsed = penumbra::parse_enum<Enum>(text)) return {*parsed, {}};
    return {{}, where + ": '" + printable(text) + "' is not allowed; allowed: " + allowed_names<Enum>()};
}

template <class T> std::string store(Parsed<T> parsed, T& slot) {
    if (parsed.error.empty()) slot = *parsed.value;
    return parsed.error;
}

Parsed<double> read_real(std::string_view key, const json& value, std::string_view allowed) {
    if (!value.is_number())
        return {{},
                "key '" + std::string(key) + "' must be a number (" + std::string(allowed) + "), got " +
                    type_of(value) + " " + shown(value)};
    return {value.get<double>(), {}};
}

// A technique's parameter object ("shadow_map", "pcf", "pcss"): every key optional, `read` sets one
// key and returns its error, or "unknown" when there is no such key.
template <class Read>
std::string read_section(std::string_view section, const json& value, std::string_view keys, Read read) {
    if (!value.is_object())
        return "key '" + std::string(section) + "' must be an object with the keys " + std::string(keys) + ", got " +
               type_of(value);
    for (const auto& [key, item] : value.items()) {
        const std::string name = std::string(section) + "." + key;
        std::string error = read(key, name, item);
        if (error == "unknown")
            return "unknown key '" + printable(name) + "'; allowed keys in '" + std::string(section) +
                   "': " + std::string(keys);
        if (!error.empty()) return error;
    }
    return {};
}

std::string read_shadow_map(const json& value, penumbra::ShadowMapParams& sm) {
    return read_section("shadow_map", value, "resolution, constant_bias, slope_bias, normal_offset, receiver_plane_bias",
                        [&](const std::string& key, const std::string& name, const json& item) -> std::string {
                            if (key == "resolution")
                                return store(read_int(name, item, "a power of two from 32 to 8192"), sm.resolution);
                            if (key == "constant_bias") return store(read_real(name, item, "0 to 10"), sm.constant_bias);
                            if (key == "slope_bias") return store(read_real(name, item, "0 to 16"), sm.slope_bias);
                            if (key == "normal_offset") return store(read_real(name, item, "0 to 8"), sm.normal_offset);
                            if (key == "receiver_plane_bias") return store(read_bool(name, item), sm.receiver_plane_bias);
                            return "unknown";
                        });
}

std::string read_pcf(const json& value, penumbra::PcfParams& pcf) {
    return read_section("pcf", value, "pattern, grid_size, poisson_taps, radius, rotate",
                        [&](const std::string& key, const std::string& name, const json& item) -> std::string {
                            if (key == "pattern") return store(read_enum<penumbra::TapPattern>(name, item), pcf.pattern);
                            if (key == "grid_size") return store(read_int(name, item, "1 to 16"), pcf.grid_size);
                            if (key == "poisson_taps") return store(read_int(name, item, "1 to 64"), pcf.poisson_taps);
                            if (key == "radius") return store(read_real(name, item, "above 0 to 1000"), pcf.radius);
                            if (key == "rotate") return store(read_bool(name, item), pcf.rotate);
                            return "unknown";
                        });
}

std::string read_pcss(const json& value, penumbra::PcssParams& pcss) {
    return read_section("pcss", value, "blocker_samples, filter_samples, max_filter_texels, rotate",
                        [&](const std::string& key, const std::string& name, const json& item) -> std::string {
                            if (key == "blocker_samples")
                                return store(read_int(name, item, "1 to 64"), pcss.blocker_samples);
                            if (key == "filter_samples")
                                return store(read_int(name, item, "1 to 128"), pcss.filter_samples);
                            if (key == "max_filter_texels")
                                return store(read_int(name, item, "1 to half the shadow-map resolution"),
                                             pcss.max_filter_texels);
                            if (key == "rotate") return store(read_bool(name, item), pcss.rotate);
                            return "unknown";
                        });
}

std::string read_oim(const json& value, penumbra::OimParams& oim) {
    return read_section("oim", value, "resolution, intervals, samples",
                        [&](const std::string& key, const std::string& name, const json& item) -> std::string {
                            if (key == "resolution")
                                return store(read_int(name, item, "a power of two from 32 to 4096"), oim.resolution);
                            if (key == "intervals") return store(read_int(name, item, "4, 8, 12 or 16"), oim.intervals);
                            if (key == "samples")
                                return store(read_int(name, item, "256, 512, 1024 or 2048"), oim.samples);
                            return "unknown";
                        });
}

std::string read_erosion(const json& value, penumbra::ErosionParams& erosion) {
    return read_section("erosion", value, "max_search_radius, edge_threshold, search_taps, blur_taps",
                        [&](const std::string& key, const std::string& name, const json& item) -> std::string {
                            if (key == "max_search_radius")
                                return store(read_int(name, item, "1 to 256 pixels"), erosion.max_search_radius);
                            if (key == "edge_threshold")
                                return store(read_real(name, item, "above 0 to 4"), erosion.edge_threshold);
                            if (key == "search_taps") return store(read_int(name, item, "1 to 64"), erosion.search_taps);
                            if (key == "blur_taps") return store(read_int(name, item, "1 to 64"), erosion.blur_taps);
                            return "unknown";
                        });
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

// What a key allows, for the messages that cannot come from the value's own check.
std::string allowed_for(const std::string& key) {
    if (key == "slices") return std::string(penumbra::allowed_slices);
    if (key == "resolution") return "a power of two from 32 to 4096";
    if (key == "filter") return "one of " + allowed_names<penumbra::Filter>();
    if (key == "fusion") return "one of " + allowed_names<penumbra::Fusion>();
    if (key == "packing") return "one of " + allowed_names<penumbra::Packing>();
    if (key == "light") return "one of " + allowed_names<penumbra::Light>();
    if (key == "target") return "one of " + allowed_names<penumbra::Target>();
    if (key == "leak_fix" || key == "self_shadow_fade" || key == "clip_footprint" || key == "alpha_test")
        return "true or false";
    if (key == "level_bound") return "-1 (every level) or 0 to log2(resolution)";
    if (key == "tangent_clip_offset") return "0 to 8 slicing texels";
    if (key == "fade_ramp") return "more than 0 to 4 (fraction of a slice's thickness)";
    if (key == "level_reduction") return "-1 (every level at full resolution) or 0 to log2(resolution)";
    return {};
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
        if (!keys.empty()) found_key = keys.back();
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
        return "unknown key '" + printable(at.found_key) + "'; allowed keys: " + std::string(key_list);
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
                where + ": the top level must be a JSON object with the keys " + std::string(key_list) +
                    ", got " + type_of(document)};
    const json* object = &document;
    if (document.contains("config")) { // a whole layout.json
        object = &document["config"];
        if (!object->is_object())
            return {{},
                    where + ": \"config\" must be an object with the keys " + std::string(key_list) +
                        ", got " + type_of(*object)};
    }

    penumbra::Config config;
    for (const auto& [key, value] : object->items()) {
        std::string error;
        if (key == "technique")
            error = store(read_enum<penumbra::Technique>(key, value), config.technique);
        else if (key == "shadow_map")
            error = read_shadow_map(value, config.shadow_map);
        else if (key == "pcf")
            error = read_pcf(value, config.pcf);
        else if (key == "pcss")
            error = read_pcss(value, config.pcss);
        else if (key == "oim")
            error = read_oim(value, config.oim);
        else if (key == "erosion")
            error = read_erosion(value, config.erosion);
        else if (key == "slices")
            error = store(read_int(key, value, allowed_for(key)), config.slices);
        else if (key == "resolution")
            error = store(read_int(key, value, allowed_for(key)), config.resolution);
        else if (key == "filter")
            error = store(read_enum<penumbra::Filter>(key, value), config.filter);
        else if (key == "fusion")
            error = store(read_enum<penumbra::Fusion>(key, value), config.fusion);
        else if (key == "packing")
            error = store(read_enum<penumbra::Packing>(key, value), config.packing);
        else if (key == "light")
            error = store(read_enum<penumbra::Light>(key, value), config.light);
        else if (key == "target")
            error = store(read_enum<penumbra::Target>(key, value), config.target);
        else if (key == "leak_fix")
            error = store(read_bool(key, value), config.leak_fix);
        else if (key == "self_shadow_fade")
            error = store(read_bool(key, value), config.self_shadow_fade);
        else if (key == "tangent_clip")
            error = store(read_bool(key, value), config.tangent_clip);
        else if (key == "slice_placement")
            error = store(read_enum<penumbra::SlicePlacement>(key, value), config.slice_placement);
        else if (key == "level_format")
            error = store(read_enum<penumbra::LevelFormat>(key, value), config.level_format);
        else if (key == "level_bound")
            error = store(read_int(key, value, allowed_for(key)), config.level_bound);
        else if (key == "tangent_clip_offset")
            error = store(read_real(key, value, allowed_for(key)), config.tangent_clip_offset);
        else if (key == "clip_footprint")
            error = store(read_bool(key, value), config.clip_footprint);
        else if (key == "fade_ramp")
            error = store(read_real(key, value, allowed_for(key)), config.fade_ramp);
        else if (key == "level_reduction")
            error = store(read_int(key, value, allowed_for(key)), config.level_reduction);
        else if (key == "prefilter_stage")
            error = store(read_enum<penumbra::PrefilterStage>(key, value), config.prefilter_stage);
        else if (key == "alpha_test")
            error = store(read_bool(key, value), config.alpha_test);
        else
            error = "unknown key '" + printable(key) + "'; allowed keys: " + std::string(key_list);
        if (!error.empty()) return {{}, where + ": " + error};
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
