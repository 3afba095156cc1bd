// playground/src/bake/oim_scene.hpp — a scene made ready for occlusion interval maps: unique texture
// coordinates (generated charts for the procedural scenes, the file's own for an OBJ), the sun at
// time t of its path, the bake (from the disk cache when it has it) and the textures the layout
// marks "bake", by name.
#pragma once

#include "bake/oim_cache.hpp"
#include "scenes/scene.hpp"

#include <penumbra/config.hpp>
#include <penumbra/sun_path.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace penumbra::playground {

struct OimSetup {
    CachedBake cached;
    std::vector<std::pair<std::string, std::vector<float>>> textures; // penumbra_rise0, penumbra_fall0, …: RGBA
    glm::vec4 time_window{0.0f};                                       // penumbra_timeWindow
};

// Bake settings of a configuration and a path.
OimBakeSettings oim_bake_settings(const penumbra::Config& config, const penumbra::SunPath& path);

// Gives `scene` unique texture coordinates and puts its sun at `t` (scene.sun.direction), then bakes
// or reads the cache in `cache_dir`. Nothing with *error set (one line) when the path is invalid, t
// lies outside [0, 1] or the mesh has no usable parameterization.
std::optional<OimSetup> prepare_oim(Scene& scene, const penumbra::Config& config, const penumbra::SunPath& path,
                                    double t, const std::filesystem::path& cache_dir, std::string* error);

// The window for t and the sun's current angular diameter, as penumbra_timeWindow.
glm::vec4 oim_time_window(const penumbra::SunPath& path, double t, double angular_diameter);

// "AZ:EL,AZ:EL,…" in degrees (penumbra-playground --sun-path); nothing with *error on bad text.
std::optional<penumbra::SunPath> parse_sun_path(const std::string& text, std::string* error);

} // namespace penumbra::playground
