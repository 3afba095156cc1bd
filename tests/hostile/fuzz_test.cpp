// A seeded random-input driver over everything a user can hand the two tools: penumbra-gen's
// arguments and config files, penumbra-playground's arguments, OBJ and glTF files and window scripts
// (label "fuzz"). Each case asserts the promise: exit 0 or 2 only, exactly one `error:` line on 2,
// nothing written on 2, no sanitizer report (when built with PENUMBRA_SANITIZE), never a signal or
// a hang. Parsers that the tools run in-process (config JSON, OBJ, scripts, the playground's
// options) are also driven directly, many more times, and their rejections checked through the
// tool on a sample.
//
//   PENUMBRA_FUZZ_SCALE=10   ten times the cases (the default, 1, is what CI runs; 0.1: a tenth)
//   PENUMBRA_FUZZ_SEED=N     another seed (default 13)
#include "child_process.hpp"

#include <penumbra_tools/config_file.hpp>
#include "app/options.hpp"
#include "../runtime/gltf_compression_files.hpp"
#include "../runtime/gltf_test_file.hpp"
#include "scenes/gltf_loader.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/obj_loader.hpp"
#include "script.hpp"

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <sys/stat.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

namespace {
namespace fs = std::filesystem;
using hostile::ChildRun;
using hostile::run_child;

const std::string gen = hostile::tool_path("PENUMBRA_TEST_GEN", PENUMBRA_GEN_PATH);
const std::string playground = hostile::tool_path("PENUMBRA_TEST_PLAYGROUND", PENUMBRA_PLAYGROUND_PATH);

int scaled(int cases) {
    const char* text = std::getenv("PENUMBRA_FUZZ_SCALE");
    const double scale = text ? std::strtod(text, nullptr) : 1.0;
    return std::max(1, static_cast<int>(std::lround(cases * (scale > 0 ? scale : 1.0))));
}
unsigned seed() {
    const char* text = std::getenv("PENUMBRA_FUZZ_SEED");
    return text ? static_cast<unsigned>(std::strtoul(text, nullptr, 10)) : 13u;
}

hostile::Scratch& scratch() {
    static hostile::Scratch s("fuzz");
    return s;
}

struct Random {
    std::mt19937 engine;
    explicit Random(unsigned salt) : engine(seed() * 7919u + salt) {}
    int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(engine); }
    bool chance(double p) { return std::uniform_real_distribution<double>(0, 1)(engine) < p; }
    template <class T> const T& pick(const std::vector<T>& pool) { return pool[std::size_t(below(int(pool.size())))]; }
    std::string bytes(int most) {
        std::string out(std::size_t(below(most + 1)), '\0');
        for (char& c : out) c = static_cast<char>(below(256));
        return out;
    }
    // A few characters flipped, inserted, removed or a span duplicated.
    std::string mutate(std::string text, const std::string& alphabet) {
        for (int edits = 1 + below(4); edits > 0; --edits) {
            const std::size_t at = text.empty() ? 0 : std::size_t(below(int(text.size())));
            const char c = alphabet[std::size_t(below(int(alphabet.size())))];
            switch (below(4)) {
            case 0: if (!text.empty()) text[at] = c; break;
            case 1: text.insert(text.begin() + std::ptrdiff_t(at), c); break;
            case 2: if (!text.empty()) text.erase(at, 1); break;
            default: text.insert(at, text.substr(at, std::size_t(below(16)))); break;
            }
        }
        return text;
    }
};

// Outcomes per input class, printed at the end of each test case; anything but exit 0 or 2 fails.
struct Tally {
    std::string name;
    std::map<std::string, int> outcomes;
    std::vector<std::string> unexpected;
    int cases = 0;
    void add(const std::string& outcome) {
        ++cases;
        ++outcomes[outcome];
    }
    ~Tally() {
        std::string line = "fuzz " + name + ": " + std::to_string(cases) + " cases;";
        for (const auto& [outcome, count] : outcomes) line += " " + outcome + ": " + std::to_string(count) + ";";
        MESSAGE(line);
        for (const std::string& u : unexpected) MESSAGE("unexpected: " << u);
    }
};

