#include "window_app.hpp"

#include "rendering/debug_views.hpp"
#include "app/headless_job.hpp"
#include "app/image_io.hpp"
#include "scenes/mesh_builder.hpp"

#include <penumbra/validate.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>

namespace penumbra::playground {

namespace {

constexpr double degrees_per_radian = 57.29577951308232;
constexpr std::size_t log_lines_kept = 200;

std::string format_ms(double ms) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.1f ms", ms);
    return buffer;
}

// Axes of the rectangle light from its two angles: straight down (u = +x, v = +z) at 0, 0.
void orient_rect(penumbra::RectLight& rect, float yaw_degrees, float tilt_degrees) {
    const glm::dmat4 rotation =
        glm::rotate(glm::rotate(glm::dmat4(1.0), glm::radians(double(yaw_degrees)), glm::dvec3(0, 1, 0)),
                    glm::radians(double(tilt_degrees)), glm::dvec3(1, 0, 0));
    rect.u_axis = glm::dvec3(rotation * glm::dvec4(1, 0, 0, 0));
    rect.v_axis = glm::dvec3(rotation * glm::dvec4(0, 0, 1, 0));
}

glm::dvec3 sun_direction(float azimuth_degrees, float elevation_degrees) {
    const double az = glm::radians(double(azimuth_degrees)), el = glm::radians(double(elevation_degrees));
    return -glm::dvec3(std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az));
}

// A second configuration worth comparing with the first: the same with mipmaps (or N-buffers when
// the first already uses mipmaps), or the same if that is not valid.
Config default_right_config(const Config& left) {
    Config right = left;
    right.filter = left.filter == Filter::mipmap ? Filter::nbuffer : Filter::mipmap;
    return validate(right).empty() ? right : left;
}

} // namespace

std::string WindowApp::describe(const Config& c) {
    const std::string common =
        " light=" + std::string(to_string(c.light)) + " target=" + std::string(to_string(c.target));
    const ShadowMapParams& sm = c.shadow_map;
    const std::string shadow_map = " shadow_resolution=" + std::to_string(sm.resolution);
    switch (c.technique) {
    case Technique::occlusion: break;
    case Technique::shadowmap: return "technique=shadowmap" + shadow_map + common;
    case Technique::pcf:
        return "technique=pcf" + shadow_map + " pattern=" + std::string(to_string(c.pcf.pattern)) +
               " taps=" + std::to_string(pcf_taps(c.pcf)) + common;
    case Technique::pcss:
        return "technique=pcss" + shadow_map + " blockers=" + std::to_string(c.pcss.blocker_samples) +
               " filter=" + std::to_string(c.pcss.filter_samples) + common;
    default: return "technique=" + std::string(to_string(c.technique)) + common;
    }
    return "slices=" + std::to_string(c.slices) + " resolution=" + std::to_string(c.resolution) +
           " filter=" + std::string(to_string(c.filter)) + " fusion=" + std::string(to_string(c.fusion)) +
           " packing=" + std::string(to_string(c.packing)) + " light=" + std::string(to_string(c.light)) +
           " leak_fix=" + (c.leak_fix ? "on" : "off") + " fade=" + (c.self_shadow_fade ? "on" : "off") +
           " tangent_clip=" + (c.tangent_clip ? "on" : "off") + " target=" + std::string(to_string(c.target));
}

const Layout& WindowApp::layout() const { return session_.runtime().layout(); }

WindowApp::WindowApp(const PlaygroundOptions& options) : options_(options), session_(options.watch_dir) {}

WindowApp::~WindowApp() {
    truth_worker_.reset(); // joins its thread before the GL objects go
    if (truth_texture_) glDeleteTextures(1, &truth_texture_);
}

std::unique_ptr<WindowApp> WindowApp::create(const PlaygroundOptions& options, Scene first, std::string* error) {
    std::unique_ptr<WindowApp> app(new WindowApp(options));
    if (!app->show_scene(std::move(first), options.scene)) {
        // show_scene has printed its "error: …" line already; an empty error says so.
        if (error) *error = app->log_.empty() ? "cannot load the scene" : "";
        return nullptr;
    }
    if (std::string e = app->session_.apply_config(options.config); !e.empty()) {
        if (error) *error = e;
        return nullptr;
    }
    app->info("config: " + describe(options.config));
    app->info("shaders: wrote " + std::to_string(app->session_.runtime().emission().files().size()) +
              " files to " + app->session_.folder().directory().string() +
              " (edit and save them to recompile)");
    app->right_config_ = default_right_config(options.config);
    app->truth_worker_ = std::make_unique<TruthWorker>();
    return app;
}

