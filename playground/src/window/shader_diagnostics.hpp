// playground/src/window/shader_diagnostics.hpp — compile and link logs as `file:line: message`
// with a few lines of the source around the line, for the panel and for stderr.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace penumbra::playground {

struct ShaderDiagnostic {
    std::string file;    // empty when the log line names no file (a link error)
    int line = 0;        // 1-based; 0 when unknown
    std::string message; // "error: syntax error, unexpected …"
};

// Parses a log whose lines look like `file:line: message` (Runtime::replace_program) or Mesa's
// `file: 0:line(column): message` (what the driver writes after the runtime's file prefix).
// Lines that match neither are kept whole as messages without a file.
std::vector<ShaderDiagnostic> parse_shader_log(const std::string& log, const std::string& default_file = {});

// `file:line: message` followed by up to `context` lines either side of `line`, numbered, the
// failing line marked with '>'. `sources` maps file names to the text that was compiled.
std::string format_diagnostic(const ShaderDiagnostic& diagnostic,
                              const std::map<std::string, std::string>& sources, int context = 2);

} // namespace penumbra::playground
