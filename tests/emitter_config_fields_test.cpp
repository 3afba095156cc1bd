// The table of configuration fields (penumbra/config_fields.hpp): one row per field of Config, each
// reaching its own member, with unique keys and flags, its default inside its range, and
// layout.json's "config" object written from it.
#include <penumbra/config_fields.hpp>
#include <penumbra/layout.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <set>
#include <string>

using namespace penumbra;

TEST_CASE("config fields: unique keys and flags, defaults in range, each row reaches its own member") {
    const Config defaults{};
    std::set<std::string_view> keys, flags;
    for (const ConfigField& f : config_fields()) {
        CAPTURE(f.key);
        CHECK(keys.insert(f.key).second);
        CHECK(!f.help.empty());
        CHECK(f.help.find("  ") == std::string_view::npos); // --help wraps at single spaces (web panel's check)
        // only rows that share a switch share a flag (--no-rotation: pcf.rotate and pcss.rotate)
        if (!flags.insert(f.flag).second) CHECK(f.kind == FieldKind::boolean);
        const double value = f.get(defaults);
        if (f.kind != FieldKind::boolean || f.flag.starts_with("--no-") || f.flag.starts_with("--[no-]")) {
            CHECK(value >= f.min);
            CHECK(value <= f.max);
        }
        if (f.kind == FieldKind::choice) CHECK(!f.names.empty());
        if (f.kind != FieldKind::choice && f.kind != FieldKind::boolean) CHECK(!allowed_text(f).empty());
        // set changes this row's member and no other row's, but a profile's, which sets its preset's
        Config changed = defaults;
        const double other = f.kind == FieldKind::boolean || f.kind == FieldKind::choice ? (value == 0 ? 1 : 0) : value + 1;
        f.set(changed, other);
        CHECK(f.get(changed) == other);
        CHECK(changed != defaults);
        const bool preset = f.key == "profile";
        for (const ConfigField& g : config_fields()) {
            if (&g != &f && !(preset && profile_sets(g.key)))
                CHECK_MESSAGE(g.get(changed) == g.get(defaults), g.key);
        }
    }
    CHECK(find_config_field("pcss.blocker_samples")->get(Config{.pcss = {.blocker_samples = 7}}) == 7);
    CHECK(find_config_field("nope") == nullptr);
}

TEST_CASE("config fields: layout.json's config object, fields added later only when not the default") {
    const Config config{.technique = Technique::pcf, .slices = 8, .pcf = {.pattern = TapPattern::grid, .radius = 0.25}};
    const std::string layout = to_json(describe_layout(config));
    CHECK(layout.find("  \"config\": " + config_to_json(config, "  ") + ",\n") != std::string::npos);
    const std::string json = config_to_json(config);
    CHECK(json.find("\"slices\": 8,") != std::string::npos);
    CHECK(json.find("\"pcf\": {\"pattern\": \"grid\", \"grid_size\": 4, \"poisson_taps\": 16, \"radius\": 0.25, "
                    "\"rotate\": true},") != std::string::npos);
    CHECK(json.find("alpha_test") == std::string::npos);
    CHECK(json.find("prefilter_stage") == std::string::npos);
    CHECK(json.ends_with("\"blur_taps\": 16}\n}"));
    const std::string cut = config_to_json(Config{.alpha_test = true});
    CHECK(cut.ends_with("\"blur_taps\": 16},\n  \"alpha_test\": true\n}"));
}

TEST_CASE("config fields: --help lines and the flag list") {
    const std::string usage = config_usage(25);
    for (const ConfigField& f : config_fields()) {
        CAPTURE(f.key);
        CHECK(usage.find(std::string(f.flag)) != std::string::npos);
    }
    CHECK(usage.find("  --slices N             slices along the light normal: 1 to 32, 64 or 128 (default 16)\n") !=
          std::string::npos);
    CHECK(usage.find("--no-tangent-clip turns it off") != std::string::npos);
    const std::string flags = config_flag_list();
    CHECK(flags.find("--tangent-clip, --no-tangent-clip") != std::string::npos);
    CHECK(flags.find("--no-rotation") == flags.rfind("--no-rotation")); // once, though two rows share it
}
