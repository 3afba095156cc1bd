// Every case of issue 13 ("hostile input never breaks the promise") as a regression test: exit 2,
// exactly one `error:` line naming what is wrong and what is allowed, nothing written, never a
// crash, a hang or a partial file (label "hostile").
#include "child_process.hpp"

#include "../runtime/gltf_compression_files.hpp"
#include "../window/virtual_display.hpp"

#include <penumbra_tools/printable.hpp>
#include "shader_diagnostics.hpp"
#include "shader_folder.hpp"
#include "script.hpp"

#include <doctest/doctest.h>

#include <sys/mount.h>
#include <sys/stat.h>

#include <fstream>
#include <map>
#include <thread>

namespace {
namespace fs = std::filesystem;
using hostile::ChildLimits;
using hostile::ChildRun;
using hostile::run_child;

const std::string gen = hostile::tool_path("PENUMBRA_TEST_GEN", PENUMBRA_GEN_PATH);
const std::string playground = hostile::tool_path("PENUMBRA_TEST_PLAYGROUND", PENUMBRA_PLAYGROUND_PATH);

hostile::Scratch& scratch() {
    static hostile::Scratch s("hostile-cases");
    return s;
}

std::map<std::string, std::string> contents(const fs::path& dir) {
    std::map<std::string, std::string> out;
    if (!fs::exists(dir)) return out;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
        out[e.path().filename().string()] = e.is_regular_file() ? hostile::read_capped(e.path(), 64u << 20) : "<dir>";
    return out;
}

// The promise for a rejected run.
void check_rejected(const ChildRun& run, const std::string& expected) {
    CAPTURE(run.err);
    CHECK(run.signal == 0);
    CHECK(run.exit_code == 2);
    CHECK(run.error_lines() == 1);
    CHECK(run.first_error_line().find(expected) != std::string::npos);
    CHECK(run.out.find("wrote") == std::string::npos);
    CHECK_FALSE(run.sanitizer_report());
}

struct Inputs {
    fs::path dir, fifo, sparse, config_1e309, config_two_errors, script_nul;
    Inputs() {
        dir = scratch().fresh("a-directory");
        fs::create_directories(dir);
        fifo = scratch().fresh("fifo");
        REQUIRE(::mkfifo(fifo.c_str(), 0666) == 0);
        sparse = scratch().write("sparse", "");
        fs::resize_file(sparse, std::uintmax_t(2) << 30); // 2 GiB of holes: no disk used
        config_1e309 = scratch().write("overflow.json", R"({"slices": 1e309})");
        config_two_errors = scratch().write("two.json", R"({"slices": 65, "resolution": 500})");
        script_nul = scratch().write("nul.script", std::string("jump\0\x01\xff", 7));
    }
};
Inputs& inputs() {
    static Inputs i;
    return i;
}

fs::path obj(const std::string& text) { return scratch().write("mesh.obj", text); }
fs::path script(const std::string& text) { return scratch().write("s.script", text); }

} // namespace

