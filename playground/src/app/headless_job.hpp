// playground/src/app/headless_job.hpp — `penumbra-playground --headless`: load the scene, render it,
// write the image and, with --reference, the ground truth, the error image and the metrics.
#pragma once

#include "rendering/headless_render.hpp"
#include "app/options.hpp"
#include "app/scene_overrides.hpp"
#include "scenes/scene.hpp"

#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace penumbra::playground {

struct SceneLoad {
    std::optional<Scene> scene; // set on success
    std::string error;          // otherwise one line: the unknown name and the allowed ones, or the file's problem
    std::vector<std::string> warnings; // parts of the file that were skipped (printed as "warning:" lines)
};

// The configuration with the keys of layout.json's "config" object, so that --config FILE.json
// reproduces the run (metrics.json, a target bundle's uniforms.json).
nlohmann::ordered_json config_json(const Config& c);

// The scene's light of that kind: the rectangle's size, centre, normal (where it emits towards), up
// (its v axis, the height side) and u axis, or the sun's direction and angular diameter in degrees.
nlohmann::ordered_json light_json(const Scene& scene, Light light);

// The camera as used: its eye position, target, vertical field of view in degrees, near and far planes.
nlohmann::ordered_json camera_json(const OrbitCamera& camera);

// True for a path this loads as a file: it ends in ".obj", ".gltf" or ".glb" (any case).
bool is_scene_file(const std::string& name_or_path);

// A built-in scene by name, or a mesh file (is_scene_file): Wavefront OBJ (scenes/obj_loader.hpp)
// or glTF 2.0 (scenes/gltf_loader.hpp). A file gets a floor under it (scenes/ground_plane.hpp)
// unless `ground` is false; the built-in scenes have their own. Warnings (skipped parts of a glTF
// file) are printed on stderr as "warning: " lines and kept in the result.
SceneLoad load_scene(const std::string& name_or_path, bool ground = true);

// --light-size: for the rectangle, its longer side becomes `size` scene units and the aspect is
// kept (the procedural scenes' 2×2 light becomes size×size); for the sun, `size` is the angular
// diameter in degrees.
void apply_light_size(Scene& scene, Light light, double size);

// The asset decides alpha_test unless the user did (--alpha-test, --no-alpha-test, or a --config file that
// turns it on): a mesh whose materials cut (glTF MASK or BLEND, OBJ map_d) casts the shadow of its cut.
// Returns the options to run with; *note says so when it turned the cut on.
PlaygroundOptions follow_asset_cuts(PlaygroundOptions options, const Scene& scene, std::string* note);

// Fraction of geometry pixels whose visibility is below 0.5 (0 when there is no geometry).
double shadowed_fraction(const HeadlessResult& result);

// The whole headless run; returns the process exit code (0 done, 1 rendering or writing failed,
// 2 bad scene or OBJ file), messages on stderr, a summary on stdout.
int run_headless(const PlaygroundOptions& options);

} // namespace penumbra::playground
