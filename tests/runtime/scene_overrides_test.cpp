// The light and camera of the command line (playground/src/app/scene_overrides.hpp): --light-center,
// --light-normal, --light-up, --light-size W[,H], --camera-position, --camera-target, parsed, checked
// and set on a scene as penumbra-playground and the GL benchmarks do. In-process, no GL.
#include "app/scene_overrides.hpp"
#include "scenes/scenes.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace penumbra::playground;

namespace {

// Parses `flag value` pairs into overrides; the first message, or "".
std::string parse_all(const std::vector<std::pair<std::string, std::string>>& flags, SceneOverrides& o) {
    for (const auto& [flag, value] : flags) {
        REQUIRE(is_scene_override_flag(flag));
        if (std::string e = parse_scene_override(flag, value, o); !e.empty()) return e;
    }
    return check_scene_overrides(o);
}

void check_vec(glm::dvec3 a, glm::dvec3 b, double eps = 1e-9) {
    CAPTURE(a.x);
    CAPTURE(a.y);
    CAPTURE(a.z);
    CHECK(glm::length(a - b) < eps);
}

Scene boxes() {
    std::optional<Scene> scene = make_scene("boxes");
    REQUIRE(scene);
    return std::move(*scene);
}

} // namespace

TEST_CASE("scene overrides: the light's normal, up and sides are the flags'; cross(u, v) is the normal") {
    SceneOverrides o;
    REQUIRE(parse_all({{"--light-center", "1,7.5,-2"},
                       {"--light-normal", "0,-2,-2"},
                       {"--light-up", "0,1,0"},
                       {"--light-size", "3,1.5"}},
                      o)
                .empty());
    Scene scene = boxes();
    REQUIRE(apply_scene_overrides(o, scene, penumbra::Light::rect).empty());
    const penumbra::RectLight& l = scene.light;
    const glm::dvec3 n = glm::normalize(glm::dvec3(0, -1, -1));
    check_vec(l.center, {1, 7.5, -2});
    check_vec(l.normal(), n);
    check_vec(glm::cross(l.u_axis, l.v_axis), n); // exactly the normal, not its opposite
    CHECK(std::abs(glm::length(l.u_axis) - 1.0) < 1e-12);
    CHECK(std::abs(glm::length(l.v_axis) - 1.0) < 1e-12);
    CHECK(std::abs(glm::dot(l.u_axis, l.v_axis)) < 1e-12);
    // v is +y projected onto the light's plane: up and towards +z here
    check_vec(l.v_axis, glm::normalize(glm::dvec3(0, 1, -1)));
    CHECK(l.width == 3.0);
    CHECK(l.height == 1.5);
}

TEST_CASE("scene overrides: without --light-up the scene's v is kept when it can be, else +y, else +z") {
    Scene scene = boxes();
    const glm::dvec3 scene_v = scene.light.v_axis;
    SceneOverrides tilted;
    REQUIRE(parse_all({{"--light-normal", "0.2,-1,0"}}, tilted).empty());
    REQUIRE(apply_scene_overrides(tilted, scene, penumbra::Light::rect).empty());
    check_vec(scene.light.normal(), glm::normalize(glm::dvec3(0.2, -1, 0)));
    CHECK(glm::dot(scene.light.v_axis, scene_v) > 0.99); // the scene's (0,0,1) is already in the plane

    // Facing along the scene's v: +y is the up side.
    Scene facing = boxes();
    SceneOverrides along_v;
    REQUIRE(parse_all({{"--light-normal", "0,0,1"}}, along_v).empty());
    REQUIRE(apply_scene_overrides(along_v, facing, penumbra::Light::rect).empty());
    check_vec(facing.light.normal(), {0, 0, 1});
    check_vec(facing.light.v_axis, {0, 1, 0});

    // The light's own v and +y both parallel to the normal: +z.
    Scene straight = boxes();
    straight.light.u_axis = {1, 0, 0};
    straight.light.v_axis = {0, 1, 0}; // a light that emits along +z; now asked to face up
    SceneOverrides up;
    REQUIRE(parse_all({{"--light-normal", "0,3,0"}}, up).empty());
    REQUIRE(apply_scene_overrides(up, straight, penumbra::Light::rect).empty());
    check_vec(straight.light.normal(), {0, 1, 0});
    check_vec(straight.light.v_axis, {0, 0, 1});
}

TEST_CASE("scene overrides: --light-size W keeps its meaning, W,H sets both sides") {
    Scene scene = boxes();
    scene.light.width = 4.0;
    scene.light.height = 2.0;
    SceneOverrides one;
    REQUIRE(parse_all({{"--light-size", "6"}}, one).empty());
    REQUIRE(apply_scene_overrides(one, scene, penumbra::Light::rect).empty());
    CHECK(scene.light.width == doctest::Approx(6.0)); // the longer side, aspect kept
    CHECK(scene.light.height == doctest::Approx(3.0));
    SceneOverrides sun;
    REQUIRE(parse_all({{"--light-size", "2"}}, sun).empty());
    REQUIRE(apply_scene_overrides(sun, scene, penumbra::Light::sun).empty());
    CHECK(scene.sun.angular_diameter == doctest::Approx(2.0 * 3.14159265358979323846 / 180.0));
    CHECK(scene.light.width == doctest::Approx(6.0)); // the sun's size leaves the rectangle alone
}

