// penumbra/detail/evsm/technique.hpp — exponential variance shadow maps as a descriptor: the shadow
// map's depth pass, the moments pass and two blur passes from the light, then the deferred shading
// with the Chebyshev bound (emit_passes.hpp says what each computes).
#pragma once

#include "../shadow_map/technique.hpp"
#include "fields.hpp"
#include "layout.hpp"
#include "validate.hpp"

namespace penumbra::detail {

inline constexpr ShaderFileSpec evsm_moments_frag{"penumbra_evsm_moments.frag", Stage::fragment, evsm_moments_fragment};
inline constexpr ShaderFileSpec evsm_blur_x_frag{"penumbra_evsm_blur_x.frag", Stage::fragment, evsm_blur_x_fragment};
inline constexpr ShaderFileSpec evsm_blur_y_frag{"penumbra_evsm_blur_y.frag", Stage::fragment, evsm_blur_y_fragment};

// Depth, moments, blur x, blur y, shading.
constexpr std::vector<ProgramPlan> evsm_programs(const Config&) {
    return {shadow_depth_program(),
            {"evsm_moments", {fullscreen_vert, evsm_moments_frag}},
            {"evsm_blur_x", {fullscreen_vert, evsm_blur_x_frag}},
            {"evsm_blur_y", {fullscreen_vert, evsm_blur_y_frag}},
            shading_example_program(),
            shading_deferred_program()};
}

constexpr bool evsm_reads_normal(const Config&) { return false; }

constexpr Text evsm_summary(const Config& config) {
    const EvsmParams& e = config.evsm;
    return cat(describe_shadow_map(config), " | evsm exponents +", format_float(e.positive_exponent), " / -",
               format_float(e.negative_exponent), ", light-bleeding reduction ", format_float(e.light_bleeding_reduction),
               ", variance bias ", format_float(e.variance_bias), ", blur ", format_int(e.blur_taps),
               " taps per axis over ", format_float(e.blur_fraction), " of the widest penumbra, at most ",
               format_int(e.max_blur_texels), " texels, moments ", to_string(evsm_moments_format(config)),
               describe_light_and_target(config));
}

constexpr Text evsm_storage_note(const Config&) {
    return Text("Shadow map depth stored as (z - near) / (far - near) along the light axis; its moments warped by "
                "e^(c+ d) and -e^(-c- d), d = 2 depth - 1.");
}

// ES: the moments are an RGBA32UI texture, read through usampler2D (which has no default precision).
constexpr std::vector<std::string_view> evsm_es_samplers(const Config& config) {
    if (evsm_filters_in_hardware(config)) return {};
    return {"usampler2D"};
}

// The moments pass reads one texel; a blur tap and the lookup are one bilinear footprint (4 texels),
// whether the hardware or the emitted code filters.
inline long long evsm_texels_per_fragment(const Config& config, const PassDesc& pass) {
    if (pass.program == "evsm_blur_x" || pass.program == "evsm_blur_y") return 4LL * config.evsm.blur_taps;
    if (pass.program == "shading_deferred") return g_buffer_texels(config) + 4;
    return 1;
}

inline constexpr auto evsm_field_rows = evsm_fields();

constexpr TechniqueDescriptor evsm_technique() {
    return {
        .fields = evsm_field_rows,
        .programs = evsm_programs,
        .visibility_snippet = evsm_visibility_snippet,
        .visibility_params = evsm_visibility_params,
        .write_visibility = write_evsm_visibility,
        .reads_normal = evsm_reads_normal,
        .param_groups = evsm_param_groups,
        .describe_layout = describe_evsm_layout,
        .problems = evsm_problems,
        .summary = evsm_summary,
        .storage_note = evsm_storage_note,
        .es_sampler_precision = evsm_es_samplers,
        .texels_per_fragment = evsm_texels_per_fragment,
        .writes_wgsl = true,
        .writes_hlsl = true,
        .reads_shared_section = "shadow_map",
    };
}

} // namespace penumbra::detail
