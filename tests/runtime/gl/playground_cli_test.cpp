// penumbra-playground --headless as a user runs it: a child process per case, its exit status,
// its stderr and the files it wrote (label "gl": it renders with EGL). PENUMBRA_PLAYGROUND_PATH is
// the built executable.
#ifdef PENUMBRA_PLAYGROUND_PATH

#include "../gltf_compression_files.hpp"
#include "../gltf_test_file.hpp"
#include "../temp_dir.hpp"
#include "app/image_io.hpp"

#include <doctest/doctest.h>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

using penumbra::playground::testing::TempDir;
namespace fs = std::filesystem;

namespace {

struct Run {
    int exit_code = -1; // when the child exited
    int signal = 0;     // when a signal ended it (SIGALRM: past the timeout; SIGSEGV: a crash)
    std::string out, err;
};

std::string read_text(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Runs the playground with `args` in `dir`; SIGALRM ends it after `timeout_s`.
Run run_playground(const TempDir& dir, const std::vector<std::string>& args, unsigned timeout_s = 120) {
    const std::string out_file = dir.file("stdout.txt"), err_file = dir.file("stderr.txt");
    std::vector<char*> argv{const_cast<char*>(PENUMBRA_PLAYGROUND_PATH)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const std::string cwd = dir.file("");
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int out = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || err < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0 || ::chdir(cwd.c_str()) != 0) ::_exit(125);
        ::alarm(timeout_s); // kept across exec
        ::execv(argv[0], argv.data());
        ::_exit(126);
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {}
    Run run;
    if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
    run.out = read_text(out_file);
    run.err = read_text(err_file);
    return run;
}

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(read_text(path)); }

// Ground 6×6 at y = 0 and a 2×2 quad at y = 1.5 above it, both facing up.
const std::string small_obj = "# written by playground_cli_test\n"
                              "v -3 0 -3\nv 3 0 -3\nv 3 0 3\nv -3 0 3\n"
                              "v -1 1.5 -1\nv 1 1.5 -1\nv 1 1.5 1\nv -1 1.5 1\n"
                              "f 4 3 2 1\n"
                              "f 8 7 6 5\n";

} // namespace

TEST_CASE("playground cli: --help documents both modes and every configuration flag") {
    TempDir dir;
    const Run run = run_playground(dir, {"--help"});
    CHECK(run.exit_code == 0);
    for (const char* text : {"--headless",
                             "window",
                             "--slices",
                             "--resolution",
                             "--filter",
                             "--fusion",
                             "--packing",
                             "--light",
                             "--target",
                             "--no-leak-fix",
                             "--no-fade",
                             "--slice-placement",
                             "--config",
                             "--light-size",
                             "--light-size W[,H]",
                             "--light-center X,Y,Z",
                             "--light-normal X,Y,Z",
                             "--light-up X,Y,Z",
                             "--camera-position X,Y,Z",
                             "--camera-target X,Y,Z",
                             "--reference",
                             "--samples",
                             "--metrics",
                             "--visibility",
                             "--watch",
                             "--frames",
                             "--screenshot",
                             "--script"}) {
        CAPTURE(text);
        CHECK(run.out.find(text) != std::string::npos);
    }
}