std::string joined(const std::vector<std::string>& args) {
    std::string out;
    for (const std::string& a : args) out += (out.empty() ? "" : " ") + penumbra_gen::printable(a, 80);
    return out;
}

// The promise, for one run of a tool. `outputs`: what must not exist after an exit 2.
void check_promise(Tally& tally, const ChildRun& run, const std::vector<std::string>& args,
                   const std::vector<fs::path>& outputs) {
    tally.add(run.outcome());
    CAPTURE(joined(args));
    CAPTURE(run.err.substr(0, 2000));
    const bool expected = run.signal == 0 && (run.exit_code == 0 || run.exit_code == 2);
    if (!expected) tally.unexpected.push_back(run.outcome() + " for " + joined(args) + ": " + run.err.substr(0, 300));
    CHECK(expected);
    CHECK_FALSE(run.sanitizer_report());
    if (run.exit_code == 2) {
        CHECK(run.error_lines() == 1);
        CHECK(run.first_error_line().size() < 4096);
        for (const fs::path& p : outputs) CHECK_FALSE(fs::exists(fs::symlink_status(p)));
    }
}

// A mesh file the loader refused, run through penumbra-playground --headless: the promise, and exit 2.
void check_refused_by_playground(Tally& through, const fs::path& scene, const std::string& png_name) {
    const fs::path png = scratch().fresh(png_name);
    const std::vector<std::string> args{"--headless", "--scene", scene.string(), "--out", png.string()};
    const ChildRun run = run_child(playground, args);
    check_promise(through, run, args, {png});
    CHECK(run.exit_code == 2);
}

// Runs of one tool, started in batches (as many at a time as there are processors), each checked
// against the promise; their outputs are removed afterwards.
struct Batch {
    struct Case {
        std::vector<std::string> args;
        std::vector<fs::path> outputs;
        std::string expected_error; // when set: the tool's error line must be exactly this
    };
    Tally& tally;
    std::string program;
    hostile::ChildLimits limits{};
    std::vector<Case> cases;
    void add(Case c) {
        cases.push_back(std::move(c));
        if (cases.size() >= 32) run();
    }
    void run() {
        std::vector<hostile::ChildJob> jobs;
        for (const Case& c : cases) jobs.push_back({program, c.args, limits});
        const std::vector<ChildRun> runs = hostile::run_children(jobs);
        for (std::size_t i = 0; i < cases.size(); ++i) {
            check_promise(tally, runs[i], cases[i].args, cases[i].outputs);
            if (!cases[i].expected_error.empty()) CHECK(runs[i].first_error_line() == cases[i].expected_error);
            std::error_code ec;
            for (const fs::path& p : cases[i].outputs) fs::remove_all(p, ec);
        }
        cases.clear();
    }
    ~Batch() { run(); }
};

// Values and tokens a hostile user types, shared by the argument fuzzers.
const std::vector<std::string>& hostile_values() {
    static const std::vector<std::string> values{
        "16", "1", "32", "0", "-1", "33", "8", "64", "128", "4096", "8192", "500", "abc", "", " 16", "16 ", "+8",
        "0x10", "1e3", "2147483647", "2147483648", "-2147483649", "99999999999999999999", "1e309", "nan", "inf",
        "-0", "1.5", "mipmap", "nbuffer", "sat", "gaussian", "probabilistic", "additive", "maximum", "average",
        "atlas", "array", "volume", "rect", "sun", "glsl330", "glsl450", "essl300", "vulkan", "SAT", "\xff\xfe",
        "\x1b[31m", "a\tb", std::string(5000, 'x'), "--out", "-", "--", "=", "/dev/zero", "/dev/null"};
    return values;
}

