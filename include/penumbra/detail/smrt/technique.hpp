// penumbra/detail/smrt/technique.hpp — shadow-map ray tracing (SMRT; Unreal Engine 5's virtual shadow
// maps) as a descriptor: the shadow map's depth pass from the light, then the deferred shading whose
// penumbraVisibility marches rays through it (emit_visibility.hpp says how).
#pragma once

#include "../shadow_map/technique.hpp"
#include "fields.hpp"
#include "layout.hpp"
#include "validate.hpp"

namespace penumbra::detail {

// Depth, shading.
constexpr std::vector<ProgramPlan> smrt_programs(const Config&) {
    return {shadow_depth_program(), shading_example_program(), shading_deferred_program()};
}

// The bias follows the receiver's slope and the rays start off it along its normal.
constexpr bool smrt_reads_normal(const Config&) { return true; }

constexpr Text smrt_summary(const Config& config) {
    const SmrtParams& s = config.smrt;
    return cat(describe_shadow_map(config), " | smrt ", format_int(s.rays), " rays of ", format_int(s.samples),
               " samples, extrapolation slope at most ", format_float(s.extrapolate_max_slope),
               ", receiver slope at most ", format_float(s.max_slope_bias), ", dither ", format_float(s.texel_dither),
               " texels, frame ", format_int(s.frame), describe_light_and_target(config));
}

constexpr Text smrt_storage_note(const Config&) {
    return Text("Shadow map depth stored as (z - near) / (far - near) along the light axis.");
}

constexpr std::vector<std::string_view> smrt_es_samplers(const Config&) { return {}; }

// The deferred pass reads one depth texel per sample of every ray (at most: a blocked ray stops).
inline long long smrt_texels_per_fragment(const Config& config, const PassDesc& pass) {
    if (pass.program == "shading_deferred")
        return g_buffer_texels(config) + static_cast<long long>(config.smrt.rays) * config.smrt.samples;
    return 1;
}

inline constexpr auto smrt_field_rows = smrt_fields();

constexpr TechniqueDescriptor smrt_technique() {
    return {
        .fields = smrt_field_rows,
        .programs = smrt_programs,
        .visibility_snippet = smrt_visibility_snippet,
        .visibility_params = smrt_visibility_params,
        .write_visibility = write_smrt_visibility,
        .reads_normal = smrt_reads_normal,
        .param_groups = smrt_param_groups,
        .describe_layout = describe_smrt_layout,
        .problems = smrt_problems,
        .summary = smrt_summary,
        .storage_note = smrt_storage_note,
        .es_sampler_precision = smrt_es_samplers,
        .texels_per_fragment = smrt_texels_per_fragment,
        .writes_wgsl = true,
        .writes_hlsl = true,
        .reads_shared_section = "shadow_map",
    };
}

} // namespace penumbra::detail
