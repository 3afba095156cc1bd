// penumbra/validation.hpp — compile and link emitted programs with glslang, errors as values.
//
//   for (const penumbra::Program& program : penumbra::emit(config).programs)
//       for (const penumbra::ShaderDiagnostic& d : penumbra::validate_program(program, config.target))
//           std::cerr << penumbra::format(d) << '\n';
//
// The only Penumbra header that includes glslang: link `penumbra::validation`
// (glslang::glslang, its default resource limits and glslang::SPIRV) to use it.
#pragma once

#include <penumbra/config.hpp>
#include <penumbra/program.hpp>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

enum class Severity { error, warning };

// One compiler or linker message, traced back to the emitter chunk that wrote the line.
struct ShaderDiagnostic {
    std::string program; // Program::name
    std::string file;    // ShaderFile::file_name; empty for link messages
    int line = 0;        // 1-based line in `file`; 0 when glslang names no line (link messages)
    Severity severity = Severity::error;
    std::string message; // glslang's text, e.g. "'foo' : undeclared identifier"
    std::string chunk;   // the `// @penumbra:<chunk>` marker in force at `line`; empty when none
};

// "file:line: error: message [emitted by <chunk>]", the form editors jump to;
// "program: error: message" when the diagnostic has no file (link messages).
inline std::string format(const ShaderDiagnostic& diagnostic) {
    std::string out = diagnostic.file.empty() ? diagnostic.program : diagnostic.file;
    if (!diagnostic.file.empty() && diagnostic.line > 0) out += ':' + std::to_string(diagnostic.line);
    out += diagnostic.severity == Severity::error ? ": error: " : ": warning: ";
    out += diagnostic.message;
    if (!diagnostic.chunk.empty()) out += " [emitted by " + diagnostic.chunk + ']';
    return out;
}

// True when any diagnostic is an error (warnings alone leave a program valid).
inline bool has_errors(const std::vector<ShaderDiagnostic>& diagnostics) {
    return std::any_of(diagnostics.begin(), diagnostics.end(),
                       [](const ShaderDiagnostic& d) { return d.severity == Severity::error; });
}

namespace detail {

// glslang keeps process-wide tables (built-in symbol tables, pool allocators); it wants exactly one
// InitializeProcess per process and a FinalizeProcess at the end. A function-local static does both
// and is thread-safe to initialise.
inline void ensure_glslang_initialized() {
    struct Process {
        Process() { glslang::InitializeProcess(); }
        ~Process() { glslang::FinalizeProcess(); }
    };
    static Process process;
}

inline EShLanguage glslang_stage(Stage stage) {
    switch (stage) {
    case Stage::vertex: return EShLangVertex;
    case Stage::fragment: return EShLangFragment;
    case Stage::compute: return EShLangCompute;
    }
    return EShLangFragment;
}

// Parses a glslang info log into diagnostics. Its lines look like
//   "ERROR: 0:12: 'foo' : undeclared identifier"       (compile: string number, line)
//   "ERROR: Linking fragment stage: Missing entry point" (link: no line)
//   "ERROR: 1 compilation errors.  No code generated."  (summary: dropped)
// Every stage is passed to glslang as a single string, so the string number is always 0 and the
// line is the line in ShaderFile::text. Lines without a severity prefix continue the previous message.
inline void parse_info_log(std::string_view log, const std::string& program, const ShaderFile* file,
                           std::vector<ShaderDiagnostic>& out) {
    auto trim = [](std::string_view s) {
        while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t')) s.remove_suffix(1);
        while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
        return s;
    };
    bool continuing = false; // whether the previous line opened a diagnostic that a bare line may extend
    while (!log.empty()) {
        std::size_t end = log.find('\n');
        std::string_view row = trim(log.substr(0, end));
        log = end == std::string_view::npos ? std::string_view{} : log.substr(end + 1);
        if (row.empty()) continue;

        Severity severity;
        if (row.starts_with("ERROR: ")) {
            severity = Severity::error;
            row.remove_prefix(7);
        } else if (row.starts_with("WARNING: ")) {
            severity = Severity::warning;
            row.remove_prefix(9);
        } else {
            if (continuing) out.back().message += ' ' + std::string(row);
            continue;
        }
        // The summary lines and "compilation terminated" repeat what the real message already said
        // (Filament PR #9803: noise around the real error hides it).
        if (row.find("compilation errors.") != std::string_view::npos ||
            row.find("compilation terminated") != std::string_view::npos ||
            row.find("No code generated") != std::string_view::npos) {
            continuing = false;
            continue;
        }

        ShaderDiagnostic diagnostic{.program = program, .severity = severity};
        // "<string>:<line>: <message>" when the message points into the source.
        std::size_t colon1 = row.find(':');
        std::size_t colon2 = colon1 == std::string_view::npos ? colon1 : row.find(':', colon1 + 1);
        auto all_digits = [](std::string_view s) {
            return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
        };
        if (file && colon2 != std::string_view::npos && all_digits(row.substr(0, colon1)) &&
            all_digits(row.substr(colon1 + 1, colon2 - colon1 - 1))) {
            diagnostic.file = file->file_name;
            diagnostic.line = std::atoi(std::string(row.substr(colon1 + 1, colon2 - colon1 - 1)).c_str());
            diagnostic.message = std::string(trim(row.substr(colon2 + 1)));
            diagnostic.chunk = std::string(chunk_at_line(file->text, diagnostic.line));
        } else {
            if (file) diagnostic.file = file->file_name;
            diagnostic.message = std::string(row);
        }
        out.push_back(std::move(diagnostic));
        continuing = true;
    }
}

} // namespace detail