struct HostileFiles {
    std::vector<std::string> configs; // paths a --config may name
    HostileFiles() {
        const fs::path fifo = scratch().fresh("fifo");
        ::mkfifo(fifo.c_str(), 0666);
        const fs::path sparse = scratch().write("sparse.json", "");
        fs::resize_file(sparse, std::uintmax_t(3) << 30);
        const fs::path dir = scratch().fresh("dir");
        fs::create_directories(dir);
        configs = {scratch().write("good.json", R"({"slices": 8, "resolution": 128, "filter": "sat"})").string(),
                   scratch().write("sun.json", R"({"light": "sun", "filter": "gaussian"})").string(),
                   scratch().write("bad.json", "{\"slices\": [").string(),
                   scratch().write("big.json", R"({"resolution": 1e309})").string(),
                   fifo.string(), sparse.string(), dir.string(), "/dev/zero", "/dev/urandom",
                   (scratch().root() / "missing.json").string()};
    }
};
const HostileFiles& files() {
    static HostileFiles f;
    return f;
}

const std::string valid_config =
    R"({"slices": 8, "resolution": 128, "filter": "sat", "fusion": "average", "packing": "array", )"
    R"("light": "rect", "leak_fix": false, "self_shadow_fade": true, "target": "glsl450"})";

std::string random_json(Random& r) {
    switch (r.below(6)) {
    case 0: return r.bytes(80);
    case 1: return valid_config.substr(0, std::size_t(r.below(int(valid_config.size()))));
    case 2: { // one key with a hostile value
        const std::vector<std::string> keys{"slices", "resolution", "filter", "fusion", "packing", "light",
                                            "leak_fix", "self_shadow_fade", "target", "config", "x", ""};
        const std::vector<std::string> values{"1e309", "-1e309", "1e400", "18446744073709551616", "-0", "1.0", "16",
                                              "null", "true", "[]", "{}", "\"sat\"", "\"\\u0000\"", "\"\\ud800\"",
                                              "99999999999999999999999999999999", "0.5e-400", "[[[[[[[[1]]]]]]]]"};
        return "{\"" + r.pick(keys) + "\": " + r.pick(values) + "}";
    }
    case 3: { // deep nesting
        const int depth = 1 + r.below(20000);
        return std::string(std::size_t(depth), '[') + (r.chance(0.5) ? std::string(std::size_t(depth), ']') : "");
    }
    case 4: return R"({"config": )" + r.mutate(valid_config, "{}[]\":,0123456789-.eE tfnul\\\x01\xc3") + "}";
    default: return r.mutate(valid_config, "{}[]\":,0123456789-.eE tfnulraxyz\\\n\t\x01\xc3\xff");
    }
}

} // namespace

TEST_CASE("fuzz: penumbra-gen arguments") {
    Tally tally{"gen-args"};
    Random r(1);
    const std::vector<std::string> flags{"--slices", "--resolution", "--filter", "--fusion", "--packing",
                                         "--light", "--target", "--config", "--out"};
    const std::vector<std::string> junk{"--bogus", "-x", "--", "-", "--slices=", "--no-fade=1", "positional",
                                        "--no-leak-fix", "--no-fade", "--help=no", "-H", "\xff"};
    Batch batch{tally, gen, {.timeout_s = 20, .cwd = scratch().root()}};
    for (int i = 0; i < scaled(800); ++i) {
        const fs::path dir = scratch().fresh("gen-out");
        std::vector<std::string> args;
        for (int t = r.below(7); t > 0; --t) {
            const int kind = r.below(10);
            if (kind <= 5) {
                const std::string& flag = r.pick(flags);
                const std::string value = flag == "--config" && r.chance(0.7) ? r.pick(files().configs)
                                          : flag == "--out"                  ? dir.string() // never elsewhere
                                                                             : r.pick(hostile_values());
                if (r.chance(0.2)) args.push_back(flag + "=" + value);
                else args.insert(args.end(), {flag, value});
            } else {
                args.push_back(r.pick(junk));
            }
        }
        if (r.chance(0.85)) args.insert(args.end(), {"--out", dir.string()});
        // "--out" followed by a hostile value could name a path outside the scratch folder: keep
        // every value after --out the scratch directory.
        for (std::size_t a = 0; a + 1 < args.size(); ++a)
            if (args[a] == "--out") args[a + 1] = dir.string();
        if (!args.empty() && args.back() == "--out") args.pop_back();
        batch.add({args, {dir}});
    }
}

