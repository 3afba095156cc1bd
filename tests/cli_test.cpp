// penumbra-gen as a user runs it: a child process per case, its exit status, its stderr's first
// line and what it left on disk (label "cli"). PENUMBRA_GEN_PATH is the built generator.
#include <penumbra/validate.hpp>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {
namespace fs = std::filesystem;

// A scratch directory for the whole run, removed at exit.
struct Scratch {
    fs::path root = fs::temp_directory_path() / ("penumbra-cli-test-" + std::to_string(::getpid()));
    int counter = 0;
    Scratch() { fs::create_directories(root); }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(root, ec);
    }
    // A fresh path that does not exist yet.
    fs::path fresh(const std::string& stem) { return root / (stem + "-" + std::to_string(++counter)); }
};
Scratch& scratch() {
    static Scratch s;
    return s;
}

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

fs::path write_text(const std::string& stem, const std::string& text) {
    const fs::path path = scratch().fresh(stem);
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

struct Run {
    int exit_code = -1; // when the child exited
    int signal = 0;     // when a signal ended it (SIGALRM: it ran past the timeout)
    std::string out, err;
    std::string first_error_line() const { return err.substr(0, err.find('\n')); }
};

// Runs penumbra-gen with `args` in the scratch directory; SIGALRM ends it after `timeout_s`.
Run run_gen(const std::vector<std::string>& args, unsigned timeout_s = 10) {
    const fs::path out_file = scratch().fresh("stdout"), err_file = scratch().fresh("stderr");
    std::vector<char*> argv{const_cast<char*>(PENUMBRA_GEN_PATH)};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        const int out = ::open(out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        const int err = ::open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        if (out < 0 || err < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0 ||
            ::chdir(scratch().root.c_str()) != 0)
            ::_exit(125);
        ::alarm(timeout_s); // kept across exec
        ::execv(argv[0], argv.data());
        ::_exit(126);
    }
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0) {
    }
    Run run;
    if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
    run.out = read_text(out_file);
    run.err = read_text(err_file);
    fs::remove(out_file);
    fs::remove(err_file);
    return run;
}

std::set<std::string> listing(const fs::path& dir) {
    std::set<std::string> names;
    for (const fs::directory_entry& e : fs::directory_iterator(dir))
        names.insert(e.path().filename().string());
    return names;
}

std::set<std::string> layout_files(const fs::path& dir) {
    const nlohmann::json layout = nlohmann::json::parse(read_text(dir / "layout.json"));
    std::set<std::string> names;
    for (const auto& f : layout.at("files")) names.insert(f.get<std::string>());
    return names;
}

std::vector<std::string> with_out(std::vector<std::string> args, const fs::path& dir) {
    args.push_back("--out");
    args.push_back(dir.string());
    return args;
}

std::string joined(const std::vector<std::string>& args) {
    std::string out;
    for (const std::string& a : args) out += (out.empty() ? "" : " ") + a;
    return out;
}

const std::string valid_config_json =
    R"({"slices": 8, "resolution": 128, "filter": "sat", "fusion": "average", "packing": "array", )"
    R"("light": "sun", "leak_fix": false, "self_shadow_fade": true, "tangent_clip": true, "target": "glsl450"})";

} // namespace

TEST_CASE("a default run writes exactly the files layout.json lists") {
    const fs::path dir = scratch().fresh("default") / "nested";
    const Run run = run_gen(with_out({}, dir));
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.err.empty());
    CHECK(run.out.find(dir.string()) != std::string::npos);
    CHECK(listing(dir) == layout_files(dir));
    const nlohmann::json config = nlohmann::json::parse(read_text(dir / "layout.json")).at("config");
    CHECK(config.at("slices") == penumbra::Config{}.slices);
    CHECK(config.at("target") == "glsl450");

    // A second run over the same directory replaces the files and leaves no temporaries.
    const Run again = run_gen(with_out({"--slices", "4"}, dir));
    REQUIRE(again.exit_code == 0);
    CHECK(listing(dir) == layout_files(dir));
}

