// penumbra/gl/runtime.hpp while it runs: reconfigure (recreate only what changed), replace_program
// (hot reload that keeps the last good program) and the shading pass timing, on the planes scene
// rendered at 96x96 (llvmpipe or a GPU). Label "gl".
#include "rendering/egl_context.hpp"
#include "rendering/gpu_scene.hpp"
#include "scenes/scenes.hpp"

#include <penumbra/gl/runtime.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <map>

using namespace penumbra::playground;
using penumbra::Config;
using penumbra::gl::Runtime;

namespace {

constexpr int kSize = 96;
const Config kSmall{.slices = 8, .resolution = 128};

// The planes scene on the GPU: a G-buffer of world positions that every runtime of a test shades.
struct Planes {
    std::optional<HeadlessContext> context;
    std::optional<Scene> scene;
    std::unique_ptr<MeshBuffers> mesh;
    std::unique_ptr<GBuffer> gbuffer;
    std::string error;

    Planes() {
        context = HeadlessContext::create(&error);
        if (!context) return;
        scene = make_scene("planes");
        if (!scene) {
            error = "no planes scene";
            return;
        }
        mesh = std::make_unique<MeshBuffers>(scene->mesh);
        gbuffer = GBuffer::create(kSize, kSize, &error);
        if (gbuffer)
            gbuffer->render(*mesh, scene->camera.projection_matrix(1.0f) * scene->camera.view_matrix());
    }
    bool ready() const { return gbuffer != nullptr; }

    std::unique_ptr<Runtime> runtime(const Config& config) {
        auto rt = Runtime::create(config, &error);
        if (rt) rt->set_light(scene->light, glm::dvec3(scene->bounds_min), glm::dvec3(scene->bounds_max));
        return rt;
    }

    // Visibility of every pixel (bottom row first), or empty with `error` set.
    std::vector<float> render(Runtime& rt, penumbra::gl::PassTiming* timing = nullptr) {
        error = rt.build([&](GLuint) { mesh->draw(); });
        if (!error.empty()) return {};
        if (!rt.shade_deferred(gbuffer->positions(), kSize, kSize, &error, timing, gbuffer->normals())) return {};
        return rt.read_visibility();
    }
};

bool identical(const std::vector<float>& a, const std::vector<float>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

std::map<std::string, GLuint> program_ids(const Runtime& rt) {
    std::map<std::string, GLuint> ids;
    for (const penumbra::Program& p : rt.emission().programs) ids[p.name] = rt.program(p.name);
    return ids;
}

std::map<std::string, GLuint> texture_ids(const Runtime& rt) {
    std::map<std::string, GLuint> ids;
    for (const penumbra::TextureDesc& t : rt.emission().layout.textures) ids[t.name] = rt.texture(t.name);
    return ids;
}

int shadowed_pixels(const std::vector<float>& visibility) {
    int n = 0;
    for (float v : visibility) n += v < 0.5f;
    return n;
}

} // namespace

// The rules that read only the kernel's window need the same levels; extent fusion (the default) also
// reads a window twice as wide, one level more (the next test).
TEST_CASE("reconfigure: changing fusion rebuilds only the shading programs and reallocates no texture") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    Config start = kSmall;
    start.fusion = penumbra::Fusion::probabilistic;
    auto rt = planes.runtime(start);
    REQUIRE_MESSAGE(rt, planes.error);
    const std::vector<float> probabilistic = planes.render(*rt);
    REQUIRE_MESSAGE(!probabilistic.empty(), planes.error);
    const auto programs_before = program_ids(*rt);
    const auto textures_before = texture_ids(*rt);

    Config additive = start;
    additive.fusion = penumbra::Fusion::additive;
    REQUIRE(rt->reconfigure(additive) == "");
    CHECK(rt->requested_config() == additive);
    CHECK(rt->last_reconfigure().programs_rebuilt == 2);
    CHECK(rt->last_reconfigure().textures_reallocated == 0);
    for (const auto& [name, id] : program_ids(*rt)) {
        const bool embeds_fusion = name == "shading_example" || name == "shading_deferred";
        CHECK_MESSAGE((id != programs_before.at(name)) == embeds_fusion, name);
    }
    CHECK(texture_ids(*rt) == textures_before);

