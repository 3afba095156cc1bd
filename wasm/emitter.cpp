// emitter.cpp — the Penumbra emitter as a WebAssembly module (wasm32-wasi, reactor): the
// `penumbra-gen --config` schema in, every file penumbra-gen writes out, from the same code
// (tools/src/config_file.cpp parses, penumbra::emit emits, tools/src/output_files.cpp
// names the files). web/three/penumbra_emitter.js is its JavaScript side; wasm/README.md the ABI.
//
// C ABI (all sizes in bytes, text UTF-8):
//   char* penumbra_input(size)        a buffer of `size` bytes the caller fills with the
//                                     configuration JSON followed by the source name
//   int   penumbra_emit(config_size, source_size)
//                                     1 emitted, 0 invalid (diagnostics), from the input buffer
//   const char* penumbra_output()     the result as JSON (below), valid until the next call
//   size_t penumbra_output_size()
//   const char* penumbra_fields()     the table of configuration fields as JSON
//   size_t penumbra_fields_size()     (penumbra::config_fields_json: the web page's panel)
// Result: {"ok": bool, "files": {"<name>": "<text>", ...} (penumbra-gen's order, layout.json
// last), "diagnostics": [{"severity": "error", "field": "...", "message": "..."}],
// "error": "error: ..." (the line penumbra-gen prints, empty when ok)}.
#include <penumbra_tools/config_file.hpp>
#include <penumbra_tools/output_files.hpp>

#include <nlohmann/json.hpp>
#include <penumbra/config_fields.hpp>
#include <penumbra/emit.hpp>

#include <cstddef>
#include <string>
#include <string_view>

namespace {

std::string input, output, fields;
bool output_ok = false;

using ordered = nlohmann::ordered_json;

ordered diagnostic(std::string field, std::string message) {
    return ordered{{"severity", "error"}, {"field", std::move(field)}, {"message", std::move(message)}};
}

std::string result_text(bool ok, ordered files, ordered diagnostics, const std::string& error) {
    output_ok = ok;
    ordered result{{"ok", ok}, {"files", std::move(files)}, {"diagnostics", std::move(diagnostics)},
                   {"error", error.empty() ? std::string() : "error: " + error}};
    // Emitted text is ASCII or UTF-8; replace (never throw: no exceptions here) anything else.
    return result.dump(-1, ' ', false, ordered::error_handler_t::replace);
}

// What penumbra-gen --config FILE does up to writing the files, with FILE's text and name given.
std::string emit_json(std::string_view config_text, std::string_view source) {
    const penumbra_gen::Parsed<penumbra::Config> parsed = penumbra_gen::parse_config_json(config_text, source);
    if (!parsed.error.empty())
        return result_text(false, ordered::object(), ordered::array({diagnostic("config", parsed.error)}), parsed.error);
    const penumbra::Result<penumbra::Emission> emitted = penumbra::emit(*parsed.value);
    if (!emitted.errors.empty()) {
        ordered diagnostics = ordered::array();
        std::string line; // as penumbra-gen prints it: every problem, "; " between them
        for (const penumbra::ConfigError& e : emitted.errors) {
            diagnostics.push_back(diagnostic(e.field, e.message));
            line += (line.empty() ? "" : "; ") + e.message;
        }
        return result_text(false, ordered::object(), std::move(diagnostics), line);
    }
    ordered files = ordered::object();
    for (penumbra_gen::OutputFile& f : penumbra_gen::output_files(*emitted.value)) files[f.name] = std::move(f.text);
    return result_text(true, std::move(files), ordered::array(), {});
}

} // namespace

extern "C" {

__attribute__((export_name("penumbra_input"))) char* penumbra_input(std::size_t size) {
    input.assign(size, '\0');
    return input.data();
}

__attribute__((export_name("penumbra_emit"))) int penumbra_emit(std::size_t config_size, std::size_t source_size) {
    if (config_size > input.size() || source_size > input.size() - config_size) {
        output = result_text(false, ordered::object(), ordered::array({diagnostic("config", "internal: input sizes exceed the buffer")}),
                             "internal: input sizes exceed the buffer");
        return 0;
    }
    const std::string_view all(input);
    output = emit_json(all.substr(0, config_size), all.substr(config_size, source_size));
    return output_ok ? 1 : 0;
}

__attribute__((export_name("penumbra_output"))) const char* penumbra_output() { return output.data(); }

__attribute__((export_name("penumbra_output_size"))) std::size_t penumbra_output_size() { return output.size(); }

__attribute__((export_name("penumbra_fields"))) const char* penumbra_fields() {
    if (fields.empty()) fields = penumbra::config_fields_json();
    return fields.data();
}

__attribute__((export_name("penumbra_fields_size"))) std::size_t penumbra_fields_size() {
    penumbra_fields();
    return fields.size();
}

} // extern "C"