void WindowApp::info(const std::string& line) {
    std::cout << line << std::endl;
    log_.push_back(line);
    if (log_.size() > log_lines_kept) log_.erase(log_.begin());
}

void WindowApp::problem(const std::string& line) {
    std::cerr << line << std::endl;
    log_.push_back(line);
    if (log_.size() > log_lines_kept) log_.erase(log_.begin());
}

void WindowApp::load_scene(const std::string& name_or_path) {
    SceneLoad loaded = penumbra::playground::load_scene(name_or_path, options_.ground);
    if (!loaded.scene) {
        problem("error: " + loaded.error);
        return;
    }
    show_scene(std::move(*loaded.scene), name_or_path);
}

bool WindowApp::show_scene(Scene scene, const std::string& name_or_path) {
    std::string error;
    // --light-*, --camera-*: every scene shown (the first and each one loaded later) gets them
    if (std::string e = apply_scene_overrides(options_.overrides, scene, options_.config.light); !e.empty()) {
        problem("error: " + e);
        return false;
    }
    // The renderer keeps a pointer to the scene: build the new one before replacing the old.
    Scene previous = std::move(scene_);
    scene_ = std::move(scene);
    std::unique_ptr<FrameRenderer> renderer = FrameRenderer::create(scene_, &error);
    if (!renderer) {
        scene_ = std::move(previous);
        problem("error: " + error);
        return false;
    }
    renderer_ = std::move(renderer);
    scene_name_ = name_or_path;
    scene_mesh_ = std::make_shared<const Mesh>(scene_.mesh);
    controls_.camera = scene_.camera;
    controls_.rect = scene_.light;
    rect_rest_ = scene_.light;
    controls_.rect_yaw_degrees = 0.0f;
    controls_.rect_tilt_degrees = 0.0f;
    const glm::dvec3 d = glm::normalize(scene_.sun.direction);
    controls_.sun_elevation_degrees =
        static_cast<float>(std::asin(std::clamp(-d.y, -1.0, 1.0)) * degrees_per_radian);
    controls_.sun_azimuth_degrees = static_cast<float>(std::atan2(-d.x, -d.z) * degrees_per_radian);
    controls_.sun_diameter_degrees = static_cast<float>(scene_.sun.angular_diameter * degrees_per_radian);
    truth_key_.clear();
    info("scene: " + scene_.name + " (" + std::to_string(scene_.mesh.triangle_count()) + " triangles)");
    return true;
}

void WindowApp::set_light_size(double size) {
    if (config().light == Light::sun) {
        controls_.sun_diameter_degrees = static_cast<float>(size);
    } else {
        controls_.rect.width = controls_.rect.height = size;
        rect_rest_.width = rect_rest_.height = size;
    }
}

void WindowApp::request_config(const Config& config, int side) {
    if (side == 1) {
        if (config == right_config_ && right_runtime_) return;
        if (const auto problems = validate(config); !problems.empty()) {
            config_message_ = "right: " + problems.front().message + " (kept the previous configuration)";
            problem("config rejected: " + config_message_);
            return;
        }
        std::string error;
        if (right_runtime_)
            error = right_runtime_->reconfigure(config);
        else if (!(right_runtime_ = penumbra::gl::Runtime::create(config, &error)))
            right_runtime_.reset();
        if (!error.empty()) {
            config_message_ = "right: " + error;
            problem("config rejected: " + config_message_);
            return;
        }
        right_config_ = config;
        config_message_.clear();
        info("config right: " + describe(config));
        return;
    }
    if (config == session_.config()) return;
    if (const auto problems = validate(config); !problems.empty()) {
        config_message_ = problems.front().message + " (kept the previous configuration)";
        problem("config rejected: " + config_message_);
        return;
    }
    pending_files_ = session_.hand_edited_files();
    if (!pending_files_.empty()) {
        pending_config_ = config;
        std::string list;
        for (const std::string& f : pending_files_) {
            if (!list.empty()) list += ", ";
            list += f;
        }
        info("config: " + std::to_string(pending_files_.size()) +
             " hand-edited file(s) would be overwritten (" + list + "); asking before applying " +
             describe(config));
        return;
    }
    apply_main_config(config);
}

void WindowApp::answer_overwrite(bool overwrite) {
    if (!pending_config_) return;
    const Config config = *pending_config_;
    pending_config_.reset();
    pending_files_.clear();
    if (!overwrite) {
        info("config: kept the hand-edited files and the configuration " + describe(session_.config()));
        return;
    }
    apply_main_config(config);
}