    const std::vector<float> reconfigured = planes.render(*rt);
    REQUIRE_MESSAGE(!reconfigured.empty(), planes.error);
    auto fresh = planes.runtime(additive);
    REQUIRE_MESSAGE(fresh, planes.error);
    CHECK(identical(reconfigured, planes.render(*fresh)));
    // 1 − Σq ≤ Π(1 − q): additive fusion is never lighter, and darker where slices overlap
    // (the leak fix alone makes every occluder mark two slices).
    int darker = 0, lighter = 0;
    for (std::size_t i = 0; i < probabilistic.size(); ++i) {
        darker += reconfigured[i] < probabilistic[i] - 1e-3f;
        lighter += reconfigured[i] > probabilistic[i] + 1e-5f;
    }
    CHECK(darker > 0);
    CHECK(lighter == 0);
}

// Extent fusion reads each slice over the kernel and over a window twice its side, so the fitted
// level_bound is one higher (penumbra::kernel_level_bound): switching to it from a rule that reads only
// the kernel builds that level (its texture and the programs that write or read the levels), switching
// back drops it; the textures of the other levels are kept, and the image is a fresh runtime's.
TEST_CASE("reconfigure: to and from extent (and clustered) fusion refits the level bound and adds or drops only its level") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    Config chained = kSmall;
    chained.fusion = penumbra::Fusion::chained;
    auto rt = planes.runtime(chained);
    REQUIRE_MESSAGE(rt, planes.error);
    REQUIRE(!planes.render(*rt).empty());
    const int bound = rt->config().level_bound;
    REQUIRE(bound >= 1);
    REQUIRE(bound < penumbra::resolution_levels(kSmall)); // room for one more
    const auto textures_chained = texture_ids(*rt);
    const std::string top = "penumbra_level" + std::to_string(bound + 1);

    Config extent = kSmall;
    REQUIRE(extent.fusion == penumbra::Fusion::extent); // the default
    REQUIRE(rt->reconfigure(extent) == "");
    CHECK(rt->config().level_bound == bound + 1);
    CHECK(rt->config().level_bound == penumbra::kernel_level_bound(rt->frame(), extent));
    CHECK(rt->last_reconfigure().textures_reallocated == 1);
    const auto textures_extent = texture_ids(*rt);
    CHECK(textures_extent.size() == textures_chained.size() + 1);
    CHECK(textures_extent.at(top) != 0);
    for (const auto& [name, id] : textures_chained) CHECK_MESSAGE(textures_extent.at(name) == id, name);
    const std::vector<float> reconfigured = planes.render(*rt);
    REQUIRE_MESSAGE(!reconfigured.empty(), planes.error);
    auto fresh = planes.runtime(extent);
    REQUIRE_MESSAGE(fresh, planes.error);
    CHECK(fresh->config().level_bound == bound + 1);
    CHECK(identical(reconfigured, planes.render(*fresh)));

    // clustered fusion reads the same doubled window (and the kernel's quadrants, within it): the same
    // bound, every texture kept, the image a fresh runtime's
    Config clustered = kSmall;
    clustered.fusion = penumbra::Fusion::clustered;
    REQUIRE(rt->reconfigure(clustered) == "");
    CHECK(rt->config().level_bound == bound + 1);
    CHECK(rt->last_reconfigure().textures_reallocated == 0);
    for (const auto& [name, id] : texture_ids(*rt)) CHECK_MESSAGE(id == textures_extent.at(name), name);
    const std::vector<float> clustered_image = planes.render(*rt);
    REQUIRE_MESSAGE(!clustered_image.empty(), planes.error);
    auto fresh_clustered = planes.runtime(clustered);
    REQUIRE_MESSAGE(fresh_clustered, planes.error);
    CHECK(identical(clustered_image, planes.render(*fresh_clustered)));

    REQUIRE(rt->reconfigure(chained) == "");
    CHECK(rt->config().level_bound == bound);
    CHECK(rt->last_reconfigure().textures_reallocated == 0);
    CHECK(texture_ids(*rt).count(top) == 0);
    for (const auto& [name, id] : texture_ids(*rt)) CHECK_MESSAGE(id == textures_chained.at(name), name);
}

