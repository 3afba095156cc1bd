// cli.hpp — the command-line pieces every program of the project repeats: a number parsed from a
// flag's text with a message that names the flag, the text and what is allowed; --help; the
// one-line "error: …" and its exit status; and the main that turns an escaped exception into an
// internal error. Part of penumbra_tools (tools/), which every program links; parse_int and
// parse_real call printable() (printable.cpp).
#pragma once

#include "printable.hpp"

#include <charconv>
#include <cmath>
#include <exception>
#include <iostream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace penumbra::cli {

// The exit status of bad arguments, for every program of the project.
inline constexpr int bad_arguments = 2;

// The whole of `text` as a number of type T (int, double, std::size_t, ...); false on anything
// else: empty text, a sign alone, trailing text, a value outside T.
template <class T> bool parse_number(std::string_view text, T& value) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size();
}

// An integer into `value`, else one line: "FLAG: 'TEXT' is not an integer; allowed: ALLOWED", or
// "FLAG: TEXT is out of range; allowed: ALLOWED" when it does not fit an int. Ranges are the
// caller's (or penumbra::validate's) to check.
inline std::string parse_int(std::string_view flag, std::string_view text, int& value, std::string_view allowed) {
    const char* end = text.data() + text.size();
    const auto [ptr, ec] = std::from_chars(text.data(), end, value);
    if (text.empty() || ec == std::errc::invalid_argument || ptr != end)
        return std::string(flag) + ": '" + penumbra_gen::printable(text) + "' is not an integer; allowed: " +
               std::string(allowed);
    if (ec == std::errc::result_out_of_range)
        return std::string(flag) + ": " + penumbra_gen::printable(text) + " is out of range; allowed: " +
               std::string(allowed);
    return {};
}

// A finite number into `value`, else one line: "FLAG: 'TEXT' is not a number; allowed: ALLOWED".
inline std::string parse_real(std::string_view flag, std::string_view text, double& value, std::string_view allowed) {
    if (!parse_number(text, value) || !std::isfinite(value))
        return std::string(flag) + ": '" + penumbra_gen::printable(text) + "' is not a number; allowed: " +
               std::string(allowed);
    return {};
}

// --help or -h anywhere among the arguments: it wins over every other problem.
inline bool asks_for_help(const std::vector<std::string>& args) {
    for (const std::string& arg : args)
        if (arg == "--help" || arg == "-h") return true;
    return false;
}

// The --help text on stdout; the exit status 0.
inline int print_usage(std::string_view usage) {
    std::cout << usage;
    return 0;
}

// "error: MESSAGE" on stderr; returns `code` for main to return.
inline int fail(std::string_view message, int code = 1) {
    std::cerr << "error: " << message << '\n';
    return code;
}

// Bad arguments: "error: MESSAGE" and the usage after it on stderr; the exit status 2.
inline int fail_with_usage(std::string_view message, std::string_view usage) {
    std::cerr << "error: " << message << '\n' << usage;
    return bad_arguments;
}

// main's body: run(argv[1..]); an exception that escapes it is a bug, said as
// "error: internal: …", and the program exits with `internal_error`.
template <class Run> int run_main(int argc, char** argv, Run run, int internal_error) {
    try {
        return run(std::vector<std::string>(argv + 1, argv + argc));
    } catch (const std::exception& e) {
        std::cerr << "error: internal: " << e.what() << '\n';
    } catch (...) {
        std::cerr << "error: internal: unknown exception\n";
    }
    return internal_error;
}

} // namespace penumbra::cli
