// penumbra/detail/technique_visibility.hpp — penumbraVisibility() of the configured technique: the
// one function every shading program and penumbra_visibility.glsl are built around, so an engine
// switches techniques without changing its own shaders.
//   occlusion                occlusion/emit_visibility.hpp
//   shadowmap, pcf, pcss     shadow_map/emit_visibility.hpp
//   oim                      oim/emit_oim.hpp (penumbraVisibility(vec2 texCoord): the maps are per surface)
#pragma once

#include "occlusion/emit_visibility.hpp"
#include "oim/emit_oim.hpp"
#include "shadow_map/emit_visibility.hpp"

namespace penumbra::detail {

constexpr std::vector<Param> technique_visibility_params(const Config& config) {
    if (uses_shadow_map(config)) return shadow_visibility_params(config);
    if (config.technique == Technique::oim) return oim_visibility_params(config);
    return visibility_params(config);
}

constexpr void write_technique_visibility(LineWriter& out, const Config& config, int& next_binding) {
    if (uses_shadow_map(config))
        write_shadow_visibility(out, config, next_binding);
    else if (config.technique == Technique::oim)
        write_oim_visibility(out, config, next_binding);
    else
        write_visibility(out, config, next_binding);
}

// The includable snippet penumbra_visibility.glsl: no #version, declarations from binding 0.
constexpr Text technique_visibility_snippet(const Config& config) {
    if (config.technique == Technique::oim) return oim_visibility_snippet(config);
    if (!uses_shadow_map(config)) return visibility_snippet(config);
    LineWriter out;
    out.line("// Penumbra ", version_string, " - penumbra_visibility.glsl: float penumbraVisibility(vec3 worldPos)");
    out.line("// ", describe(config));
    out.comment("Include after the #version line of a stage for this target. Bindings start at 0.");
    if (config.target == Target::essl300) out.comment("ES: declare precision highp sampler2DShadow before it.");
    out.blank();
    int binding = 0;
    write_shadow_visibility(out, config, binding);
    return out.take();
}

} // namespace penumbra::detail