void WindowApp::apply_main_config(const Config& config) {
    if (std::string e = session_.apply_config(config); !e.empty()) {
        config_message_ = e + " (kept the previous configuration)";
        problem("config rejected: " + config_message_);
        return;
    }
    config_message_.clear();
    truth_key_.clear();
    info("config: " + describe(config));
}

void WindowApp::reset_to_generated() {
    if (std::string e = session_.reset_to_generated(); !e.empty())
        problem("reset: " + e);
    else
        info("shaders: reset to generated");
}

std::string WindowApp::edit_file(const std::string& file_name, const std::string& mode, const std::string& a,
                                 const std::string& b) {
    ShaderFolder& folder = session_.folder();
    if (!folder.contains(file_name)) {
        std::string names;
        for (const ShaderFile& f : session_.runtime().emission().files()) {
            if (!names.empty()) names += ", ";
            names += f.file_name;
        }
        return "no watched file '" + file_name + "'; the files are: " + names;
    }
    const std::filesystem::path path = folder.path(file_name);
    std::ifstream in(path, std::ios::binary);
    std::ostringstream buffer;
    buffer << in.rdbuf();
    std::string text = buffer.str();
    if (mode == "append") {
        text += (text.empty() || text.back() == '\n' ? "" : "\n") + a + "\n";
    } else {
        const std::size_t at = text.find(a);
        if (at == std::string::npos) return "'" + a + "' does not occur in " + file_name;
        text.replace(at, a.size(), b);
    }
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << text;
    if (!out) return "cannot write " + path.string();
    return {};
}

std::string WindowApp::restore_file(const std::string& file_name) {
    return session_.folder().restore(file_name);
}

FrameSettings WindowApp::frame_settings() const {
    FrameSettings s;
    s.camera = controls_.camera;
    s.rect = controls_.rect;
    orient_rect(s.rect, controls_.rect_yaw_degrees, controls_.rect_tilt_degrees);
    float sun_azimuth = controls_.sun_azimuth_degrees;
    if (controls_.animate_light) {
        // The light circles its rest position (a sixth of the light's span per second).
        const double radius = 0.5 * std::max(rect_rest_.width, rect_rest_.height);
        s.rect.center = controls_.rect.center +
                        radius * glm::dvec3(std::cos(animation_seconds_), 0.0, std::sin(animation_seconds_));
        sun_azimuth += static_cast<float>(20.0 * animation_seconds_);
    }
    s.sun.direction = sun_direction(sun_azimuth, controls_.sun_elevation_degrees);
    s.sun.angular_diameter = controls_.sun_diameter_degrees / degrees_per_radian;
    if (controls_.animate_object) s.moving_object = renderer_->moving_object_at(animation_seconds_);
    s.view = controls_.view;
    s.slice = controls_.view_slice;
    s.level = controls_.view_level;
    s.texture = controls_.view_texture;
    s.truth_texture =
        truth_snapshot_.samples_per_axis > 0 || truth_snapshot_.progress > 0 ? truth_texture_ : 0;
    return s;
}