// Compiles every stage of `program` as `target` would, then links them. Empty result = valid
// (a result of warnings only is valid too: see has_errors).
//   glsl330, glsl450, essl300: GLSL as an OpenGL / OpenGL ES driver reads it (the #version line
//     of the text decides the dialect; 330, 450 and 300 es are the defaults when it is missing);
//   vulkan: Vulkan 1.0 rules (KHR_vulkan_glsl), and SPIR-V 1.0 is generated to catch what only
//     code generation rejects;
//   hlsl: glslang's HLSL front end (entry point main), SPIR-V for Vulkan as for vulkan, with every
//     vertex stage's position inverted in y (glslang's --invert-y): the HLSL writes Direct3D's
//     top-down rows (language.hpp), which a Vulkan build turns back. Each stage is linked alone, as
//     Direct3D has no program link (a stage may see fewer members of a cbuffer than another).
// Link is skipped when a stage fails to compile: its errors would only repeat.
// With `spirv` (vulkan and hlsl), the SPIR-V of each stage, in the order of program.stages, is stored
// there: the binaries a Vulkan runner creates its shader modules from.
inline std::vector<ShaderDiagnostic> validate_program(const Program& program, Target target,
                                                      std::vector<std::vector<unsigned int>>* spirv = nullptr) {
    detail::ensure_glslang_initialized();

    const bool hlsl = target == Target::hlsl;
    const bool vulkan = target == Target::vulkan || hlsl; // SPIR-V for Vulkan
    int default_version = 450;
    EProfile default_profile = ECoreProfile;
    if (target == Target::glsl330) default_version = 330;
    if (target == Target::essl300) default_version = 300, default_profile = EEsProfile;

    // Vulkan rules must be asked for in the messages too, not only in the environment.
    const auto messages =
        static_cast<EShMessages>((vulkan ? EShMsgSpvRules | EShMsgVulkanRules : EShMsgDefault) |
                                 (hlsl ? EShMsgReadHlsl : EShMsgDefault));

    std::vector<ShaderDiagnostic> diagnostics;
    // Shaders must outlive the program that links them, so they are declared first.
    std::vector<std::unique_ptr<glslang::TShader>> shaders;
    // One linker for the program; HLSL: one a stage (the linker of stage i is linkers[i]).
    std::vector<std::unique_ptr<glslang::TProgram>> linkers;
    linkers.push_back(std::make_unique<glslang::TProgram>());
    bool compiled = true;

    for (const ShaderFile& file : program.stages) {
        const EShLanguage stage = detail::glslang_stage(file.stage);
        auto& shader = *shaders.emplace_back(std::make_unique<glslang::TShader>(stage));
        const char* text = file.text.c_str();
        shader.setStrings(&text, 1);
        if (hlsl) {
            shader.setEnvInput(glslang::EShSourceHlsl, stage, glslang::EShClientVulkan, 100);
            shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_0);
            shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
            shader.setEntryPoint("main");
            shader.setInvertY(file.stage == Stage::vertex);
        } else if (vulkan) {
            shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientVulkan, 100);
            shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_0);
            shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_0);
        } else {
            // EShClientNone, not EShClientOpenGL: the latter applies ARB_gl_spirv rules (explicit
            // locations on every uniform), which a GL driver compiling GLSL text does not.
            shader.setEnvInput(glslang::EShSourceGlsl, stage, glslang::EShClientNone, 0);
            shader.setEnvTarget(glslang::EShTargetNone, glslang::EShTargetLanguageVersion(0));
        }
        const bool ok =
            shader.parse(GetDefaultResources(), default_version, default_profile,
                         /*forceDefaultVersionAndProfile=*/false, /*forwardCompatible=*/false, messages);
        detail::parse_info_log(shader.getInfoLog(), program.name, &file, diagnostics);
        if (!ok) {
            compiled = false;
            // A failed parse with an empty log should not happen; never report "valid" for it.
            if (!has_errors(diagnostics))
                diagnostics.push_back(
                    {.program = program.name, .file = file.file_name, .message = "compilation failed"});
            continue;
        }
        if (hlsl && shaders.size() > 1) linkers.push_back(std::make_unique<glslang::TProgram>());
        linkers.back()->addShader(&shader);
    }
    if (!compiled) return diagnostics;

    for (const std::unique_ptr<glslang::TProgram>& linker : linkers) {
        const bool linked = linker->link(messages);
        detail::parse_info_log(linker->getInfoLog(), program.name, nullptr, diagnostics);
        if (!linked) {
            if (!has_errors(diagnostics))
                diagnostics.push_back({.program = program.name, .message = "link failed"});
            return diagnostics;
        }
    }

    if (vulkan) {
        // Code generation rejects a few things the front end accepts; run it once per stage.
        for (std::size_t i = 0; i < program.stages.size(); ++i) {
            const ShaderFile& file = program.stages[i];
            const glslang::TProgram& linker = *linkers[hlsl ? i : 0];
            const glslang::TIntermediate* intermediate =
                linker.getIntermediate(detail::glslang_stage(file.stage));
            if (!intermediate) {
                if (spirv) spirv->emplace_back();
                continue;
            }
            std::vector<unsigned int> binary;
            spv::SpvBuildLogger logger;
            glslang::GlslangToSpv(*intermediate, binary, &logger);
            if (spirv) spirv->push_back(std::move(binary));
            // The logger's lines read "error: …", "warning: …", "Missing functionality: …".
            const std::string log = logger.getAllMessages();
            std::string_view rest = log;
            while (!rest.empty()) {
                const std::size_t end = rest.find('\n');
                const std::string_view row = rest.substr(0, end);
                rest = end == std::string_view::npos ? std::string_view{} : rest.substr(end + 1);
                if (row.empty()) continue;
                diagnostics.push_back(
                    {.program = program.name,
                     .file = file.file_name,
                     .severity = row.starts_with("error:") ? Severity::error : Severity::warning,
                     .message = "SPIR-V: " + std::string(row)});
            }
        }
    }
    return diagnostics;
}

} // namespace penumbra