TEST_CASE("reconfigure: changing resolution reallocates every fixed-size texture") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    auto rt = planes.runtime(kSmall);
    REQUIRE_MESSAGE(rt, planes.error);
    REQUIRE(!planes.render(*rt).empty());
    const GLuint slicing = rt->program("slicing");

    Config coarser = kSmall;
    coarser.resolution = 64;
    REQUIRE(rt->reconfigure(coarser) == "");
    int fixed = 0; // output-sized textures follow the output size, caller ones are the caller's
    for (const penumbra::TextureDesc& t : rt->emission().layout.textures) fixed += t.size == penumbra::TextureSize::fixed;
    CHECK(fixed >= 2);
    CHECK(rt->last_reconfigure().textures_reallocated == fixed);
    // The resolution is baked into the prefilter and shading code, not into slicing, nor into the
    // level pass of reduced levels (level_reduction: its tile sizes are pass uniforms).
    REQUIRE(penumbra::reduces_levels(kSmall));
    CHECK(rt->last_reconfigure().programs_rebuilt == static_cast<int>(rt->emission().programs.size()) - 2);
    CHECK(rt->program("slicing") == slicing);
    for (const penumbra::TextureDesc& t : rt->emission().layout.textures) {
        if (t.size != penumbra::TextureSize::fixed) continue;
        GLint width = 0, height = 0;
        glGetTextureLevelParameteriv(rt->texture(t.name), 0, GL_TEXTURE_WIDTH, &width);
        glGetTextureLevelParameteriv(rt->texture(t.name), 0, GL_TEXTURE_HEIGHT, &height);
        CHECK_MESSAGE(width == t.width, t.name);
        CHECK_MESSAGE(height == t.height, t.name);
        // reduced levels (level_reduction 2): level l at 64 / 2^(l - 2)
        const int level = t.name.starts_with("penumbra_level") && t.name.size() > 14 && t.name[14] >= '0' && t.name[14] <= '9' ? std::stoi(t.name.substr(14)) : 0;
        CHECK_MESSAGE(height == 64 / penumbra::level_spacing(coarser, level), t.name);
    }
    const std::vector<float> reconfigured = planes.render(*rt);
    REQUIRE_MESSAGE(!reconfigured.empty(), planes.error);
    auto fresh = planes.runtime(coarser);
    REQUIRE_MESSAGE(fresh, planes.error);
    CHECK(identical(reconfigured, planes.render(*fresh)));
}

TEST_CASE("reconfigure: packing array -> atlas renders the same scene") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    Config array = kSmall;
    array.packing = penumbra::Packing::array;
    auto rt = planes.runtime(array);
    REQUIRE_MESSAGE(rt, planes.error);
    const std::vector<float> with_array = planes.render(*rt);
    REQUIRE_MESSAGE(!with_array.empty(), planes.error);
    const GLuint array_levels = rt->texture("penumbra_levels");
    REQUIRE(array_levels != 0);

    Config atlas = kSmall;
    atlas.packing = penumbra::Packing::atlas;
    atlas.level_reduction = -1; // every level at full resolution, like the array's
    REQUIRE(rt->reconfigure(atlas) == "");
    CHECK(rt->texture("penumbra_levels") == 0);
    CHECK(!glIsTexture(array_levels)); // released, not leaked
    CHECK(rt->texture("penumbra_level0") != 0);
    const std::vector<float> with_atlas = planes.render(*rt);
    REQUIRE_MESSAGE(!with_atlas.empty(), planes.error);
    auto fresh = planes.runtime(atlas);
    REQUIRE_MESSAGE(fresh, planes.error);
    CHECK(identical(with_atlas, planes.render(*fresh)));

    // Both packings compute the same model with the same filtered values (docs/model.md §3): they agree
    // to float rounding (measured on llvmpipe: mean 2e-9, max 5e-6).
    double sum = 0.0, worst = 0.0;
    for (std::size_t i = 0; i < with_array.size(); ++i) {
        const double e = std::abs(static_cast<double>(with_array[i]) - with_atlas[i]);
        sum += e;
        worst = std::max(worst, e);
    }
    const double mean = sum / with_array.size();
    MESSAGE("array vs atlas, planes 96x96: mean |diff| " << mean << ", max " << worst << ", shadowed pixels "
                                                         << shadowed_pixels(with_array) << " / "
                                                         << shadowed_pixels(with_atlas));
    CHECK(shadowed_pixels(with_atlas) > 100);
    CHECK(std::abs(shadowed_pixels(with_atlas) - shadowed_pixels(with_array)) <
          shadowed_pixels(with_array) / 20);
    CHECK(mean < 1e-4);
    CHECK(worst < 1e-3);
}