void WindowApp::update_truth(int width, int height, const FrameSettings& s) {
    if (controls_.view != View::truth && controls_.view != View::error) {
        if (!truth_key_.empty()) truth_worker_->cancel();
        truth_key_.clear();
        return;
    }
    // Restart whenever what the truth depends on changed.
    std::ostringstream key;
    const glm::vec3 eye = s.camera.eye_position();
    key << width << 'x' << height << ' ' << eye.x << ' ' << eye.y << ' ' << eye.z << ' ' << s.camera.target.x
        << ' ' << s.camera.target.y << ' ' << s.camera.target.z << ' ' << int(config().light) << ' '
        << s.rect.center.x << ' ' << s.rect.center.y << ' ' << s.rect.center.z << ' ' << s.rect.width << ' '
        << s.rect.height << ' ' << s.rect.u_axis.x << ' ' << s.rect.u_axis.y << ' ' << s.rect.v_axis.x << ' '
        << s.rect.v_axis.z << ' ' << s.sun.direction.x << ' ' << s.sun.direction.z << ' '
        << s.sun.angular_diameter << ' ' << int(controls_.truth_reference) << ' '
        << (s.moving_object ? (*s.moving_object)[3][0] + 7.0f * (*s.moving_object)[3][2] : 0.0f);
    if (key.str() != truth_key_ && renderer_->gbuffer()) {
        truth_key_ = key.str();
        const std::size_t n = static_cast<std::size_t>(width) * height;
        std::vector<glm::vec4> positions(n), normals(n);
        glGetTextureImage(renderer_->gbuffer()->positions(), 0, GL_RGBA, GL_FLOAT,
                          static_cast<GLsizei>(n * sizeof(glm::vec4)), positions.data());
        glGetTextureImage(renderer_->gbuffer()->normals(), 0, GL_RGBA, GL_FLOAT,
                          static_cast<GLsizei>(n * sizeof(glm::vec4)), normals.data());
        TruthJob job;
        if (s.moving_object) {
            Mesh combined = scene_.mesh;
            Mesh box;
            add_box(box, *s.moving_object);
            append_mesh(combined, box, glm::mat4(1.0f));
            job.mesh = std::make_shared<const Mesh>(std::move(combined));
        } else {
            job.mesh = scene_mesh_;
        }
        if (config().light == Light::sun)
            job.light = s.sun;
        else
            job.light = s.rect;
        job.positions.resize(n);
        job.normals.resize(n);
        truth_geometry_.assign(n, 0);
        for (std::size_t i = 0; i < n; ++i) {
            truth_geometry_[i] = positions[i].w >= 0.5f;
            job.positions[i] = positions[i].w < 0.5f ? glm::vec3(std::numeric_limits<float>::quiet_NaN())
                                                     : glm::vec3(positions[i]);
            // Turned to the side the camera sees, as the headless reference does (reference_all).
            const glm::vec3 n(normals[i]);
            job.normals[i] = glm::dot(n, eye - glm::vec3(positions[i])) < 0.0f ? -n : n;
        }
        job.first_samples_per_axis = 2;
        job.max_samples_per_axis = 16;
        job.reference =
            controls_.truth_reference; // irradiance unless the panel says otherwise (the side seen)
        if (std::string e = truth_worker_->start(std::move(job)); !e.empty())
            problem("truth: " + e);
        else
            ++truth_jobs_started_;
        if (!truth_texture_ || truth_width_ != width || truth_height_ != height) {
            if (truth_texture_) glDeleteTextures(1, &truth_texture_);
            glCreateTextures(GL_TEXTURE_2D, 1, &truth_texture_);
            glTextureStorage2D(truth_texture_, 1, GL_R32F, width, height);
            truth_width_ = width;
            truth_height_ = height;
        }
        const std::vector<float> unknown(n, std::numeric_limits<float>::quiet_NaN());
        glTextureSubImage2D(truth_texture_, 0, 0, 0, width, height, GL_RED, GL_FLOAT, unknown.data());
        truth_snapshot_ = {};
    }
    if (truth_worker_->version() != truth_snapshot_.version) {
        const TruthState previous_state = truth_snapshot_.state;
        TruthSnapshot latest = truth_worker_->snapshot();
        // a job that a change cancelled may publish once more: its numbers are not this view's
        if (latest.job != truth_jobs_started_) return;
        truth_snapshot_ = std::move(latest);
        if (truth_snapshot_.state == TruthState::failed && previous_state != TruthState::failed)
            problem("truth: " + truth_snapshot_.error);
        if (truth_snapshot_.visibility.size() == static_cast<std::size_t>(width) * height) {
            glTextureSubImage2D(truth_texture_, 0, 0, 0, width, height, GL_RED, GL_FLOAT,
                                truth_snapshot_.visibility.data());
            // MAE and p95 over the pixels traced so far; in split screen each half on its own
            // (each runtime shaded only its half).
            const bool split = controls_.split && right_runtime_;
            penumbra::gl::Runtime* runtimes[2] = {&session_.runtime(),
                                                  split ? right_runtime_.get() : nullptr};
            for (int side = 0; side < 2; ++side) {
                error_numbers_[side] = {};
                if (!runtimes[side]) continue;
                std::vector<unsigned char> mask = truth_geometry_;
                if (split)
                    for (std::size_t i = 0; i < mask.size(); ++i)
                        if ((static_cast<int>(i % width) > width / 2) != (side == 1)) mask[i] = 0;
                const std::vector<float> estimate = runtimes[side]->read_visibility();
                if (auto metrics = visibility_error(estimate, truth_snapshot_.visibility, mask))
                    error_numbers_[side] = metrics->all;
            }
            if (truth_snapshot_.state == TruthState::finished && previous_state != TruthState::finished) {
                char line[200];
                std::snprintf(line, sizeof line,
                              "truth (%s): %dx%d rays per pixel in %.1f s; MAE %.4f, p95 %.4f over %zu px",
                              to_string(controls_.truth_reference), truth_snapshot_.samples_per_axis,
                              truth_snapshot_.samples_per_axis, truth_snapshot_.seconds,
                              error_numbers_[0].mae, error_numbers_[0].p95, error_numbers_[0].count);
                info(line);
            }
        }
    }
}

