// penumbra/light_frame.hpp: the slicing camera sees the bounds, the uv formula of docs/model.md §1.
#include <penumbra/light_frame.hpp>

#include "scenes/scenes.hpp"

#include <doctest/doctest.h>

#include <optional>
#include <random>
#include <string_view>

namespace {

glm::dvec2 uv_of(const glm::mat4& clip_from_world, glm::dvec3 x) {
    const glm::dvec4 c = glm::dmat4(clip_from_world) * glm::dvec4(x, 1.0);
    return {0.5 + 0.5 * c.x / c.w, 0.5 + 0.5 * c.y / c.w};
}

penumbra::RectLight tilted_light() {
    penumbra::RectLight light;
    light.center = {0.5, 8.0, -0.3};
    light.u_axis = glm::normalize(glm::dvec3(1.0, 0.2, 0.0));
    const glm::dvec3 down = glm::normalize(glm::dvec3(0.1, -1.0, 0.05));
    light.u_axis = glm::normalize(light.u_axis - glm::dot(light.u_axis, down) * down);
    light.v_axis = glm::normalize(glm::cross(down, light.u_axis)); // cross(u, v) = down
    light.width = 2.0;
    light.height = 1.0;
    return light;
}

} // namespace

TEST_CASE("light_frame: rect light, corners inside [0,1]^2 and the uv formula") {
    for (const penumbra::RectLight& light : {penumbra::RectLight{}, tilted_light()}) {
        const glm::dvec3 lo(-5.0, 0.0, -4.0), hi(5.0, 3.0, 4.0);
        const penumbra::SliceFrame f = penumbra::slice_frame(light, lo, hi, 8);
        CHECK(f.contained);
        CHECK(f.cop_distance > 0.0f);
        bool touches = false;
        for (const glm::dvec3& c : penumbra::detail::box_corners(lo, hi)) {
            const glm::dvec2 uv = uv_of(f.slice_clip_from_world, c);
            CHECK(uv.x >= -1e-4);
            CHECK(uv.x <= 1.0 + 1e-4);
            CHECK(uv.y >= -1e-4);
            CHECK(uv.y <= 1.0 + 1e-4);
            touches = touches || std::abs(uv.x) < 1e-3 || std::abs(uv.x - 1) < 1e-3 || std::abs(uv.y) < 1e-3 ||
                      std::abs(uv.y - 1) < 1e-3;
        }
        CHECK(touches); // d is the largest: some corner is on the pyramid's side
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> dist(0.0, 1.0);
        const double d = f.cop_distance, w = light.width, h = light.height;
        for (int i = 0; i < 200; ++i) {
            const glm::dvec3 x = lo + (hi - lo) * glm::dvec3(dist(rng), dist(rng), dist(rng));
            const glm::dvec3 r = x - light.center;
            const double a = glm::dot(r, glm::normalize(light.u_axis)), b = glm::dot(r, glm::normalize(light.v_axis));
            const double z = glm::dot(r, light.normal());
            const glm::dvec3 p = glm::dvec3(glm::dmat4(f.light_from_world) * glm::dvec4(x, 1.0));
            CHECK(p.x == doctest::Approx(a).epsilon(1e-4));
            CHECK(p.y == doctest::Approx(b).epsilon(1e-4));
            CHECK(p.z == doctest::Approx(z).epsilon(1e-4));
            const glm::dvec2 uv = uv_of(f.slice_clip_from_world, x);
            CHECK(uv.x == doctest::Approx(0.5 + a * d / ((d + z) * w)).epsilon(1e-4));
            CHECK(uv.y == doctest::Approx(0.5 + b * d / ((d + z) * h)).epsilon(1e-4));
            // slice depths cover the point
            const double z0 = f.slice_depths.x, zs = z0 + 8.0 * f.slice_depths.y;
            CHECK(z >= z0 - 1e-4);
            CHECK(z <= zs + 1e-4);
        }
    }
}

TEST_CASE("light_frame: slice depths span exactly the bounds' depth range (with a tiny pad)") {
    penumbra::RectLight light; // centre (0,10,0), pointing down
    const penumbra::SliceFrame f = penumbra::slice_frame(light, {-1, 0, -1}, {1, 4, 1}, 16);
    CHECK(f.slice_depths.x == doctest::Approx(6.0).epsilon(1e-3));
    CHECK(f.slice_depths.x + 16 * f.slice_depths.y == doctest::Approx(10.0).epsilon(1e-3));
    // bounds narrower than the light: d is capped, still contained
    CHECK(f.contained);
    CHECK(f.cop_distance == doctest::Approx(2000.0));
}