TEST_CASE("playground cli: bad arguments exit 2 with a message naming what is allowed, and write nothing") {
    struct Case {
        std::vector<std::string> args;
        std::string expected; // in stderr
    };
    const std::vector<Case> cases{
        {{"--bogus"}, "error: unknown flag '--bogus'; allowed: --headless,"},
        {{"--headless", "--out", "a.png", "--filter", "box"},
         "error: --filter: 'box' is not allowed; allowed: mipmap, nbuffer, sat, gaussian"},
        {{"--headless", "--out", "a.png", "--scene", "nope"},
         "error: --scene: unknown scene 'nope'; allowed: planes, boxes, tree, butterfly, terrain, crowd, "
         "box, cutout, "
         "room, window, cornell, or a"},
        {{"--headless", "--scene", "planes"}, "error: --out: missing"},
        {{"--headless", "--out", "a.png", "--slices", "40"},
         "error: slices: 40 is out of range; allowed: 1 to 32, 64 or 128"},
        {{"--headless", "--out", "a.png", "--slices", "many"}, "error: --slices: 'many' is not an integer"},
        {{"--headless", "--out", "a.png", "--size", "64"}, "error: --size: '64' is not WxH"},
        {{"--headless", "--out", "a.png", "--samples", "0"},
         "error: --samples: 0 is out of range; allowed: 1 to 1024"},
        {{"--headless", "--out", "a.png", "--target", "vulkan"}, "error: --target: 'vulkan' cannot run here"},
        {{"--headless", "--out", "a.png", "--technique", "pcf", "--target", "wgsl"},
         "error: --target: 'wgsl' cannot run here"},
        {{"--headless", "--out", "a.png", "--light-size", "-1"},
         "error: --light-size: '-1' is not a positive number"},
        {{"--headless", "--out", "a.png", "--light", "sun", "--light-size", "120"}, "below 90"},
        {{"--headless", "--out", "a.png", "--light-normal", "0,0,0"},
         "error: --light-normal: '0,0,0' has zero length; allowed: a direction X,Y,Z"},
        {{"--headless", "--out", "a.png", "--light-up", "0,-0,0"},
         "error: --light-up: '0,-0,0' has zero length"},
        {{"--headless", "--out", "a.png", "--light-normal", "1,1,0", "--light-up", "-2,-2,0"},
         "error: --light-up: -0.707107,-0.707107,0 is parallel to --light-normal 0.707107,0.707107,0; "
         "allowed:"},
        {{"--headless", "--out", "a.png", "--light-size", "2,0"},
         "error: --light-size: '2,0' is not a positive number pair"},
        {{"--headless", "--out", "a.png", "--light-size=1,2,3"},
         "error: --light-size: '1,2,3' has 3 numbers; allowed: W,"},
        {{"--headless", "--out", "a.png", "--light", "sun", "--light-size", "1,2"},
         "error: --light-size: W,H sizes the rectangle light, but the light is the sun"},
        {{"--headless", "--out", "a.png", "--light", "sun", "--light-center", "0,5,0"},
         "error: --light-center: places the rectangle light, but this run's light is the sun"},
        {{"--headless", "--out", "a.png", "--light-center", "0,nan,0"},
         "error: --light-center: '0,nan,0': 'nan' is not a finite number; allowed: a point X,Y,Z"},
        {{"--headless", "--out", "a.png", "--light-normal", "0,-1"},
         "error: --light-normal: '0,-1' has 2 numbers"},
        {{"--headless", "--out", "a.png", "--camera-position", "1,inf,2"},
         "error: --camera-position: '1,inf,2': 'inf'"},
        {{"--headless", "--out", "a.png", "--camera-position", "1,2,3", "--camera-target", "1,2,3"},
         "error: --camera-target: 1,2,3 is the camera's position (--camera-position); allowed: a point "
         "other"},
        // what only the scene tells: the built-in scenes' light faces straight down
        {{"--headless", "--out", "a.png", "--scene", "planes", "--light-up", "0,1,0"},
         "error: --light-up: 0,1,0 is parallel to the scene light's normal 0,-1,0; allowed:"},
        {{"--headless", "--out", "a.png", "--error-out", "e.png"}, "error: --error-out: needs --reference"},
        {{"--headless", "--out", "a.png", "--config", "missing.json"},
         "error: --config: cannot open 'missing.json'"},
        {{"--headless", "--out", "a.png", "--filter", "gaussian"}, "error: filter: gaussian"},
        {{"--headless", "--out"}, "error: --out: missing value"},
    };
    for (const Case& c : cases) {
        TempDir dir;
        CAPTURE(c.expected);
        const Run run = run_playground(dir, c.args);
        CHECK(run.signal == 0);
        CHECK(run.exit_code == 2);
        CHECK_MESSAGE(run.err.find(c.expected) != std::string::npos, run.err);
        CHECK(!fs::exists(dir.file("a.png")));
    }
}