TEST_CASE("--validate passes the emitted programs through glslang") {
    const std::vector<std::vector<std::string>> cases{
        {},
        {"--filter", "sat", "--packing", "array", "--target", "glsl330", "--resolution", "64"},
        {"--filter", "gaussian", "--light", "sun", "--packing", "volume", "--target", "vulkan",
         "--resolution", "256"},
        {"--filter", "mipmap", "--packing", "atlas", "--target", "essl300"},
        {"--slices", "5", "--fusion", "average", "--no-leak-fix", "--no-fade", "--resolution=32"},
        {"--slices", "64", "--resolution", "256", "--fusion", "chained", "--tangent-clip"},       // bits, unpacked
        {"--slices", "128", "--resolution", "64", "--packing", "array", "--target", "vulkan"},
        // HLSL: glslang's HLSL front end, each stage linked alone
        {"--target", "hlsl", "--slices", "8", "--resolution", "64"},
        {"--target", "hlsl", "--technique", "pcss", "--alpha-test"},
    };
    for (const std::vector<std::string>& args : cases) {
        CAPTURE(joined(args));
        const fs::path dir = scratch().fresh("validate");
        std::vector<std::string> full = with_out(args, dir);
        full.push_back("--validate");
        const Run run = run_gen(full);
        INFO(run.err);
        CHECK(run.exit_code == 0);
        CHECK(run.out.find("validated") != std::string::npos);
        if (run.exit_code == 0) CHECK(listing(dir) == layout_files(dir));
    }
}

TEST_CASE("--target msl: the vulkan programs through SPIRV-Cross, one function a .metal file, indices in layout.json") {
    const fs::path dir = scratch().fresh("msl");
    const Run run = run_gen(with_out({"--target", "msl", "--technique", "pcss"}, dir));
    INFO(run.err);
    REQUIRE(run.exit_code == 0);
    CHECK(run.out.find("translated by SPIRV-Cross") != std::string::npos);
    CHECK(listing(dir) == layout_files(dir));
    const nlohmann::json layout = nlohmann::json::parse(read_text(dir / "layout.json"));
    CHECK(layout.at("config").at("target") == "msl");
    CHECK(layout.at("msl").at("first_free_buffer").get<int>() >= 1);
    for (const nlohmann::json& program : layout.at("programs")) {
        CAPTURE(program.at("name").get<std::string>());
        REQUIRE(program.at("msl_functions").size() == program.at("files").size());
        for (std::size_t i = 0; i < program.at("files").size(); ++i) {
            const std::string file = program.at("files")[i], function = program.at("msl_functions")[i];
            CHECK(file.ends_with(".metal"));
            CHECK(read_text(dir / file).find(" " + function + "(") != std::string::npos);
        }
        for (const nlohmann::json& p : program.at("parameters"))
            if (p.contains("binding") || p.contains("block")) CHECK(p.contains("msl"));
    }
    // What the vulkan target refuses, msl refuses in its own name.
    const Run refused = run_gen(with_out({"--target", "msl", "--slices", "32"}, scratch().fresh("msl_refused")));
    CHECK(refused.exit_code == 2);
    CHECK(refused.err.find("target 'msl'") != std::string::npos);
}

TEST_CASE("layout.json (version 2): phases, structured state, the deferred pass and its textures") {
    const fs::path dir = scratch().fresh("layout_v2");
    REQUIRE(run_gen(with_out({"--packing", "array"}, dir)).exit_code == 0);
    const nlohmann::json layout = nlohmann::json::parse(read_text(dir / "layout.json"));
    CHECK(layout.at("layout_version") == 3);
    CHECK(layout.at("technique") == "occlusion");
    const std::string result = layout.at("result");
    std::map<std::string, nlohmann::json> textures;
    for (const nlohmann::json& t : layout.at("textures")) textures[t.at("name")] = t;
    REQUIRE(textures.count(result) == 1);
    CHECK(textures.at(result).at("size") == "output");
    const nlohmann::json& world = textures.at("penumbra_worldPositions");
    CHECK(world.at("source") == "caller");
    CHECK(world.at("internal_format") == "RGBA32F");
    CHECK(textures.at("penumbra_levels").at("border_color") == nlohmann::json::array({0, 0, 0, 0}));
    int screen_passes = 0;
    for (const nlohmann::json& pass : layout.at("passes")) {
        CHECK(pass.at("state").is_object());
        CHECK(pass.at("state").at("blend").is_boolean());
        if (pass.at("phase") != "screen") continue;
        ++screen_passes;
        CHECK(pass.at("program") == "shading_deferred");
        CHECK(pass.at("outputs").at(0).at("texture") == result);
        bool reads_world = false;
        for (const nlohmann::json& in : pass.at("inputs")) reads_world = reads_world || in.at("texture") == "penumbra_worldPositions";
        CHECK(reads_world);
    }
    CHECK(screen_passes == 1);
    CHECK(layout.at("passes").at(0).at("state").at("blend_equation") == "MAX");
}

