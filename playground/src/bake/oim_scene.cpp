// playground/src/bake/oim_scene.cpp
#include "bake/oim_scene.hpp"

#include "scenes/charts.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/uv_coverage.hpp"

#include <penumbra/detail/oim/emit_oim.hpp>

#include <charconv>
#include <cmath>

namespace penumbra::playground {

OimBakeSettings oim_bake_settings(const penumbra::Config& config, const penumbra::SunPath& path) {
    OimBakeSettings settings;
    settings.resolution = config.oim.resolution;
    settings.intervals = config.oim.intervals;
    settings.samples = config.oim.samples;
    settings.path = path;
    return settings;
}

glm::vec4 oim_time_window(const penumbra::SunPath& path, double t, double angular_diameter) {
    const penumbra::SunWindow w = penumbra::sun_window(path, t, angular_diameter);
    return {static_cast<float>(w.start), static_cast<float>(w.end), static_cast<float>(w.inverse_width),
            static_cast<float>(t)};
}

std::optional<OimSetup> prepare_oim(Scene& scene, const penumbra::Config& config, const penumbra::SunPath& path,
                                    double t, const std::filesystem::path& cache_dir, std::string* error) {
    auto fail = [&](std::string message) {
        if (error) *error = std::move(message);
        return std::nullopt;
    };
    if (const std::vector<penumbra::ConfigError> problems = penumbra::validate(path); !problems.empty())
        return fail(problems.front().message);
    if (!(t >= 0.0 && t <= 1.0)) return fail("--sun-time: " + std::to_string(t) + " is out of range; allowed: 0 to 1");
    const int R = config.oim.resolution;
    if (scene.generated_charts) {
        if (std::string problem = generate_charts(scene.mesh, R); !problem.empty())
            return fail("scene '" + scene.name + "': " + problem);
    } else if (std::string problem = check_unique_uvs(scene.mesh, R); !problem.empty()) {
        return fail("scene '" + scene.name + "' " + problem +
                    "; occlusion interval maps need unique texture coordinates (no automatic parameterization)");
    }
    scene.sun.direction = -penumbra::sun_direction(path, t);

    OimSetup setup;
    // alpha_test: the bake's rays pass where the cut materials are cut; off, the casters are solid
    setup.cached = bake_with_cache(config.alpha_test ? scene.mesh : without_cuts(scene.mesh),
                                   oim_bake_settings(config, path), cache_dir);
    for (int p = 0; p < penumbra::oim_pairs(config.oim); ++p) {
        setup.textures.push_back({penumbra::detail::oim_rise_name(p).str(), setup.cached.bake.texture(p, false)});
        setup.textures.push_back({penumbra::detail::oim_fall_name(p).str(), setup.cached.bake.texture(p, true)});
    }
    setup.time_window = oim_time_window(path, t, scene.sun.angular_diameter);
    return setup;
}

std::optional<penumbra::SunPath> parse_sun_path(const std::string& text, std::string* error) {
    penumbra::SunPath path{{}};
    const std::string bad = "--sun-path: '" + text +
                            "' is not a list of AZIMUTH:ELEVATION pairs; allowed: degrees, e.g. 100:10,180:50,260:10";
    std::size_t start = 0;
    while (start <= text.size() && !text.empty()) {
        const std::size_t end = std::min(text.find(',', start), text.size());
        const std::string item = text.substr(start, end - start);
        const std::size_t colon = item.find(':');
        double az = 0.0, el = 0.0;
        if (colon == std::string::npos) {
            if (error) *error = bad;
            return std::nullopt;
        }
        const char* a = item.data();
        const auto [pa, ea] = std::from_chars(a, a + colon, az);
        const auto [pe, ee] = std::from_chars(a + colon + 1, a + item.size(), el);
        if (ea != std::errc() || pa != a + colon || ee != std::errc() || pe != a + item.size()) {
            if (error) *error = bad;
            return std::nullopt;
        }
        path.points.push_back({az, el});
        start = end + 1;
    }
    if (const std::vector<penumbra::ConfigError> problems = penumbra::validate(path); !problems.empty()) {
        if (error) *error = "--sun-path: " + problems.front().message;
        return std::nullopt;
    }
    return path;
}

} // namespace penumbra::playground