TEST_CASE("playground cli: --reference writes the image, the visibility, the truth, the error image and the metrics") {
    TempDir dir;
    const Run run = run_playground(dir, {"--headless", "--scene", "planes", "--size", "64x48", "--slices", "8",
                                         "--resolution", "128", "--filter", "sat", "--out", "planes.png",
                                         "--visibility", "vis.pfm", "--reference", "--samples", "4", "--metrics",
                                         "metrics.json"});
    REQUIRE_MESSAGE(run.exit_code == 0, run.err);
    CHECK(run.out.find("penumbra: MAE") != std::string::npos);
    for (const char* file :
         {"planes.png", "vis.pfm", "planes.reference.pfm", "planes.reference.oriented.pfm",
          "planes.reference.irradiance.pfm", "planes.reference.png", "planes.error.png", "metrics.json"}) {
        CAPTURE(file);
        CHECK(fs::exists(dir.file(file)));
    }
    std::string error;
    const auto visibility = penumbra::playground::read_pfm(dir.file("vis.pfm"), &error);
    const auto truth = penumbra::playground::read_pfm(dir.file("planes.reference.pfm"), &error);
    REQUIRE_MESSAGE(visibility, error);
    REQUIRE_MESSAGE(truth, error);
    CHECK(visibility->width == 64);
    CHECK(visibility->height == 48);
    CHECK(truth->pixels.size() == visibility->pixels.size());

    const nlohmann::json m = read_json(dir.file("metrics.json"));
    CHECK(m["scene"] == "planes");
    CHECK(!m["renderer"].get<std::string>().empty());
    CHECK(m["width"] == 64);
    CHECK(m["height"] == 48);
    CHECK(m["config"]["filter"] == "sat");
    CHECK(m["config"]["slices"] == 8);
    CHECK(m["reference"]["samples_per_axis"] == 4);
    // The headline is the fair reference; the whole light's numbers follow under their own name.
    CHECK(m["reference"]["headline"] == "irradiance");
    CHECK(m["reference"]["all"] == m["reference"]["irradiance"]["all"]);
    CHECK(m["reference"]["penumbra"] == m["reference"]["irradiance"]["penumbra"]);
    CHECK(m["reference"]["whole_light_visibility"]["penumbra"]["pixels"].get<int>() > 0);
    CHECK(m["reference"]["oriented"]["penumbra"]["pixels"].get<int>() > 0);
    CHECK(run.out.find("whole-light visibility:") != std::string::npos);
    CHECK(run.out.find("irradiance (the shaded image's reference") < run.out.find("  penumbra: MAE"));
    CHECK(run.out.find("false light") != std::string::npos);
    // the false light and false shadow: shares of pixels the planes scene has (lit floor, shadowed floor)
    for (const char* rate : {"false_light", "false_shadow"}) {
        CAPTURE(rate);
        const nlohmann::json& r = m["reference"][rate];
        CHECK(r["of"].get<int>() > 0);
        CHECK(r["pixels"].get<int>() <= r["of"].get<int>());
        CHECK(r["fraction"].get<double>() == doctest::Approx(r["pixels"].get<double>() / r["of"].get<double>()));
    }
    for (const char* set : {"all", "penumbra"}) {
        CAPTURE(set);
        const nlohmann::json& s = m["reference"][set];
        CHECK(s["pixels"].get<int>() > 0);
        CHECK(s["mae"].get<double>() >= 0.0);
        CHECK(s["mae"].get<double>() <= s["rmse"].get<double>());
        CHECK(s["rmse"].get<double>() <= 1.0);
        CHECK(s["p95"].get<double>() <= 1.0);
        CHECK(std::abs(s["signed"].get<double>()) <= s["mae"].get<double>() + 1e-12);
    }
    std::vector<std::string> pass_names;
    for (const nlohmann::json& pass : m["passes"]) {
        pass_names.push_back(pass["name"]);
        CHECK(pass["ms"].get<double>() >= 0.0);
    }
    REQUIRE(pass_names.size() >= 3);
    CHECK(pass_names.front() == "slicing");
    CHECK(pass_names.back() == "shading");
}