TEST_CASE("fuzz: penumbra-gen config files") {
    Tally tally{"gen-config"};
    Random r(2);
    Batch batch{tally, gen};
    for (int i = 0; i < scaled(500); ++i) {
        const fs::path dir = scratch().fresh("gen-out");
        const fs::path file = scratch().write("fuzz.json", random_json(r));
        batch.add({{"--config", file.string(), "--out", dir.string()}, {dir}});
        // (the config file is left in the scratch folder, removed at the end)
    }
}

TEST_CASE("fuzz: config JSON in-process (both tools' reader)") {
    Tally tally{"config-in-process"};
    Random r(3);
    for (int i = 0; i < scaled(1500); ++i) {
        const std::string text = random_json(r);
        const penumbra_gen::Parsed<penumbra::Config> parsed = penumbra_gen::parse_config_json(text, "fuzz.json");
        tally.add(parsed.error.empty() ? "accepted" : "rejected");
        if (!parsed.error.empty()) {
            CAPTURE(penumbra_gen::printable(text, 200));
            CHECK(parsed.error.find('\n') == std::string::npos);
            CHECK(parsed.error.size() < 2048);
            CHECK(parsed.error.rfind("fuzz.json: ", 0) == 0);
        }
    }
}

TEST_CASE("fuzz: penumbra-playground arguments") {
    Tally tally{"playground-args"};
    Random r(4);
    const std::vector<std::string> flags{"--scene", "--size", "--light-size", "--out", "--visibility", "--samples",
                                         "--metrics", "--reference-out", "--error-out", "--slices", "--resolution",
                                         "--filter", "--light", "--target", "--config", "--frames", "--script",
                                         "--watch", "--screenshot"};
    const std::vector<std::string> special{"16x16", "99999x99999", "0x0", "8192x8192", "8193x1", "-1x5", "16x",
                                           "x16", "16x16x16", "1e3x1e3", "planes", "boxes", "nope", "a.obj",
                                           "/dev/zero.obj", "1e30", "89.9", "90", "0.0001", "-3"};
    int children = 0;
    Batch batch{tally, playground};
    for (int i = 0; i < scaled(800); ++i) {
        const fs::path out = scratch().fresh("pg-out.png");
        std::vector<std::string> args{"--headless"};
        for (int t = r.below(6); t > 0; --t) {
            const std::string& flag = r.pick(flags);
            std::string value = r.chance(0.5) ? r.pick(special) : r.pick(hostile_values());
            if (flag == "--config" && r.chance(0.7)) value = r.pick(files().configs);
            if (r.chance(0.2)) args.push_back(flag + "=" + value);
            else args.insert(args.end(), {flag, value});
        }
        if (r.chance(0.9)) args.insert(args.end(), {"--out", out.string()});
        // Every output flag names a path in the scratch folder only.
        const std::set<std::string> outputs{"--out", "--visibility", "--metrics", "--reference-out", "--error-out",
                                            "--watch", "--screenshot"};
        std::vector<fs::path> written{out};
        for (std::size_t a = 0; a < args.size(); ++a) {
            const std::size_t eq = args[a].find('=');
            const std::string flag = args[a].substr(0, eq);
            if (!outputs.count(flag)) continue;
            const fs::path p = scratch().fresh("pg-file");
            written.push_back(p);
            if (eq != std::string::npos) args[a] = flag + "=" + p.string();
            else if (a + 1 < args.size()) args[++a] = p.string();
        }
        const penumbra::playground::ParsedOptions parsed =
            penumbra::playground::parse_options(std::vector<std::string>(args.begin(), args.end()));
        if (parsed.options || parsed.help) { // would render: counted, not run (the GL tests render)
            tally.add("accepted in-process (not rendered)");
            continue;
        }
        CHECK(parsed.error.find('\n') == std::string::npos);
        ++children;
        batch.add({args, written, "error: " + parsed.error}); // the tool says what the parser says
    }
    batch.run();
    MESSAGE("playground-args: " << children << " runs of the tool");
}

