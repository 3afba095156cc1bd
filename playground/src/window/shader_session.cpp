#include "shader_session.hpp"

#include "shader_diagnostics.hpp"

#include <penumbra_tools/printable.hpp>

#include <penumbra/validate.hpp>

#include <thread>

namespace penumbra::playground {

using penumbra_gen::printable_lines;

ShaderSession::ShaderSession(std::filesystem::path watch_directory) : folder_(std::move(watch_directory)) {}

std::string ShaderSession::apply_config(const Config& config) {
    // The validator first: its message names the field, the value and what is allowed.
    if (const std::vector<ConfigError> problems = validate(config); !problems.empty()) {
        std::string message;
        for (const ConfigError& e : problems) {
            if (!message.empty()) message += "; ";
            message += e.message;
        }
        return message;
    }
    std::string error;
    if (runtime_) {
        error = runtime_->reconfigure(config);
        if (!error.empty()) return error;
    } else {
        runtime_ = penumbra::gl::Runtime::create(config, &error);
        if (!runtime_) return error;
    }
    const std::vector<ShaderFile> files = runtime_->emission().files();
    sources_.clear();
    errors_.clear();
    for (const ShaderFile& f : files) sources_[f.file_name] = f.text;
    return folder_.write_generated(files);
}

std::string ShaderSession::rebuild_programs_using(const std::string& file_name,
                                                  std::vector<std::string>* programs) {
    std::string log;
    for (const Program& program : runtime_->emission().programs) {
        bool uses = false;
        std::vector<ShaderFile> stages = program.stages;
        for (ShaderFile& stage : stages) {
            uses = uses || stage.file_name == file_name;
            stage.text = sources_[stage.file_name];
        }
        if (!uses) continue;
        programs->push_back(program.name);
        // On failure the runtime keeps the program it had: the last good one keeps rendering.
        if (std::string e = runtime_->replace_program(program.name, stages); !e.empty()) log += e + "\n";
    }
    return log;
}

std::vector<ReloadEvent> ShaderSession::poll(double frame_milliseconds) {
    std::vector<ReloadEvent> events;
    std::vector<ShaderFolder::Change> changes = folder_.poll();
    if (changes.empty() && folder_.has_pending()) {
        // Slow frames (llvmpipe at full size): sleeping out the debounce now shows the new
        // program a whole frame earlier than noticing it settled at the next frame.
        const auto settle = folder_.time_to_settle();
        if (std::chrono::duration<double, std::milli>(settle).count() < frame_milliseconds) {
            std::this_thread::sleep_for(settle);
            changes = folder_.poll();
        }
    }
    for (ShaderFolder::Change& change : changes) {
        ReloadEvent event{change.file_name, {}, false, {}, change.saved_at};
        if (!change.problem.empty()) { // not read, so not compiled: the last good program stays
            event.diagnostics = printable_lines(change.file_name + ": cannot read it: " + change.problem);
            errors_[change.file_name] = event.diagnostics;
            events.push_back(std::move(event));
            continue;
        }
        sources_[change.file_name] = std::move(change.text);
        if (change.file_name == runtime_->emission().snippet.file_name) {
            event.diagnostics =
                change.file_name +
                ": not compiled by the playground (it is the snippet for engines; every program "
                "has its own copy): edit the program's own file instead";
            events.push_back(std::move(event));
            continue;
        }
        const auto compile_start = std::chrono::steady_clock::now();
        const std::string log = rebuild_programs_using(change.file_name, &event.programs);
        event.compile_milliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - compile_start)
                .count();
        event.ok = log.empty();
        if (event.ok) {
            errors_.erase(change.file_name);
        } else {
            // The driver's log may quote any part of the file: cut and escaped before it is
            // parsed, and the whole report bounded.
            std::string formatted;
            for (const ShaderDiagnostic& d : parse_shader_log(printable_lines(log), change.file_name))
                formatted += format_diagnostic(d, sources_) + "\n";
            formatted = printable_lines(formatted);
            errors_[change.file_name] = formatted;
            event.diagnostics = std::move(formatted);
        }
        events.push_back(std::move(event));
    }
    return events;
}

std::string ShaderSession::reset_to_generated() {
    // The folder holds the emitted text; runtime_->emission() holds what runs (edits included).
    std::vector<ShaderFile> generated = runtime_->emission().files();
    for (ShaderFile& file : generated) file.text = folder_.generated_text(file.file_name);
    std::string problems;
    for (const ShaderFile& file : generated) {
        const bool differs = sources_[file.file_name] != file.text;
        sources_[file.file_name] = file.text;
        std::vector<std::string> programs;
        if (differs && file.file_name != runtime_->emission().snippet.file_name)
            problems += rebuild_programs_using(file.file_name, &programs);
    }
    errors_.clear();
    if (std::string e = folder_.write_generated(generated); !e.empty()) problems += e;
    return problems;
}

} // namespace penumbra::playground
