// playground/src/window/app.cpp — `penumbra-playground` without --headless: the GLFW window, the
// Dear ImGui panel, the frame loop, mouse orbit, --frames / --script / --screenshot, and the
// summary printed at exit (frame times, GPU pass times, hot-reload latency).
#include "app/headless_job.hpp"
#include "app/options.hpp"
#include "panel.hpp"
#include "script.hpp"
#include "script_runner.hpp"
#include "window_app.hpp"

#include <epoxy/gl.h> // before GLFW: epoxy provides the GL declarations

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>

namespace penumbra::playground {

namespace {

std::string glfw_error;

void record_glfw_error(int, const char* description) {
    glfw_error = description ? description : "unknown error";
}

void explain_no_window(const std::string& what) {
    std::cerr << "error: " << what << " (GLFW: " << (glfw_error.empty() ? "no details" : glfw_error) << ")\n"
              << "  The window needs a display with OpenGL 4.5 core. Without one:\n"
              << "    penumbra-playground --headless --scene boxes --out boxes.png    renders to a file "
                 "(EGL, no display)\n"
              << "    xvfb-run -a penumbra-playground ...                           runs the window on a "
                 "virtual display\n";
}

// Mouse orbit: the scroll wheel arrives by callback, the drags are read each frame.
double scroll_accumulated = 0.0;
void on_scroll(GLFWwindow*, double, double y) { scroll_accumulated += y; }

void orbit_camera(GLFWwindow* window, OrbitCamera& camera, double& last_x, double& last_y) {
    double x = 0, y = 0;
    glfwGetCursorPos(window, &x, &y);
    const double dx = x - last_x, dy = y - last_y;
    last_x = x;
    last_y = y;
    const bool ui = ImGui::GetIO().WantCaptureMouse;
    if (!ui && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS) {
        camera.yaw_radians -= static_cast<float>(0.008 * dx);
        camera.pitch_radians = std::clamp(camera.pitch_radians + static_cast<float>(0.008 * dy), -1.5f, 1.5f);
    }
    if (!ui && glfwGetMouseButton(window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS)
        camera.distance *= static_cast<float>(std::exp(0.01 * dy));
    if (!ui && scroll_accumulated != 0.0)
        camera.distance *= static_cast<float>(std::pow(0.9, scroll_accumulated));
    scroll_accumulated = 0.0;
    camera.distance = std::max(camera.distance, 0.01f);
}

void print_summary(WindowApp& app, int width, int height) {
    FrameStats& stats = app.stats();
    char line[256];
    std::snprintf(line, sizeof line, "frames: %zu at %dx%d, frame time median %.1f ms", app.frame_index(),
                  width, height, stats.frame.median());
    std::string passes = "gpu passes (median ms):";
    for (const std::string& name : stats.pass_order) {
        char entry[96];
        std::snprintf(entry, sizeof entry, " %s %.2f", name.c_str(), stats.passes.at(name).median());
        passes += entry;
    }
    app.info(line);
    app.info(passes);
    if (!app.reload_latencies().empty()) {
        std::snprintf(line, sizeof line, "reload: save to first frame median %.1f ms over %zu reloads",
                      median(app.reload_latencies()), app.reload_latencies().size());
        app.info(line);
    }
}

} // namespace

int run_window(const PlaygroundOptions& given) {
    PlaygroundOptions options = given;
    std::optional<ScriptRunner> script;
    if (!options.script_path.empty()) {
        ScriptParse parsed = load_script(options.script_path);
        if (!parsed.error.empty()) {
            std::cerr << "error: " << parsed.error << "\n";
            return 2;
        }
        script.emplace(std::move(parsed.actions));
    }
    // A bad scene is bad input (exit 2) with or without a display: checked before the window opens.
    SceneLoad loaded = load_scene(options.scene, options.ground);
    if (!loaded.scene) {
        std::cerr << "error: " << loaded.error << "\n";
        return 2;
    }
    {
        // What only the scene can tell of --light-up and --camera-* (bad input too): on a copy of its light
        // and camera, before the window opens.
        Scene probe;
        probe.light = loaded.scene->light;
        probe.camera = loaded.scene->camera;
        probe.bounds_min = loaded.scene->bounds_min;
        probe.bounds_max = loaded.scene->bounds_max;
        if (std::string e = apply_scene_overrides(options.overrides, probe, options.config.light);
            !e.empty()) {
            std::cerr << "error: " << e << "\n";
            return 2;
        }
    }
    std::string cut_note;
    options = follow_asset_cuts(options, *loaded.scene, &cut_note);
    if (!cut_note.empty()) std::cout << cut_note << "\n";
    const bool automated = options.frames > 0 || script.has_value();

    glfwSetErrorCallback(record_glfw_error);
    if (!glfwInit()) {
        explain_no_window("no display to open a window on");
        return 1;
    }
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    const int width = options.width > 0 ? options.width : 1280;
    const int height = options.height > 0 ? options.height : 720;
    GLFWwindow* window = glfwCreateWindow(width, height, "Penumbra playground", nullptr, nullptr);
    if (!window) {
        explain_no_window("cannot open a window with an OpenGL 4.5 core context");
        glfwTerminate();
        return 1;
    }
    glfwMakeContextCurrent(window);
    glfwSwapInterval(automated ? 0 : 1);      // measuring: as fast as it goes
    glfwSetScrollCallback(window, on_scroll); // before ImGui, which chains to it

    IMGUI_CHECKVERSION();
    ImGui::CreateContext();
    ImGui::GetIO().IniFilename = nullptr; // no imgui.ini in the user's folder
    ImGui::StyleColorsDark();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGui_ImplOpenGL3_Init("#version 450 core");

    int exit_code = 0;
    std::string error;
    std::unique_ptr<WindowApp> app = WindowApp::create(options, std::move(*loaded.scene), &error);
    int fb_width = width, fb_height = height;
    if (!app) {
        if (!error.empty()) std::cerr << "error: " << error << "\n"; // empty: already printed
        exit_code = 1;
    } else {
        app->info(std::string("window: ") + std::to_string(width) + "x" + std::to_string(height) + ", " +
                  reinterpret_cast<const char*>(glGetString(GL_RENDERER)));
        double mouse_x = 0, mouse_y = 0;
        glfwGetCursorPos(window, &mouse_x, &mouse_y);
        auto previous = std::chrono::steady_clock::now();
        bool screenshot_taken = false;
        while (!glfwWindowShouldClose(window)) {
            glfwPollEvents();
            orbit_camera(window, app->controls().camera, mouse_x, mouse_y);
            if (script) {
                if (std::string e = script->step(*app); !e.empty()) {
                    app->problem("error: " + e);
                    exit_code = 1;
                    break;
                }
            }
            // --frames N quits after N frames; a script that is still running extends the run,
            // and a script without --frames ends the run when it is done.
            const bool script_done = !script || script->done();
            const bool last =
                script_done &&
                ((options.frames > 0 && app->frame_index() + 1 >= std::size_t(options.frames)) ||
                 (options.frames == 0 && script));
            glfwGetFramebufferSize(window, &fb_width, &fb_height);
            if (last && !options.screenshot_path.empty()) {
                app->request_screenshot(options.screenshot_path);
                screenshot_taken = true;
            }
            const auto start = std::chrono::steady_clock::now();
            const double dt =
                automated ? 1.0 / 60.0 : std::chrono::duration<double>(start - previous).count();
            app->render_frame(fb_width, fb_height, dt);

            ImGui_ImplOpenGL3_NewFrame();
            ImGui_ImplGlfw_NewFrame();
            ImGui::NewFrame();
            draw_panel(*app);
            ImGui::Render();
            ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
            glfwSwapBuffers(window);
            app->frame_presented();

            const auto end = std::chrono::steady_clock::now();
            app->stats().frame.add(std::chrono::duration<double, std::milli>(end - start).count());
            previous = start;
            if (last) break;
        }
        if (!options.screenshot_path.empty() && !screenshot_taken && exit_code == 0) {
            // Closed by the user: one more frame, without the panel, for the screenshot.
            app->request_screenshot(options.screenshot_path);
            app->render_frame(fb_width, fb_height, 0.0);
        }
        print_summary(*app, fb_width, fb_height);
        if (app->screenshot_failed() && exit_code == 0) exit_code = 1; // writing failed
    }
    app.reset(); // GL objects go while the context is current
    ImGui_ImplOpenGL3_Shutdown();
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
    glfwDestroyWindow(window);
    glfwTerminate();
    return exit_code;
}

} // namespace penumbra::playground
