// bench/compare/progress.hpp — progress of a long run on stderr: what is being done, step i of n,
// and the estimated time left from the average duration of the steps of each kind done so far.
#pragma once

#include <chrono>
#include <cstdio>
#include <map>
#include <string>

namespace penumbra::bench {

class Progress {
public:
    // Declares `count` more steps of `kind` ("truth", "measure", "flicker frame", ...).
    void plan(const std::string& kind, int count) { kinds_[kind].planned += count; }

    // Prints "[i/n] what (eta mm:ss)" and starts timing the step; the previous one ends here.
    void step(const std::string& kind, const std::string& what) {
        finish();
        current_ = &kinds_[kind];
        started_ = Clock::now();
        std::fprintf(stderr, "[%d/%d] %s  (%s left)\n", done() + 1, planned(), what.c_str(), eta_text().c_str());
    }

    // Ends the current step (also called by step()).
    void finish() {
        if (!current_) return;
        current_->seconds += std::chrono::duration<double>(Clock::now() - started_).count();
        ++current_->done;
        current_ = nullptr;
    }

    // A kind's step turned out not to be needed (a cached result): it no longer counts.
    void skip(const std::string& kind) { --kinds_[kind].planned; }

private:
    using Clock = std::chrono::steady_clock;
    struct Kind {
        int planned = 0, done = 0;
        double seconds = 0;
    };

    int done() const {
        int n = 0;
        for (const auto& [name, k] : kinds_) n += k.done;
        return n;
    }
    int planned() const {
        int n = 0;
        for (const auto& [name, k] : kinds_) n += k.planned;
        return n;
    }
    std::string eta_text() const {
        double all_seconds = 0;
        int all_done = 0;
        for (const auto& [name, k] : kinds_) {
            all_seconds += k.seconds;
            all_done += k.done;
        }
        if (all_done == 0) return "time unknown";
        double left = 0;
        for (const auto& [name, k] : kinds_) {
            const double mean = k.done > 0 ? k.seconds / k.done : all_seconds / all_done;
            left += mean * (k.planned - k.done);
        }
        char text[32];
        std::snprintf(text, sizeof text, "about %d:%02d", static_cast<int>(left) / 60, static_cast<int>(left) % 60);
        return text;
    }

    std::map<std::string, Kind> kinds_;
    Kind* current_ = nullptr;
    Clock::time_point started_;
};

} // namespace penumbra::bench
