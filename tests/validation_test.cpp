// Tests of penumbra/validation.hpp on small hand-written programs: valid ones pass on every
// target, broken ones give one-line diagnostics that point at the file, line and chunk.
#include <penumbra/validation.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace penumbra;

namespace {

// "#version" line and whether stage interfaces need explicit locations (Vulkan does).
struct Dialect {
    Target target;
    const char* version;
    bool locations;
};

constexpr Dialect dialects[] = {
    {Target::glsl330, "#version 330 core\n", false},
    {Target::glsl450, "#version 450 core\n", false},
    {Target::essl300, "#version 300 es\nprecision highp float;\n", false},
    {Target::vulkan, "#version 450\n", true},
};

// A full-screen pass: vertex position in, uv across, colour out.
Program textured_quad(const Dialect& d) {
    const std::string at0 = d.locations ? "layout(location = 0) " : "";
    const std::string vertex = std::string(d.version) + "layout(location = 0) in vec3 position;\n" + at0 +
                               "out vec2 uv;\n"
                               "void main() {\n"
                               "    uv = position.xy * 0.5 + 0.5;\n"
                               "    gl_Position = vec4(position, 1.0);\n"
                               "}\n";
    const std::string fragment = std::string(d.version) + at0 +
                                 "in vec2 uv;\n"
                                 "layout(location = 0) out vec4 color;\n"
                                 "void main() { color = vec4(uv, 0.0, 1.0); }\n";
    return {.name = "quad",
            .stages = {{.file_name = "quad.vert", .stage = Stage::vertex, .text = vertex},
                       {.file_name = "quad.frag", .stage = Stage::fragment, .text = fragment}}};
}

std::string all(const std::vector<ShaderDiagnostic>& diagnostics) {
    std::string out;
    for (const ShaderDiagnostic& d : diagnostics) out += format(d) + '\n';
    return out;
}

} // namespace

TEST_CASE("a valid vertex + fragment program passes on every target") {
    for (const Dialect& d : dialects) {
        CAPTURE(to_string(d.target));
        const auto diagnostics = validate_program(textured_quad(d), d.target);
        CHECK_MESSAGE(diagnostics.empty(), all(diagnostics));
    }
}

TEST_CASE("an undeclared identifier is reported at its file, line and chunk") {
    const std::string fragment = "#version 450 core\n"                   // 1
                                 "// @penumbra:outputs\n"                // 2
                                 "out vec4 color;\n"                     // 3
                                 "// @penumbra:shade_fragment\n"         // 4
                                 "void main() {\n"                       // 5
                                 "    color = vec4(penumbra_missing);\n" // 6
                                 "}\n";
    const Program program{
        .name = "broken",
        .stages = {{.file_name = "broken.frag", .stage = Stage::fragment, .text = fragment}}};

    const auto diagnostics = validate_program(program, Target::glsl450);
    REQUIRE_MESSAGE(diagnostics.size() == 1, all(diagnostics));
    const ShaderDiagnostic& d = diagnostics[0];
    CHECK(d.program == "broken");
    CHECK(d.file == "broken.frag");
    CHECK(d.line == 6);
    CHECK(d.severity == Severity::error);
    CHECK(d.chunk == "shade_fragment");
    CHECK(d.message.find("penumbra_missing") != std::string::npos);
    CHECK(d.message.find("undeclared identifier") != std::string::npos);
    CHECK(format(d) == "broken.frag:6: error: " + d.message + " [emitted by shade_fragment]");
}

TEST_CASE("format: file:line for compile messages, program name for link messages") {
    CHECK(format({.program = "slicing",
                  .file = "penumbra_slicing.frag",
                  .line = 12,
                  .severity = Severity::error,
                  .message = "'x' : undeclared identifier",
                  .chunk = "fusion"}) ==
          "penumbra_slicing.frag:12: error: 'x' : undeclared identifier [emitted by fusion]");
    CHECK(format({.program = "slicing",
                  .file = "penumbra_slicing.frag",
                  .line = 3,
                  .severity = Severity::warning,
                  .message = "something odd"}) == "penumbra_slicing.frag:3: warning: something odd");
    CHECK(format({.program = "slicing", .message = "Linking fragment stage: Missing entry point"}) ==
          "slicing: error: Linking fragment stage: Missing entry point");
}

TEST_CASE("a stage without main gives a link diagnostic with no line") {
    for (const Dialect& d : dialects) {
        CAPTURE(to_string(d.target));
        Program program = textured_quad(d);
        std::string& text = program.stages[1].text;
        text.replace(text.find("void main()"), 11, "void shade()");

        const auto diagnostics = validate_program(program, d.target);
        REQUIRE_MESSAGE(has_errors(diagnostics), all(diagnostics));
        const ShaderDiagnostic& first = diagnostics[0];
        CHECK(first.program == "quad");
        CHECK(first.file.empty());
        CHECK(first.line == 0);
        CHECK(first.message.find("entry point") != std::string::npos);
        CHECK(format(first).starts_with("quad: error: "));
    }
}

TEST_CASE("a fragment input that no vertex output feeds fails to link") {
    Program program = textured_quad(dialects[1]);
    std::string& text = program.stages[1].text;
    text.replace(text.find("in vec2 uv;"), 11, "in vec3 uv;");
    const auto diagnostics = validate_program(program, Target::glsl450);
    CHECK_MESSAGE(has_errors(diagnostics), all(diagnostics));
}

TEST_CASE("only errors make a program invalid") {
    CHECK_FALSE(has_errors({}));
    CHECK_FALSE(has_errors({{.program = "p", .severity = Severity::warning, .message = "w"}}));
    CHECK(has_errors({{.program = "p", .severity = Severity::warning, .message = "w"},
                      {.program = "p", .severity = Severity::error, .message = "e"}}));
}