TEST_CASE("--profile and the JSON key profile: the preset, with the fields given beside it winning") {
    auto config_of = [](const fs::path& dir) { return nlohmann::json::parse(read_text(dir / "layout.json")).at("config"); };
    const fs::path large = scratch().fresh("profile-large");
    REQUIRE(run_gen(with_out({"--profile", "large"}, large)).exit_code == 0);
    const nlohmann::json c = config_of(large);
    CHECK(c.at("profile") == "large");
    CHECK(c.at("slices") == 16);
    CHECK(c.at("fusion") == "extent");
    CHECK(c.at("irradiance_quadrants") == true);
    CHECK_FALSE(c.contains("irradiance_window")); // on, the default, so not written
    // a flag given beside it wins, before or after it; under --light sun the window stays on, with no effect
    const fs::path mixed = scratch().fresh("profile-mixed");
    REQUIRE(run_gen(with_out({"--fusion", "chained", "--profile", "large", "--light", "sun"}, mixed)).exit_code == 0);
    const nlohmann::json m = config_of(mixed);
    CHECK(m.at("fusion") == "chained");
    CHECK(m.value("irradiance_window", true));
    // the same from JSON, whatever the order of its keys; layout.json reads back to the same emission
    const fs::path from_json = scratch().fresh("profile-json");
    REQUIRE(run_gen(with_out({"--config", write_text("profile.json", R"({"fusion": "extent", "profile": "large"})").string()},
                             from_json))
                .exit_code == 0);
    CHECK(config_of(from_json).at("fusion") == "extent");
    CHECK(config_of(from_json).value("irradiance_window", true));
    // --no-irradiance-window: weighed by area, written as false
    const fs::path area = scratch().fresh("profile-area");
    REQUIRE(run_gen(with_out({"--profile", "large", "--no-irradiance-window"}, area)).exit_code == 0);
    CHECK(config_of(area).at("irradiance_window") == false);
    const fs::path again = scratch().fresh("profile-again");
    REQUIRE(run_gen(with_out({"--config", (large / "layout.json").string()}, again)).exit_code == 0);
    CHECK(read_text(again / "layout.json") == read_text(large / "layout.json"));
    // the default writes no profile key (layouts of earlier versions stay as they were)
    const fs::path plain = scratch().fresh("profile-none");
    REQUIRE(run_gen(with_out({}, plain)).exit_code == 0);
    CHECK_FALSE(config_of(plain).contains("profile"));
    const Run wrong = run_gen(with_out({"--profile", "huge"}, scratch().fresh("profile-wrong")));
    CHECK(wrong.exit_code == 2);
    CHECK(wrong.err.find("--profile: 'huge' is not allowed; allowed: balanced, large, fast") !=
          std::string::npos);
    // fast: its slices, resolution, fusion and the light by area, and a --slices beside it wins
    const fs::path fast = scratch().fresh("profile-fast");
    REQUIRE(run_gen(with_out({"--slices", "4", "--profile", "fast"}, fast)).exit_code == 0);
    const nlohmann::json f = config_of(fast);
    CHECK(f.at("profile") == "fast");
    CHECK(f.at("slices") == 4);
    CHECK(f.at("resolution") == 128);
    CHECK(f.at("fusion") == "chained");
    CHECK(f.at("irradiance_window") == false);
}

