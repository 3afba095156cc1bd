// playground/src/window/window_app.hpp — everything the window shows and what can change it:
// the scene, the configuration(s), light, camera, animation, view, hot reload, timings, the
// ground truth in the background. The panel (panel.hpp) and the automation script
// (script_runner.hpp) both act through these methods, so a script does what a click does.
#pragma once

#include "frame_renderer.hpp"
#include "frame_stats.hpp"
#include "app/options.hpp"
#include "scenes/scene.hpp"
#include "shader_session.hpp"
#include "reference/truth_worker.hpp"

#include <penumbra/config.hpp>

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace penumbra::playground {

// What the user controls besides the configuration. Angles in degrees (panel units).
struct Controls {
    OrbitCamera camera;
    penumbra::RectLight rect;       // centre and size; axes come from the two angles below
    float rect_yaw_degrees = 0.0f;  // rotation of the rectangle about +y
    float rect_tilt_degrees = 0.0f; // tilt of its normal away from straight down
    float sun_azimuth_degrees = 0.0f;
    float sun_elevation_degrees = 90.0f; // 90: straight down
    float sun_diameter_degrees = 0.5f;
    bool animate_light = false;  // the light circles its position (the sun turns)
    bool animate_object = false; // a box circles over the scene
    View view = View::shaded;
    // What the truth and error views trace and compare with: irradiance, the shaded image's reference
    TruthReference truth_reference = TruthReference::irradiance;
    int view_slice = 0; // slice_texture / level_map views: which slice (level_map: −1 nearest above)
    int view_level = 0; // slice_texture view: which filter level
    LayoutTextureView view_texture; // texture view: texture (empty: the layout's first), level, layer, …
    bool split = false; // right half: the second configuration
};

class WindowApp {
public:
    // nullptr with *error when the scene or the first configuration cannot be set up (*error empty:
    // the problem was printed already, as an "error: …" line).
    // `first` is options.scene already loaded (run_window checks it before a window opens, so a
    // large mesh file is read once and its warnings are printed once).
    static std::unique_ptr<WindowApp> create(const PlaygroundOptions& options, Scene first, std::string* error);

    // --- configuration (side 0: main, 1: split screen's right half)
    const Config& config(int side = 0) const { return side == 0 ? session_.config() : right_config_; }
    // Applies `config` live. An invalid one is refused with the validator's message (the state
    // stays); when shader files were edited by hand the change waits for answer_overwrite().
    void request_config(const Config& config, int side = 0);
    bool overwrite_question() const { return pending_config_.has_value(); }
    const std::vector<std::string>& overwrite_files() const { return pending_files_; }
    void answer_overwrite(bool overwrite);
    const std::string& config_message() const { return config_message_; }
    // What the main side's runtime runs: its textures, programs and passes.
    const Layout& layout() const;

    // --- scene, light, camera, view
    Controls& controls() { return controls_; }
    const std::string& scene_name() const { return scene_name_; }
    void load_scene(const std::string& name_or_path);
    // Makes a loaded scene the current one (false, with the problem logged, when it cannot be drawn).
    bool show_scene(Scene scene, const std::string& name_or_path);
    void reset_camera() { controls_.camera = scene_.camera; }
    void set_light_size(double size); // rectangle side (scene units) or sun diameter (degrees)

    // --- hot reload
    ShaderSession& shaders() { return session_; }
    void reset_to_generated();
    // Script edits: append a line / replace text in a watched file; empty string or the problem.
    std::string edit_file(const std::string& file_name, const std::string& mode, const std::string& a,
                          const std::string& b);
    std::string restore_file(const std::string& file_name);
    std::size_t reloads_done() const { return reloads_done_; }

    // --- frames
    // Polls the shader folder, advances the animation by `dt` seconds, renders into the window's
    // framebuffer (width × height), takes requested screenshots. Returns false on a GL failure
    // that makes further frames pointless.
    bool render_frame(int width, int height, double dt);
    // Call after the frame has been presented: logs the reloads that reached the screen.
    void frame_presented();
    void request_screenshot(const std::string& path) { screenshots_.push_back(path); }
    // After this frame: the visibility as floats into `path` (PFM), and in the truth and error views the
    // truth traced so far into `<path less .pfm>.truth.pfm` (NaN where not traced yet or no light is
    // above the surface): the numbers behind the views, for a script and the tests.
    void request_readback(const std::string& path) { readbacks_.push_back(path); }
    // A screenshot or read-back could not be written (nothing was left at its path): the run fails (exit 1).
    bool screenshot_failed() const { return screenshot_failed_; }
    std::string capture(const std::string& path, int width, int height); // reads framebuffer 0
    std::string read_back(const std::string& path, int width, int height);
    std::size_t frame_index() const { return frame_index_; }
    FrameStats& stats() { return stats_; }
    const std::vector<double>& reload_latencies() const { return reload_latencies_; }
    const std::string& frame_error() const { return frame_error_; }

    // --- ground truth
    const TruthSnapshot& truth() const { return truth_snapshot_; }
    // The truth of what is shown now (the latest job, not one that a change cancelled) is traced to its last
    // pass.
    bool truth_finished() const {
        return truth_snapshot_.state == TruthState::finished && truth_snapshot_.job == truth_jobs_started_;
    }
    // MAE and p95 of |visibility − truth| over the pixels traced so far; side 1: the split
    // screen's right half (side 0 is then the left half).
    const ErrorStats& error_numbers(int side = 0) const { return error_numbers_[side]; }

    // --- log: info on stdout, problems on stderr; the last lines also go to the panel
    void info(const std::string& line);
    void problem(const std::string& line);
    const std::vector<std::string>& log_lines() const { return log_; }

    static std::string describe(const Config& config);
    ~WindowApp();
    WindowApp(const WindowApp&) = delete;
    WindowApp& operator=(const WindowApp&) = delete;

private:
    WindowApp(const PlaygroundOptions& options);
    void apply_main_config(const Config& config);
    FrameSettings frame_settings() const;
    void update_truth(int width, int height, const FrameSettings& settings);

    PlaygroundOptions options_;
    std::string scene_name_;
    Scene scene_;
    std::shared_ptr<const Mesh> scene_mesh_; // for the truth worker
    Controls controls_;
    double animation_seconds_ = 0.0;
    penumbra::RectLight rect_rest_; // light centre before the animation moves it

    ShaderSession session_;
    Config right_config_;
    std::unique_ptr<penumbra::gl::Runtime> right_runtime_;
    std::optional<Config> pending_config_;
    std::vector<std::string> pending_files_;
    std::string config_message_;

    std::unique_ptr<FrameRenderer> renderer_;
    FrameStats stats_;
    std::size_t frame_index_ = 0;
    std::string frame_error_;
    std::vector<std::string> screenshots_;
    std::vector<std::string> readbacks_;
    bool screenshot_failed_ = false;
    std::size_t reloads_done_ = 0;
    std::vector<ReloadEvent> shown_reloads_; // applied this frame, logged once presented
    std::vector<double> reload_latencies_;

    std::unique_ptr<TruthWorker> truth_worker_;
    std::uint64_t truth_jobs_started_ = 0; // start() calls that the worker accepted (its job ids)
    TruthSnapshot truth_snapshot_;
    std::string truth_key_;
    GLuint truth_texture_ = 0;
    int truth_width_ = 0, truth_height_ = 0;
    std::vector<unsigned char> truth_geometry_; // 1 where the truth job has a surface (GL row order)
    ErrorStats error_numbers_[2];

    std::vector<std::string> log_;
};

} // namespace penumbra::playground