TEST_CASE("hostile: unbounded and blocking inputs are refused at once") {
    const Inputs& in = inputs();
    struct Case {
        const char* name;
        const std::string* tool;
        std::vector<std::string> args;
        std::string expected;
    };
    const fs::path out = scratch().fresh("never");
    const fs::path png = scratch().fresh("never.png");
    const std::vector<Case> cases{
        {"gen config /dev/zero", &gen, {"--config", "/dev/zero"}, "'/dev/zero': it is a character device"},
        {"gen config /dev/urandom", &gen, {"--config", "/dev/urandom"}, "it is a character device, not a regular file; allowed: a regular file of at most 1 MiB"},
        {"gen config FIFO", &gen, {"--config", in.fifo.string()}, "it is a FIFO"},
        {"gen config directory", &gen, {"--config", in.dir.string()}, "it is a directory"},
        {"gen config 2 GiB sparse", &gen, {"--config", in.sparse.string()}, "it has 2147483648 bytes; allowed: a regular file of at most 1 MiB"},
        {"playground config /dev/zero", &playground, {"--headless", "--config", "/dev/zero", "--out", png.string()}, "character device"},
        {"playground config FIFO", &playground, {"--headless", "--config", in.fifo.string(), "--out", png.string()}, "it is a FIFO"},
        {"script /dev/zero", &playground, {"--script", "/dev/zero"}, "--script: cannot read '/dev/zero': it is a character device"},
        {"script FIFO", &playground, {"--script", in.fifo.string()}, "it is a FIFO"},
        {"script directory", &playground, {"--script", in.dir.string()}, "it is a directory"},
        {"script sparse", &playground, {"--script", in.sparse.string()}, "allowed: a regular file of at most 1 MiB"},
        {"obj /dev/zero", &playground, {"--headless", "--scene", [&] { fs::path p = scratch().fresh("zero.obj"); fs::create_symlink("/dev/zero", p); return p.string(); }(), "--out", png.string()}, "it is a character device"},
        {"obj sparse", &playground, {"--headless", "--scene", [&] { fs::path p = in.sparse; p += ".obj"; fs::create_symlink(in.sparse, p); return p.string(); }(), "--out", png.string()}, "allowed: a regular file of at most 256 MiB"},
        {"obj FIFO via link", &playground, {"--headless", "--scene", [&] { fs::path p = in.fifo; p += "-link.obj"; fs::create_symlink(in.fifo, p); return p.string(); }(), "--out", png.string()}, "it is a FIFO"},
        {"obj directory", &playground, {"--headless", "--scene", [&] { fs::path p = scratch().fresh("dir.obj"); fs::create_directories(p); return p.string(); }(), "--out", png.string()}, "it is a directory"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.name);
        std::vector<std::string> args = c.args;
        if (c.tool == &gen) args.insert(args.end(), {"--out", out.string()});
        const auto start = std::chrono::steady_clock::now();
        const ChildRun run = run_child(*c.tool, args, {.timeout_s = 10});
        CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(3));
        check_rejected(run, c.expected);
        CHECK_FALSE(fs::exists(out));
        CHECK_FALSE(fs::exists(png));
    }
}

TEST_CASE("hostile: numbers out of range name the key or flag and the allowed range") {
    const Inputs& in = inputs();
    const fs::path out = scratch().fresh("never");
    const fs::path png = scratch().fresh("never.png");
    struct Case {
        const char* name;
        const std::string* tool;
        std::vector<std::string> args;
        std::string expected;
    };
    const std::vector<Case> cases{
        {"config 1e309", &gen, {"--config", in.config_1e309.string(), "--out", out.string()}, "key 'slices': 1e309 is out of range; allowed: 1 to 32, 64 or 128"},
        {"config 1e309 playground", &playground, {"--headless", "--config", in.config_1e309.string(), "--out", png.string()}, "key 'slices': 1e309 is out of range; allowed: 1 to 32, 64 or 128"},
        {"config two errors, one line", &gen, {"--config", in.config_two_errors.string(), "--out", out.string()}, "slices: 65 is out of range; allowed: 1 to 32, 64 or 128; resolution: 500"},
        {"flags two errors, one line", &gen, {"--slices", "0", "--resolution", "7", "--out", out.string()}, "slices: 0 is out of range"},
        {"size 99999x99999", &playground, {"--headless", "--size", "99999x99999", "--out", png.string()}, "--size: 99999x99999 is out of range; allowed: two integers 1 to 8192"},
        {"size 0x16", &playground, {"--headless", "--size", "0x16", "--out", png.string()}, "--size: 0x16 is out of range"},
        {"size not WxH", &playground, {"--headless", "--size", "16by16", "--out", png.string()}, "'16by16' is not WxH"},
        {"light-size 1e30 sun", &playground, {"--headless", "--light", "sun", "--filter", "gaussian", "--light-size", "1e30", "--out", png.string()}, "--light-size: 1e+30 degrees is too wide for the sun; allowed: an angular diameter above 0 and below 90"},
        {"light-size nan", &playground, {"--headless", "--light-size", "nan", "--out", png.string()}, "is not a positive number"},
    };
    for (const Case& c : cases) {
        CAPTURE(c.name);
        check_rejected(run_child(*c.tool, c.args), c.expected);
        CHECK_FALSE(fs::exists(out));
        CHECK_FALSE(fs::exists(png));
    }
}

