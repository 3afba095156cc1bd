#include "script.hpp"

#include <penumbra_tools/bounded_read.hpp>
#include <penumbra_tools/printable.hpp>

#include <charconv>
#include <cmath>
#include <map>
#include <sstream>

namespace penumbra::playground {

namespace {

using penumbra_gen::printable;

// How many numbers each numeric verb takes: {minimum, maximum}.
const std::map<std::string, std::pair<int, int>>& numeric_verbs() {
    static const std::map<std::string, std::pair<int, int>> verbs{
        {"light", {3, 3}}, {"light_size", {1, 2}},  {"sun", {2, 2}},       {"camera", {2, 3}},
        {"wait", {1, 1}},  {"wait_reload", {0, 1}}, {"wait_truth", {0, 1}}};
    return verbs;
}

constexpr const char* allowed_verbs = "set, light, light_size, sun, camera, edit, restore, reset, answer, "
                                      "wait, wait_reload, wait_truth, screenshot, "
                                      "readback";

// The `index`th whitespace-separated word of `row`.
std::string word_of(const std::string& row, int index) {
    std::istringstream words(row);
    std::string word;
    for (int i = 0; i <= index; ++i) words >> word;
    return word;
}

std::string trim(const std::string& s) {
    const auto first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

} // namespace

ScriptParse parse_script(const std::string& text, const std::string& name) {
    ScriptParse out;
    std::istringstream lines(text);
    std::string row;
    for (int number = 1; std::getline(lines, row); ++number) {
        if (const auto hash = row.find('#'); hash != std::string::npos && row.rfind("edit", 0) != 0)
            row.resize(hash);
        row = trim(row);
        if (row.empty() || row[0] == '#') continue;
        auto fail = [&](const std::string& message) {
            out.error = printable(name, 200) + ":" + std::to_string(number) + ": " + message;
            out.actions.clear();
            return out;
        };
        std::istringstream words(row);
        ScriptAction action;
        action.line = number;
        words >> action.verb;
        if (auto it = numeric_verbs().find(action.verb); it != numeric_verbs().end()) {
            std::string word;
            while (words >> word) {
                double value = 0.0;
                const char* begin = word.data() + (word[0] == '+' ? 1 : 0);
                const auto [ptr, ec] = std::from_chars(begin, word.data() + word.size(), value);
                if (ec == std::errc::invalid_argument || ptr != word.data() + word.size())
                    return fail(action.verb + ": '" + printable(word) + "' is not a number");
                if (ec == std::errc::result_out_of_range || !std::isfinite(value))
                    return fail(action.verb + ": '" + printable(word) + "' is out of range; allowed: finite numbers");
                action.numbers.push_back(value);
            }
            const auto [least, most] = it->second;
            const int count = static_cast<int>(action.numbers.size());
            if (count < least || count > most)
                return fail(action.verb + " takes " + std::to_string(least) +
                            (least == most ? "" : " to " + std::to_string(most)) + " numbers, got " +
                            std::to_string(count));
            // Waits end: a frame count and a timeout in stated ranges, checked here, not while running.
            if (action.verb == "wait" &&
                (action.numbers[0] < 0 || action.numbers[0] > max_wait_frames ||
                 action.numbers[0] != std::floor(action.numbers[0])))
                return fail("wait: " + printable(word_of(row, 1)) + " is out of range; allowed: a whole number of frames from 0 to " +
                            std::to_string(max_wait_frames));
            if ((action.verb == "wait_reload" || action.verb == "wait_truth") && count == 1 &&
                (action.numbers[0] < 0 || action.numbers[0] > max_wait_reload_seconds))
                return fail(action.verb + ": " + printable(word_of(row, 1)) +
                            " is out of range; allowed: 0 to " + std::to_string(max_wait_reload_seconds) +
                            " seconds");
        } else if (action.verb == "set") {
            std::string key, value;
            if (!(words >> key >> value)) return fail("set takes KEY VALUE, e.g. 'set slices 8'");
            action.args = {key, value};
        } else if (action.verb == "edit") {
            std::string file, mode;
            if (!(words >> file >> mode))
                return fail("edit takes FILE append TEXT or FILE replace OLD => NEW");
            std::string rest;
            std::getline(words, rest);
            rest = trim(rest);
            if (mode == "append") {
                action.args = {file, mode, rest};
            } else if (mode == "replace") {
                // "OLD => NEW"; a line ending in " =>" deletes OLD.
                std::size_t arrow = rest.find(" => ");
                if (arrow == std::string::npos && rest.size() >= 3 &&
                    rest.compare(rest.size() - 3, 3, " =>") == 0)
                    arrow = rest.size() - 3;
                if (arrow == std::string::npos || arrow == 0)
                    return fail("edit FILE replace needs 'OLD => NEW' (spaces around =>)");
                action.args = {file, mode, rest.substr(0, arrow),
                               arrow + 4 <= rest.size() ? rest.substr(arrow + 4) : ""};
            } else {
                return fail("edit: unknown mode '" + printable(mode) + "'; allowed: append, replace");
            }
        } else if (action.verb == "restore" || action.verb == "screenshot" || action.verb == "readback" ||
                   action.verb == "answer") {
            std::string word;
            if (!(words >> word)) return fail(action.verb + " needs an argument");
            if (action.verb == "answer" && word != "overwrite" && word != "cancel")
                return fail("answer: '" + printable(word) + "' is not allowed; allowed: overwrite, cancel");
            action.args = {word};
        } else if (action.verb != "reset") {
            return fail("unknown action '" + printable(action.verb) + "'; allowed: " + allowed_verbs);
        }
        out.actions.push_back(std::move(action));
    }
    return out;
}

ScriptParse load_script(const std::string& path) {
    const penumbra_gen::BoundedRead file = penumbra_gen::read_bounded_file(path, penumbra_gen::script_file_limit);
    if (!file.text) return {{}, "--script: cannot read '" + printable(path, 200) + "': " + file.problem};
    return parse_script(*file.text, path);
}

} // namespace penumbra::playground