TEST_CASE("--config reads a config object or a whole layout.json; flags override it") {
    const fs::path first = scratch().fresh("from-json");
    REQUIRE(run_gen(with_out({"--config", write_text("config.json", valid_config_json).string()}, first))
                .exit_code == 0);
    const nlohmann::json layout = nlohmann::json::parse(read_text(first / "layout.json"));
    const nlohmann::json given = nlohmann::json::parse(valid_config_json);
    for (const auto& [key, value] : given.items()) CHECK(layout.at("config").at(key) == value);

    // layout.json itself, and its "config" object alone, give back the same layout.json.
    const fs::path whole = scratch().fresh("from-layout");
    REQUIRE(run_gen(with_out({"--config", (first / "layout.json").string()}, whole)).exit_code == 0);
    CHECK(read_text(whole / "layout.json") == read_text(first / "layout.json"));
    const fs::path object = scratch().fresh("from-object");
    const fs::path object_file = write_text("object.json", layout.at("config").dump(2));
    REQUIRE(run_gen(with_out({"--config", object_file.string()}, object)).exit_code == 0);
    CHECK(read_text(object / "layout.json") == read_text(first / "layout.json"));

    // Flags win over the file; keys left out keep Config{}'s defaults.
    const fs::path overridden = scratch().fresh("overridden");
    const fs::path partial = write_text("partial.json", R"({"slices": 12, "packing": "volume"})");
    REQUIRE(run_gen(with_out({"--config", partial.string(), "--packing", "array", "--no-fade", "--tangent-clip"},
                              overridden))
                .exit_code == 0);
    const nlohmann::json config = nlohmann::json::parse(read_text(overridden / "layout.json")).at("config");
    CHECK(config.at("slices") == 12);
    CHECK(config.at("packing") == "array");
    CHECK(config.at("self_shadow_fade") == false);
    CHECK(config.at("leak_fix") == true);
    CHECK(config.at("tangent_clip") == true);
    CHECK(read_text(overridden / "penumbra_visibility.glsl").find("penumbraVisibility(vec3 worldPos, vec3 worldNormal)") !=
          std::string::npos);
    CHECK(config.at("resolution") == penumbra::Config{}.resolution);

    // --slice-placement and the JSON key slice_placement; a wrong value names the allowed ones
    const fs::path adaptive = scratch().fresh("adaptive");
    const fs::path placement = write_text("placement.json", R"({"slice_placement": "adaptive"})");
    REQUIRE(run_gen(with_out({"--config", placement.string()}, adaptive)).exit_code == 0);
    CHECK(nlohmann::json::parse(read_text(adaptive / "layout.json")).at("config").at("slice_placement") == "adaptive");
    CHECK(fs::exists(adaptive / "penumbra_slice_boundaries.frag"));
    const Run wrong = run_gen(with_out({"--slice-placement", "quantile"}, scratch().fresh("wrong-placement")));
    CHECK(wrong.exit_code == 2);
    CHECK(wrong.err.find("--slice-placement: 'quantile' is not allowed; allowed: uniform, adaptive") != std::string::npos);

    // --alpha-test and the JSON key alpha_test (cut-out casters): layout.json says so only when on,
    // the caster programs take penumbra_uv and the per-draw parameters, and the file reads back
    const fs::path cut = scratch().fresh("alpha-test");
    REQUIRE(run_gen(with_out({"--alpha-test", "--technique", "pcss"}, cut)).exit_code == 0);
    const nlohmann::json cut_layout = nlohmann::json::parse(read_text(cut / "layout.json"));
    CHECK(cut_layout.at("config").at("alpha_test") == true);
    CHECK(read_text(cut / "penumbra_shadow_depth.frag").find("penumbra_alphaCutoff) discard;") != std::string::npos);
    bool draw_sampler = false;
    for (const nlohmann::json& program : cut_layout.at("programs"))
        for (const nlohmann::json& param : program.at("parameters"))
            if (param.at("name") == "penumbra_alphaTexture")
                draw_sampler = param.at("source") == "draw" && !param.contains("texture") && program.at("name") == "shadow_depth";
    CHECK(draw_sampler);
    const fs::path cut_again = scratch().fresh("alpha-test-again");
    REQUIRE(run_gen(with_out({"--config", (cut / "layout.json").string()}, cut_again)).exit_code == 0);
    CHECK(read_text(cut_again / "layout.json") == read_text(cut / "layout.json"));
    CHECK_FALSE(nlohmann::json::parse(read_text(adaptive / "layout.json")).at("config").contains("alpha_test"));
    const Run not_bool = run_gen(with_out({"--config", write_text("cut.json", R"({"alpha_test": 1})").string()},
                                          scratch().fresh("alpha-test-wrong")));
    CHECK(not_bool.exit_code == 2);
    CHECK(not_bool.err.find("alpha_test") != std::string::npos);
}

namespace {
struct BadInput {
    const char* name;
    std::vector<std::string> args;     // "--out DIR" is added unless `no_out`
    const char* expected;              // text the first stderr line must contain
    const char* config_json = nullptr; // written to a file and passed as --config when set
    bool no_out = false;
};
} // namespace

