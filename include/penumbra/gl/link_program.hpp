// penumbra/gl/link_program.hpp — compiles and links a Program (emitted, hand-edited, or any
// GLSL you wrap in one) on the current OpenGL context, with compile logs located as
// "file_name:line: message" whatever the driver's own format.
//
// Header-only; includes <epoxy/gl.h>.
#pragma once

#include "../program.hpp"

#include <epoxy/gl.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

namespace penumbra::gl {

namespace detail {

// One line of a driver's compile log as "file_name:line: message". Understands Mesa
// ("0:12(5): error: …"), NVIDIA ("0(12) : error C1035: …") and AMD/Intel ("ERROR: 0:12: …");
// other lines get "file_name: line".
inline std::string located_log_line(const std::string& file_name, std::string_view line) {
    auto number = [&](std::size_t& at, int& value) {
        const auto [end, ec] = std::from_chars(line.data() + at, line.data() + line.size(), value);
        if (ec != std::errc()) return false;
        at = static_cast<std::size_t>(end - line.data());
        return true;
    };
    auto skip = [&](std::size_t& at, std::string_view text) {
        if (line.substr(at, text.size()) != text) return false;
        at += text.size();
        return true;
    };
    auto located = [&](int line_number, std::string_view message) {
        return file_name + ":" + std::to_string(line_number) + ": " + std::string(message);
    };
    int source = 0, line_number = 0, column = 0;
    std::size_t at = 0;
    if (number(at, source) && skip(at, ":") && number(at, line_number) && skip(at, "(") &&
        number(at, column) && skip(at, "): "))
        return located(line_number, line.substr(at)); // Mesa
    at = 0;
    if (number(at, source) && skip(at, "(") && number(at, line_number) && skip(at, ")") &&
        (skip(at, " : ") || skip(at, ": ")))
        return located(line_number, line.substr(at)); // NVIDIA
    for (std::string_view severity : {"ERROR", "WARNING"}) {
        at = 0;
        if (skip(at, severity) && skip(at, ": ") && number(at, source) && skip(at, ":") &&
            number(at, line_number) && skip(at, ": "))
            return located(line_number, std::string(severity == "ERROR" ? "error: " : "warning: ") +
                                            std::string(line.substr(at))); // AMD, Intel
    }
    return file_name + ": " + std::string(line);
}

// A whole compile log, one located line per message.
inline std::string located_log(const std::string& file_name, std::string_view log) {
    std::string out;
    while (!log.empty()) {
        const std::size_t end = std::min(log.find('\n'), log.size());
        std::string_view line = log.substr(0, end);
        while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.remove_suffix(1);
        if (!line.empty()) out += (out.empty() ? "" : "\n") + located_log_line(file_name, line);
        log.remove_prefix(std::min(end + 1, log.size()));
    }
    return out;
}

// The process's tally behind link_counts(): a driver that compiles at link or at first draw
// (llvmpipe compiles every program with LLVM) pays for each of these, so tests and tools print it.
struct LinkTally {
    std::mutex mutex;
    long compiles = 0, links = 0, repeated_links = 0;
    double seconds = 0.0;                   // inside link_program (drivers that compile at first draw: less)
    std::unordered_set<std::size_t> linked; // hashes of every linked program's stage texts
};
inline LinkTally& link_tally() {
    static LinkTally tally;
    return tally;
}
inline void count_link(const Program& program, double seconds) {
    std::string stages;
    for (const ShaderFile& file : program.stages) stages += file.text + '\0';
    LinkTally& tally = link_tally();
    const std::lock_guard lock(tally.mutex);
    tally.compiles += static_cast<long>(program.stages.size());
    ++tally.links;
    tally.seconds += seconds;
    if (!tally.linked.insert(std::hash<std::string>{}(stages)).second) ++tally.repeated_links;
}

} // namespace detail

// What link_program did in this process so far: shaders compiled, programs linked, and how many of
// those links repeated the exact text of a program linked before (in any context), and the time spent
// in link_program (a driver may compile more at a program's first draw: llvmpipe does).
struct LinkCounts {
    long compiles = 0, links = 0, repeated_links = 0;
    double seconds = 0.0;
};
inline LinkCounts link_counts() {
    detail::LinkTally& tally = detail::link_tally();
    const std::lock_guard lock(tally.mutex);
    return {tally.compiles, tally.links, tally.repeated_links, tally.seconds};
}

inline GLenum stage_enum(Stage stage) {
    switch (stage) {
    case Stage::vertex: return GL_VERTEX_SHADER;
    case Stage::compute: return GL_COMPUTE_SHADER;
    default: return GL_FRAGMENT_SHADER;
    }
}

// The program id, or 0 with the compile logs ("file:line: message", one per line) or the link
// log ("<program> (link): …") appended to *log.
inline GLuint link_program(const Program& program, std::string* log) {
    const auto start = std::chrono::steady_clock::now();
    const GLuint id = glCreateProgram();
    std::vector<GLuint> shaders;
    bool ok = true;
    for (const ShaderFile& file : program.stages) {
        const GLuint s = glCreateShader(stage_enum(file.stage));
        const char* text = file.text.c_str();
        glShaderSource(s, 1, &text, nullptr);
        glCompileShader(s);
        GLint status = 0;
        glGetShaderiv(s, GL_COMPILE_STATUS, &status);
        if (!status) {
            GLint length = 0;
            glGetShaderiv(s, GL_INFO_LOG_LENGTH, &length);
            std::string text_log(static_cast<std::size_t>(std::max(length, 1)), '\0');
            glGetShaderInfoLog(s, length, nullptr, text_log.data());
            std::string located = detail::located_log(file.file_name, text_log.c_str());
            if (located.empty()) located = file.file_name + ": does not compile (the driver gave no log)";
            *log += (log->empty() ? "" : "\n") + located;
            ok = false;
        }
        glAttachShader(id, s);
        shaders.push_back(s);
    }
    if (ok) {
        glLinkProgram(id);
        GLint status = 0;
        glGetProgramiv(id, GL_LINK_STATUS, &status);
        if (!status) {
            GLint length = 0;
            glGetProgramiv(id, GL_INFO_LOG_LENGTH, &length);
            std::string text_log(static_cast<std::size_t>(std::max(length, 1)), '\0');
            glGetProgramInfoLog(id, length, nullptr, text_log.data());
            *log += (log->empty() ? "" : "\n") + program.name + " (link): " + text_log.c_str();
            ok = false;
        }
    }
    for (GLuint s : shaders) glDeleteShader(s);
    detail::count_link(program, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (!ok) {
        glDeleteProgram(id);
        return 0;
    }
    return id;
}

} // namespace penumbra::gl
