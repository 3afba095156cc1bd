#include "frame_renderer.hpp"

#include "rendering/light_term.hpp"
#include "scenes/mesh_builder.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>

namespace penumbra::playground {

namespace {

// The same example shading as the headless renderer (rendering/light_term.hpp), on the GPU.
constexpr const char* compose_fragment_head = R"(#version 450 core
layout(binding = 0) uniform sampler2D worldPositions;
layout(binding = 1) uniform sampler2D worldNormals;
layout(binding = 2) uniform sampler2D visibilityLeft;
layout(binding = 3) uniform sampler2D visibilityRight;
uniform int view;            // 0 shaded, 1 visibility
uniform int splitColumn;     // first pixel column of the right half; -1: no split
uniform int lightIsSun;
uniform vec3 lightCentre;    // world, rectangle light
uniform vec3 lightHalfU;     // world, half its side along u
uniform vec3 lightHalfV;     // world, half its side along v
uniform vec3 sunDirection;   // world, direction the sunlight travels
uniform vec3 eye;            // world, the camera
out vec4 color;
)";

constexpr const char* compose_fragment_main = R"(

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    if (splitColumn >= 0 && pixel.x == splitColumn) { color = vec4(1.0, 0.85, 0.2, 1.0); return; }
    vec4 position = texelFetch(worldPositions, pixel, 0);
    if (position.w < 0.5) { color = vec4(0.55, 0.65, 0.8, 1.0); return; }
    bool right = splitColumn >= 0 && pixel.x > splitColumn;
    float v = right ? texelFetch(visibilityRight, pixel, 0).r : texelFetch(visibilityLeft, pixel, 0).r;
    if (view == 1) { color = vec4(vec3(v), 1.0); return; }
    vec3 normal = texelFetch(worldNormals, pixel, 0).xyz;
    float lightTerm = lightIsSun != 0 ? penumbra_sunLightTerm(position.xyz, normal, eye, sunDirection)
                                      : penumbra_rectLightTerm(position.xyz, normal, eye, lightCentre, lightHalfU, lightHalfV);
    float shade = 0.15 + 0.85 * lightTerm * v;
    color = vec4(vec3(shade * 0.9), 1.0);
}
)";

double query_milliseconds(GLuint query) {
    GLuint64 ns = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &ns);
    return ns * 1e-6;
}

} // namespace

const char* to_string(View view) {
    switch (view) {
    case View::shaded: return "shaded";
    case View::visibility: return "visibility";
    case View::truth: return "truth";
    case View::error: return "error";
    case View::slice_texture: return "slice_texture";
    case View::slice_map: return "slice_map";
    case View::level_map: return "level_map";
    case View::texture: return "texture";
    }
    return "?";
}

std::unique_ptr<FrameRenderer> FrameRenderer::create(const Scene& scene, std::string* error) {
    std::unique_ptr<FrameRenderer> r(new FrameRenderer());
    r->scene_ = &scene;
    r->compose_program_ = build_program("compose", fullscreen_triangle_vertex,
                                        std::string(compose_fragment_head) + light_term_glsl + compose_fragment_main, error);
    if (!r->compose_program_) return nullptr;
    glCreateVertexArrays(1, &r->empty_vao_);
    glGenQueries(3, r->queries_);
    // Without the debug views the window still works: those views then say why they are missing.
    r->debug_views_ = DebugViews::create(&r->debug_views_error_);
    // The moving object: a box circling over the middle of the scene, sized to the scene.
    const glm::vec3 extent = scene.bounds_max - scene.bounds_min;
    const float span = std::max({extent.x, extent.z, 1e-3f});
    r->object_size_ = 0.08f * span;
    r->object_radius_ = 0.25f * span;
    r->object_height_ = scene.bounds_min.y + std::max(0.3f * extent.y, 2.0f * r->object_size_);
    const glm::vec3 centre = 0.5f * (scene.bounds_min + scene.bounds_max);
    const float reach = r->object_radius_ + r->object_size_;
    r->bounds_min_ = glm::min(
        scene.bounds_min, glm::vec3(centre.x - reach, r->object_height_ - r->object_size_, centre.z - reach));
    r->bounds_max_ = glm::max(
        scene.bounds_max, glm::vec3(centre.x + reach, r->object_height_ + r->object_size_, centre.z + reach));
    return r;
}

FrameRenderer::~FrameRenderer() {
    if (compose_program_) glDeleteProgram(compose_program_);
    if (empty_vao_) glDeleteVertexArrays(1, &empty_vao_);
    if (queries_[0]) glDeleteQueries(3, queries_);
}

glm::mat4 FrameRenderer::moving_object_at(double seconds) const {
    const glm::vec3 centre = 0.5f * (scene_->bounds_min + scene_->bounds_max);
    const float angle = static_cast<float>(0.6 * seconds); // about one turn in 10 s
    const glm::vec3 position(centre.x + object_radius_ * std::cos(angle), object_height_,
                             centre.z + object_radius_ * std::sin(angle));
    return glm::scale(glm::rotate(glm::translate(glm::mat4(1.0f), position), angle, glm::vec3(0, 1, 0)),
                      glm::vec3(object_size_));
}