TEST_CASE("bad arguments and bad config files: exit 2, one clear error line, nothing written") {
    const std::vector<BadInput> cases{
        {"unknown flag", {"--slcies", "8"}, "unknown flag '--slcies'; allowed: --technique, --profile, --light, --target, --alpha-test, --no-alpha-test, --slices"},
        {"short unknown flag", {"-s"}, "unknown flag '-s'"},
        {"positional", {"extra"}, "unexpected argument 'extra'"},
        {"missing value", {"--slices"}, "--slices: missing value", nullptr, true},
        {"missing value before flag", {"--filter"}, "--filter: missing value", nullptr, true},
        {"not an integer", {"--slices", "abc"}, "--slices: 'abc' is not an integer; allowed: 1 to 32, 64 or 128"},
        {"trailing text", {"--resolution", "512px"}, "--resolution: '512px' is not an integer"},
        {"empty integer", {"--slices="}, "--slices: '' is not an integer"},
        {"beyond int",
         {"--slices", "99999999999999999999"},
         "--slices: 99999999999999999999 is out of range"},
        {"enum",
         {"--filter", "box"},
         "--filter: 'box' is not allowed; allowed: mipmap, nbuffer, sat, gaussian"},
        {"enum case",
         {"--target", "GLSL450"},
         "--target: 'GLSL450' is not allowed; allowed: glsl330, glsl450, essl300, vulkan, wgsl, hlsl, msl"},
        {"fusion", {"--fusion=min"}, "allowed: probabilistic, additive, maximum, average"},
        {"packing", {"--packing", "cube"}, "allowed: atlas, array, volume"},
        {"light", {"--light", "point"}, "allowed: rect, sun"},
        {"switch with value", {"--validate=yes"}, "--validate: takes no value"},
        {"missing --out", {"--slices", "8"}, "--out", nullptr, true},
        {"empty --out", {"--out", ""}, "--out: empty path", nullptr, true},
        {"slices out of range", {"--slices", "0"}, "slices: 0 is out of range; allowed: 1 to 32, 64 or 128"},
        {"resolution not a power of two", {"--resolution", "500"}, "resolution: 500 is not allowed"},
        {"missing config",
         {"--config", "/nonexistent/penumbra.json"},
         "--config: cannot open '/nonexistent/penumbra.json'"},
        {"config is a directory", {"--config", "/"}, "--config: cannot read '/': it is a directory"},
        {"json syntax", {}, "parse error at line 1, column", "{\"slices\": 8,"},
        {"json syntax line 3", {}, "line 3, column", "{\n  \"slices\": 8,\n  \"filter\" \"sat\"\n}"},
        {"empty file", {}, "parse error", ""},
        {"unknown key", {}, "unknown key 'slice'; allowed keys: technique, slices, resolution", R"({"slice": 8})"},
        {"string for an integer", {}, "key 'slices' must be an integer", R"({"slices": "16"})"},
        {"fraction", {}, "key 'resolution' must be an integer", R"({"resolution": 512.5})"},
        {"huge integer", {}, "key 'slices': 99999999999 is out of range", R"({"slices": 99999999999})"},
        {"huge negative", {}, "key 'slices': -99999999999 is out of range", R"({"slices": -99999999999})"},
        {"uint64 max", {}, "key 'resolution'", R"({"resolution": 18446744073709551615})"},
        {"number for a bool", {}, "key 'leak_fix' must be true or false", R"({"leak_fix": 1})"},
        {"number for an enum", {}, "key 'filter' must be a string", R"({"filter": 2})"},
        {"enum name in json",
         {},
         "key 'light': 'area' is not allowed; allowed: rect, sun",
         R"({"light": "area"})"},
        {"raw bytes escaped", {}, "last read: '\"sl\\xff'", "{\"sl\xff\": 1}"},
        {"array top level", {}, "top level must be a JSON object", "[1, 2]"},
        {"string top level", {}, "top level must be a JSON object", "\"slices\""},
        {"config not an object", {}, "\"config\" must be an object", R"({"config": 5})"},
        {"invalid value in json", {}, "slices: 65 is out of range", R"({"slices": 65})"},
    };
    for (const BadInput& c : cases) {
        CAPTURE(c.name);
        const fs::path dir = scratch().fresh("bad");
        std::vector<std::string> args = c.args;
        if (c.config_json) {
            args.push_back("--config");
            args.push_back(write_text("bad.json", c.config_json).string());
        }
        if (!c.no_out) args = with_out(args, dir);
        const Run run = run_gen(args);
        CAPTURE(run.err);
        CHECK(run.exit_code == 2);
        CHECK(run.first_error_line().starts_with("error: "));
        CHECK(run.first_error_line().find(c.expected) != std::string::npos);
        CHECK(run.out.empty());
        CHECK(!fs::exists(dir));
    }
}

TEST_CASE("--out naming an existing file: exit 2, the file untouched") {
    const fs::path file = write_text("not-a-dir", "keep me");
    const Run run = run_gen(with_out({}, file));
    CHECK(run.exit_code == 2);
    CHECK(run.first_error_line().find("is not a directory") != std::string::npos);
    CHECK(read_text(file) == "keep me");
}

