// penumbra/msl.hpp — Metal Shading Language: the vulkan target's programs, compiled to SPIR-V by
// glslang and translated by SPIRV-Cross, errors as values.
//
//   penumbra::Config config{.target = penumbra::Target::msl};
//   penumbra::Result<penumbra::Emission> metal = penumbra::emit_msl(config);
//   for (const penumbra::ShaderFile& f : metal.value->files()) write(f.file_name, f.text);
//   write("layout.json", penumbra::to_json(metal.value->layout));
//
// Penumbra does not write MSL by hand: SPIRV-Cross, the translator MoltenVK and most engines use,
// already does it well. What this header adds is the contract an engine binds by:
//   - every file defines one function named after it (msl_function_name: penumbra_slicing.vert.metal
//     defines penumbra_slicing_vert), so every file of an emission links into one Metal library;
//   - each program's resources get argument-table indices numbered from 0 in the order of their
//     Vulkan bindings — buffers (the uniform blocks), textures, samplers (a sampled texture's sampler
//     has its texture's index) — the same in every stage of the program, and layout.json gives each
//     parameter its "msl" indices; vertex buffers of the programs that draw geometry go at
//     "first_free_buffer" and above;
//   - vertex positions are flipped in y (SPIRV-Cross's flip_vert_y): Metal's framebuffer rows run
//     top-down where Vulkan's viewport puts NDC y = -1, so texture rows mean what they mean on the
//     other targets.
// There is no snippet: SPIRV-Cross translates whole stages, and a Metal engine reads the deferred
// pass's visibility (penumbra_deferred.frag.metal) instead of calling a function in its own shaders.
//
// The only Penumbra header that includes SPIRV-Cross: link `penumbra::msl` (penumbra::validation and
// spirv-cross-c-shared) to use it. No Metal compiler runs where Penumbra is tested (Linux): the MSL
// is checked for what SPIRV-Cross writes (tests/msl_test.cpp), not compiled.
#pragma once

#include <penumbra/emit.hpp>
#include <penumbra/validation.hpp>

#include <spirv_cross/spirv_cross_c.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

