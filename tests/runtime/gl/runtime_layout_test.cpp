// Runtime::create(Emission) runs a hand-made layout from its data alone: a depth-only pass with
// a depth attachment, a depth texture read with hardware comparison, a bake texture, a min-max
// chain whose passes read one level and render the next, output-sized and caller textures, and a
// uniform from the table. Label "gl".
#include "rendering/egl_context.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <string>

using namespace penumbra;
using penumbra::playground::HeadlessContext;

namespace {

const std::string fullscreen_vert = R"(#version 450 core
void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
)";

// Depth-only: a full-screen triangle at clip z = -0.5 (window depth 0.25); no colour output.
const std::string depth_vert = R"(#version 450 core
layout(location = 0) in vec3 position;
void main() { gl_Position = vec4(position.xy, -0.5, 1.0); }
)";
const std::string depth_frag = R"(#version 450 core
void main() {}
)";

// Level 0 of the chain from the bake: (value, value).
const std::string chain0_frag = R"(#version 450 core
layout(binding = 0) uniform sampler2D bake;
layout(location = 0) out vec2 result;
void main() { float v = texelFetch(bake, ivec2(gl_FragCoord.xy), 0).r; result = vec2(v, v); }
)";

// Level n + 1 from level n (the only level the pass sees: lod 0 is its base level): min, max.
const std::string reduce_frag = R"(#version 450 core
layout(binding = 0) uniform sampler2D source;
layout(location = 0) out vec2 result;
void main()
{
    ivec2 t = ivec2(gl_FragCoord.xy) * 2;
    vec2 a = texelFetch(source, t, 0).rg, b = texelFetch(source, t + ivec2(1, 0), 0).rg;
    vec2 c = texelFetch(source, t + ivec2(0, 1), 0).rg, d = texelFetch(source, t + ivec2(1, 1), 0).rg;
    result = vec2(min(min(a.x, b.x), min(c.x, d.x)), max(max(a.y, b.y), max(c.y, d.y)));
}
)";

// Screen: caller value + shadow test against the depth map + chain top (min, max) + a table uniform.
const std::string screen_frag = R"(#version 450 core
layout(binding = 0) uniform sampler2D callerInput;
layout(binding = 1) uniform sampler2DShadow depthMap;
layout(binding = 2) uniform sampler2D chain;
uniform vec2 penumbra_sliceDepths;
layout(location = 0) out vec4 result;
void main()
{
    ivec2 texel = ivec2(gl_FragCoord.xy);
    float lit = texture(depthMap, vec3(vec2(0.5), texel.x == 0 ? 0.2 : 0.3)); // depth 0.25 stored
    vec2 top = texelFetch(chain, ivec2(0), 3).rg;
    result = vec4(texelFetch(callerInput, texel, 0).r + 10.0 * lit + 100.0 * top.x + 1000.0 * top.y
                  + 10000.0 * penumbra_sliceDepths.y);
}
)";

TextureDesc texture(std::string name, TextureFormat format, int size, int mips = 1) {
    return {.name = std::move(name), .format = format, .width = size, .height = size, .mip_levels = mips};
}

PassDesc pass(std::string name, Phase phase, PassAction action, std::string program, std::vector<BindingDesc> inputs,
              std::vector<AttachmentDesc> outputs) {
    return {.name = std::move(name), .action = action, .program = std::move(program), .inputs = std::move(inputs),
            .outputs = std::move(outputs), .phase = phase};
}

// One triangle covering the viewport, world positions at attribute 0: the "scene" of the depth pass.
struct ScreenTriangle {
    GLuint vao = 0, vbo = 0;
    ScreenTriangle() {
        glCreateVertexArrays(1, &vao);
        glCreateBuffers(1, &vbo);
        const float triangle[9] = {-1, -1, 0, 3, -1, 0, -1, 3, 0};
        glNamedBufferData(vbo, sizeof triangle, triangle, GL_STATIC_DRAW);
        glVertexArrayVertexBuffer(vao, 0, vbo, 0, 3 * sizeof(float));
        glEnableVertexArrayAttrib(vao, 0);
        glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(vao, 0, 0);
    }
    ScreenTriangle(const ScreenTriangle&) = delete;
    ScreenTriangle& operator=(const ScreenTriangle&) = delete;
    ~ScreenTriangle() {
        glDeleteBuffers(1, &vbo);
        glDeleteVertexArrays(1, &vao);
    }
    void draw() const {
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
    }
};

