// bench/arguments.hpp — the benchmarks' command-line pieces: comma-separated lists and whole numbers.
#pragma once

#include <charconv>
#include <string_view>
#include <system_error>
#include <vector>

namespace penumbra::bench {

// "a,b,c" → {"a", "b", "c"}; "" → {} (an empty list, e.g. --scenes '' for no built-in scene).
inline std::vector<std::string_view> split(std::string_view text, char separator = ',') {
    std::vector<std::string_view> parts;
    while (!text.empty()) {
        const std::size_t comma = text.find(separator);
        parts.push_back(text.substr(0, comma));
        if (comma == std::string_view::npos) break;
        text.remove_prefix(comma + 1);
    }
    return parts;
}

// The whole of `text` as a number of type T (int, double, ...); false on anything else.
template <class T> bool parse_number(std::string_view text, T& value) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && end == text.data() + text.size();
}

} // namespace penumbra::bench