TEST_CASE("reconfigure: an invalid configuration returns a diagnostic and changes nothing") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    auto rt = planes.runtime(kSmall);
    REQUIRE_MESSAGE(rt, planes.error);
    REQUIRE(rt->reconfigure(kSmall) == ""); // the same configuration: nothing to do
    CHECK(rt->last_reconfigure().programs_rebuilt == 0);
    CHECK(rt->last_reconfigure().textures_reallocated == 0);
    const std::vector<float> before = planes.render(*rt);
    REQUIRE_MESSAGE(!before.empty(), planes.error);
    const auto programs = program_ids(*rt);
    const auto textures = texture_ids(*rt);

    Config invalid = kSmall;
    invalid.slices = 40;
    const std::string diagnostic = rt->reconfigure(invalid);
    CHECK(diagnostic.find("slices") != std::string::npos);
    CHECK(diagnostic.find("40") != std::string::npos);
    CHECK(rt->requested_config() == kSmall);
    CHECK(program_ids(*rt) == programs);
    CHECK(texture_ids(*rt) == textures);
    CHECK(identical(planes.render(*rt), before));
}

TEST_CASE("replace_program: a syntax error names file and line and keeps the last good program") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    auto rt = planes.runtime(kSmall);
    REQUIRE_MESSAGE(rt, planes.error);
    const std::vector<float> before = planes.render(*rt);
    REQUIRE_MESSAGE(!before.empty(), planes.error);
    const GLuint running = rt->program("shading_deferred");
    const std::vector<penumbra::ShaderFile> original = rt->emission().programs.back().stages;
    REQUIRE(rt->emission().programs.back().name == "shading_deferred");
    REQUIRE(original.size() == 2);
    REQUIRE(original[1].file_name == "penumbra_deferred.frag");

    std::vector<penumbra::ShaderFile> broken = original;
    broken[1].text.insert(broken[1].text.find('\n') + 1, "this is not GLSL;\n"); // line 2
    const std::string diagnostic = rt->replace_program("shading_deferred", broken);
    MESSAGE(diagnostic);
    CHECK(diagnostic.find("penumbra_deferred.frag:2: ") != std::string::npos);
    CHECK(rt->program("shading_deferred") == running);
    CHECK(rt->emission().programs.back().stages == original);
    CHECK(identical(planes.render(*rt), before));

    // A link error (a function declared and called, never defined: it compiles, and no linker can
    // resolve it) is reported and also keeps the program. A stage without main() is no such test: an
    // NVIDIA H200 linked one.
    std::vector<penumbra::ShaderFile> unresolved = original;
    unresolved[1].text = "#version 450 core\nout vec4 colour;\nvec4 penumbra_nowhere();\nvoid main()\n{\n    colour = penumbra_nowhere();\n}\n";
    const std::string link_diagnostic = rt->replace_program("shading_deferred", unresolved);
    CHECK(link_diagnostic.find("shading_deferred (link)") != std::string::npos);
    CHECK(rt->program("shading_deferred") == running);

    // A good edit takes effect: wrap the emitted main() and write 1 − visibility.
    std::vector<penumbra::ShaderFile> inverted = original;
    const std::size_t at = inverted[1].text.find("void main()");
    REQUIRE(at != std::string::npos);
    inverted[1].text.replace(at, 11, "void penumbra_emitted_main()");
    inverted[1].text += "void main()\n{\n    penumbra_emitted_main();\n"
                        "    penumbra_visibility = vec4(vec3(1.0 - penumbra_visibility.x), 1.0);\n}\n";
    REQUIRE(rt->replace_program("shading_deferred", inverted) == "");
    CHECK(rt->program("shading_deferred") != running);
    CHECK(glIsProgram(running)); // retired, not deleted: an undo links nothing
    const GLuint edited = rt->program("shading_deferred");
    CHECK(rt->emission().programs.back().stages == inverted);
    const std::vector<float> after = planes.render(*rt);
    REQUIRE(after.size() == before.size());
    int mismatches = 0;
    for (std::size_t i = 0; i < after.size(); ++i)
        mismatches += std::abs(after[i] - (1.0f - before[i])) > 1e-6f;
    CHECK(mismatches == 0);

    // Reconfiguring to the same configuration brings the emitted program back (its code differs): the
    // one retired at the edit, linked again by nobody.
    REQUIRE(rt->reconfigure(kSmall) == "");
    CHECK(rt->last_reconfigure().programs_rebuilt == 1);
    CHECK(rt->last_reconfigure().programs_linked == 0);
    CHECK(rt->program("shading_deferred") == running);
    CHECK(identical(planes.render(*rt), before));
    // The runtime deletes what it retired when it goes.
    rt.reset();
    CHECK(!glIsProgram(running));
    CHECK(!glIsProgram(edited));
}