bool WindowApp::render_frame(int width, int height, double dt) {
    for (ReloadEvent& event : session_.poll(stats_.frame.last())) {
        ++reloads_done_;
        if (event.ok) {
            shown_reloads_.push_back(std::move(event));
            continue;
        }
        problem("reload: " + event.file_name + " failed; the last good program keeps rendering");
        problem(event.diagnostics);
    }
    if (controls_.animate_light || controls_.animate_object) animation_seconds_ += dt;
    if (controls_.split && !right_runtime_) request_config(right_config_, 1);
    const FrameSettings settings = frame_settings();
    penumbra::gl::Runtime* right = controls_.split ? right_runtime_.get() : nullptr;
    const std::string error = renderer_->render(session_.runtime(), right, settings, width, height, stats_);
    if (!error.empty() && error != frame_error_) problem("frame: " + error);
    frame_error_ = error;
    update_truth(width, height, settings);
    for (const std::string& path : screenshots_)
        if (std::string e = capture(path, width, height); !e.empty()) {
            problem("error: screenshot: " + e);
            screenshot_failed_ = true;
        }
    screenshots_.clear();
    for (const std::string& path : readbacks_)
        if (std::string e = read_back(path, width, height); !e.empty()) {
            problem("error: readback: " + e);
            screenshot_failed_ = true;
        }
    readbacks_.clear();
    ++frame_index_;
    return true;
}

void WindowApp::frame_presented() {
    const auto now = std::chrono::system_clock::now();
    for (const ReloadEvent& event : shown_reloads_) {
        const double ms = std::chrono::duration<double, std::milli>(now - event.saved_at).count();
        reload_latencies_.push_back(ms);
        std::string programs;
        for (const std::string& p : event.programs) {
            if (!programs.empty()) programs += ", ";
            programs += p;
        }
        info("reload: " + event.file_name + " ok (" + programs + "); save to first frame " + format_ms(ms) +
             " (compile " + format_ms(event.compile_milliseconds) + ")");
    }
    shown_reloads_.clear();
}

std::string WindowApp::capture(const std::string& path, int width, int height) {
    std::vector<float> rgb(static_cast<std::size_t>(width) * height * 3);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_FLOAT, rgb.data());
    std::string error;
    if (!write_png_rgb(path, width, height, rgb, RowOrder::bottom_up, &error)) return error;
    info("screenshot: wrote " + path + " (frame " + std::to_string(frame_index_) + ", " +
         std::to_string(width) + "x" + std::to_string(height) + ")");
    return {};
}

std::string WindowApp::read_back(const std::string& path, int width, int height) {
    // Both come bottom row first: GL's order, and the G-buffer's for the truth.
    auto gl_rows = [&](const std::vector<float>& pixels) {
        return FloatImage{
            .width = width, .height = height, .channels = 1, .pixels = pixels, .rows = RowOrder::bottom_up};
    };
    const std::vector<float> visibility = session_.runtime().read_visibility();
    if (visibility.size() != static_cast<std::size_t>(width) * height)
        return path + ": the visibility is " + std::to_string(visibility.size()) +
               " values, not the window's " + std::to_string(width) + "x" + std::to_string(height);
    std::string error;
    if (!write_pfm(path, gl_rows(visibility), &error)) return error;
    std::string wrote = path;
    if (truth_snapshot_.visibility.size() == visibility.size()) {
        const std::string stem = path.ends_with(".pfm") ? path.substr(0, path.size() - 4) : path;
        if (!write_pfm(stem + ".truth.pfm", gl_rows(truth_snapshot_.visibility), &error)) return error;
        wrote += " and " + stem + ".truth.pfm (" + std::string(to_string(controls_.truth_reference)) + ", " +
                 std::to_string(truth_snapshot_.samples_per_axis) + "x" +
                 std::to_string(truth_snapshot_.samples_per_axis) + " rays)";
    }
    info("readback: wrote " + wrote + " (frame " + std::to_string(frame_index_) + ", " +
         std::to_string(width) + "x" + std::to_string(height) + ")");
    return {};
}

} // namespace penumbra::playground