TEST_CASE("hostile: bad meshes are errors with the file and the line") {
    const fs::path png = scratch().fresh("never.png");
    const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    const std::vector<std::pair<std::string, std::string>> cases{
        {"v 3e38 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", ":1: "},
        {tri + "f 1 2 99999999999999999999\n", "line 4: vertex index '99999999999999999999' is out of range"},
        {"v nan 1 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 1: x coordinate 'nan' is out of range; allowed: finite numbers within"},
        {"v 0 0 0\nv a b c\nv 0 1 0\nf 1 2 3\n", "line 2: x coordinate 'a' is not a number"},
        {tri + "v inf 0 0\nf 1 2 3\n", "line 4: x coordinate 'inf' is out of range"},
        {tri + "f 1 2 3x\n", "line 4: vertex index '3x' is not an integer"},
        {tri + "vn 0 1e999 0\nf 1//1 2//1 3//1\n", "line 4: y of the normal '1e999' is out of range"},
        {tri + "f 1 2 -9\n", "line 4: the face has a relative vertex index -9 that points before the first vertex"},
        {"v 1 2\nf 1 1 1\n", "line 1: 'v' needs 3 numbers"},
    };
    for (const auto& [text, expected] : cases) {
        CAPTURE(text);
        const fs::path file = obj(text);
        const ChildRun run = run_child(playground, {"--headless", "--scene", file.string(), "--out", png.string()});
        std::string where = expected;
        if (where == ":1: ") where = "line 1: x coordinate '3e38' is out of range; allowed: finite numbers within ±1e9";
        check_rejected(run, where);
        CHECK(run.first_error_line().find(file.string()) != std::string::npos);
        CHECK_FALSE(fs::exists(png));
    }
}

