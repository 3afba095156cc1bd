#include "shader_diagnostics.hpp"

#include <penumbra_tools/printable.hpp>

#include <algorithm>
#include <cstdio>
#include <regex>
#include <sstream>

namespace penumbra::playground {

using penumbra_gen::printable_lines;

std::vector<ShaderDiagnostic> parse_shader_log(const std::string& log, const std::string& default_file) {
    // Mesa: "0:12(5): error: …", possibly after "name.frag: ".
    static const std::regex mesa(R"(^\s*(?:([^:\s]+):\s*)?\d+:(\d+)\(\d+\):\s*(.*)$)");
    // Already formatted: "name.frag:12: error: …".
    static const std::regex formatted(R"(^\s*([^:\s]+\.(?:vert|frag|comp|glsl)):(\d+):\s*(.*)$)");
    std::vector<ShaderDiagnostic> out;
    std::istringstream lines(log);
    std::string row, file = default_file;
    while (std::getline(lines, row)) {
        if (std::all_of(row.begin(), row.end(), [](unsigned char c) { return std::isspace(c); })) continue;
        std::smatch m;
        if (std::regex_match(row, m, formatted)) {
            file = m[1];
            out.push_back({file, std::stoi(m[2]), m[3]});
        } else if (std::regex_match(row, m, mesa)) {
            if (m[1].matched) file = m[1];
            out.push_back({file, std::stoi(m[2]), m[3]});
        } else {
            out.push_back({{}, 0, row});
        }
    }
    return out;
}

std::string format_diagnostic(const ShaderDiagnostic& d, const std::map<std::string, std::string>& sources,
                              int context) {
    // Source lines and messages may hold anything a file held: cut and escaped, the same way
    // as every message of both tools.
    std::string out = printable_lines(
        d.file.empty() ? d.message : d.file + ":" + std::to_string(d.line) + ": " + d.message, 300, 300);
    auto source = sources.find(d.file);
    if (d.line <= 0 || source == sources.end()) return out;
    std::istringstream lines(source->second);
    std::string row;
    for (int number = 1; std::getline(lines, row); ++number) {
        if (number < d.line - context) continue;
        if (number > d.line + context) break;
        char prefix[32];
        std::snprintf(prefix, sizeof prefix, "\n%c %4d | ", number == d.line ? '>' : ' ', number);
        out += prefix + printable_lines(row, 300, 300);
    }
    return out;
}

} // namespace penumbra::playground