TEST_CASE("invalid combinations: exit 2 with penumbra::validate's message") {
    using namespace penumbra;
    struct Combination {
        std::vector<std::string> args;
        Config config; // the same configuration, for the expected message
        const char* field;
    };
    const std::vector<Combination> cases{
        {{"--filter", "gaussian", "--light", "rect"}, {.filter = Filter::gaussian}, "filter"},
        {{"--packing", "volume", "--filter", "sat"},
         {.filter = Filter::sat, .packing = Packing::volume},
         "packing"},
        {{"--filter", "sat", "--target", "essl300", "--packing", "array"},
         {.filter = Filter::sat, .packing = Packing::array, .target = Target::essl300},
         "filter"},
        {{"--slices", "32", "--target", "essl300", "--resolution", "128"},
         {.slices = 32, .resolution = 128, .target = Target::essl300},
         "slices"},
        {{"--slices", "32", "--resolution", "512", "--target", "glsl330"},
         {.slices = 32, .resolution = 512, .target = Target::glsl330},
         "resolution"},
        {{"--slices", "64", "--target", "essl300", "--resolution", "128"},
         {.slices = 64, .resolution = 128, .target = Target::essl300},
         "slices"},
        {{"--slices", "128", "--resolution", "1024"}, {.slices = 128, .resolution = 1024}, "resolution"},
    };
    for (const Combination& c : cases) {
        CAPTURE(joined(c.args));
        const std::vector<ConfigError> errors = validate(c.config);
        REQUIRE(!errors.empty());
        CHECK(errors.front().field == c.field);
        const fs::path dir = scratch().fresh("combination");
        const Run run = run_gen(with_out(c.args, dir));
        CHECK(run.exit_code == 2);
        CHECK(run.first_error_line() == "error: " + errors.front().message);
        CHECK(run.err == [&] {
            std::string all;
            for (const ConfigError& e : errors) all += "error: " + e.message + "\n";
            return all;
        }());
        CHECK(!fs::exists(dir));
    }
}

TEST_CASE("--help documents every flag and every allowed value") {
    for (const char* flag : {"--help", "-h"}) {
        const Run run = run_gen({"--slices", "abc", flag});
        CHECK(run.exit_code == 0);
        for (const char* name :
             {"--slices", "--resolution", "--filter", "--fusion", "--packing", "--light", "--target",
              "--no-leak-fix", "--no-fade", "--tangent-clip", "--no-tangent-clip", "--slice-placement", "--config",
              "--validate", "--out", "--help"})
            CHECK_MESSAGE(run.out.find(name) != std::string::npos, name);
        auto check_names = [&]<class Enum>(Enum) {
            for (std::string_view name : penumbra::EnumNames<Enum>::names)
                CHECK_MESSAGE(run.out.find(name) != std::string::npos, name);
        };
        check_names(penumbra::Filter{});
        check_names(penumbra::Fusion{});
        check_names(penumbra::Packing{});
        check_names(penumbra::Light{});
        check_names(penumbra::SlicePlacement{});
        check_names(penumbra::Target{});
        CHECK(run.out.find("default 16") != std::string::npos);
        CHECK(run.out.find("default 512") != std::string::npos);
    }
}

