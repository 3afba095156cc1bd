// penumbra/emit.hpp — the run-time entry point: every file of a configuration, and its layout.
//
//   penumbra::Result<penumbra::Emission> result = penumbra::emit(config);
//   if (!result.errors.empty()) { /* show result.errors[i].message */ }
//   for (const penumbra::Program& program : result.value->programs) { /* compile program.stages */ }
//
// Header-only by default; with PENUMBRA_SEPARATE_IMPLEMENTATION one translation unit compiles the
// emitter (#define PENUMBRA_IMPLEMENTATION before this include) and the others only declare it
// (detail/api.hpp, docs/getting-started.md "Compile cost").
#pragma once

#include "detail/api.hpp"
#include "layout.hpp"

#include <optional>
#include <vector>

namespace penumbra {

// Everything one configuration emits.
struct Emission {
    std::vector<Program> programs; // in pass order: slicing, prefilter, shading_example, shading_deferred
    ShaderFile snippet;            // penumbra_visibility.glsl: include it in the engine's own shaders
    Layout layout;                 // what to allocate and run; to_json(layout) is layout.json

    // Every distinct file (stage files and snippet), in the order of layout.files.
    std::vector<ShaderFile> files() const {
        std::vector<ShaderFile> out;
        for (const Program& program : programs)
            for (const ShaderFile& stage : program.stages) {
                bool seen = false;
                for (const ShaderFile& f : out) seen = seen || f.file_name == stage.file_name;
                if (!seen) out.push_back(stage);
            }
        if (!snippet.file_name.empty()) out.push_back(snippet); // target msl has none (msl.hpp)
        return out;
    }
};

template <class T> struct Result {
    std::optional<T> value;          // set when errors is empty
    std::vector<ConfigError> errors; // why there is no value
};

#if PENUMBRA_DECLARATIONS_ONLY
Result<Emission> emit(const Config& config);
#else

namespace detail {
inline ShaderFile emit_file(const Config& config, const ShaderFileSpec& file) {
    return {file_name(config, file.name).str(), file.stage, file.text(config).str()};
}
} // namespace detail

// The text of the file named `file_name` (one of layout.files but layout.json) for a configuration; the
// same function the compile-time API runs. An empty ShaderFile when the configuration has no such file.
// Precondition: is_valid(config). Header-only (not declared with PENUMBRA_SEPARATE_IMPLEMENTATION).
inline ShaderFile emit_file(const Config& config, std::string_view file_name) {
    for (const detail::ShaderFileSpec& file : detail::shader_files(config))
        if (detail::file_name(config, file.name) == detail::Text(file_name)) return detail::emit_file(config, file);
    return {};
}

PENUMBRA_ENTRY_POINT Result<Emission> emit(const Config& config) {
    Result<Emission> result;
    result.errors = validate(config);
    if (!result.errors.empty()) return result;
    Emission emission;
    for (const detail::ProgramPlan& plan : detail::program_plan(config)) {
        Program program{std::string(plan.name), {}};
        for (const detail::ShaderFileSpec& stage : plan.stages) program.stages.push_back(detail::emit_file(config, stage));
        emission.programs.push_back(std::move(program));
    }
    emission.snippet = detail::emit_file(config, detail::visibility_snippet_file(config));
    emission.layout = describe_layout(config);
    result.value = std::move(emission);
    return result;
}

#endif // PENUMBRA_DECLARATIONS_ONLY

} // namespace penumbra
