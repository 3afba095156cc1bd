// penumbra/detail/problem.hpp — what validation is made of: a problem with a configuration (field,
// value, message) and the helpers every technique's checks format their messages with
// (detail/<technique>/validate.hpp; penumbra/validate.hpp turns problems into ConfigErrors).
#pragma once

#include "../config.hpp"
#include "text.hpp"

#include <vector>

namespace penumbra::detail {

struct Problem {
    std::string_view field;
    Text value;
    Text message;
};

template <class Enum> constexpr bool in_range(Enum value) {
    return static_cast<std::size_t>(value) < EnumNames<Enum>::names.size();
}

template <class Enum> constexpr Text joined_names() {
    Text out;
    for (std::string_view name : EnumNames<Enum>::names) {
        if (!out.empty()) out += ", ";
        out += name;
    }
    return out;
}

constexpr bool is_power_of_two(int value) { return value > 0 && (value & (value - 1)) == 0; }

// A double as diagnostics print it; values no literal can hold are named, not formatted.
constexpr Text format_value(double value) {
    if (value != value) return Text("nan");
    if (value > 1e9 || value < -1e9) return Text(value > 0 ? "a number above 1e9" : "a number below -1e9");
    return format_float(value);
}

// Appends the problem "<field>: <value> <message>".
constexpr void add_problem(std::vector<Problem>& problems, std::string_view field, Text value, Text message) {
    problems.push_back({field, value, cat(field, ": ", value, " ", message)});
}

// An enumerator that names a value of its enumeration (a cast from a number may not).
template <class Enum> constexpr void check_known(std::vector<Problem>& problems, std::string_view field, Enum value) {
    if (!in_range(value))
        add_problem(problems, field, format_int(static_cast<int>(value)),
                    cat("is not a known value; allowed: ", joined_names<Enum>()));
}

// An integer field within lo to hi; `why` says what is wrong with a value outside.
constexpr void check_int_range(std::vector<Problem>& problems, std::string_view field, int value, int lo, int hi,
                               std::string_view why) {
    if (value < lo || value > hi)
        add_problem(problems, field, format_int(value), cat(why, "; allowed: ", format_int(lo), " to ", format_int(hi)));
}

// A real field within lo (excluded when `lo_open`) to hi. `!(lo <= v && v <= hi)` also catches NaN.
constexpr void check_real_range(std::vector<Problem>& problems, std::string_view field, double value, double lo,
                                double hi, bool lo_open, std::string_view units) {
    const bool above_lo = lo_open ? value > lo : value >= lo;
    if (!(above_lo && value <= hi))
        add_problem(problems, field, format_value(value),
                    cat("is out of range; allowed: ", lo_open ? "more than " : "", format_float(lo), " to ",
                        format_float(hi), " ", units));
}

} // namespace penumbra::detail
