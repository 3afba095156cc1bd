#include "printable.hpp"

namespace penumbra_gen {
namespace {

void escape_into(std::string& out, std::string_view text, bool keep_tabs) {
    constexpr char hex[] = "0123456789abcdef";
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if ((c >= 0x20 && c < 0x7f) || (keep_tabs && c == '\t')) {
            out += static_cast<char>(c);
        } else {
            out += "\\x";
            out += hex[c >> 4];
            out += hex[c & 15];
        }
    }
}

} // namespace

std::string printable(std::string_view text, std::size_t limit) {
    std::string out;
    escape_into(out, text.substr(0, limit), false);
    if (text.size() > limit) out += "...";
    return out;
}

std::string printable_lines(std::string_view text, std::size_t line_limit, std::size_t total_limit) {
    std::string out;
    std::size_t shown = 0; // input bytes accounted for
    while (!text.empty()) {
        if (shown >= total_limit) {
            out += "... (" + std::to_string(text.size()) + " more bytes not shown)";
            break;
        }
        const std::size_t end = text.find('\n');
        std::string_view line = text.substr(0, end);
        if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        const std::size_t budget = std::min(line_limit, total_limit - shown);
        escape_into(out, line.substr(0, budget), true);
        if (line.size() > budget) out += "... (" + std::to_string(line.size() - budget) + " more bytes)";
        shown += std::min(line.size(), budget) + 1;
        if (end == std::string_view::npos) break;
        out += '\n';
        text.remove_prefix(end + 1);
    }
    return out;
}

} // namespace penumbra_gen
