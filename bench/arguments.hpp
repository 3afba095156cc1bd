// bench/arguments.hpp — the benchmarks' command-line pieces: comma-separated lists, and the
// project's number parsing, --help and "error: …" (tools/include/penumbra_tools/cli.hpp).
#pragma once

#include <penumbra_tools/cli.hpp>

#include <string_view>
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
using penumbra::cli::parse_number;

} // namespace penumbra::bench