TEST_CASE("light_frame: sun window covers the bounds") {
    penumbra::SunLight sun;
    sun.direction = glm::normalize(glm::dvec3(0.3, -1.0, 0.2));
    const glm::dvec3 lo(-5.0, 0.0, -4.0), hi(5.0, 3.0, 4.0);
    const penumbra::SliceFrame f = penumbra::slice_frame(sun, lo, hi, 8);
    CHECK(f.tan_angular_radius == doctest::Approx(std::tan(0.0093 / 2)));
    for (const glm::dvec3& c : penumbra::detail::box_corners(lo, hi)) {
        const glm::dvec2 uv = uv_of(f.slice_clip_from_world, c);
        CHECK(uv.x >= 0.0);
        CHECK(uv.x <= 1.0);
        CHECK(uv.y >= 0.0);
        CHECK(uv.y <= 1.0);
        const glm::dvec3 p = glm::dvec3(glm::dmat4(f.light_from_world) * glm::dvec4(c, 1.0));
        CHECK(p.z > 0.0);
        CHECK(p.z >= f.slice_depths.x - 1e-4);
        CHECK(p.z <= f.slice_depths.x + 8 * f.slice_depths.y + 1e-4);
        // the visibility snippet's mapping: uv = 0.5 + p.xy / (2 · half size)
        CHECK(uv.x == doctest::Approx(0.5 + p.x / (2.0 * f.window_half_size)).epsilon(1e-4));
    }
}

TEST_CASE("shadow_frame: rect light, the frustum holds the bounds, depth runs 0 to 1, the snippet's uv formula") {
    for (const penumbra::RectLight& light : {penumbra::RectLight{}, tilted_light()}) {
        const glm::dvec3 lo(-5.0, 0.0, -4.0), hi(5.0, 3.0, 4.0);
        const penumbra::ShadowFrame f = penumbra::shadow_frame(light, lo, hi);
        CHECK(f.contained);
        const double near = f.depth_range.x, far = f.depth_range.y;
        CHECK(near > 0.0);
        bool touches = false;
        for (const glm::dvec3& c : penumbra::detail::box_corners(lo, hi)) {
            const glm::dvec2 uv = uv_of(f.shadow_clip_from_world, c);
            CHECK(uv.x >= 0.0);
            CHECK(uv.x <= 1.0);
            CHECK(uv.y >= 0.0);
            CHECK(uv.y <= 1.0);
            touches = touches || std::abs(uv.x) < 2e-3 || std::abs(uv.x - 1) < 2e-3 || std::abs(uv.y) < 2e-3 ||
                      std::abs(uv.y - 1) < 2e-3;
            const glm::dvec3 p = glm::dvec3(glm::dmat4(f.light_from_world) * glm::dvec4(c, 1.0));
            const double stored = (p.z - near) / (far - near);
            CHECK(stored >= -1e-5);
            CHECK(stored <= 1.0 + 1e-5);
            // penumbra_shadowCoord: uv = 0.5 + xy / (2 tan_half_fov z)
            CHECK(uv.x == doctest::Approx(0.5 + p.x / (2.0 * f.tan_half_fov * p.z)).epsilon(1e-4));
            CHECK(uv.y == doctest::Approx(0.5 + p.y / (2.0 * f.tan_half_fov * p.z)).epsilon(1e-4));
        }
        CHECK(touches); // the smallest frustum that holds the bounds
        // LIGHT_SIZE_UV: the light's size on the near plane over the frustum's width there
        CHECK(f.light_size_uv.x == doctest::Approx(light.width / (2.0 * f.tan_half_fov * near)).epsilon(1e-4));
        CHECK(f.light_size_uv.y == doctest::Approx(light.height / (2.0 * f.tan_half_fov * near)).epsilon(1e-4));
    }
    penumbra::RectLight low; // bounds reach above the light plane
    low.center = {0.0, 2.0, 0.0};
    CHECK_FALSE(penumbra::shadow_frame(low, {-1, 0, -1}, {1, 4, 1}).contained);
}

TEST_CASE("shadow_frame: sun, orthographic window over the bounds, depth range of the bounds") {
    penumbra::SunLight sun;
    sun.direction = glm::normalize(glm::dvec3(0.3, -1.0, 0.2));
    sun.angular_diameter = 0.1;
    const glm::dvec3 lo(-5.0, 0.0, -4.0), hi(5.0, 3.0, 4.0);
    const penumbra::ShadowFrame f = penumbra::shadow_frame(sun, lo, hi);
    for (const glm::dvec3& c : penumbra::detail::box_corners(lo, hi)) {
        const glm::dvec2 uv = uv_of(f.shadow_clip_from_world, c);
        const glm::dvec3 p = glm::dvec3(glm::dmat4(f.light_from_world) * glm::dvec4(c, 1.0));
        CHECK(uv.x == doctest::Approx(0.5 + p.x / (2.0 * f.window_half_size)).epsilon(1e-4));
        CHECK(p.z >= f.depth_range.x);
        CHECK(p.z <= f.depth_range.y);
    }
    CHECK(f.tan_angular_radius == doctest::Approx(std::tan(0.05)));
    CHECK(f.light_size_uv.x == doctest::Approx(std::tan(0.05) / f.window_half_size).epsilon(1e-4));
}

