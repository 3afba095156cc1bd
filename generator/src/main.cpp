// penumbra-gen — the shaders and layout.json of one Penumbra configuration, written to a directory.
//
// A straight pipeline: arguments → configuration (the --config file, then the flags) →
// penumbra::validate/emit (emit_msl for target msl: glslang and SPIRV-Cross) → glslang (--validate)
// → files → summary. Problems are values until
// this file prints them as one `error: …` line each.
//
// Exit status: 0 written; 1 glslang rejected emitted code (a Penumbra bug; the files are still
// written so the failing file can be inspected at the reported line); 2 bad arguments, bad config
// file, invalid configuration or unwritable output (nothing written); 3 internal error.
#include <penumbra_tools/arguments.hpp>
#include <penumbra_tools/cli.hpp>
#include <penumbra_tools/config_file.hpp>
#include <penumbra_tools/write_files.hpp>

#include <penumbra/emit.hpp>
#include <penumbra/msl.hpp>
#include <penumbra/validation.hpp>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

enum Exit { ok = 0, invalid_shaders = 1, bad_input = 2, internal_error = 3 };

// Every failure this file reports is bad input (exit status 2); glslang's are counted apart.
int fail(const std::string& message) { return penumbra::cli::fail(message, bad_input); }

std::string describe(const penumbra::Config& c) {
    using penumbra::to_string;
    if (c.technique != penumbra::Technique::occlusion) return penumbra::detail::describe(c).str();
    return std::to_string(c.slices) + " slices, " + std::to_string(c.resolution) + "², " +
           std::string(to_string(c.filter)) + ", " + std::string(to_string(c.fusion)) + ", " +
           std::string(to_string(c.packing)) + ", " + std::string(to_string(c.light)) + ", " +
           std::string(to_string(c.target)) + (c.leak_fix ? "" : ", no leak fix") +
           (c.self_shadow_fade ? "" : ", no fade") + (c.tangent_clip ? ", tangent clip" : "") +
           (c.slice_placement == penumbra::SlicePlacement::adaptive ? ", adaptive slices" : "") +
           (c.alpha_test ? ", alpha test" : "");
}

int run(const std::vector<std::string>& args) {
    using namespace penumbra_gen;

    // 1. Arguments.
    const Parsed<Arguments> parsed = parse_arguments(args);
    if (!parsed.error.empty()) return fail(parsed.error);
    const Arguments& arguments = *parsed.value;
    if (arguments.help) return penumbra::cli::print_usage(usage());

    // 2. Configuration: the file, then the flags over it.
    penumbra::Config config{};
    if (arguments.config_file) {
        const Parsed<penumbra::Config> from_file = read_config_file(*arguments.config_file);
        if (!from_file.error.empty()) return fail(from_file.error);
        config = *from_file.value;
    }
    config = apply(arguments.flags, config);

    // 3. Validate and emit (emit runs penumbra::validate; every problem on the one error line).
    //    Metal: the vulkan target's programs through glslang and SPIRV-Cross, which compile every
    //    stage on the way (so --validate has nothing left to check there).
    const bool msl = config.target == penumbra::Target::msl;
    penumbra::Result<penumbra::Emission> emitted = msl ? penumbra::emit_msl(config) : penumbra::emit(config);
    if (!emitted.errors.empty()) {
        std::string message;
        for (const penumbra::ConfigError& e : emitted.errors) message += (message.empty() ? "" : "; ") + e.message;
        return fail(message);
    }
    const penumbra::Emission& emission = *emitted.value;
    if (arguments.validate && config.target == penumbra::Target::wgsl)
        return fail("--validate: glslang reads GLSL and HLSL, not WGSL; allowed: --validate with glsl330, "
                    "glsl450, essl300, "
                    "vulkan, hlsl or msl (WGSL is checked by Chromium's compiler: ctest -R wgsl_matrix)");

    // 4. glslang, when asked: every diagnostic, with the path the file is written to.
    int rejected_programs = 0;
    if (arguments.validate && !msl)
        for (const penumbra::Program& program : emission.programs) {
            std::vector<penumbra::ShaderDiagnostic> diagnostics =
                penumbra::validate_program(program, config.target);
            for (penumbra::ShaderDiagnostic& d : diagnostics) {
                if (!d.file.empty()) d.file = (std::filesystem::path(arguments.out_dir) / d.file).string();
                std::cerr << penumbra::format(d) << '\n';
            }
            if (penumbra::has_errors(diagnostics)) ++rejected_programs;
        }

    // 5. Files: every shader file, then layout.json (the manifest) last.
    const std::vector<OutputFile> files = output_files(emission);
    if (std::string error = write_files(arguments.out_dir, files); !error.empty()) return fail(error);

    // 6. Summary.
    std::cout << "penumbra-gen: wrote " << files.size() << " files to " << arguments.out_dir << " ("
              << describe(config) << ")";
    if (msl)
        std::cout << "; " << emission.programs.size()
                  << " programs compiled with glslang and translated by SPIRV-Cross (no Metal compiler here)\n";
    else if (!arguments.validate)
        std::cout << "; not validated (--validate runs glslang)\n";
    else if (rejected_programs == 0)
        std::cout << "; " << emission.programs.size() << " programs validated with glslang\n";
    else
        std::cout << '\n';
    if (rejected_programs > 0) {
        std::cerr << "error: glslang rejected " << rejected_programs << " of " << emission.programs.size()
                  << " programs (diagnostics above); the files were written for inspection\n";
        return invalid_shaders;
    }
    return ok;
}

} // namespace

int main(int argc, char** argv) { return penumbra::cli::run_main(argc, argv, run, internal_error); }