// Debian's assimp-testmodels ships glTF files written to break importers (scripts/setup.sh
// installs it; without it this case says so). Through the tool: exit 2, one line, no image.
TEST_CASE("hostile: glTF files written to break importers are one error line") {
    const fs::path root = "/usr/share/assimp/models/glTF2";
    if (!fs::is_directory(root)) {
        MESSAGE("assimp-testmodels is not installed (scripts/setup.sh installs it): skipped");
        return;
    }
    const fs::path png = scratch().fresh("never.png");
    const std::vector<std::pair<std::string, std::string>> cases{
        {"IndexOutOfRange/IndexOutOfRange.gltf", "mesh 0 primitive 0's index 0 is 255 but it has 24 vertices"},
        {"BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "position 0 is not a finite number"},
        {"RecursiveNodes/RecursiveNodes.gltf", "node 0 is its own ancestor"},
        {"MissingBin/BoxTextured.gltf", "BoxTextured0.bin' does not exist"},
        {"IncorrectVertexArrays/Cube.gltf", "not a multiple of 3"},
    };
    for (const auto& [file, expected] : cases) {
        CAPTURE(file);
        const fs::path path = root / file;
        const ChildRun run = run_child(playground, {"--headless", "--scene", path.string(), "--out", png.string()});
        check_rejected(run, expected);
        CHECK(run.first_error_line().find(path.string()) != std::string::npos);
        CHECK_FALSE(fs::exists(png));
    }
}

// Compressed glTF whose streams lie (tests/runtime/gltf_compression_files.hpp: Draco cut short or
// with a wrong attribute id, meshopt counts and strides that lie, sizes past the 64 Mi vertex
// limit): exit 2, one line naming the file and the stream, no image.
TEST_CASE("hostile: broken Draco and meshopt streams are one error line") {
    const std::filesystem::path dir = scratch().fresh("compressed");
    std::filesystem::create_directories(dir);
    const std::vector<penumbra::playground::testing::BrokenCompressedFile> cases =
        penumbra::playground::testing::broken_compressed_files(dir.string());
    if (cases.empty()) {
        MESSAGE("gltfpack or assimp-testmodels is not installed (scripts/setup.sh installs them): skipped");
        return;
    }
    const fs::path png = scratch().fresh("never.png");
    for (const auto& c : cases) {
        CAPTURE(c.name);
        const ChildRun run = run_child(playground, {"--headless", "--scene", c.path, "--out", png.string()});
        check_rejected(run, c.expected);
        CHECK(run.first_error_line().find(c.path) != std::string::npos);
        CHECK_FALSE(fs::exists(png));
    }
}

TEST_CASE("hostile: window scripts that could never end are parse errors") {
    const std::vector<std::pair<std::string, std::string>> cases{
        {"wait 2147483648", "wait: 2147483648 is out of range; allowed: a whole number of frames from 0 to 1000000"},
        {"wait 1e30", "wait: 1e30 is out of range"},
        {"wait nan", "wait: 'nan' is out of range; allowed: finite numbers"},
        {"wait inf", "wait: 'inf' is out of range"},
        {"wait -1", "wait: -1 is out of range"},
        {"wait 2.5", "wait: 2.5 is out of range; allowed: a whole number"},
        {"wait_reload 1e10", "wait_reload: 1e10 is out of range; allowed: 0 to 600 seconds"},
        {"wait_reload -1", "wait_reload: -1 is out of range"},
        {"wait_reload nan", "wait_reload: 'nan' is out of range"},
        {"light 1 nan 2", "light: 'nan' is out of range"},
        {"camera 1e999 0", "camera: '1e999' is out of range"},
        {std::string("jump\0\x01\xff", 7), "unknown action 'jump\\x00\\x01\\xff'"},
        {std::string("answer \x1b[2J"), "answer: '\\x1b[2J' is not allowed"},
    };
    for (const auto& [text, expected] : cases) {
        CAPTURE(text);
        const penumbra::playground::ScriptParse parsed = penumbra::playground::parse_script(text, "s.txt");
        CHECK(parsed.actions.empty());
        CHECK(parsed.error.find(expected) != std::string::npos);
        CHECK(parsed.error.find('\0') == std::string::npos);
        // The same through the tool: exit 2 before any window is opened.
        check_rejected(run_child(playground, {"--script", script(text).string()}), expected);
    }
}

TEST_CASE("hostile: penumbra-gen output is all or nothing") {
    SUBCASE("layout.json is a directory: nothing of the 9 other files is left") {
        const fs::path dir = scratch().fresh("out");
        fs::create_directories(dir / "layout.json");
        const ChildRun run = run_child(gen, {"--out", dir.string()});
        check_rejected(run, "cannot write '" + (dir / "layout.json").string() + "': it is a directory");
        CHECK(contents(dir) == std::map<std::string, std::string>{{"layout.json", "<dir>"}});
    }
    SUBCASE("a file in the middle is a directory: the previous emission stays as it was") {
        const fs::path dir = scratch().fresh("out");
        REQUIRE(run_child(gen, {"--out", dir.string()}).exit_code == 0);
        fs::remove(dir / "penumbra_shading.frag");
        fs::create_directories(dir / "penumbra_shading.frag");
        const auto before = contents(dir);
        check_rejected(run_child(gen, {"--slices", "4", "--filter", "sat", "--out", dir.string()}),
                       "penumbra_shading.frag': it is a directory");
        CHECK(contents(dir) == before);
    }
    SUBCASE("file size limit (a full disk for the writer): the real file and the reason, nothing left") {
        const fs::path dir = scratch().fresh("out") / "nested";
        const ChildRun run = run_child(gen, {"--out", dir.string()}, {.file_size = 2000});
        check_rejected(run, "File too large; nothing was written");
        CHECK(run.first_error_line().find(".penumbra-") == std::string::npos); // never a temporary name
        CHECK(run.first_error_line().find("cannot write '" + dir.string() + "/penumbra_") != std::string::npos);
        CHECK_FALSE(fs::exists(dir));
        CHECK_FALSE(fs::exists(dir.parent_path())); // the directories it created are gone too
    }
    SUBCASE("file size limit over an earlier emission: every previous file comes back") {
        const fs::path dir = scratch().fresh("out");
        REQUIRE(run_child(gen, {"--filter", "sat", "--out", dir.string()}).exit_code == 0);
        const auto before = contents(dir);
        std::uintmax_t largest = 0;
        for (const auto& [name, text] : before) largest = std::max<std::uintmax_t>(largest, text.size());
        // Every file but the largest fits: the failure comes after others were written.
        const ChildRun run = run_child(gen, {"--slices", "32", "--filter", "sat", "--out", dir.string()},
                                       {.file_size = largest - 1});
        check_rejected(run, "File too large");
        CHECK(contents(dir) == before);
    }
    SUBCASE("a full tmpfs (when this test may mount one)") {
        const fs::path mount_point = scratch().fresh("tmpfs");
        fs::create_directories(mount_point);
        if (::getuid() != 0 || ::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=256k") != 0) {
            MESSAGE("skipped: cannot mount a tmpfs here (needs root and mount rights)");
            return;
        }
        struct Unmount {
            fs::path at;
            ~Unmount() { ::umount(at.c_str()); }
        } unmount{mount_point};
        const fs::path dir = mount_point / "out";
        REQUIRE(run_child(gen, {"--out", dir.string()}).exit_code == 0);
        const auto before = contents(dir);
        // Fill the file system but for 8 KiB.
        const std::uintmax_t free_bytes = fs::space(mount_point).available;
        { std::ofstream(mount_point / "filler", std::ios::binary) << std::string(free_bytes > 8192 ? free_bytes - 8192 : 0, 'x'); }
        const ChildRun run = run_child(gen, {"--slices", "32", "--filter", "sat", "--out", dir.string()});
        check_rejected(run, "No space left on device; nothing was written");
        CHECK(contents(dir) == before);
    }
    SUBCASE("a sticky shared directory where another user owns layout.json") {
        if (::getuid() != 0) {
            MESSAGE("skipped: needs root to act as two users");
            return;
        }
        if (run_child(gen, {"--help"}, {.uid = 65534}).exit_code != 0) {
            MESSAGE("skipped: user 65534 cannot run " << gen << " here (a folder above it is private)");
            return;
        }
        const fs::path dir = scratch().fresh("shared");
        fs::create_directories(dir);
        fs::permissions(dir, fs::perms::all | fs::perms::sticky_bit); // like /tmp
        REQUIRE(run_child(gen, {"--out", dir.string()}).exit_code == 0);
        for (const fs::directory_entry& e : fs::directory_iterator(dir))
            REQUIRE(::chown(e.path().c_str(), e.path().filename() == "layout.json" ? 1234 : 65534, 65534) == 0);
        const auto before = contents(dir);
        const ChildRun run = run_child(gen, {"--slices", "4", "--filter", "sat", "--out", dir.string()}, {.uid = 65534});
        check_rejected(run, "cannot replace '" + (dir / "layout.json").string() + "': Operation not permitted");
        CHECK(contents(dir) == before);
    }
}

TEST_CASE("hostile: generation leaves exactly the files layout.json lists, never deletes others") {
    const fs::path dir = scratch().fresh("out");
    REQUIRE(run_child(gen, {"--filter", "nbuffer", "--out", dir.string()}).exit_code == 0);
    CHECK(fs::exists(dir / "penumbra_nbuffer_level.frag"));
    { std::ofstream(dir / "notes.txt") << "mine"; }
    REQUIRE(run_child(gen, {"--filter", "sat", "--out", dir.string()}).exit_code == 0);
    CHECK_FALSE(fs::exists(dir / "penumbra_nbuffer_level.frag")); // stale: no longer listed
    CHECK(fs::exists(dir / "penumbra_sat_pass.frag"));
    CHECK(hostile::read_capped(dir / "notes.txt") == "mine");
    // A layout.json that lists paths outside the folder, or files of no emission, is not obeyed.
    const fs::path outside = scratch().write("outside.txt", "keep");
    { std::ofstream(dir / "layout.json") << R"({"config": {}, "files": [")" << outside.string() << R"(", "../outside.txt", "..", "notes"]})"; }
    { std::ofstream(dir / "notes") << "mine too"; }
    REQUIRE(run_child(gen, {"--out", dir.string()}).exit_code == 0);
    CHECK(hostile::read_capped(outside) == "keep");
    CHECK_FALSE(fs::exists(dir / "notes")); // a plain name it listed: treated as Penumbra's
}

TEST_CASE("hostile: playground files are whole or absent, and 'wrote' only for whole files") {
    const fs::path dir = scratch().fresh("render");
    fs::create_directories(dir);
    const std::vector<std::string> small{"--headless", "--scene", "planes", "--size", "96x96", "--slices", "2", "--resolution", "32"};
    SUBCASE("PNG past the file size limit") {
        std::vector<std::string> args = small;
        args.insert(args.end(), {"--out", (dir / "full.png").string()});
        const ChildRun run = run_child(playground, args, {.file_size = 1500});
        CAPTURE(run.err);
        CHECK(run.exit_code == 1);
        CHECK(run.error_lines() == 1);
        CHECK(run.first_error_line().find("cannot write '" + (dir / "full.png").string() + "': File too large") != std::string::npos);
        CHECK(run.out.find("wrote") == std::string::npos);
        CHECK(fs::is_empty(dir));
    }
    SUBCASE("a run is one transaction: metrics that cannot be written leave no image, PFM or temporary") {
        std::vector<std::string> args = small;
        args.insert(args.end(), {"--out", (dir / "ok.png").string(), "--visibility", (dir / "vis.pfm").string(),
                                 "--metrics", (dir / "metrics.json").string()});
        fs::create_directories(dir / "metrics.json"); // not writable as a file
        const ChildRun run = run_child(playground, args);
        CAPTURE(run.err);
        CHECK(run.exit_code == 1);
        CHECK(run.error_lines() == 1);
        CHECK(run.first_error_line().find("metrics.json': it is a directory") != std::string::npos);
        CHECK(run.out.find("wrote") == std::string::npos);
        CHECK_FALSE(fs::exists(dir / "ok.png"));
        CHECK_FALSE(fs::exists(dir / "vis.pfm"));
        // Only the directory that was in the way is left; no temporary.
        for (const fs::directory_entry& e : fs::directory_iterator(dir)) CHECK(e.path().filename() == "metrics.json");
    }
    SUBCASE("a run that fails keeps the previous run's files as they were") {
        std::vector<std::string> args = small;
        args.insert(args.end(), {"--out", (dir / "keep.png").string(), "--reference", "--samples", "1", "--metrics",
                                 (dir / "keep.json").string()});
        REQUIRE(run_child(playground, args).exit_code == 0);
        const std::map<std::string, std::string> before = contents(dir);
        CHECK(before.size() == 7); // keep.png, keep.reference{,.oriented,.irradiance}.pfm,
                                   // keep.reference.png, keep.error.png, keep.json
        // The same run with the error image in the way (a directory): nothing changes.
        args.insert(args.end(), {"--slices", "4", "--error-out", (dir / "blocked").string()});
        fs::create_directories(dir / "blocked");
        const ChildRun run = run_child(playground, args);
        CAPTURE(run.err);
        CHECK(run.exit_code == 1);
        CHECK(run.first_error_line().find("blocked': it is a directory") != std::string::npos);
        std::map<std::string, std::string> after = contents(dir);
        after.erase("blocked");
        CHECK(after == before);
    }
    SUBCASE("a device is never replaced") {
        std::vector<std::string> args = small;
        args.insert(args.end(), {"--out", "/dev/null"});
        const ChildRun run = run_child(playground, args);
        CHECK(run.exit_code == 1);
        CHECK(run.first_error_line().find("'/dev/null': it is not a regular file") != std::string::npos);
        CHECK(fs::is_character_file("/dev/null"));
    }
}

TEST_CASE("hostile: a window screenshot that cannot be written is not 'wrote', and fails the run") {
    if (!penumbra::test::has_virtual_display()) {
        MESSAGE("skipped: no xvfb-run");
        return;
    }
    const fs::path dir = scratch().fresh("window");
    fs::create_directories(dir / "shot.png"); // a directory where the screenshot goes
    const penumbra::test::VirtualDisplayRun run = penumbra::test::run_under_virtual_display(
        dir, "'" + playground +
                 "' --scene planes --size 64x48 --slices 2 --resolution 32 --frames 2"
                 " --screenshot shot.png --watch shaders > out.txt 2> err.txt");
    const std::string out = hostile::read_capped(dir / "out.txt"), err = hostile::read_capped(dir / "err.txt");
    CAPTURE(err);
    CAPTURE(run.display_log);
    CHECK(run.exit_code == 1);
    CHECK(err.find("error: screenshot: cannot write 'shot.png': it is a directory") != std::string::npos);
    CHECK(out.find("screenshot: wrote") == std::string::npos);
    CHECK(fs::is_directory(dir / "shot.png"));
    CHECK(fs::is_empty(dir / "shot.png"));
}

TEST_CASE("hostile: shader diagnostics are bounded and escaped") {
    using penumbra::playground::ShaderFolder;
    const fs::path dir = scratch().fresh("watch");
    ShaderFolder folder(dir, std::chrono::milliseconds(0));
    REQUIRE(folder.write_generated({{"a.frag", penumbra::Stage::fragment, "void main() {}\n"},
                                    {"b.frag", penumbra::Stage::fragment, "void main() {}\n"}}).empty());
    // A 2 GiB file of NUL bytes (sparse) and a 10 MB line: not read, reported with the limit.
    fs::resize_file(dir / "a.frag", std::uintmax_t(2) << 30);
    { std::ofstream(dir / "b.frag") << std::string(10u << 20, 'x') << "\n"; }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const auto start = std::chrono::steady_clock::now();
    const std::vector<ShaderFolder::Change> changes = folder.poll(ShaderFolder::Clock::now() + std::chrono::seconds(1));
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(2));
    REQUIRE(changes.size() == 2);
    for (const ShaderFolder::Change& c : changes) {
        CAPTURE(c.file_name);
        CHECK(c.text.empty());
        CHECK(c.problem.find("allowed: a regular file of at most 1 MiB") != std::string::npos);
    }
    // A long binary line in the source and in the log: cut with a marker, escaped, bounded.
    const std::string huge(1u << 20, '\0');
    const std::string formatted = penumbra::playground::format_diagnostic(
        {"c.frag", 2, "error: " + huge}, {{"c.frag", "ok\n" + huge + "\nok\n"}});
    CHECK(formatted.size() < 4096);
    CHECK(formatted.find('\0') == std::string::npos);
    CHECK(formatted.find("\\x00\\x00") != std::string::npos);
    CHECK(formatted.find("more bytes)") != std::string::npos);
    const std::string log = penumbra_gen::printable_lines(std::string(1u << 20, '\n') + huge);
    CHECK(log.size() < 64 * 1024);
    CHECK(log.find("more bytes not shown") != std::string::npos);
}