TEST_CASE(
    "scene overrides: the camera looks from --camera-position at --camera-target; either alone keeps the "
    "scene's other") {
    Scene scene = boxes();
    const glm::vec3 scene_eye = scene.camera.eye_position();
    const glm::vec3 scene_target = scene.camera.target;
    SceneOverrides both;
    REQUIRE(parse_all({{"--camera-position", "3,4,12"}, {"--camera-target", "0,1,0"}}, both).empty());
    Scene a = scene;
    REQUIRE(apply_scene_overrides(both, a, penumbra::Light::rect).empty());
    check_vec(glm::dvec3(a.camera.eye_position()), {3, 4, 12}, 1e-4);
    check_vec(glm::dvec3(a.camera.target), {0, 1, 0}, 1e-6);
    CHECK(a.camera.z_far > glm::length(glm::vec3(3, 4, 12))); // the scene stays inside the far plane

    SceneOverrides position;
    REQUIRE(parse_all({{"--camera-position", "-5,6,7"}}, position).empty());
    Scene b = scene;
    REQUIRE(apply_scene_overrides(position, b, penumbra::Light::rect).empty());
    check_vec(glm::dvec3(b.camera.eye_position()), {-5, 6, 7}, 1e-4);
    check_vec(glm::dvec3(b.camera.target), glm::dvec3(scene_target), 1e-6);

    SceneOverrides target;
    REQUIRE(parse_all({{"--camera-target", "1,0,1"}}, target).empty());
    Scene c = scene;
    REQUIRE(apply_scene_overrides(target, c, penumbra::Light::rect).empty());
    check_vec(glm::dvec3(c.camera.eye_position()), glm::dvec3(scene_eye), 1e-4);
    check_vec(glm::dvec3(c.camera.target), {1, 0, 1}, 1e-6);

    // Straight above: a finite view, 0.1 degrees off the vertical.
    SceneOverrides above;
    REQUIRE(parse_all({{"--camera-position", "0,10,0"}, {"--camera-target", "0,0,0"}}, above).empty());
    Scene d = scene;
    REQUIRE(apply_scene_overrides(above, d, penumbra::Light::rect).empty());
    const glm::mat4 view = d.camera.view_matrix();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) CHECK(std::isfinite(view[i][j]));
    check_vec(glm::dvec3(d.camera.eye_position()), {0, 10, 0}, 0.02);
}

TEST_CASE("scene overrides: bad values name the flag and what is allowed") {
    struct Case {
        std::vector<std::pair<std::string, std::string>> flags;
        std::string expected;
    };
    const std::vector<Case> cases{
        {{{"--light-normal", "0,0,0"}},
         "--light-normal: '0,0,0' has zero length; allowed: a direction X,Y,Z"},
        {{{"--light-up", "0,0,0"}}, "--light-up: '0,0,0' has zero length; allowed:"},
        {{{"--light-normal", "0,-1,0"}, {"--light-up", "0,2,0"}},
         "--light-up: 0,1,0 is parallel to --light-normal 0,-1,0; allowed: a direction at least 0.06 degrees "
         "off"},
        {{{"--light-size", "0"}}, "--light-size: '0' is not a positive number; allowed: W,"},
        {{{"--light-size", "-1"}}, "--light-size: '-1' is not a positive number"},
        {{{"--light-size", "2,-1"}}, "--light-size: '2,-1' is not a positive number pair; allowed:"},
        {{{"--light-size", "1,2,3"}}, "--light-size: '1,2,3' has 3 numbers; allowed: W,"},
        {{{"--light-size", "nan"}}, "--light-size: 'nan' is not a positive number"},
        {{{"--light-size", "1,inf"}}, "--light-size: '1,inf': 'inf' is not a finite number; allowed:"},
        {{{"--light-center", "nan,0,0"}},
         "--light-center: 'nan,0,0': 'nan' is not a finite number; allowed: a point X,Y,Z"},
        {{{"--light-center", "1,2"}},
         "--light-center: '1,2' has 2 numbers; allowed: a point X,Y,Z, three finite"},
        {{{"--light-center", "1,2,3,4"}}, "--light-center: '1,2,3,4' has 4 numbers"},
        {{{"--light-center", "1e10,0,0"}},
         "--light-center: '1e10,0,0' is out of range; allowed: a point X,Y,Z"},
        {{{"--light-normal", "1,,0"}}, "--light-normal: '1,,0': '' is not a finite number"},
        {{{"--light-normal", "0,-inf,0"}}, "--light-normal: '0,-inf,0': '-inf' is not a finite number"},
        {{{"--camera-position", "x,1,2"}},
         "--camera-position: 'x,1,2': 'x' is not a finite number; allowed: a point"},
        {{{"--camera-position", "1,2,3"}, {"--camera-target", "1,2,3"}},
         "--camera-target: 1,2,3 is the camera's position (--camera-position); allowed: a point other than "
         "the "
         "position"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.expected);
        SceneOverrides o;
        const std::string error = parse_all(c.flags, o);
        CHECK_MESSAGE(error.rfind(c.expected, 0) == 0, error);
    }

    // What only the scene tells: --light-up parallel to its light's normal, a position at its camera's
    // target.
    Scene scene = boxes();
    SceneOverrides up;
    REQUIRE(parse_all({{"--light-up", "0,1,0"}}, up).empty()); // the boxes' light faces straight down
    const penumbra::RectLight before = scene.light;
    CHECK(apply_scene_overrides(up, scene, penumbra::Light::rect)
              .rfind("--light-up: 0,1,0 is parallel to the scene "
                     "light's normal 0,-1,0",
                     0) == 0);
    check_vec(scene.light.u_axis, before.u_axis); // left as it was
    SceneOverrides at_target;
    scene.camera.target = {0.0f, 0.5f, -1.0f};
    REQUIRE(parse_all({{"--camera-position", "0,0.5,-1"}}, at_target).empty());
    CHECK(apply_scene_overrides(at_target, scene, penumbra::Light::rect).rfind("--camera-position: ", 0) ==
          0);
}