TEST_CASE("fuzz: OBJ files") {
    Tally tally{"obj"};
    Tally through{"obj-through-tool"};
    Random r(5);
    const std::string base = "# a quad\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvn 0 1 0\nvt 0 0\nf 1/1/1 2/1/1 3/1/1 4/1/1\n"
                             "v 0 1 0\nv 1 1 0\nv 0 1 1\nf -3 -2 -1\ng top\nf 5 6 7\n";
    const std::vector<std::string> numbers{"3e38", "-3e38", "1e9", "1e10", "nan", "-nan", "inf", "1e309", "a",
                                           "0x1p3", "", "1,5", "+1", "1e-320", "99999999999999999999", "-0"};
    int children = 0;
    for (int i = 0; i < scaled(600); ++i) {
        std::string text;
        switch (r.below(4)) {
        case 0: text = r.bytes(200); break;
        case 1: text = r.mutate(base, "vnft/ \n-0123456789.e#\r\t\x01\xff"); break;
        case 2: { // a hostile number or index in one place
            text = base;
            const std::string token = r.pick(numbers);
            const std::size_t at = text.find(r.chance(0.5) ? "v 1 0 1" : "f 5 6 7");
            text.insert(at + 2, token + " ");
            break;
        }
        default: text = base + "f 1 2 " + std::to_string(static_cast<long long>(r.engine()) * 1000003LL) + "\n"; break;
        }
        const fs::path file = scratch().write("fuzz", text);
        fs::path obj = file;
        obj += ".obj";
        fs::rename(file, obj);
        const penumbra::playground::LoadResult loaded = penumbra::playground::load_obj_scene(obj.string());
        CAPTURE(penumbra_gen::printable(text, 300));
        if (loaded.scene) {
            tally.add("accepted");
            const auto& s = *loaded.scene;
            for (const glm::vec3& p : s.mesh.positions) CHECK((std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)));
            CHECK((std::isfinite(s.light.width) && std::isfinite(s.light.height) && std::isfinite(s.light.center.x) &&
                   std::isfinite(s.light.center.y) && std::isfinite(s.light.center.z)));
        } else {
            tally.add("rejected");
            CHECK(loaded.error.find('\n') == std::string::npos);
            CHECK(loaded.error.find(obj.string()) != std::string::npos);
            if (i % 5 == 0) { // and through the tool
                ++children;
                check_refused_by_playground(through, obj, "obj.png");
            }
        }
        fs::remove(obj);
    }
    MESSAGE("obj: " << children << " rejected files also run through the tool");
}

