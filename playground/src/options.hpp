// playground/src/options.hpp — what penumbra-playground was asked to do, parsed once from argv
// and shared by the headless renderer and the window.
#pragma once

#include <penumbra/config.hpp>

#include <optional>
#include <string>

namespace penumbra::playground {

struct PlaygroundOptions {
    bool headless = false;
    std::string scene = "boxes";   // a built-in scene name or a path ending in .obj
    penumbra::Config config;
    int width = 0, height = 0;      // 0: mode default (headless 512x512, window 1280x720)
    std::optional<double> light_size; // --light-size: rectangle side / sun angular diameter (degrees)

    // headless
    std::string out_path;           // --out image.png
    std::string visibility_path;    // --visibility vis.pfm
    std::string metrics_path;       // --metrics metrics.json
    bool reference = false;         // --reference
    int samples = 32;               // --samples N (rays per light axis)

    // window
    std::string watch_dir = "playground-shaders"; // --watch DIR
    int frames = 0;                 // --frames N: quit after N frames (0: run until closed)
    std::string screenshot_path;    // --screenshot FILE: last frame as PNG
    std::string script_path;        // --script FILE
};

// The interactive window (playground/src/window/). Returns the process exit code; without a
// display it says so, points to --headless, and returns 1.
int run_window(const PlaygroundOptions& options);

} // namespace penumbra::playground
