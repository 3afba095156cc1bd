// Tests of penumbra/msl.hpp: the vulkan target's programs through glslang and SPIRV-Cross, the
// contract an engine binds by (one function a file, argument-table indices in layout.json), and
// the refusals. tests/msl/msl_matrix.py runs penumbra-gen --target msl over every technique variant.
#include <penumbra/msl.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace penumbra;

namespace {

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

const ShaderFile* find_file(const Emission& emission, const std::string& name) {
    for (const Program& program : emission.programs)
        for (const ShaderFile& f : program.stages)
            if (f.file_name == name) return &f;
    return nullptr;
}

} // namespace

TEST_CASE("msl: emit() refuses it, naming where Metal is written") {
    const std::vector<ConfigError> errors = validate(Config{.target = Target::msl});
    REQUIRE(errors.size() == 1);
    CHECK(errors[0].field == "target");
    CHECK(has(errors[0].message, "target: msl is translated from the vulkan target's SPIR-V by SPIRV-Cross"));
    CHECK(has(errors[0].message, "penumbra-gen --target msl"));
    CHECK(has(errors[0].message, "penumbra::emit_msl"));
    CHECK_FALSE(emit(Config{.target = Target::msl}).value);
    // and emit_msl writes msl only
    const Result<Emission> glsl = emit_msl(Config{.target = Target::glsl450});
    CHECK_FALSE(glsl.value);
    REQUIRE(glsl.errors.size() == 1);
    CHECK(has(glsl.errors[0].message, "emit_msl writes target msl"));
}

TEST_CASE("msl: occlusion textures as .metal files, one function each, indices per program") {
    const Result<Emission> result = emit_msl(Config{.target = Target::msl});
    REQUIRE(result.errors.empty());
    const Emission& emission = *result.value;
    CHECK(emission.layout.config.target == Target::msl);
    CHECK(emission.snippet.file_name.empty()); // whole stages only: no snippet
    CHECK(emission.layout.files.back() == "layout.json");
    for (const ShaderFile& f : emission.files()) {
        CAPTURE(f.file_name);
        CHECK(f.file_name.ends_with(".metal"));
        CHECK(has(f.text, "#include <metal_stdlib>"));
        CHECK(has(f.text, "| target msl")); // the configuration, restated above SPIRV-Cross's text
        CHECK(has(f.text, " " + msl_function_name(f.file_name) + "("));
        CHECK_FALSE(has(f.text, " main0("));
    }
    CHECK(msl_function_name("penumbra_slicing.vert.metal") == "penumbra_slicing_vert");

    // The deferred pass: its uniform block at buffer 0, the filter levels at textures and samplers 0…
    const ShaderFile* deferred = find_file(emission, "penumbra_deferred.frag.metal");
    REQUIRE(deferred);
    CHECK(has(deferred->text, "fragment penumbra_deferred_frag_out penumbra_deferred_frag("));
    CHECK(has(deferred->text, "constant PenumbraVisibility& "));
    CHECK(has(deferred->text, "[[buffer(0)]]"));
    CHECK(has(deferred->text, "texture2d<float> penumbra_level0 [[texture(0)]]"));
    CHECK(has(deferred->text, "sampler penumbra_level0Smplr [[sampler(0)]]"));
    // The vertex stage is flipped in y for Metal's top-down rows.
    const ShaderFile* slicing = find_file(emission, "penumbra_slicing.vert.metal");
    REQUIRE(slicing);
    CHECK(has(slicing->text, "out.gl_Position.y = -(out.gl_Position.y);"));

    // layout.json: every bound parameter has its indices; the msl object; the functions.
    for (const ProgramDesc& program : emission.layout.programs)
        for (const ParamDesc& d : program.parameters) {
            CAPTURE(program.name + "." + d.name);
            if (d.offset >= 0) CHECK(d.msl_buffer >= 0);
            if (d.offset < 0 && d.binding >= 0) CHECK((d.msl_texture >= 0 && d.msl_sampler == d.msl_texture));
        }
    const std::string json = to_json(emission.layout);
    CHECK(has(json, "\"msl\": {\"language_version\": \"2.1\", \"flip_vertex_y\": true, \"first_free_buffer\": "));
    CHECK(has(json, "\"msl_functions\": [\"penumbra_fullscreen_vert\", \"penumbra_pack_atlas_frag\"]"));
    CHECK(has(json, "\"msl\": {\"texture\": 0, \"sampler\": 0}"));
    CHECK_FALSE(has(json, "penumbra_visibility.glsl"));
}

TEST_CASE("msl: what the vulkan target refuses, refused in msl's name") {
    const Result<Emission> result = emit_msl(Config{.slices = 32, .target = Target::msl});
    CHECK_FALSE(result.value);
    REQUIRE_FALSE(result.errors.empty());
    CHECK(has(result.errors[0].message, "target 'msl' (the vulkan target's passes, translated)"));
    CHECK(has(result.errors[0].message, "allowed for msl:"));
    CHECK_FALSE(has(result.errors[0].message, "vulkan:"));
}

TEST_CASE("msl: every technique translates, the shadow-map family's comparison sampler included") {
    for (Technique technique : {Technique::shadowmap, Technique::pcf, Technique::pcss, Technique::oim,
                                Technique::erosion, Technique::evsm}) {
        CAPTURE(to_string(technique));
        const Result<Emission> result = emit_msl(Config{.technique = technique, .target = Target::msl});
        INFO((result.errors.empty() ? std::string() : result.errors[0].message));
        REQUIRE(result.errors.empty());
        CHECK(!result.value->files().empty());
    }
    const Result<Emission> pcf = emit_msl(Config{.technique = Technique::pcf, .target = Target::msl});
    REQUIRE(pcf.value);
    bool compares = false;
    for (const ShaderFile& f : pcf.value->files()) compares = compares || has(f.text, "sample_compare(");
    CHECK(compares);
}