// glTF: mutations of a small valid asset (tests/runtime/gltf_test_file.hpp) as .glb (bytes of the
// container, the JSON or the buffer changed) and as .gltf + .bin (the JSON's text or a number in it).
TEST_CASE("fuzz: glTF files") {
    namespace t = penumbra::playground::testing;
    Tally tally{"gltf"};
    Tally through{"gltf-through-tool"};
    Random r(7);
    const std::string bin = t::gltf_test_buffer();
    const std::string glb = t::make_glb(t::gltf_test_json(""), bin);
    const std::vector<std::string> numbers{"-1", "4294967295", "4294967296", "1e309", "-0", "99", "3.5", "1e20",
                                           "5120", "5130", "null", "\"x\"", "[]", "{}", "2147483648", "NaN"};
    int children = 0;
    for (int i = 0; i < scaled(600); ++i) {
        const bool binary = r.chance(0.5);
        const int kind = r.below(4);
        const std::string buffer = kind == 2 ? r.mutate(bin, std::string("\0\x7f\x80\xff\x01", 5)) : bin;
        const fs::path bin_path = scratch().write("fuzz.bin", buffer); // the .gltf's external buffer
        const std::string json = t::gltf_test_json(binary ? "" : bin_path.filename().string());
        std::string text;
        switch (kind) {
        case 0: // bytes anywhere (the header, chunk lengths, JSON, buffer)
            text = binary ? r.mutate(glb, std::string("\0\x01\x02\x04\xff{}[]\":,0123456789", 23))
                          : r.mutate(json, "{}[]\":,0123456789.e-");
            break;
        case 1: { // one number of the JSON replaced by a hostile one
            std::string j = json;
            std::vector<std::size_t> digits;
            for (std::size_t k = 0; k < j.size(); ++k)
                if (std::isdigit(static_cast<unsigned char>(j[k])) &&
                    (k == 0 || !std::isalnum(static_cast<unsigned char>(j[k - 1])) ))
                    digits.push_back(k);
            const std::size_t at = digits[std::size_t(r.below(int(digits.size())))];
            std::size_t end = at;
            while (end < j.size() && (std::isdigit(static_cast<unsigned char>(j[end])) || j[end] == '.')) ++end;
            j.replace(at, end - at, r.pick(numbers));
            text = binary ? t::make_glb(j, bin) : j;
            break;
        }
        case 2: // the buffer's bytes
            text = binary ? t::make_glb(json, buffer) : json;
            break;
        default: // cut short
            text = binary ? glb.substr(0, std::size_t(r.below(int(glb.size()))))
                          : json.substr(0, std::size_t(r.below(int(json.size()))));
            break;
        }
        const fs::path file = scratch().write("fuzz", text);
        fs::path path = file;
        path += binary ? ".glb" : ".gltf";
        fs::rename(file, path);
        const penumbra::playground::LoadResult loaded = penumbra::playground::load_gltf_scene(path.string());
        CAPTURE(binary);
        CAPTURE(penumbra_gen::printable(text, 300));
        if (loaded.scene) {
            tally.add("accepted");
            const auto& s = *loaded.scene;
            CHECK(penumbra::playground::validate_mesh(s.mesh).empty());
            for (const glm::vec3& p : s.mesh.positions) CHECK((std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)));
            CHECK((std::isfinite(s.light.width) && std::isfinite(s.light.center.y) && std::isfinite(s.camera.distance)));
        } else {
            tally.add("rejected");
            CHECK(loaded.error.find('\n') == std::string::npos);
            CHECK(loaded.error.find(path.string()) != std::string::npos);
            if (i % 6 == 0) { // and through the tool
                ++children;
                check_refused_by_playground(through, path, "gltf.png");
            }
        }
        fs::remove(path);
        fs::remove(bin_path);
    }
    MESSAGE("gltf: " << children << " rejected files also run through the tool");
}