TEST_CASE("playground cli: --config is read first, flags override it; --light-size resizes the light") {
    TempDir dir;
    dir.write("shadows.json", R"({"slices": 4, "filter": "mipmap", "fusion": "additive"})");
    const Run rect = run_playground(dir, {"--headless", "--scene", "boxes", "--size", "32x32", "--config", "shadows.json",
                                          "--fusion", "maximum", "--light-size", "4", "--out", "a.png", "--metrics",
                                          "rect.json"});
    REQUIRE_MESSAGE(rect.exit_code == 0, rect.err);
    const nlohmann::json m = read_json(dir.file("rect.json"));
    CHECK(m["config"]["slices"] == 4);
    CHECK(m["config"]["filter"] == "mipmap");
    CHECK(m["config"]["fusion"] == "maximum");
    CHECK(m["light"]["width"] == doctest::Approx(4.0));
    CHECK(m["light"]["height"] == doctest::Approx(4.0));

    // metrics.json carries a "config" object, so it reproduces the run's configuration.
    const Run sun = run_playground(dir, {"--headless", "--scene", "boxes", "--size", "32x32", "--config", "rect.json",
                                         "--light", "sun", "--filter", "gaussian", "--light-size", "3", "--out",
                                         "b.png", "--metrics", "sun.json"});
    REQUIRE_MESSAGE(sun.exit_code == 0, sun.err);
    const nlohmann::json s = read_json(dir.file("sun.json"));
    CHECK(s["config"]["slices"] == 4);
    CHECK(s["config"]["light"] == "sun");
    CHECK(s["light"]["angular_diameter_degrees"] == doctest::Approx(3.0));
}

TEST_CASE(
    "playground cli: --light-* and --camera-* set the scene's light and camera; metrics.json records them") {
    TempDir dir;
    const Run run = run_playground(
        dir,
        {"--headless", "--scene",         "planes",    "--size",         "32x32",     "--slices",
         "4",          "--resolution",    "64",        "--light-center", "1,6,-0.5",  "--light-normal",
         "0,-3,-1",    "--light-up",      "0,0,-1",    "--light-size",   "3,1.5",     "--camera-position",
         "2,7,9",      "--camera-target", "0,0.5,0",   "--reference",    "--samples", "2",
         "--out",      "a.png",           "--metrics", "m.json"});
    REQUIRE_MESSAGE(run.exit_code == 0, run.err);
    const nlohmann::json m = read_json(dir.file("m.json"));
    auto vec = [](const nlohmann::json& j) {
        return glm::dvec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
    };
    auto near = [](glm::dvec3 a, glm::dvec3 b, double eps) { return glm::length(a - b) < eps; };
    const nlohmann::json& l = m["light"];
    CHECK(l["kind"] == "rect");
    CHECK(near(vec(l["center"]), {1, 6, -0.5}, 1e-12));
    CHECK(near(vec(l["normal"]), glm::normalize(glm::dvec3(0, -3, -1)), 1e-12));
    // up: (0,0,-1) projected onto the light's plane; cross(u, v) is the normal
    const glm::dvec3 n = glm::normalize(glm::dvec3(0, -3, -1));
    const glm::dvec3 up = glm::normalize(glm::dvec3(0, 0, -1) - n * glm::dot(n, glm::dvec3(0, 0, -1)));
    CHECK(near(vec(l["up"]), up, 1e-12));
    CHECK(near(glm::cross(vec(l["u_axis"]), vec(l["up"])), n, 1e-12));
    CHECK(l["width"].get<double>() == 3.0);
    CHECK(l["height"].get<double>() == 1.5);
    const nlohmann::json& c = m["camera"];
    CHECK(near(vec(c["position"]), {2, 7, 9}, 1e-4));
    CHECK(near(vec(c["target"]), {0, 0.5, 0}, 1e-6));
    CHECK(c["fov_y_degrees"].get<double>() == doctest::Approx(45.0).epsilon(1e-4));
    CHECK(m["reference"]["all"]["pixels"].get<int>() > 0); // the truth ran under that light and camera

    // One flag alone keeps the rest of the scene's: --light-size W its meaning of before (the longer side).
    const Run alone = run_playground(dir, {"--headless", "--scene", "planes", "--size", "16x16", "--slices",
                                           "4", "--resolution", "64", "--light-size", "5", "--camera-target",
                                           "0,1,0", "--out", "b.png", "--metrics", "b.json"});
    REQUIRE_MESSAGE(alone.exit_code == 0, alone.err);
    const nlohmann::json b = read_json(dir.file("b.json"));
    CHECK(near(vec(b["light"]["normal"]), {0, -1, 0}, 1e-12));
    CHECK(std::max(b["light"]["width"].get<double>(), b["light"]["height"].get<double>()) ==
          doctest::Approx(5.0));
    CHECK(near(vec(b["camera"]["target"]), {0, 1, 0}, 1e-6));
}

