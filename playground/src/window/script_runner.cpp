#include "script_runner.hpp"

#include <penumbra_tools/technique_flags.hpp>

#include <penumbra/config.hpp>

#include <penumbra_tools/printable.hpp>

#include <charconv>
#include <cstdlib>

namespace penumbra::playground {

namespace {

using penumbra_gen::printable;

std::string set_bool(bool& field, const std::string& key, const std::string& value) {
    if (value == "on" || value == "true" || value == "1")
        field = true;
    else if (value == "off" || value == "false" || value == "0")
        field = false;
    else
        return key + ": '" + printable(value) + "' is not allowed; allowed: on, off";
    return {};
}

std::string set_int(int& field, const std::string& key, const std::string& value) {
    const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), field);
    if (ec != std::errc() || end != value.data() + value.size())
        return key + ": '" + printable(value) + "' is not an integer";
    return {};
}

// `set KEY VALUE`: a configuration field (validated by request_config) or a window control.
std::string set_value(WindowApp& app, std::string key, const std::string& value) {
    int side = 0;
    if (key.rfind("right.", 0) == 0) {
        side = 1;
        key = key.substr(6);
    }
    Config config = app.config(side);
    std::string error;
    // A configuration field's flag without the dashes (technique_flags.hpp): `set pcss_blockers 32`
    // is `--pcss-blockers 32`, `set right.technique pcss` is `--technique pcss`.
    std::string flag = "--" + key;
    for (char& c : flag)
        if (c == '_') c = '-';
    if (penumbra_gen::is_config_flag(flag)) {
        penumbra_gen::ConfigFlags flags;
        error = penumbra_gen::parse_config_flag(flag, value, flags);
        if (!error.empty()) return error;
        app.request_config(penumbra_gen::apply(flags, config), side);
        return {};
    }
    if (key == "leak_fix")
        error = set_bool(config.leak_fix, key, value);
    else if (key == "fade")
        error = set_bool(config.self_shadow_fade, key, value);
    else if (side == 0) {
        Controls& c = app.controls();
        if (key == "animate_light") return set_bool(c.animate_light, key, value);
        if (key == "animate_object") return set_bool(c.animate_object, key, value);
        if (key == "split") return set_bool(c.split, key, value);
        if (key == "scene") {
            app.load_scene(value);
            return app.scene_name() == value ? "" : "scene: cannot load '" + printable(value) + "'";
        }
        if (key == "view") {
            std::string allowed;
            for (int v = 0; v < view_count; ++v) {
                if (value == to_string(View(v))) {
                    c.view = View(v);
                    return {};
                }
                allowed += (v ? ", " : "") + std::string(to_string(View(v)));
            }
            return "view: '" + printable(value) + "' is not allowed; allowed: " + allowed;
        }
        if (key == "reference") {
            for (const TruthReference r :
                 {TruthReference::irradiance, TruthReference::oriented, TruthReference::whole_light})
                if (value == (r == TruthReference::whole_light ? "whole_light" : to_string(r))) {
                    c.truth_reference = r;
                    return {};
                }
            return "reference: '" + printable(value) +
                   "' is not allowed; allowed: irradiance, oriented, whole_light";
        }
        if (key == "view_slice") return set_int(c.view_slice, key, value);
        if (key == "view_level") return set_int(c.view_level, key, value);
        if (key == "view_texture") {
            c.view_texture.texture = value; // checked when drawn: the message lists the layout's textures
            return {};
        }
        if (key == "view_texture_level") return set_int(c.view_texture.level, key, value);
        if (key == "view_texture_layer") return set_int(c.view_texture.layer, key, value);
        if (key == "view_texture_channel") return set_int(c.view_texture.channel, key, value);
        if (key == "view_texture_max") {
            char* end = nullptr;
            const float v = std::strtof(value.c_str(), &end);
            if (end == value.c_str() || *end != '\0' || !(v > 0.0f) || v > 1e9f)
                return "view_texture_max: '" + printable(value) + "' is not allowed; allowed: a number in (0, 1e9]";
            c.view_texture.max_value = v;
            return {};
        }
        return "set: unknown key '" + printable(key) +
               "'; allowed: leak_fix, fade and the configuration flags of penumbra-gen without dashes "
               "(slices, "
               "technique, pcss_blockers, …) (also as right.KEY), "
               "view, reference, view_slice, view_level, view_texture, view_texture_level, "
               "view_texture_layer, "
               "view_texture_channel, view_texture_max, split, animate_light, animate_object, scene";
    } else {
        return "set: unknown key 'right." + printable(key) + "'";
    }
    if (!error.empty()) return error;
    // An invalid combination is not a script error: the window refuses it and says why, which
    // is what a script may want to check.
    app.request_config(config, side);
    return {};
}

} // namespace