// Compressed glTF: mutations of two seeds nobody here wrote, each as .glb and as .gltf + .bin: a
// Draco primitive of assimp-testmodels' 2CylinderEngine (2,750 triangles) and a torus packed by
// Debian's gltfpack -cc (meshopt). Stream bytes changed in place (so the decoders see them), a
// number of the extension objects, buffer views or accessors replaced by a hostile one, the
// stream cut short, the JSON text or the file's bytes changed.
TEST_CASE("fuzz: compressed glTF files") {
    namespace t = penumbra::playground::testing;
    if (!t::have_gltfpack() || !fs::is_regular_file(t::draco_engine)) {
        MESSAGE("gltfpack or assimp-testmodels is not installed (scripts/setup.sh installs them): skipped");
        return;
    }
    Tally tally{"compressed-gltf"};
    Tally through{"compressed-gltf-through-tool"};
    Random r(8);
    struct Seed {
        std::string name;
        nlohmann::json json; // buffer 0 without uri
        std::string bin;
    };
    std::vector<Seed> seeds;
    {
        auto [json, bin] = t::draco_seed("");
        seeds.push_back({"draco", json, bin});
        const fs::path obj = scratch().write("torus.obj", t::torus_obj(16, 8));
        const fs::path glb = scratch().fresh("torus.glb");
        REQUIRE(t::run_gltfpack(obj.string(), glb.string()));
        const std::string bytes = t::read_binary(glb.string());
        seeds.push_back({"meshopt", nlohmann::json::parse(t::glb_json(bytes)), t::glb_bin(bytes)});
        for (const Seed& seed : seeds) { // both seeds load as they are
            const fs::path file = scratch().write("seed.glb", t::make_glb(seed.json.dump(), seed.bin));
            const penumbra::playground::LoadResult loaded = penumbra::playground::load_gltf_scene(file.string());
            REQUIRE_MESSAGE(loaded.scene, loaded.error);
            fs::remove(file);
        }
    }
    const std::vector<nlohmann::json> hostile{0, 1, 2, 3, 4, 5, 6, 7, 8, 12, 16, 255, 256, 257, 65535, 65536,
                                              67108864, 67108865, 4294967295ull, 4294967296ull, -1, 1e20, 2.5,
                                              "x", nullptr, nlohmann::json::array(), nlohmann::json::object()};
    // Every number under the compression extensions, buffer views, accessors and buffers.
    auto numbers = [](const nlohmann::json& j) {
        std::vector<nlohmann::json::json_pointer> out;
        const nlohmann::json flat = j.flatten();
        for (const auto& [key, value] : flat.items())
            if (value.is_number() && (key.find("/extensions/") != std::string::npos || key.starts_with("/bufferViews/") ||
                                      key.starts_with("/accessors/") || key.starts_with("/buffers/")))
                out.emplace_back(key);
        return out;
    };
    int children = 0, decoder_refusals = 0;
    for (int i = 0; i < scaled(1200); ++i) {
        const Seed& seed = seeds[std::size_t(r.below(int(seeds.size())))];
        const bool binary = r.chance(0.5);
        nlohmann::json json = seed.json;
        std::string bin = seed.bin, text;
        const int kind = r.below(5);
        switch (kind) {
        case 0: // stream bytes changed in place
            for (int n = 1 + r.below(8); n > 0; --n) bin[std::size_t(r.below(int(bin.size())))] = char(r.below(256));
            break;
        case 1: { // a number replaced
            const auto pointers = numbers(json);
            const auto& at = pointers[std::size_t(r.below(int(pointers.size())))];
            if (r.chance(0.3) && json[at].is_number_unsigned()) // near the truth: off by a little
                json[at] = json[at].get<std::int64_t>() + (r.chance(0.5) ? 1 : -1) * (1 + r.below(16));
            else
                json[at] = r.pick(hostile);
            break;
        }
        case 2: { // the stream cut short, the buffer's length saying so
            bin.resize(std::size_t(r.below(int(bin.size()))) & ~std::size_t(3));
            json["buffers"][0]["byteLength"] = bin.size();
            break;
        }
        default: break; // 3: the JSON text, 4: the file's bytes (below)
        }
        const fs::path bin_path = scratch().write("fuzz-compressed.bin", bin);
        if (!binary) json["buffers"][0]["uri"] = bin_path.filename().string();
        text = json.dump();
        if (kind == 3) text = r.mutate(text, "{}[]\":,0123456789.e-");
        text = binary ? t::make_glb(text, bin) : text;
        if (kind == 4) text = r.mutate(text, std::string("\0\x01\x02\x04\xff{}[]\":,0123456789", 23));
        const fs::path file = scratch().write("fuzz-compressed", text);
        fs::path path = file;
        path += binary ? ".glb" : ".gltf";
        fs::rename(file, path);
        const penumbra::playground::LoadResult loaded = penumbra::playground::load_gltf_scene(path.string());
        CAPTURE(seed.name);
        CAPTURE(binary);
        CAPTURE(kind);
        CAPTURE(penumbra_gen::printable(json.dump(), 600));
        if (loaded.scene) {
            tally.add("accepted");
            const auto& s = *loaded.scene;
            CHECK(penumbra::playground::validate_mesh(s.mesh).empty());
            for (const glm::vec3& p : s.mesh.positions) CHECK((std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)));
        } else {
            const bool decoder = loaded.error.find("does not decode") != std::string::npos;
            decoder_refusals += decoder;
            tally.add(decoder ? "rejected by a decoder" : "rejected");
            CHECK(loaded.error.find('\n') == std::string::npos);
            CHECK(loaded.error.find(path.string()) != std::string::npos);
            if (i % 20 == 0) { // and through the tool
                ++children;
                check_refused_by_playground(through, path, "compressed.png");
            }
        }
        fs::remove(path);
        fs::remove(bin_path);
    }
    CHECK(decoder_refusals > 50); // the mutations reach the decoders, not only the JSON checks
    MESSAGE("compressed gltf: " << children << " rejected files also run through the tool");
}