TEST_CASE("playground cli: an OBJ file written by the test loads and casts a shadow; a truncated one is an error") {
    TempDir dir;
    dir.write("quads.obj", small_obj);
    const Run run = run_playground(dir, {"--headless", "--scene", "quads.obj", "--size", "64x64", "--slices", "8",
                                         "--resolution", "128", "--out", "quads.png", "--metrics", "quads.json"});
    REQUIRE_MESSAGE(run.exit_code == 0, run.err);
    const nlohmann::json m = read_json(dir.file("quads.json"));
    CHECK(m["scene"] == "quads");
    CHECK(m["shadowed_fraction"].get<double>() > 0.02);
    CHECK(m["shadowed_fraction"].get<double>() < 0.8);

    // Cut in the middle of the last face: "f 8 7" has two corners.
    dir.write("cut.obj", small_obj.substr(0, small_obj.rfind(' ', small_obj.size() - 4)));
    const Run cut = run_playground(dir, {"--headless", "--scene", "cut.obj", "--out", "cut.png"});
    CHECK(cut.signal == 0);
    CHECK(cut.exit_code == 2);
    CHECK_MESSAGE(cut.err.find("cut.obj") != std::string::npos, cut.err);
    CHECK(!fs::exists(dir.file("cut.png")));

    const Run missing = run_playground(dir, {"--headless", "--scene", "absent.obj", "--out", "absent.png"});
    CHECK(missing.exit_code == 2);
    CHECK_MESSAGE(missing.err.find("absent.obj") != std::string::npos, missing.err);
}

TEST_CASE("playground cli: a .glb written by the test stands on a floor; --no-ground takes it away") {
    TempDir dir;
    dir.write("t.glb", penumbra::playground::testing::make_glb(penumbra::playground::testing::gltf_test_json(""),
                                                              penumbra::playground::testing::gltf_test_buffer()));
    double shadowed[2] = {0, 0};
    for (const bool ground : {true, false}) {
        CAPTURE(ground);
        // --no-tangent-clip: the whole light's visibility, so that a side turned from the light (which the clip
        // gives 0: it receives none) does not count as shadowed; only what casts on something does
        std::vector<std::string> args{"--headless", "--scene", "t.glb", "--size", "48x48", "--slices", "4",
                                      "--resolution", "64", "--no-tangent-clip", "--out", "t.png", "--metrics", "t.json"};
        if (!ground) args.push_back("--no-ground");
        const Run run = run_playground(dir, args);
        REQUIRE_MESSAGE(run.exit_code == 0, run.err);
        const nlohmann::json m = read_json(dir.file("t.json"));
        CHECK(m["scene"] == "t");
        CHECK(m["ground"] == ground);
        shadowed[ground] = m["shadowed_fraction"].get<double>();
    }
    // The triangles alone cast no shadow on anything the camera sees; on the floor their shadows are.
    CHECK(shadowed[0] == 0.0);
    CHECK(shadowed[1] > 0.002);
}

TEST_CASE("playground cli: a gltfpack -cc (meshopt, quantized) file renders like the OBJ it was made from") {
    namespace t = penumbra::playground::testing;
    if (!t::have_gltfpack()) {
        MESSAGE("gltfpack is not installed (scripts/setup.sh installs it): skipped");
        return;
    }
    TempDir dir;
    dir.write("torus.obj", t::torus_obj());
    REQUIRE(t::run_gltfpack(dir.file("torus.obj"), dir.file("torus.glb")));
    std::vector<penumbra::playground::FloatImage> visibility;
    std::vector<double> shadowed;
    for (const std::string scene : {"torus.obj", "torus.glb"}) {
        CAPTURE(scene);
        const Run run = run_playground(dir, {"--headless", "--scene", scene, "--size", "48x48", "--slices", "4",
                                             "--resolution", "64", "--out", scene + ".png", "--visibility",
                                             scene + ".pfm", "--metrics", scene + ".json"});
        REQUIRE_MESSAGE(run.exit_code == 0, run.err);
        std::string error;
        const auto image = penumbra::playground::read_pfm(dir.file(scene + ".pfm"), &error);
        REQUIRE_MESSAGE(image, error);
        visibility.push_back(*image);
        shadowed.push_back(read_json(dir.file(scene + ".json"))["shadowed_fraction"].get<double>());
    }
    REQUIRE(visibility[0].pixels.size() == visibility[1].pixels.size());
    double difference = 0;
    for (std::size_t i = 0; i < visibility[0].pixels.size(); ++i)
        difference += std::abs(visibility[0].pixels[i] - visibility[1].pixels[i]);
    difference /= double(visibility[0].pixels.size());
    MESSAGE("torus OBJ vs gltfpack -cc: shadowed " << shadowed[0] << " / " << shadowed[1]
                                                  << ", mean visibility difference " << difference);
    CHECK(shadowed[0] > 0.01); // the torus shadows its floor
    CHECK(std::abs(shadowed[0] - shadowed[1]) < 0.005);
    CHECK(difference < 0.01);
}

