// playground/src/window/shader_session.hpp — the runtime of the main configuration together with
// its watched shader folder: configuration changes, hot reload, diagnostics, "reset to generated".
//
// All GL work (compiling, swapping programs) happens in poll() and the configuration calls, which
// the window calls on its render thread.
#pragma once

#include "shader_folder.hpp"

#include <penumbra/config.hpp>
#include <penumbra/gl/runtime.hpp>

#include <chrono>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace penumbra::playground {

struct ReloadEvent {
    std::string file_name;
    std::vector<std::string> programs; // programs rebuilt from this file
    bool ok = false;
    std::string diagnostics;                        // formatted `file:line: message` + context when !ok
    std::chrono::system_clock::time_point saved_at; // modification time of the file
    double compile_milliseconds = 0.0;              // compiling and linking the programs (CPU)
};

class ShaderSession {
public:
    explicit ShaderSession(std::filesystem::path watch_directory);

    // Builds the runtime for `config` and writes its files. Empty string on success, else the
    // validator's or the driver's message (and, for a later call, the previous runtime stays).
    std::string apply_config(const Config& config);

    // Re-emits and swaps after the user answered "overwrite" (or nothing was edited): same as
    // apply_config; kept separate from the question so that the caller decides when to ask.
    std::vector<std::string> hand_edited_files() const { return folder_.hand_edited(); }

    // Checks the folder; compiles what changed and swaps each program that compiles. Returns what
    // happened, one event per changed file. With `frame_milliseconds` longer than the rest of
    // the debounce, a save still settling is waited for here instead of at the next frame.
    std::vector<ReloadEvent> poll(double frame_milliseconds = 0.0);

    // Every file back to the emitted text, on disk and in the runtime.
    std::string reset_to_generated();

    bool reload_pending() const { return folder_.has_pending(); }
    penumbra::gl::Runtime& runtime() { return *runtime_; }
    const penumbra::gl::Runtime& runtime() const { return *runtime_; }
    const Config& config() const { return runtime_->config(); }
    ShaderFolder& folder() { return folder_; }

    // Current compile errors by file (empty when every file compiles), for the panel.
    const std::map<std::string, std::string>& errors() const { return errors_; }

private:
    std::string rebuild_programs_using(const std::string& file_name, std::vector<std::string>* programs);

    ShaderFolder folder_;
    std::unique_ptr<penumbra::gl::Runtime> runtime_;
    std::map<std::string, std::string> sources_; // file name → text last handed to the compiler
    std::map<std::string, std::string> errors_;  // file name → formatted diagnostics
};

} // namespace penumbra::playground