TEST_CASE("fuzz: window scripts") {
    Tally tally{"script"};
    Tally through{"script-through-tool"};
    Random r(6);
    const std::string base = "set slices 8\nlight 1 2 3\nlight_size 2 1\nsun 30 60\ncamera 10 20 5\nwait 3\n"
                             "edit penumbra_shading.frag replace a => b\nwait_reload 2\nscreenshot x.png\nanswer cancel\n";
    const std::vector<std::string> numbers{"2147483648", "1e30", "nan", "inf", "-inf", "-1", "1e10", "0.5", "1e6",
                                           "1000001", "600", "600.1", "0x10", "1e309", "", "-0", "4294967296"};
    const std::vector<std::string> verbs{"wait", "wait_reload", "light", "light_size", "sun", "camera", "set",
                                         "edit", "answer", "screenshot", "restore", "reset", "jump"};
    int children = 0;
    for (int i = 0; i < scaled(1000); ++i) {
        std::string text;
        switch (r.below(4)) {
        case 0: text = r.bytes(120); break;
        case 1: text = r.mutate(base, "0123456789.e- \n#=>\t\x01\xff"); break;
        default: {
            text = r.pick(verbs);
            for (int n = r.below(4); n > 0; --n) text += " " + r.pick(numbers);
            text += "\n";
        }
        }
        const penumbra::playground::ScriptParse parsed = penumbra::playground::parse_script(text, "fuzz.script");
        CAPTURE(penumbra_gen::printable(text, 300));
        if (parsed.error.empty()) {
            tally.add("accepted");
            for (const penumbra::playground::ScriptAction& a : parsed.actions) {
                for (double n : a.numbers) CHECK(std::isfinite(n));
                if (a.verb == "wait") CHECK((a.numbers[0] >= 0 && a.numbers[0] <= penumbra::playground::max_wait_frames));
                if (a.verb == "wait_reload" && !a.numbers.empty())
                    CHECK((a.numbers[0] >= 0 && a.numbers[0] <= penumbra::playground::max_wait_reload_seconds));
            }
        } else {
            tally.add("rejected");
            CHECK(parsed.error.find('\n') == std::string::npos);
            for (char c : parsed.error) CHECK((static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7f));
            if (i % 10 == 0) { // and through the tool: exit 2 before any window opens
                ++children;
                const fs::path file = scratch().write("fuzz.script", text);
                const std::vector<std::string> args{"--script", file.string()};
                const ChildRun run = run_child(playground, args);
                check_promise(through, run, args, {});
                CHECK(run.exit_code == 2);
                fs::remove(file);
            }
        }
    }
    MESSAGE("script: " << children << " rejected scripts also run through the tool");
}