Emission hand_made() {
    Emission e;
    auto program = [&](std::string name, const std::string& vert, const std::string& frag) {
        e.programs.push_back({name, {{name + ".vert", Stage::vertex, vert}, {name + ".frag", Stage::fragment, frag}}});
        ProgramDesc desc{name, {name + ".vert", name + ".frag"}, {}};
        if (name == "screen") desc.parameters.push_back({"penumbra_sliceDepths", "vec2", "", "", UniformSource::light});
        e.layout.programs.push_back(desc);
    };
    program("depth", depth_vert, depth_frag);
    program("chain0", fullscreen_vert, chain0_frag);
    program("reduce", fullscreen_vert, reduce_frag);
    program("screen", fullscreen_vert, screen_frag);

    Layout& l = e.layout;
    TextureDesc depth = texture("depthMap", TextureFormat::depth32f, 4);
    depth.wrap = Wrap::clamp_to_border;
    depth.border_color = {1.0f, 1.0f, 1.0f, 1.0f};
    l.textures.push_back(depth);
    TextureDesc bake = texture("bake", TextureFormat::r32f, 8);
    bake.source = TextureSource::bake;
    l.textures.push_back(bake);
    TextureDesc chain = texture("chain", TextureFormat::rg32f, 8, 4);
    chain.min_filter = TextureFilter::nearest_mipmap_nearest;
    l.textures.push_back(chain);
    TextureDesc caller = texture("callerInput", TextureFormat::rgba32f, 0);
    caller.size = TextureSize::output;
    caller.source = TextureSource::caller;
    l.textures.push_back(caller);
    TextureDesc result = texture("result", TextureFormat::r32f, 0);
    result.size = TextureSize::output;
    l.textures.push_back(result);
    l.result = "result";

    PassDesc depth_pass = pass("depth", Phase::shadow, PassAction::draw_scene, "depth", {}, {{"depthMap", 0, -1}});
    depth_pass.state.depth_test = depth_pass.state.depth_write = true;
    depth_pass.state.clear_depth = 1.0f;
    l.passes.push_back(depth_pass);
    l.passes.push_back(pass("chain0", Phase::shadow, PassAction::fullscreen, "chain0", {{"bake", "bake", 0}}, {{"chain", 0, -1}}));
    for (int level = 0; level < 3; ++level)
        l.passes.push_back(pass("reduce", Phase::shadow, PassAction::fullscreen, "reduce", {{"source", "chain", 0, level}},
                                {{"chain", level + 1, -1}}));
    // the depth map is compared by its binding's sampler, not by the texture
    // (the other bindings read their textures with the textures' own filters and wrap)
    for (PassDesc& p : l.passes)
        for (BindingDesc& in : p.inputs) in.sampling = detail::sampling_of(nullptr, *find_texture(l, in.texture));
    BindingDesc compared{"depthMap", "depthMap", 1};
    compared.sampling = {TextureFilter::nearest, TextureFilter::nearest, Wrap::clamp_to_border, {1.0f, 1.0f, 1.0f, 1.0f},
                         CompareFunc::lequal};
    BindingDesc caller_input{"callerInput", "callerInput", 0}, chain_input{"chain", "chain", 2};
    caller_input.sampling = detail::sampling_of(nullptr, caller);
    chain_input.sampling = detail::sampling_of(nullptr, chain);
    l.passes.push_back(pass("screen", Phase::screen, PassAction::fullscreen, "screen",
                            {caller_input, compared, chain_input}, {{"result", 0, -1}}));
    return e;
}

} // namespace