TEST_CASE("replace_program: unknown program or other stages give a diagnostic") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    auto rt = planes.runtime(kSmall);
    REQUIRE_MESSAGE(rt, planes.error);
    const std::string unknown = rt->replace_program("shading", {});
    CHECK(unknown.find("no program named 'shading'") != std::string::npos);
    CHECK(unknown.find("shading_deferred") != std::string::npos); // lists what exists
    const std::vector<penumbra::ShaderFile> fragment_only{rt->emission().programs.back().stages.back()};
    const std::string stages = rt->replace_program("shading_deferred", fragment_only);
    CHECK(stages.find("stages frag given; the program has vert, frag") != std::string::npos);
}

TEST_CASE("shade_deferred: times the shading pass when asked") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    auto rt = planes.runtime(kSmall);
    REQUIRE_MESSAGE(rt, planes.error);
    penumbra::gl::PassTiming timing;
    REQUIRE_MESSAGE(!planes.render(*rt, &timing).empty(), planes.error);
    CHECK(timing.name == "shading");
    CHECK(timing.milliseconds > 0.0);
    CHECK(timing.milliseconds < 10000.0);
}

// RuntimeOptions::fit_level_bound (penumbra/level_bound.hpp): set_light builds only the levels the
// light's kernels reach, the image is the one of every level, and a larger light grows the bound
// (a smaller one keeps it).
TEST_CASE("fit_level_bound: only the levels the light reaches, the same image, grown with the light") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    auto fitted = planes.runtime(kSmall);
    REQUIRE_MESSAGE(fitted, planes.error);
    const int all = penumbra::resolution_levels(kSmall);
    const int bound = fitted->config().level_bound;
    CHECK(fitted->requested_config() == kSmall);
    CHECK(bound == penumbra::kernel_level_bound(fitted->frame(), kSmall));
    REQUIRE(bound >= 1);
    REQUIRE(bound < all); // the planes scene's default light reaches fewer than log2(128) = 7 levels
    CHECK(fitted->layout().max_level == bound);
    CHECK(fitted->texture("penumbra_level" + std::to_string(bound)) != 0);
    CHECK(fitted->texture("penumbra_level" + std::to_string(bound + 1)) == 0);

    Config every_level = kSmall;
    every_level.level_bound = all; // set: never fitted
    auto full = planes.runtime(every_level);
    REQUIRE_MESSAGE(full, planes.error);
    CHECK(full->config().level_bound == all);
    const std::vector<float> a = planes.render(*fitted), b = planes.render(*full);
    REQUIRE_MESSAGE(!a.empty(), planes.error);
    REQUIRE_MESSAGE(!b.empty(), planes.error);
    CHECK(identical(a, b)); // no receiver inside the bounds reads above the bound

    penumbra::RectLight large = planes.scene->light;
    large.width *= 8;
    large.height *= 8;
    CHECK(fitted->set_light(large, glm::dvec3(planes.scene->bounds_min), glm::dvec3(planes.scene->bounds_max)) == "");
    const int grown = fitted->config().level_bound;
    CHECK(grown > bound);
    CHECK(grown == penumbra::kernel_level_bound(fitted->frame(), kSmall));
    CHECK(fitted->set_light(planes.scene->light, glm::dvec3(planes.scene->bounds_min),
                            glm::dvec3(planes.scene->bounds_max)) == "");
    CHECK(fitted->config().level_bound == grown); // a smaller light keeps the levels
}

