// penumbra/profiles.hpp — shadow quality tiers: named presets of the occlusion-texture fields.
//
//   penumbra::Config config = penumbra::apply_profile({}, penumbra::Profile::large);
//   // the same from the tools and the add-ons: --profile large, {"profile": "large"}, profile: "large"
//
// `balanced` is Config{}, the default. `large` is for lights several times the size of the scene's own
// rectangle (a window, a sky panel, an overcast sky), where the irradiance falls steeply across the light:
// it fuses the tangent clip's four quadrants apart as well (irradiance_quadrants), five passes of the slice
// loop instead of two, and trades frame time for error (lower at every light size, most from x1 to x8).
// `fast` is for a frame budget below PCSS's: 8 slices of 128², fused by `chained` (one lookup a slice, not
// extent's two) and the light weighed by area (one pass of the slice loop, not the window's two); about a
// sixth of `balanced`'s frame on llvmpipe, with a higher error, still below PCSS 16/16's in most cells.
// All three run on every target (so none takes more than 16 slices, which OpenGL 3.3, ES 3.0 and Vulkan's
// guaranteed render targets and atlas width allow, nor solid casters, which need a logic op). The
// measurements behind each preset (error by light size against the irradiance reference, frame cost) are
// in docs/model.md §1.11.
//
// A profile sets every field it names (profile_fields), to its preset's value or else the default's; the
// fields a caller gives explicitly win over it whatever their order (apply_profile's `explicit_keys`: the
// command line's flags, a JSON file's keys).
#pragma once

#include "config.hpp"

#include <array>
#include <span>
#include <string_view>

namespace penumbra {

// The fields a profile sets: each one's key in the table of fields (penumbra/config_fields.hpp), and how it
// takes the preset's value.
struct ProfileField {
    std::string_view key;
    void (*take)(Config& config, const Config& preset);
};
inline constexpr std::array<ProfileField, 5> profile_fields{{
    {"slices", [](Config& c, const Config& p) { c.slices = p.slices; }},
    {"resolution", [](Config& c, const Config& p) { c.resolution = p.resolution; }},
    {"fusion", [](Config& c, const Config& p) { c.fusion = p.fusion; }},
    {"irradiance_window", [](Config& c, const Config& p) { c.irradiance_window = p.irradiance_window; }},
    {"irradiance_quadrants",
     [](Config& c, const Config& p) { c.irradiance_quadrants = p.irradiance_quadrants; }},
}};

// Whether a profile sets the field `key`.
constexpr bool profile_sets(std::string_view key) {
    for (const ProfileField& field : profile_fields)
        if (field.key == key) return true;
    return false;
}

// One line on what the profile is for (the tools' --help, the panels).
constexpr std::string_view profile_summary(Profile profile) {
    switch (profile) {
    case Profile::balanced: return "the default: the lowest error within the default frame time at every light size";
    case Profile::large: return "large lights (x4 and up): the irradiance window's quadrants";
    case Profile::fast:
        return "a frame budget below PCSS's: 8 slices of 128, chained fusion, the light weighed by area";
    }
    return "";
}

// `config` with `profile`'s preset, except the fields in `explicit_keys`. `balanced` and `large` keep the
// irradiance window on (it weighs a rectangle's light within the tangent clip, and has no effect elsewhere);
// `fast` weighs the light by area.
constexpr Config apply_profile(Config config, Profile profile, std::span<const std::string_view> explicit_keys = {}) {
    auto given = [&](std::string_view key) {
        for (std::string_view k : explicit_keys)
            if (k == key) return true;
        return false;
    };
    const Config defaults{};
    Config preset = defaults;
    if (profile == Profile::large) preset.irradiance_quadrants = true;
    if (profile == Profile::fast) {
        preset.slices = 8;
        preset.resolution = 128;
        preset.fusion = Fusion::chained;
        preset.irradiance_window = false;
    }
    config.profile = profile;
    for (const ProfileField& field : profile_fields)
        if (!given(field.key)) field.take(config, preset);
    return config;
}

} // namespace penumbra