TEST_CASE("gl runtime: a hand-made layout runs from its data (depth, compare, bake, level chain, caller)") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    auto rt = gl::Runtime::create(hand_made(), &error);
    REQUIRE_MESSAGE(rt, error);
    CHECK(rt->texture("result") == 0); // output-sized: allocated at the first screen run
    CHECK(rt->texture("callerInput") == 0);

    // bake: 8x8 values 1..64; the chain's top level holds (1, 64)
    std::vector<float> texels(64);
    for (int i = 0; i < 64; ++i) texels[i] = static_cast<float>(i + 1);
    CHECK(rt->supply_texture("chain", texels).find("not a bake texture") != std::string::npos);
    CHECK(rt->supply_texture("bake", std::vector<float>(3)).find("needs 64") != std::string::npos);
    REQUIRE(rt->supply_texture("bake", texels).empty());

    SliceFrame frame;
    frame.slice_depths = {0.0f, 0.5f};
    rt->set_frame(frame);

    ScreenTriangle triangle;
    int draws = 0;
    const std::string built = rt->build([&](GLuint) {
        triangle.draw();
        ++draws;
    });
    REQUIRE_MESSAGE(built.empty(), built);
    CHECK(draws == 1);

    // the screen phase needs its caller texture
    CHECK(rt->run_screen({}, 2, 1).find("no texture given for callerInput") != std::string::npos);
    GLuint caller = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &caller);
    glTextureStorage2D(caller, 1, GL_RGBA32F, 2, 1);
    const float caller_texels[8] = {1, 0, 0, 0, 2, 0, 0, 0};
    glTextureSubImage2D(caller, 0, 0, 0, 2, 1, GL_RGBA, GL_FLOAT, caller_texels);
    const std::string screened = rt->run_screen({{"callerInput", caller}}, 2, 1);
    REQUIRE_MESSAGE(screened.empty(), screened);
    const std::vector<float> values = rt->read_visibility();
    REQUIRE(values.size() == 2);
    // x = 0: reference 0.2 <= stored 0.25 → lit 1; x = 1: 0.3 > 0.25 → 0. Chain top (1, 64); slice thickness 0.5.
    CHECK(values[0] == doctest::Approx(1.0 + 10.0 + 100.0 + 64000.0 + 5000.0));
    CHECK(values[1] == doctest::Approx(2.0 + 0.0 + 100.0 + 64000.0 + 5000.0));
    // levels were restored after the passes: the chain is complete again
    GLint base = -1, max_level = -1;
    glGetTextureParameteriv(rt->texture("chain"), GL_TEXTURE_BASE_LEVEL, &base);
    glGetTextureParameteriv(rt->texture("chain"), GL_TEXTURE_MAX_LEVEL, &max_level);
    CHECK(base == 0);
    CHECK(max_level == 3);

    // a new size reallocates the output-sized textures
    glDeleteTextures(1, &caller);
    glCreateTextures(GL_TEXTURE_2D, 1, &caller);
    glTextureStorage2D(caller, 1, GL_RGBA32F, 3, 2);
    REQUIRE(rt->run_screen({{"callerInput", caller}}, 3, 2).empty());
    CHECK(rt->read_visibility().size() == 6);
    CHECK(rt->texture("result") != 0);
    glDeleteTextures(1, &caller);
}

// layout.json's conventions are data the runner follows: change the depth binding's comparison in the
// layout (not in the shader) and the result flips.
TEST_CASE("gl runtime: a binding's sampling decides the comparison, not the texture") {
    std::string error;
    auto context = HeadlessContext::create(&error);
    REQUIRE_MESSAGE(context, error);
    for (const CompareFunc compare : {CompareFunc::lequal, CompareFunc::greater}) {
        CAPTURE(to_string(compare));
        Emission e = hand_made();
        for (PassDesc& p : e.layout.passes)
            for (BindingDesc& in : p.inputs)
                if (in.texture == "depthMap") in.sampling.compare = compare;
        auto rt = gl::Runtime::create(e, &error);
        REQUIRE_MESSAGE(rt, error);
        std::vector<float> texels(64);
        for (int i = 0; i < 64; ++i) texels[i] = static_cast<float>(i + 1);
        REQUIRE(rt->supply_texture("bake", texels).empty());
        SliceFrame frame;
        frame.slice_depths = {0.0f, 0.5f};
        rt->set_frame(frame);
        ScreenTriangle triangle;
        REQUIRE(rt->build([&](GLuint) { triangle.draw(); }).empty());
        GLuint caller = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &caller);
        glTextureStorage2D(caller, 1, GL_RGBA32F, 2, 1);
        const float caller_texels[8] = {1, 0, 0, 0, 2, 0, 0, 0};
        glTextureSubImage2D(caller, 0, 0, 0, 2, 1, GL_RGBA, GL_FLOAT, caller_texels);
        REQUIRE(rt->run_screen({{"callerInput", caller}}, 2, 1).empty());
        const std::vector<float> values = rt->read_visibility();
        REQUIRE(values.size() == 2);
        // LEQUAL: x = 0 (reference 0.2 <= stored 0.25) lit, x = 1 not; GREATER: the other way round
        const bool leq = compare == CompareFunc::lequal;
        CHECK(values[0] == doctest::Approx(1.0 + (leq ? 10.0 : 0.0) + 100.0 + 64000.0 + 5000.0));
        CHECK(values[1] == doctest::Approx(2.0 + (leq ? 0.0 : 10.0) + 100.0 + 64000.0 + 5000.0));
        glDeleteTextures(1, &caller);
    }
}