// A ceiling panel in a closed room (docs/model.md §1.2b): the bounds reach the light's plane beside the
// light and lie behind it above. The pyramid opens no wider than max_frustum_half_angle, and still holds
// the floor's corners (they are deep enough); walls right under the ceiling lie outside it.
TEST_CASE("light_frame: a ceiling panel in a room, the pyramid's angle is capped, the floor held") {
    penumbra::RectLight panel; // 1.2 x 0.6, facing down, 2 cm under a 3 m ceiling
    panel.center = {0.0, 2.98, 0.0};
    panel.width = 1.2;
    panel.height = 0.6;
    const glm::dvec3 lo(-3.0, 0.0, -2.5), hi(3.0, 3.0, 2.5);
    const penumbra::SliceFrame f = penumbra::slice_frame(panel, lo, hi, 16);
    CHECK_FALSE(f.contained);
    const double d = f.cop_distance;
    const double half_angle = std::atan(0.5 * std::max(panel.width, panel.height) / d);
    CHECK(half_angle <= penumbra::max_frustum_half_angle + 1e-6);
    CHECK(d > 0.05); // not collapsed by the corners on the ceiling
    // the slices start at the light's plane: nothing behind it is sliced
    CHECK(f.slice_depths.x == doctest::Approx(0.0).epsilon(1e-3));
    CHECK(f.slice_depths.x + 16 * f.slice_depths.y == doctest::Approx(2.98).epsilon(1e-3));
    for (const glm::dvec3& corner : penumbra::detail::box_corners(lo, glm::dvec3(hi.x, 0.0, hi.z))) {
        const glm::dvec2 uv = uv_of(f.slice_clip_from_world, corner); // the floor's corners
        CHECK(uv.x >= -1e-4);
        CHECK(uv.x <= 1.0 + 1e-4);
        CHECK(uv.y >= -1e-4);
        CHECK(uv.y <= 1.0 + 1e-4);
    }
    const glm::dvec2 wall_top = uv_of(f.slice_clip_from_world, {3.0, 2.9, 0.0}); // beside the light, outside
    CHECK(wall_top.x > 1.0);
}

TEST_CASE("light_frame: bounds whose top meets the light's plane do not collapse the pyramid") {
    penumbra::RectLight panel; // at the very top of the bounds: corners at depth +1e-9 beside the light
    panel.center = {0.0, 3.0 + 1e-9, 0.0};
    const glm::dvec3 lo(-3.0, 0.0, -3.0), hi(3.0, 3.0, 3.0);
    const penumbra::SliceFrame f = penumbra::slice_frame(panel, lo, hi, 16);
    CHECK_FALSE(f.contained);
    CHECK(f.cop_distance == doctest::Approx(1.0 / std::tan(penumbra::max_frustum_half_angle)).epsilon(1e-6));
    const penumbra::ShadowFrame s = penumbra::shadow_frame(panel, lo, hi);
    CHECK_FALSE(s.contained);
    CHECK(s.tan_half_fov == doctest::Approx(std::tan(penumbra::max_frustum_half_angle)).epsilon(1e-6));
    // a light above the scene is not affected by the cap: the default light over the built-in frame
    const penumbra::SliceFrame above =
        penumbra::slice_frame(penumbra::RectLight{}, {-5, 0, -5}, {5, 3, 5}, 16);
    CHECK(above.contained);
    CHECK(std::atan(1.0 / above.cop_distance) < penumbra::max_frustum_half_angle - 0.2);
}

// Light above a scene never reaches the pyramid's cap, so rooms leave every built-in scene's slicing as it
// was.
TEST_CASE("light_frame: every built-in scene, its light x1 to x32, stays inside the capped angle") {
    for (std::string_view name : penumbra::playground::scene_names()) {
        const std::optional<penumbra::playground::Scene> scene = penumbra::playground::make_scene(name);
        REQUIRE(scene);
        for (double scale : {1.0, 2.0, 4.0, 8.0, 16.0, 32.0}) {
            penumbra::RectLight light = scene->light;
            light.width *= scale;
            light.height *= scale;
            const penumbra::SliceFrame f =
                penumbra::slice_frame(light, scene->bounds_min, scene->bounds_max, 16);
            CAPTURE(name);
            CAPTURE(scale);
            CHECK(f.contained);
            CHECK(std::atan(0.5 * std::max(light.width, light.height) / f.cop_distance) <
                  penumbra::max_frustum_half_angle - 0.1);
            CHECK(penumbra::shadow_frame(light, scene->bounds_min, scene->bounds_max).contained);
        }
    }
}
