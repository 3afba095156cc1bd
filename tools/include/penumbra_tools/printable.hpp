// printable.hpp — untrusted text made safe for a message: the one escaping function of both
// tools (penumbra-gen and penumbra-playground), for arguments, file contents quoted in errors,
// script errors and shader diagnostics.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace penumbra_gen {

// `text` made safe for a one-line message: control and non-ASCII bytes as \xNN, cut at `limit`
// bytes of input with "..." after it.
std::string printable(std::string_view text, std::size_t limit = 60);

// Several lines of untrusted text (a compile log, source lines around an error) made safe for a
// terminal: each line escaped as printable() does, except that tabs stay tabs; a line longer than
// `line_limit` bytes is cut with "... (N more bytes)"; after `total_limit` bytes of input the rest
// is left out with "... (N more bytes not shown)". Line ends are kept as '\n'.
std::string printable_lines(std::string_view text, std::size_t line_limit = 300,
                            std::size_t total_limit = 16 * 1024);

} // namespace penumbra_gen