bool FrameRenderer::update_meshes(const std::optional<glm::mat4>& moving_object) {
    if (mesh_built_ && moving_object == mesh_object_) return false;
    if (!moving_object) {
        mesh_ = std::make_unique<MeshBuffers>(scene_->mesh);
    } else {
        // One buffer for scene + object: both the G-buffer and the slicing pass draw it at once.
        Mesh combined = scene_->mesh;
        add_box(combined, *moving_object);
        complete_cut_materials(combined); // the object is solid
        mesh_ = std::make_unique<MeshBuffers>(combined);
    }
    mesh_object_ = moving_object;
    mesh_built_ = true;
    return true;
}

std::string FrameRenderer::render(penumbra::gl::Runtime& left, penumbra::gl::Runtime* right,
                                  const FrameSettings& settings, int width, int height, FrameStats& stats) {
    if (width < 1 || height < 1) return {}; // minimised
    if (!gbuffer_ || gbuffer_->width() != width || gbuffer_->height() != height) {
        std::string error;
        gbuffer_ = GBuffer::create(width, height, &error);
        if (!gbuffer_) return error;
    }
    const bool geometry_changed = update_meshes(settings.moving_object);

    glBeginQuery(GL_TIME_ELAPSED, queries_[0]);
    gbuffer_->render(*mesh_, settings.camera.projection_matrix(static_cast<float>(width) / height) *
                                 settings.camera.view_matrix());
    glEndQuery(GL_TIME_ELAPSED);
    stats.add_pass("gbuffer", query_milliseconds(queries_[0]));

    // The slicing range follows the whole scene (moving object's path included).
    const int split_column = right ? width / 2 : -1;
    GLuint visibility[2] = {0, 0};
    penumbra::gl::Runtime* runtimes[2] = {&left, right};
    for (int side = 0; side < 2; ++side) {
        penumbra::gl::Runtime* runtime = runtimes[side];
        if (!runtime) continue;
        const std::string prefix = side == 0 ? "" : "right.";
        if (runtime->config().light == Light::sun)
            runtime->set_light(settings.sun, glm::dvec3(bounds_min_), glm::dvec3(bounds_max_));
        else
            runtime->set_light(settings.rect, glm::dvec3(bounds_min_), glm::dvec3(bounds_max_));
        // The passes from the light run only when the light, the geometry or the configuration
        // changed (layout.json "phase_inputs"): a camera-only change reuses the occlusion textures.
        std::vector<penumbra::gl::PassTiming> timings;
        if (std::string d = runtime->update(
                [&](GLuint program) { // each material's casters with its alpha texture and cutoff (alpha_test)
                    mesh_->draw_materials(
                        [&](GLuint alpha, float cutoff, bool closed) {
                            runtime->bind_caster_material(program, alpha, 0, cutoff);
                            runtime->bind_caster_closed(program, closed); // solid_casters
                        },
                        true);
                },
                geometry_changed, nullptr, &timings); !d.empty())
            return prefix + d;
        // A pass that runs once per level (nbuffer_level, …) counts as one entry: its total.
        std::vector<std::pair<std::string, double>> totals;
        for (const auto& t : timings) {
            auto it =
                std::find_if(totals.begin(), totals.end(), [&](const auto& e) { return e.first == t.name; });
            if (it == totals.end())
                totals.emplace_back(t.name, t.milliseconds);
            else
                it->second += t.milliseconds;
        }
        for (const auto& [name, ms] : totals) stats.add_pass(prefix + name, ms);
        // In split screen each runtime shades only its half: the scissor limits the
        // full-screen pass that shade_deferred draws.
        if (right) {
            glEnable(GL_SCISSOR_TEST);
            if (side == 0)
                glScissor(0, 0, split_column, height);
            else
                glScissor(split_column, 0, width - split_column, height);
        }
        std::string error;
        glBeginQuery(GL_TIME_ELAPSED, queries_[1]);
        visibility[side] = runtime->shade_deferred(gbuffer_->positions(), width, height, &error, nullptr, gbuffer_->normals());
        glEndQuery(GL_TIME_ELAPSED);
        glDisable(GL_SCISSOR_TEST);
        if (!visibility[side]) return prefix + error;
        stats.add_pass(prefix + "shading", query_milliseconds(queries_[1]));
    }

    const bool needs_truth = settings.view == View::truth || settings.view == View::error;
    if (settings.view >= View::slice_texture || (needs_truth && settings.truth_texture)) {
        glBeginQuery(GL_TIME_ELAPSED, queries_[2]);
        const std::string error = draw_debug_view(runtimes, visibility, settings, width, height);
        glEndQuery(GL_TIME_ELAPSED);
        stats.add_pass("debug view", query_milliseconds(queries_[2]));
        return error;
    }

    glBeginQuery(GL_TIME_ELAPSED, queries_[2]);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glUseProgram(compose_program_);
    const GLuint textures[4] = {gbuffer_->positions(), gbuffer_->normals(), visibility[0],
                                visibility[1] ? visibility[1] : visibility[0]};
    for (GLuint unit = 0; unit < 4; ++unit) glBindTextureUnit(unit, textures[unit]);
    auto location = [&](const char* name) { return glGetUniformLocation(compose_program_, name); };
    // Truth and error views show the visibility until the first truth pass arrives.
    glUniform1i(location("view"), settings.view == View::shaded ? 0 : 1);
    glUniform1i(location("splitColumn"), split_column);
    glUniform1i(location("lightIsSun"), left.config().light == Light::sun ? 1 : 0);
    glUniform3fv(location("lightCentre"), 1, glm::value_ptr(glm::vec3(settings.rect.center)));
    glUniform3fv(location("lightHalfU"), 1,
                 glm::value_ptr(glm::vec3(0.5 * settings.rect.width * glm::normalize(settings.rect.u_axis))));
    glUniform3fv(location("lightHalfV"), 1,
                 glm::value_ptr(glm::vec3(0.5 * settings.rect.height * glm::normalize(settings.rect.v_axis))));
    glUniform3fv(location("sunDirection"), 1, glm::value_ptr(glm::vec3(settings.sun.direction)));
    glUniform3fv(location("eye"), 1, glm::value_ptr(settings.camera.eye_position()));
    glBindVertexArray(empty_vao_);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glUseProgram(0);
    glEndQuery(GL_TIME_ELAPSED);
    stats.add_pass("compose", query_milliseconds(queries_[2]));
    if (const GLenum e = glGetError(); e != GL_NO_ERROR)
        return "GL error " + std::to_string(e) + " in the frame";
    return {};
}