TEST_CASE("playground cli: assimp-testmodels' Draco 2CylinderEngine renders like the uncompressed .glb") {
    const std::string root = "/usr/share/assimp/models/glTF2/";
    if (!fs::is_regular_file(root + "draco/2CylinderEngine.gltf")) {
        MESSAGE("assimp-testmodels is not installed (scripts/setup.sh installs it): skipped");
        return;
    }
    TempDir dir;
    std::vector<penumbra::playground::FloatImage> visibility;
    for (const std::string scene : {"draco/2CylinderEngine.gltf", "2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}) {
        CAPTURE(scene);
        const Run run = run_playground(dir, {"--headless", "--scene", root + scene, "--size", "48x48", "--slices", "4",
                                             "--resolution", "64", "--out", "engine.png", "--visibility", "engine.pfm"});
        REQUIRE_MESSAGE(run.exit_code == 0, run.err);
        std::string error;
        const auto image = penumbra::playground::read_pfm(dir.file("engine.pfm"), &error);
        REQUIRE_MESSAGE(image, error);
        visibility.push_back(*image);
    }
    REQUIRE(visibility[0].pixels.size() == visibility[1].pixels.size());
    double difference = 0, shadow = 0;
    for (std::size_t i = 0; i < visibility[0].pixels.size(); ++i) {
        difference += std::abs(visibility[0].pixels[i] - visibility[1].pixels[i]);
        shadow += 1.0 - visibility[1].pixels[i];
    }
    difference /= double(visibility[0].pixels.size());
    MESSAGE("2CylinderEngine Draco vs .glb: mean visibility difference " << difference);
    CHECK(shadow > 1.0); // something is shadowed
    CHECK(difference < 0.01);
}

TEST_CASE("playground cli: --technique renders any technique; metrics.json has one schema, warm pass times") {
    TempDir dir;
    std::vector<nlohmann::json> all;
    for (const char* technique : {"occlusion", "shadowmap", "pcf", "pcss"}) {
        CAPTURE(technique);
        const std::string metrics = std::string(technique) + ".json";
        const Run run = run_playground(dir, {"--headless", "--scene", "boxes", "--size", "32x32", "--technique",
                                             technique, "--shadow-resolution", "256", "--reference", "--samples", "2",
                                             "--out", std::string(technique) + ".png", "--metrics", metrics});
        REQUIRE_MESSAGE(run.exit_code == 0, run.err);
        CHECK(run.out.find("(GPU ms, warm)") != std::string::npos);
        const nlohmann::json m = read_json(dir.file(metrics));
        CHECK(m["technique"] == technique);
        CHECK(m["config"]["technique"] == technique);
        CHECK(m["timing"].get<std::string>().starts_with("warm"));
        CHECK(m["texture_bytes"].get<long long>() > 0);
        CHECK(m["passes"].back()["name"] == "shading");
        if (std::string(technique) != "occlusion") CHECK(m["passes"].front()["name"] == "shadow_depth");
        all.push_back(m);
    }
    // the same keys for every technique
    auto keys = [](const nlohmann::json& j) {
        std::vector<std::string> out;
        for (const auto& [key, value] : j.items()) out.push_back(key);
        return out;
    };
    for (const nlohmann::json& m : all) {
        CHECK(keys(m) == keys(all.front()));
        CHECK(keys(m["reference"]["penumbra"]) == keys(all.front()["reference"]["penumbra"]));
    }
    // a shadow map of 256² in 32-bit depth: 256 KiB (pcss too: its blocker search reads the same map
    // through a second sampler, no copy) plus the 32×32 R32F result
    CHECK(all[1]["texture_bytes"] == 256 * 256 * 4 + 32 * 32 * 4);
    CHECK(all[3]["texture_bytes"] == 256 * 256 * 4 + 32 * 32 * 4);
    // metrics.json reproduces a technique's run
    const Run again = run_playground(dir, {"--headless", "--scene", "boxes", "--size", "32x32", "--config", "pcss.json",
                                           "--out", "again.png", "--metrics", "again.json"});
    REQUIRE_MESSAGE(again.exit_code == 0, again.err);
    CHECK(read_json(dir.file("again.json"))["config"] == all[3]["config"]);
    const Run bad = run_playground(dir, {"--headless", "--scene", "boxes", "--technique", "pcss", "--pcss-blockers",
                                         "0", "--out", "x.png"});
    CHECK(bad.exit_code == 2);
    CHECK(bad.err.find("pcss.blocker_samples: 0 is out of range") != std::string::npos);
}

// web/rooms/room.gltf (web/rooms/make_room.py) brings its EXT_lights_area ceiling panel: metrics.json
// records it; --light-* flags still win over it; a light with a bad size is exit 2 naming it, nothing
// written.
TEST_CASE("playground cli: a glTF room brings its light (EXT_lights_area); --light-* flags override it") {
    TempDir dir;
    const std::string room =
        (fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path() / "web/rooms/room.gltf")
            .string();
    REQUIRE_MESSAGE(fs::exists(room), room);
    auto vec = [](const nlohmann::json& j) {
        return glm::dvec3(j[0].get<double>(), j[1].get<double>(), j[2].get<double>());
    };
    auto near = [](glm::dvec3 a, glm::dvec3 b) { return glm::length(a - b) < 1e-6; };
    const std::vector<std::string> common{"--headless", "--scene", room,           "--size", "24x24",
                                          "--slices",   "4",       "--resolution", "64"};
    std::vector<std::string> args = common;
    args.insert(args.end(), {"--out", "room.png", "--metrics", "room.json"});
    const Run run = run_playground(dir, args);
    REQUIRE_MESSAGE(run.exit_code == 0, run.err);
    CHECK_MESSAGE(run.err.find("warning") == std::string::npos, run.err);
    const nlohmann::json m = read_json(dir.file("room.json"));
    CHECK(m["scene"] == "room");
    const nlohmann::json& l = m["light"];
    CHECK(l["kind"] == "rect");
    CHECK(near(vec(l["center"]), {0, 2.98, -0.6}));
    CHECK(near(vec(l["normal"]), {0, -1, 0}));
    CHECK(l["width"].get<double>() == doctest::Approx(1.2).epsilon(1e-9));
    CHECK(l["height"].get<double>() == doctest::Approx(0.6).epsilon(1e-9));

    // The flags are applied to the loaded scene, its light already the file's: they win.
    args = common;
    args.insert(args.end(), {"--light-center", "0.5,2.5,0", "--light-size", "1,0.8", "--out", "flags.png",
                             "--metrics", "flags.json"});
    const Run flags = run_playground(dir, args);
    REQUIRE_MESSAGE(flags.exit_code == 0, flags.err);
    const nlohmann::json f = read_json(dir.file("flags.json"))["light"];
    CHECK(near(vec(f["center"]), {0.5, 2.5, 0}));
    CHECK(near(vec(f["normal"]), {0, -1, 0})); // not given: the file's
    CHECK(f["width"].get<double>() == 1.0);
    CHECK(f["height"].get<double>() == 0.8);

    // A size of 0: one error line naming the file, the light and the field; no image.
    std::string text = read_text(room);
    const std::string size = "\"size\": 0.6";
    REQUIRE(text.find(size) != std::string::npos);
    dir.write("flat.gltf", text.replace(text.find(size), size.size(), "\"size\": 0"));
    const Run flat = run_playground(dir, {"--headless", "--scene", "flat.gltf", "--out", "flat.png"});
    CHECK(flat.signal == 0);
    CHECK(flat.exit_code == 2);
    CHECK_MESSAGE(flat.err.find("flat.gltf") != std::string::npos, flat.err);
    CHECK_MESSAGE(
        flat.err.find("EXT_lights_area light 0 'ceiling panel': size is 0; allowed: a finite number "
                      "greater than 0") != std::string::npos,
        flat.err);
    CHECK(!fs::exists(dir.file("flat.png")));
}

#endif // PENUMBRA_PLAYGROUND_PATH
