// playground/src/window/script_runner.hpp — runs a parsed --script against the window, a few
// actions per frame: everything up to the next wait happens before that frame is rendered.
#pragma once

#include "script.hpp"
#include "window_app.hpp"

#include <chrono>
#include <string>
#include <vector>

namespace penumbra::playground {

class ScriptRunner {
public:
    explicit ScriptRunner(std::vector<ScriptAction> actions) : actions_(std::move(actions)) {}

    // Runs actions until one waits. Empty string, or "script line N: problem" (the script stops).
    std::string step(WindowApp& app);
    bool done() const {
        return next_ >= actions_.size() && frames_to_wait_ == 0 && !waiting_for_reload_ &&
               !waiting_for_truth_;
    }

private:
    std::string run(const ScriptAction& action, WindowApp& app);

    std::vector<ScriptAction> actions_;
    std::size_t next_ = 0;
    int frames_to_wait_ = 0;
    bool waiting_for_reload_ = false;
    bool waiting_for_truth_ = false;
    std::chrono::steady_clock::time_point truth_deadline_{};
    std::size_t reloads_before_edit_ = 0;
    std::chrono::steady_clock::time_point reload_deadline_{};
};

} // namespace penumbra::playground