std::string FrameRenderer::draw_debug_view(penumbra::gl::Runtime* runtimes[2], const GLuint visibility[2],
                                           const FrameSettings& settings, int width, int height) {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    const float black[4] = {0, 0, 0, 1};
    glViewport(0, 0, width, height);
    glClearBufferfv(GL_COLOR, 0, black);
    if (!debug_views_) return "debug views unavailable: " + debug_views_error_;
    const bool split = runtimes[1] != nullptr;
    const int split_column = split ? width / 2 : width;
    std::string error;
    for (int side = 0; side < (split ? 2 : 1) && error.empty(); ++side) {
        const penumbra::gl::Runtime& runtime = *runtimes[side];
        const int x0 = side == 0 ? 0 : split_column, x1 = side == 0 ? split_column : width;
        const bool occlusion_view = settings.view == View::slice_texture || settings.view == View::slice_map ||
                                    settings.view == View::level_map;
        if (occlusion_view && runtime.config().technique != Technique::occlusion) {
            error = std::string("view ") + to_string(settings.view) + " shows occlusion textures; technique '" +
                    std::string(to_string(runtime.config().technique)) + "' has none: use the texture view";
            continue;
        }
        if (settings.view == View::texture) {
            glViewport(x0, 0, x1 - x0, height);
            LayoutTextureView view = settings.texture;
            if (view.texture.empty() && !runtime.layout().textures.empty())
                view.texture = runtime.layout().textures.front().name;
            error = debug_views_->draw_layout_texture(runtime, view);
            continue;
        }
        if (settings.view == View::slice_texture) {
            // The texture itself: each half shows its runtime's texture whole.
            glViewport(x0, 0, x1 - x0, height);
            const int slice = std::clamp(settings.slice, 0, runtime.config().slices - 1);
            const int level = std::clamp(settings.level, 0, max_level(runtime.config()));
            error = debug_views_->draw_slice_texture(runtime, {.slice = slice, .level = level});
            continue;
        }
        // Per-pixel views: the full image, each half cut out of it with the scissor.
        glViewport(0, 0, width, height);
        glEnable(GL_SCISSOR_TEST);
        glScissor(x0, 0, x1 - x0, height);
        if (settings.view == View::slice_map)
            error = debug_views_->draw_slice_level(runtime, gbuffer_->positions(),
                                                   {.mode = SliceLevelMode::slice});
        else if (settings.view == View::level_map)
            error = debug_views_->draw_slice_level(
                runtime, gbuffer_->positions(),
                {.mode = SliceLevelMode::level, .slice = settings.slice < 0 ? -1 : settings.slice});
        else if (settings.view == View::truth)
            error = debug_views_->draw_scalar(settings.truth_texture);
        else
            error = debug_views_->draw_error(visibility[side], settings.truth_texture,
                                             {.max_error = settings.error_scale});
        glDisable(GL_SCISSOR_TEST);
    }
    glViewport(0, 0, width, height);
    return error;
}

} // namespace penumbra::playground
