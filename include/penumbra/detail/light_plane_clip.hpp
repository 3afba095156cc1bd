// penumbra/detail/light_plane_clip.hpp — the passes that draw casters from a rectangular light (slicing,
// the adaptive depth bins, the shadow-map family's depth pass) keep only what lies in front of the
// light's plane (docs/model.md §1.2b). Geometry behind it (a ceiling above a panel, the wall around a
// window, a lamp's housing) is not between any receiver and the light, so it must cast nothing; without
// the clip it would land in the first slice, or at the shadow map's near plane, and cover the whole light.
#pragma once

#include "glsl_common.hpp"

namespace penumbra::detail {

// Fragment stage, first in main() after the alpha test: a fragment on or behind the light's plane
// (light-frame depth <= 0, interpolated per fragment, so a triangle that crosses the plane keeps its
// part in front) is discarded. The sun's frame starts above the scene: nothing to clip there.
constexpr void write_light_plane_clip(LineWriter& out, const Config& config) {
    if (config.light != Light::rect) return;
    out.comment("only what lies in front of the light's plane casts a shadow (docs/model.md §1.2b):");
    out.comment("a ceiling above the light, the wall around a window, a lamp's housing are behind it");
    out.line(if_then(config, "penumbra_depth <= 0.0", "discard;"));
}

} // namespace penumbra::detail