TEST_CASE("fuzz: random argument vectors never crash, and exit 2 writes nothing") {
    std::mt19937 random(20240611);
    auto pick = [&](const std::vector<std::string>& pool) {
        return pool[std::uniform_int_distribution<std::size_t>(0, pool.size() - 1)(random)];
    };
    auto chance = [&](double p) { return std::uniform_real_distribution<double>(0, 1)(random) < p; };
    const fs::path good_config = write_text("fuzz-good.json", valid_config_json);
    const fs::path bad_config = write_text("fuzz-bad.json", "{\"slices\": [");
    const std::vector<std::string> value_flags{"--slices",  "--resolution", "--filter", "--fusion",
                                               "--packing", "--light",      "--target"};
    const std::vector<std::string> values{"16",
                                          "1",
                                          "32",
                                          "0",
                                          "-1",
                                          "33",
                                          "8",
                                          "64",
                                          "128",
                                          "32",
                                          "4096",
                                          "8192",
                                          "500",
                                          "abc",
                                          "",
                                          "16x",
                                          "0x10",
                                          " 16",
                                          "2147483647",
                                          "-2147483648",
                                          "99999999999",
                                          "mipmap",
                                          "nbuffer",
                                          "sat",
                                          "gaussian",
                                          "probabilistic",
                                          "additive",
                                          "maximum",
                                          "average",
                                          "atlas",
                                          "array",
                                          "volume",
                                          "rect",
                                          "sun",
                                          "glsl330",
                                          "glsl450",
                                          "essl300",
                                          "vulkan",
                                          "SAT",
                                          "foo",
                                          "\xff\xfe",
                                          "--out"};
    const std::vector<std::string> junk{
        "--bogus",      "-x",         "--",         "-",        "--slices=",       "--filter=sat",
        "--validate=1", "positional", "--no-fade=", "--config", "--target=vulkan", "-h2"};
    int written = 0, rejected = 0;
    for (int i = 0; i < 200; ++i) {
        const fs::path dir = scratch().fresh("fuzz-args");
        std::vector<std::string> args;
        const int tokens = std::uniform_int_distribution<int>(0, 6)(random);
        for (int t = 0; t < tokens; ++t) {
            const int kind = std::uniform_int_distribution<int>(0, 9)(random);
            if (kind <= 4) {
                const std::string flag = pick(value_flags);
                const std::string value = pick(values);
                if (chance(0.2))
                    args.push_back(flag + "=" + value);
                else
                    args.insert(args.end(), {flag, value});
            } else if (kind == 5) {
                args.push_back(chance(0.5) ? "--no-leak-fix" : "--no-fade");
            } else if (kind == 6) {
                args.insert(args.end(),
                            {"--config", chance(0.5)   ? good_config.string()
                                         : chance(0.5) ? bad_config.string()
                                                       : (scratch().root / "missing.json").string()});
            } else if (kind == 7 && chance(0.3)) {
                args.push_back("--validate");
            } else {
                args.push_back(pick(junk));
            }
        }
        // --out is only ever followed by `dir` (or ends the vector), so nothing lands elsewhere.
        if (chance(0.9)) {
            const auto at =
                args.begin() + std::uniform_int_distribution<std::ptrdiff_t>(0, std::ssize(args))(random);
            if (chance(0.2))
                args.insert(at, "--out=" + dir.string());
            else
                args.insert(at, {"--out", dir.string()});
        } else if (chance(0.5)) {
            args.push_back("--out");
        }
        CAPTURE(joined(args));
        const Run run = run_gen(args);
        CAPTURE(run.err);
        CHECK(run.signal == 0);
        CHECK((run.exit_code == 0 || run.exit_code == 1 || run.exit_code == 2));
        if (run.exit_code == 1) CHECK(std::find(args.begin(), args.end(), "--validate") != args.end());
        if (run.exit_code == 2) {
            CHECK(run.first_error_line().starts_with("error: "));
            CHECK(!fs::exists(dir));
        }
        written += run.exit_code == 0;
        rejected += run.exit_code == 2;
        std::error_code ec;
        fs::remove_all(dir, ec);
    }
    CHECK(written >= 10); // the mix exercises both outcomes
    CHECK(rejected >= 10);
}

TEST_CASE("fuzz: truncated, random and mutated config files exit 0 or 2, never crash or hang") {
    std::mt19937 random(7);
    int written = 0;
    std::vector<std::string> documents;
    // Every proper prefix of a valid config is malformed JSON.
    for (std::size_t length = 0; length < valid_config_json.size(); ++length)
        documents.push_back(valid_config_json.substr(0, length));
    const std::size_t truncated = documents.size();
    for (int i = 0; i < 40; ++i) { // random bytes
        std::string bytes(std::uniform_int_distribution<std::size_t>(0, 64)(random), '\0');
        for (char& c : bytes) c = static_cast<char>(std::uniform_int_distribution<int>(0, 255)(random));
        documents.push_back(bytes);
    }
    const std::string alphabet = "{}[]\":,0123456789-.eE tfnulraxyz\\\n\t\x01\xc3";
    for (int i = 0; i < 80; ++i) { // a few characters flipped, inserted or removed
        std::string text = valid_config_json;
        for (int edits = std::uniform_int_distribution<int>(1, 4)(random); edits > 0; --edits) {
            const std::size_t at = std::uniform_int_distribution<std::size_t>(0, text.size() - 1)(random);
            const char c =
                alphabet[std::uniform_int_distribution<std::size_t>(0, alphabet.size() - 1)(random)];
            switch (std::uniform_int_distribution<int>(0, 2)(random)) {
            case 0: text[at] = c; break;
            case 1: text.insert(text.begin() + static_cast<std::ptrdiff_t>(at), c); break;
            default: text.erase(at, 1); break;
            }
        }
        documents.push_back(text);
    }
    for (std::size_t i = 0; i < documents.size(); ++i) {
        CAPTURE(i);
        CAPTURE(documents[i]);
        const fs::path dir = scratch().fresh("fuzz-json");
        const fs::path file = write_text("fuzz.json", documents[i]);
        const Run run = run_gen(with_out({"--config", file.string()}, dir));
        CAPTURE(run.err);
        CHECK(run.signal == 0);
        CHECK((run.exit_code == 0 || run.exit_code == 2));
        if (i < truncated) CHECK(run.exit_code == 2);
        if (run.exit_code == 2) {
            CHECK(run.first_error_line().starts_with("error: "));
            std::istringstream lines(run.err); // each line an error (validate may report several)
            for (std::string line; std::getline(lines, line);) CHECK(line.starts_with("error: "));
            CHECK(!fs::exists(dir));
        }
        written += run.exit_code == 0;
        std::error_code ec;
        fs::remove_all(dir, ec);
        fs::remove(file, ec);
    }
    CHECK(written >= 1); // some mutations leave a valid configuration
}

