// playground/src/app/options.hpp — what penumbra-playground was asked to do, parsed once from argv
// and shared by the headless renderer and the window.
#pragma once

#include "app/scene_overrides.hpp"

#include <penumbra/config.hpp>

#include <optional>
#include <string>
#include <vector>

namespace penumbra::playground {

struct PlaygroundOptions {
    bool headless = false;
    std::string scene = "boxes";   // a built-in scene name or a path ending in .obj, .gltf or .glb
    bool ground = true;             // a mesh file gets a floor under it (--no-ground: not)
    penumbra::Config config;
    bool alpha_test_given = false;  // --[no-]alpha-test, or a --config file that turns it on; else the scene's
                                    // materials decide (follow_asset_cuts)
    int width = 0, height = 0;      // 0: mode default (headless 512x512, window 1280x720)
    // --light-size, --light-center, --light-normal, --light-up, --camera-position, --camera-target: set on
    // the scene once it is made (app/scene_overrides.hpp). overrides.light_size: rectangle side / sun
    // angular diameter (degrees)
    SceneOverrides overrides;
    // technique oim: the sun on its path (penumbra/sun_path.hpp) and where bakes are cached
    double sun_time = 0.5;          // --sun-time T: path time, 0 to 1
    std::string sun_path;           // --sun-path AZ:EL,…: degrees (empty: the default day)
    std::string bake_cache;         // --bake-cache DIR (empty: bake/oim_cache.hpp's default folder)

    // headless
    std::string out_path;           // --out image.png
    std::string visibility_path;    // --visibility vis.pfm
    std::string metrics_path;       // --metrics metrics.json
    bool reference = false;         // --reference
    int samples = 32;               // --samples N (rays per light axis)
    std::string reference_path;     // --reference-out truth.pfm (default: next to --out, <stem>.reference.pfm)
    std::string error_image_path;   // --error-out error.png (default: next to --out, <stem>.error.png)

    // window
    std::string watch_dir = "playground-shaders"; // --watch DIR
    int frames = 0;                 // --frames N: quit after N frames (0: run until closed)
    std::string screenshot_path;    // --screenshot FILE: last frame as PNG
    std::string script_path;        // --script FILE
};

struct ParsedOptions {
    std::optional<PlaygroundOptions> options; // set when error is empty and help is false
    bool help = false;                        // --help / -h anywhere: print usage() and exit 0
    std::string error;                        // one line, without the "error: " prefix
};

// Parses argv[1..]: `--flag value` and `--flag=value`; a later flag wins. The configuration flags
// are penumbra-gen's (--config FILE.json read first, flags override it); the result is validated.
ParsedOptions parse_options(const std::vector<std::string>& args);

// The --help text: both modes, every flag, every allowed value and default.
std::string usage();

// The interactive window (playground/src/window/). Returns the process exit code; without a
// display it says so, points to --headless, and returns 1.
int run_window(const PlaygroundOptions& options);

} // namespace penumbra::playground