std::string ScriptRunner::step(WindowApp& app) {
    if (waiting_for_reload_) {
        if (app.reloads_done() > reloads_before_edit_)
            waiting_for_reload_ = false;
        else if (std::chrono::steady_clock::now() > reload_deadline_)
            return "script line " + std::to_string(actions_[next_ - 1].line) +
                   ": wait_reload: no reload happened in time";
        else
            return {};
    }
    if (frames_to_wait_ > 0) {
        --frames_to_wait_;
        if (frames_to_wait_ > 0) return {};
    }
    if (waiting_for_truth_) {
        const TruthSnapshot& truth = app.truth();
        const View view = app.controls().view;
        auto stop = [&](const std::string& why) {
            waiting_for_truth_ = false;
            const int line = actions_[next_ - 1].line;
            next_ = actions_.size();
            return "script line " + std::to_string(line) + ": wait_truth: " + why;
        };
        if (view != View::truth && view != View::error)
            return stop("the truth is traced only in the truth and error views (set view error)");
        if (truth.state == TruthState::failed) return stop("the truth failed: " + truth.error);
        if (!app.truth_finished()) {
            if (std::chrono::steady_clock::now() <= truth_deadline_) return {};
            return stop("the truth was not finished in time (" + std::to_string(truth.samples_per_axis) +
                        "x" + std::to_string(truth.samples_per_axis) + " rays done)");
        }
        waiting_for_truth_ = false;
    }
    while (next_ < actions_.size()) {
        const ScriptAction& action = actions_[next_++];
        if (std::string e = run(action, app); !e.empty()) {
            next_ = actions_.size();
            return "script line " + std::to_string(action.line) + ": " + e;
        }
        // A screenshot shows the state up to here: later actions wait for the next frame.
        if (frames_to_wait_ > 0 || waiting_for_reload_ || waiting_for_truth_ || action.verb == "screenshot" ||
            action.verb == "readback")
            return {};
    }
    return {};
}

std::string ScriptRunner::run(const ScriptAction& a, WindowApp& app) {
    Controls& c = app.controls();
    if (a.verb == "set") return set_value(app, a.args[0], a.args[1]);
    if (a.verb == "light") {
        c.rect.center = glm::dvec3(a.numbers[0], a.numbers[1], a.numbers[2]);
        return {};
    }
    if (a.verb == "light_size") {
        if (a.numbers[0] <= 0 || (a.numbers.size() > 1 && a.numbers[1] <= 0))
            return "light_size: sizes must be > 0";
        app.set_light_size(a.numbers[0]);
        if (a.numbers.size() > 1) c.rect.height = a.numbers[1];
        return {};
    }
    if (a.verb == "sun") {
        c.sun_azimuth_degrees = static_cast<float>(a.numbers[0]);
        c.sun_elevation_degrees = static_cast<float>(a.numbers[1]);
        return {};
    }
    if (a.verb == "camera") {
        c.camera.yaw_radians = glm::radians(static_cast<float>(a.numbers[0]));
        c.camera.pitch_radians = glm::radians(static_cast<float>(a.numbers[1]));
        if (a.numbers.size() > 2) c.camera.distance = static_cast<float>(a.numbers[2]);
        return {};
    }
    if (a.verb == "edit" || a.verb == "restore") {
        reloads_before_edit_ = app.reloads_done();
        if (a.verb == "restore") return app.restore_file(a.args[0]);
        return app.edit_file(a.args[0], a.args[1], a.args[2], a.args.size() > 3 ? a.args[3] : "");
    }
    if (a.verb == "reset") {
        app.reset_to_generated();
        return {};
    }
    if (a.verb == "answer") {
        if (!app.overwrite_question()) return "answer: no question is open";
        app.answer_overwrite(a.args[0] == "overwrite");
        return {};
    }
    if (a.verb == "wait") {
        frames_to_wait_ = static_cast<int>(a.numbers[0]);
        return {};
    }
    if (a.verb == "wait_reload") {
        waiting_for_reload_ = app.reloads_done() <= reloads_before_edit_;
        const double seconds = a.numbers.empty() ? 5.0 : a.numbers[0];
        reload_deadline_ = std::chrono::steady_clock::now() +
                           std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                               std::chrono::duration<double>(seconds));
        return {};
    }
    if (a.verb == "wait_truth") {
        // The truth restarts when the frame after a change is drawn: wait from that frame on.
        waiting_for_truth_ = true;
        frames_to_wait_ = 2;
        const double seconds = a.numbers.empty() ? 300.0 : a.numbers[0];
        truth_deadline_ = std::chrono::steady_clock::now() +
                          std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                              std::chrono::duration<double>(seconds));
        return {};
    }
    if (a.verb == "screenshot") {
        app.request_screenshot(a.args[0]);
        return {};
    }
    if (a.verb == "readback") {
        app.request_readback(a.args[0]);
        return {};
    }
    return "unknown action " + a.verb; // parse_script lets none through
}

} // namespace penumbra::playground