TEST_CASE("--technique and each technique's flags: files, layout.json, --help, messages, exit codes") {
    const std::vector<std::vector<std::string>> cases{
        {"--technique", "shadowmap"},
        {"--technique", "pcf", "--pcf-grid", "3", "--pcf-radius", "0.25", "--no-rotation", "--target", "essl300"},
        {"--technique", "pcf", "--pcf-taps", "32", "--light", "sun", "--target", "vulkan"},
        {"--technique", "pcss", "--pcss-blockers", "17", "--pcss-filter", "34", "--shadow-resolution", "512",
         "--shadow-bias", "0.01", "--shadow-slope-bias", "2", "--target", "glsl330"},
    };
    for (const std::vector<std::string>& args : cases) {
        CAPTURE(joined(args));
        const fs::path dir = scratch().fresh("technique");
        std::vector<std::string> full = with_out(args, dir);
        full.push_back("--validate");
        const Run run = run_gen(full);
        INFO(run.err);
        REQUIRE(run.exit_code == 0);
        CHECK(listing(dir) == layout_files(dir));
        CHECK(listing(dir).count("penumbra_shadow_depth.frag") == 1);
        CHECK(listing(dir).count("penumbra_visibility.glsl") == 1);
        const nlohmann::json layout = nlohmann::json::parse(read_text(dir / "layout.json"));
        CHECK(layout.at("config").at("technique") == args[1]);
        // layout.json gives back the same files
        const fs::path again = scratch().fresh("technique-again");
        REQUIRE(run_gen(with_out({"--config", (dir / "layout.json").string()}, again)).exit_code == 0);
        for (const std::string& name : listing(dir)) CHECK(read_text(again / name) == read_text(dir / name));
    }
    const fs::path pcss = scratch().fresh("pcss-flags");
    REQUIRE(run_gen(with_out({"--technique", "pcss", "--pcss-blockers", "17", "--pcss-filter", "34"}, pcss))
                .exit_code == 0);
    const nlohmann::json config = nlohmann::json::parse(read_text(pcss / "layout.json")).at("config");
    CHECK(config.at("pcss").at("blocker_samples") == 17);
    CHECK(config.at("pcss").at("filter_samples") == 34);

    const std::vector<std::pair<std::vector<std::string>, std::string>> bad{
        {{"--technique", "vsm"}, "--technique: 'vsm' is not allowed; allowed: occlusion, shadowmap, pcf, pcss"},
        {{"--technique", "pcss", "--pcss-filter", "0"}, "pcss.filter_samples: 0 is out of range; allowed: 1 to 128"},
        {{"--technique", "pcf", "--pcf-radius", "wide"}, "--pcf-radius: 'wide' is not a number"},
        {{"--technique", "pcss", "--shadow-resolution", "100"}, "shadow_map.resolution: 100 is not allowed"},
        {{"--no-rotation=1"}, "--no-rotation: takes no value"},
    };
    for (const auto& [args, expected] : bad) {
        CAPTURE(joined(args));
        const fs::path dir = scratch().fresh("technique-bad");
        const Run run = run_gen(with_out(args, dir));
        CHECK(run.exit_code == 2);
        CHECK(run.first_error_line().find(expected) != std::string::npos);
        CHECK(!fs::exists(dir));
    }
    const Run help = run_gen({"--help"});
    for (const char* flag : {"--technique", "--shadow-resolution", "--shadow-bias", "--shadow-slope-bias",
                             "--pcf-pattern", "--pcf-grid", "--pcf-taps", "--pcf-radius", "--pcss-blockers",
                             "--pcss-filter", "--pcss-max-texels", "--no-rotation"})
        CHECK_MESSAGE(help.out.find(flag) != std::string::npos, flag);
    for (std::string_view name : penumbra::EnumNames<penumbra::Technique>::names)
        CHECK(help.out.find(name) != std::string::npos);
}