// Runtime::update skips the passes from the light when neither the light nor the geometry nor the
// configuration changed (layout.json "phase_inputs"), and the image stays the same.
TEST_CASE("update: the shadow phase runs only when the light, the geometry or the configuration changed") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    auto rt = planes.runtime(kSmall);
    REQUIRE_MESSAGE(rt, planes.error);
    int draws = 0;
    auto draw = [&](GLuint) {
        ++draws;
        planes.mesh->draw();
    };
    bool ran = false;
    CHECK(!rt->shadow_current());
    REQUIRE(rt->update(draw, false, &ran) == "");
    CHECK(ran); // never built
    const int first = draws;
    CHECK(first >= 1);
    REQUIRE(rt->shade_deferred(planes.gbuffer->positions(), kSize, kSize, &planes.error, nullptr, planes.gbuffer->normals()));
    const std::vector<float> before = rt->read_visibility();

    const glm::dvec3 lo(planes.scene->bounds_min), hi(planes.scene->bounds_max);
    CHECK(rt->set_light(planes.scene->light, lo, hi) == ""); // the same light: nothing to redo
    std::vector<penumbra::gl::PassTiming> timings{{"stale", 1.0}};
    REQUIRE(rt->update(draw, false, &ran, &timings) == "");
    CHECK(!ran);
    CHECK(timings.empty());
    CHECK(draws == first);
    REQUIRE(rt->shade_deferred(planes.gbuffer->positions(), kSize, kSize, &planes.error, nullptr, planes.gbuffer->normals()));
    CHECK(identical(rt->read_visibility(), before));

    REQUIRE(rt->update(draw, true, &ran) == ""); // the caller says the geometry moved
    CHECK(ran);
    CHECK(draws == 2 * first);

    penumbra::RectLight moved = planes.scene->light;
    moved.center.x += 0.1;
    CHECK(rt->set_light(moved, lo, hi) == "");
    REQUIRE(rt->update(draw, false, &ran) == "");
    CHECK(ran);
    REQUIRE(rt->update(draw, false, &ran) == "");
    CHECK(!ran);

    Config other = kSmall;
    other.fusion = penumbra::Fusion::additive;
    REQUIRE(rt->reconfigure(other) == "");
    REQUIRE(rt->update(draw, false, &ran) == "");
    CHECK(ran); // a new configuration may have new textures
}

// A setting and back: the second switch takes the programs the first retired, links nothing, and
// renders what it rendered before.
TEST_CASE("reconfigure: switching to a setting and back links nothing the second time") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    auto rt = planes.runtime(kSmall);
    REQUIRE_MESSAGE(rt, planes.error);
    const std::vector<float> before = planes.render(*rt);
    REQUIRE_MESSAGE(!before.empty(), planes.error);
    const auto programs_before = program_ids(*rt);

    Config probabilistic = kSmall;
    probabilistic.fusion = penumbra::Fusion::probabilistic;
    REQUIRE(rt->reconfigure(probabilistic) == "");
    CHECK(rt->last_reconfigure().programs_linked > 0);
    CHECK(rt->last_reconfigure().programs_linked == rt->last_reconfigure().programs_rebuilt);

    const long links = penumbra::gl::link_counts().links;
    REQUIRE(rt->reconfigure(kSmall) == "");
    CHECK(rt->last_reconfigure().programs_rebuilt > 0);
    CHECK(rt->last_reconfigure().programs_linked == 0);
    CHECK(penumbra::gl::link_counts().links == links);
    CHECK(program_ids(*rt) == programs_before);
    CHECK(identical(planes.render(*rt), before));
}

// Created lit, a runtime links each program once, fitted to the light; created and then lit, it links
// every level's programs first. Both end with the same code.
TEST_CASE("create lit: each program linked once, the programs of create then set_light") {
    Planes planes;
    REQUIRE_MESSAGE(planes.ready(), planes.error);
    const glm::dvec3 lo(planes.scene->bounds_min), hi(planes.scene->bounds_max);

    const long before_lit = penumbra::gl::link_counts().links;
    std::string error;
    auto lit = Runtime::create(kSmall, planes.scene->light, lo, hi, &error);
    REQUIRE_MESSAGE(lit, error);
    const long lit_links = penumbra::gl::link_counts().links - before_lit;
    CHECK(lit_links == static_cast<long>(lit->emission().programs.size()));

    const long before_unlit = penumbra::gl::link_counts().links;
    auto unlit = planes.runtime(kSmall);
    REQUIRE_MESSAGE(unlit, planes.error);
    const long unlit_links = penumbra::gl::link_counts().links - before_unlit;
    CHECK(unlit_links > lit_links); // planes at this size fit fewer levels than every level

    CHECK(lit->config() == unlit->config());
    REQUIRE(lit->emission().programs.size() == unlit->emission().programs.size());
    for (std::size_t i = 0; i < lit->emission().programs.size(); ++i)
        CHECK_MESSAGE(penumbra::gl::detail::same_code(lit->emission().programs[i], unlit->emission().programs[i]),
                      lit->emission().programs[i].name);
    CHECK(identical(planes.render(*lit), planes.render(*unlit)));
}