namespace penumbra {

namespace detail {

// Metal guarantees 31 buffer, 31 texture and 16 sampler arguments a function on every GPU family.
inline constexpr int msl_max_buffers = 31;
inline constexpr int msl_max_textures = 31;
inline constexpr int msl_max_samplers = 16;

inline std::string msl_file_name(const std::string& vulkan_file_name) { return vulkan_file_name + ".metal"; }

// Numbers the program's buffers and textures from 0 in the order of their Vulkan bindings (see the
// header comment); an error message when Metal's guaranteed argument tables are too small.
inline std::string assign_msl_indices(ProgramDesc& program) {
    std::vector<int> blocks, textures;
    for (const ParamDesc& d : program.parameters) {
        std::vector<int>& list = d.offset >= 0 ? blocks : textures;
        const int binding = d.offset >= 0 ? d.block_binding : d.binding;
        if (binding >= 0 && std::find(list.begin(), list.end(), binding) == list.end()) list.push_back(binding);
    }
    std::sort(blocks.begin(), blocks.end());
    std::sort(textures.begin(), textures.end());
    const int buffer_count = static_cast<int>(blocks.size()), texture_count = static_cast<int>(textures.size());
    if (buffer_count > msl_max_buffers || texture_count > msl_max_textures || texture_count > msl_max_samplers)
        return "program " + program.name + " binds " + std::to_string(buffer_count) + " buffers and " +
               std::to_string(texture_count) + " sampled textures; Metal guarantees " +
               std::to_string(msl_max_buffers) + " buffers, " + std::to_string(msl_max_textures) +
               " textures and " + std::to_string(msl_max_samplers) + " samplers a function";
    auto index_of = [](const std::vector<int>& list, int binding) {
        return static_cast<int>(std::find(list.begin(), list.end(), binding) - list.begin());
    };
    for (ParamDesc& d : program.parameters) {
        if (d.offset >= 0) d.msl_buffer = index_of(blocks, d.block_binding);
        else if (d.binding >= 0) d.msl_texture = d.msl_sampler = index_of(textures, d.binding);
    }
    return {};
}

// The comment lines that open the vulkan stage (what it is, its configuration), restated for the MSL
// file, which SPIRV-Cross writes without comments.
inline std::string msl_header(const std::string& vulkan_text, const std::string& function) {
    std::string header;
    std::size_t at = vulkan_text.find('\n') + 1; // past #version
    while (at < vulkan_text.size() && vulkan_text.compare(at, 2, "//") == 0) {
        const std::size_t end = vulkan_text.find('\n', at);
        std::string line = vulkan_text.substr(at, end - at);
        if (std::size_t t = line.find("target vulkan"); t != std::string::npos)
            line.replace(t, 13, "target msl");
        header += line + '\n';
        if (end == std::string::npos) break;
        at = end + 1;
    }
    return header + "// Metal Shading Language 2.1, function " + function +
           ": SPIRV-Cross's translation of the vulkan target's SPIR-V (penumbra/msl.hpp says how it binds)\n\n";
}

inline SpvExecutionModel spirv_execution_model(Stage stage) {
    switch (stage) {
    case Stage::vertex: return SpvExecutionModelVertex;
    case Stage::fragment: return SpvExecutionModelFragment;
    case Stage::compute: return SpvExecutionModelGLCompute;
    }
    return SpvExecutionModelFragment;
}

// One SPIRV-Cross context: every object made from it is freed with it.
struct SpirvCrossContext {
    spvc_context context = nullptr;
    SpirvCrossContext() { spvc_context_create(&context); }
    ~SpirvCrossContext() { spvc_context_destroy(context); }
    SpirvCrossContext(const SpirvCrossContext&) = delete;
    SpirvCrossContext& operator=(const SpirvCrossContext&) = delete;
    std::string last_error() const { return spvc_context_get_last_error_string(context); }
};

// One stage's SPIR-V as MSL 2.1, with the program's indices and its function named `function`; an
// error message (and no text) when SPIRV-Cross refuses it or meets a resource layout.json does not name.
inline std::string translate_stage(const std::vector<unsigned int>& spirv, Stage stage, const ProgramDesc& program,
                                   const std::string& function, std::string& error) {
    SpirvCrossContext cross;
    if (!cross.context) return error = "SPIRV-Cross could not create a context", std::string();
    spvc_parsed_ir ir = nullptr;
    spvc_compiler compiler = nullptr;
    spvc_compiler_options options = nullptr;
    const SpvExecutionModel model = spirv_execution_model(stage);
    if (spvc_context_parse_spirv(cross.context, spirv.data(), spirv.size(), &ir) != SPVC_SUCCESS ||
        spvc_context_create_compiler(cross.context, SPVC_BACKEND_MSL, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                     &compiler) != SPVC_SUCCESS ||
        spvc_compiler_create_compiler_options(compiler, &options) != SPVC_SUCCESS)
        return error = "SPIRV-Cross: " + cross.last_error(), std::string();
    spvc_compiler_options_set_uint(options, SPVC_COMPILER_OPTION_MSL_VERSION, SPVC_MAKE_MSL_VERSION(2, 1, 0));
    spvc_compiler_options_set_bool(options, SPVC_COMPILER_OPTION_FLIP_VERTEX_Y, stage == Stage::vertex);
    spvc_compiler_install_compiler_options(compiler, options);
    spvc_compiler_rename_entry_point(compiler, "main", function.c_str(), model);

    // Every resource the stage declares must be a parameter of the program, with its indices.
    auto find_param = [&](unsigned set, unsigned binding) -> const ParamDesc* {
        for (const ParamDesc& d : program.parameters) {
            const int b = d.offset >= 0 ? d.block_binding : d.binding;
            if (b == static_cast<int>(binding) && d.set == static_cast<int>(set)) return &d;
        }
        return nullptr;
    };
    spvc_resources resources = nullptr;
    if (spvc_compiler_create_shader_resources(compiler, &resources) != SPVC_SUCCESS)
        return error = "SPIRV-Cross: " + cross.last_error(), std::string();
    for (spvc_resource_type type : {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, SPVC_RESOURCE_TYPE_SAMPLED_IMAGE,
                                    SPVC_RESOURCE_TYPE_STORAGE_BUFFER, SPVC_RESOURCE_TYPE_STORAGE_IMAGE,
                                    SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS,
                                    SPVC_RESOURCE_TYPE_PUSH_CONSTANT}) {
        const spvc_reflected_resource* list = nullptr;
        std::size_t count = 0;
        spvc_resources_get_resource_list_for_type(resources, type, &list, &count);
        for (std::size_t i = 0; i < count; ++i) {
            const unsigned set = spvc_compiler_get_decoration(compiler, list[i].id, SpvDecorationDescriptorSet);
            const unsigned binding = spvc_compiler_get_decoration(compiler, list[i].id, SpvDecorationBinding);
            const ParamDesc* d = type == SPVC_RESOURCE_TYPE_UNIFORM_BUFFER || type == SPVC_RESOURCE_TYPE_SAMPLED_IMAGE
                                     ? find_param(set, binding)
                                     : nullptr;
            if (!d)
                return error = std::string("resource ") + list[i].name + " (set " + std::to_string(set) + ", binding " +
                               std::to_string(binding) + ") of program " + program.name +
                               " is no parameter of layout.json that Metal indices are given for",
                       std::string();
            spvc_msl_resource_binding b;
            spvc_msl_resource_binding_init(&b);
            b.stage = model;
            b.desc_set = set;
            b.binding = binding;
            if (d->msl_buffer >= 0) b.msl_buffer = static_cast<unsigned>(d->msl_buffer);
            if (d->msl_texture >= 0) b.msl_texture = static_cast<unsigned>(d->msl_texture);
            if (d->msl_sampler >= 0) b.msl_sampler = static_cast<unsigned>(d->msl_sampler);
            spvc_compiler_msl_add_resource_binding(compiler, &b);
        }
    }

    const char* source = nullptr;
    if (spvc_compiler_compile(compiler, &source) != SPVC_SUCCESS || !source)
        return error = "SPIRV-Cross: " + cross.last_error(), std::string();
    return source;
}

} // namespace detail

// The emission of `config` (target msl) in Metal Shading Language 2.1: the vulkan target's programs
// and layout, every stage translated, layout.json with the MSL indices (see the header comment).
// Errors as emit() gives them (the configuration as the vulkan target would have it); an error
// naming glslang or SPIRV-Cross is a Penumbra bug, reported rather than written.
inline Result<Emission> emit_msl(const Config& config) {
    if (config.target != Target::msl)
        return {{}, {{"target", std::string(to_string(config.target)),
                      "target: " + std::string(to_string(config.target)) +
                          " is not msl; emit_msl writes target msl, emit() the others"}}};
    Config vulkan = config;
    vulkan.target = Target::vulkan;
    Result<Emission> emitted = emit(vulkan);
    if (!emitted.value) {
        // The vulkan target's limits are msl's: say so in the target's own name.
        for (ConfigError& e : emitted.errors)
            for (std::size_t at; (at = e.message.find("'vulkan'")) != std::string::npos;)
                e.message.replace(at, 8, "'msl' (the vulkan target's passes, translated)");
        for (ConfigError& e : emitted.errors)
            for (std::size_t at; (at = e.message.find("for vulkan:")) != std::string::npos;)
                e.message.replace(at, 11, "for msl:");
        return emitted;
    }
    Emission emission = std::move(*emitted.value);
    emission.layout.config.target = Target::msl;
    emission.snippet = {};

    auto fail = [](const std::string& message) {
        return Result<Emission>{{}, {{"target", "msl", "target: msl could not be written (a Penumbra bug): " + message}}};
    };
    std::vector<ShaderFile> translated; // each distinct file once: a shared stage must translate alike
    for (Program& program : emission.programs) {
        auto desc = std::find_if(emission.layout.programs.begin(), emission.layout.programs.end(),
                                 [&](const ProgramDesc& p) { return p.name == program.name; });
        if (desc == emission.layout.programs.end()) return fail("program " + program.name + " is not in the layout");
        if (std::string error = detail::assign_msl_indices(*desc); !error.empty()) return fail(error);

        std::vector<std::vector<unsigned int>> spirv;
        const std::vector<ShaderDiagnostic> diagnostics = validate_program(program, Target::vulkan, &spirv);
        if (has_errors(diagnostics) || spirv.size() != program.stages.size())
            return fail("glslang rejected the vulkan program " + program.name + " translated to MSL: " +
                        (diagnostics.empty() ? std::string("no SPIR-V") : format(diagnostics.front())));
        for (std::size_t i = 0; i < program.stages.size(); ++i) {
            ShaderFile& stage = program.stages[i];
            const std::string name = detail::msl_file_name(stage.file_name);
            std::string error;
            const std::string function = msl_function_name(name);
            std::string text = detail::translate_stage(spirv[i], stage.stage, *desc, function, error);
            if (!error.empty()) return fail(stage.file_name + ": " + error);
            text = detail::msl_header(stage.text, function) + text;
            for (const ShaderFile& seen : translated)
                if (seen.file_name == name && seen.text != text)
                    return fail(name + " translates differently in program " + program.name +
                                " than in an earlier program that shares it");
            stage.file_name = name;
            stage.text = std::move(text);
            translated.push_back(stage);
            desc->files[i] = name;
        }
    }
    // The written files: each distinct stage file, then layout.json (no snippet).
    emission.layout.files.clear();
    for (const ShaderFile& f : emission.files()) emission.layout.files.push_back(f.file_name);
    emission.layout.files.emplace_back("layout.json");
    return {std::move(emission), {}};
}

} // namespace penumbra
