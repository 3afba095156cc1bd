// penumbra/detail/occlusion/emit_generic.hpp — the generic deferred visibility pass: the same model as
// emit_visibility.hpp with nothing specialized (issue 3, §7).
//
// Slice count, resolution, level count, tile count, fusion rule and fade are uniforms; the slice
// and level loops are real `for` loops over those uniforms; a slice's channel is picked by
// indexing the texel with the channel number. Only what the resources fix stays static: the
// sampler types of the storage (atlas sampler2D, array sampler2DArray, volume sampler3D). Where a
// storage has one texture per filter level or per four slices, the generic program declares a
// sampler array of the largest size any valid configuration needs and indexes it with a loop
// counter, which is dynamically uniform. So one program serves every slice count, resolution,
// fusion rule and fade setting of a filter × packing × light × target.
//
// The arithmetic follows emit_visibility.hpp operation by operation, so the two programs differ
// only where a literal becomes a uniform (what the compiler may fold).
#pragma once

#include "emit_prefilter.hpp"
#include "emit_visibility.hpp"
#include "../emit_shading.hpp"

namespace penumbra::detail {

// Largest sampler arrays a valid configuration needs: resolution 4096 has levels 0 to 12, and
// 32 slices fill eight RGBA textures (validate.hpp bounds both).
inline constexpr int generic_level_textures = 13;
inline constexpr int generic_volume_textures = 8;

// GLSL 3.30 and ESSL 3.00 index sampler arrays with constant expressions only; 4.x and Vulkan
// GLSL accept a dynamically uniform index.
constexpr bool indexes_sampler_arrays(const Config& config) {
    return config.target == Target::glsl450 || config.target == Target::vulkan;
}

constexpr bool uses_generic_level_loop(const Config& config) {
    return config.packing == Packing::atlas && has_level_images(config);
}

// The configuration-derived values the generic program reads as uniforms.
constexpr std::vector<Param> generic_value_params() {
    return {
        {"penumbra_sliceCount", "int", "number of slices S", ""},
        {"penumbra_resolution", "float", "occlusion texture side R", "texels"},
        {"penumbra_maxLevel", "int", "highest filter level L = log2(R)", ""},
        {"penumbra_tileCount", "int", "RGBA occlusion textures T = ceil(S / 4)", ""},
        {"penumbra_invTileCount", "float", "1 / T: width of one tile in an atlas", "uv"},
        {"penumbra_fusion", "int", "fusion rule: 0 probabilistic, 1 additive, 2 maximum, 3 average, 4 chained, 5 correlated, 6 extent", ""},
        {"penumbra_fade", "int", "paper §3.4.2 self-shadow fade: 1 on, 0 off", ""},
        {"penumbra_fadeRamp", "float", "the fade's ramp, as a fraction of a slice's thickness", ""},
        {"penumbra_tangentClipOffset", "float", "the tangent clip's sideways offset along the normal", "slicing texels"},
        {"penumbra_clipFootprint", "float",
         "how many slice thicknesses the receiver's own footprint spans (1 + leak-fix reach) with clip_footprint on, 0 off", ""},
        {"penumbra_levelReduction", "int",
         "atlas levels above this one at half the resolution of the one below (level_reduction); 99: none", ""},
    };
}

// A sampler of the generic program; `count` > 1 declares an array.
struct GenericSamplerDecl {
    Text name;
    std::string_view type;
    int count;
    std::string_view meaning;
};

// The storage samplers; the names of single samplers match the specialized program's.
constexpr std::vector<GenericSamplerDecl> generic_storage_samplers(const Config& config) {
    if (config.filter == Filter::mipmap)
        return {config.packing == Packing::atlas
                    ? GenericSamplerDecl{"penumbra_occlusionAtlas", "sampler2D", 1, "occlusion tiles side by side, mip chain"}
                    : GenericSamplerDecl{"penumbra_occlusion", "sampler2DArray", 1, "one layer per RGBA texture, mip chain"}};
    if (config.filter == Filter::sat)
        return {config.packing == Packing::atlas
                    ? GenericSamplerDecl{"penumbra_satAtlas", "sampler2D", 1, "exclusive summed-area tables side by side"}
                    : GenericSamplerDecl{"penumbra_sat", "sampler2DArray", 1, "exclusive summed-area tables, one layer each"}};
    if (config.packing == Packing::atlas)
        return {{"penumbra_levelAtlases", "sampler2D", generic_level_textures,
                 "element l: filter level l, tiles side by side; elements above L unused"}};
    if (config.packing == Packing::array)
        return {{"penumbra_levels", "sampler2DArray", 1, "filter levels, layer = level * T + texture"}};
    return {{"penumbra_volumes", "sampler3D", generic_volume_textures,
             "element t: slices 4t to 4t+3, levels along depth; elements from T on unused"}};
}

// Every sampler, in declaration (and binding) order: storage, then the G-buffer (world positions,
// and world normals when the kernels are clipped to the tangent plane).
constexpr std::vector<GenericSamplerDecl> generic_samplers_decl(const Config& config) {
    std::vector<GenericSamplerDecl> samplers = generic_storage_samplers(config);
    for (const Param& gbuffer : deferred_params(config)) samplers.push_back({gbuffer.name, gbuffer.type, 1, gbuffer.meaning});
    return samplers;
}

// What this text is specialized for: only the fields that pick resources, inputs and dialect.
constexpr Text describe_generic(const Config& config) {
    return cat("filter ", to_string(config.filter), " | packing ", to_string(config.packing), " | light ",
               to_string(config.light), " | target ", to_string(config.target),
               choose(clips_to_tangent_plane(config), " | tangent clip", ""),
               choose(weighs_irradiance(config), " + irradiance window", ""));
}

constexpr void write_generic_preamble(LineWriter& out, const Config& config, std::string_view title) {
    write_version(out, config);
    out.line("// Penumbra ", version_string, " - generic reference: ", title);
    out.line("// ", describe_generic(config));
    out.comment("Slices, resolution, levels, tiles, fusion and fade are uniforms: one program for all of them.");
    write_precision(out, config);
    out.blank();
}

// Declarations: the light's and the configuration's values (one block on Vulkan), then the
// samplers. An array of n samplers takes n texture units on OpenGL, one binding of n
// descriptors on Vulkan.
constexpr void write_generic_params(LineWriter& out, const Config& config) {
    std::vector<Param> values;
    for (Param& p : visibility_params(config))
        if (!is_sampler(p)) values.push_back(std::move(p));
    for (Param& p : generic_value_params()) values.push_back(std::move(p));
    int binding = 0;
    write_params(out, config, values, "PenumbraGeneric", binding);
    out.chunk("generic_samplers");
    for (const GenericSamplerDecl& s : generic_samplers_decl(config)) {
        const Text array = choose(s.count > 1, cat("[", format_int(s.count), "]"), Text());
        const Text declaration = cat("uniform ", s.type, " ", s.name, array, "; // ", s.meaning);
        if (is_vulkan(config)) out.line("layout(set = ", format_int(vulkan_descriptor_set), ", binding = ", format_int(binding), ") ", declaration);
        else if (has_explicit_bindings(config)) out.line("layout(binding = ", format_int(binding), ") ", declaration);
        else out.line(declaration, ", first texture unit ", format_int(binding));
        binding += is_vulkan(config) ? 1 : s.count;
    }
    out.line("layout(location = 0) out vec4 penumbra_visibility;");
    out.blank();
}

constexpr void write_generic_kernel(LineWriter& out, const Config& config) {
    write_kernel_function(out, config, "penumbra_resolution", "float(penumbra_maxLevel)");
    if (clips_to_tangent_plane(config)) write_tangent_clip_function(out, config);
    out.chunk("fade");
    out.comment("paper §3.4.2 when penumbra_fade is 1; otherwise planes strictly above the point count fully");
    out.line("float penumbra_weight(float zPoint, float zeta)");
    out.line("{");
    out.line("if (penumbra_fade != 0) return clamp((zPoint - zeta) / (penumbra_sliceDepths.y * penumbra_fadeRamp), 0.0, 1.0);");
    out.line("return 1.0 - step(zPoint, zeta);");
    out.line("}");
    out.blank();
}

// texture(array[index], coordinates) for an array of `count` samplers: direct where the dialect
// allows a dynamically uniform index, else a chain of constant indices (fixed, not per config).
constexpr void write_array_read(LineWriter& out, const Config& config, std::string_view function,
                                std::string_view coordinates_type, std::string_view array, int count) {
    out.line("vec4 ", function, "(int index, ", coordinates_type, " coordinates)");
    out.line("{");
    if (indexes_sampler_arrays(config)) {
        out.line("return textureLod(", array, "[index], coordinates, 0.0);");
    } else {
        out.comment("this dialect indexes sampler arrays with constants only");
        for (int i = 0; i + 1 < count; ++i)
            out.line("if (index == ", format_int(i), ") return textureLod(", array, "[", format_int(i),
                     "], coordinates, 0.0);");
        out.line("return textureLod(", array, "[", format_int(count - 1), "], coordinates, 0.0);");
    }
    out.line("}");
    out.blank();
}

// vec4 penumbra_filtered(vec4 kernel, int tile): all four channels of RGBA texture `tile`,
// filtered over the kernel (every storage but the atlas of level images).
constexpr void write_generic_lookup(LineWriter& out, const Config& config) {
    out.chunk("lookup");
    if (config.filter == Filter::mipmap) {
        out.line("vec4 penumbra_filtered(vec4 kernel, int tile)");
        out.line("{");
        if (config.packing == Packing::atlas)
            out.line("return textureLod(penumbra_occlusionAtlas, vec2((float(tile) + kernel.x) * penumbra_invTileCount, "
                     "kernel.y), kernel.w);");
        else
            out.line("return textureLod(penumbra_occlusion, vec3(kernel.xy, float(tile)), kernel.w);");
        out.line("}");
    } else if (config.filter == Filter::sat) {
        out.comment("Crow 1984: prefix sum at texel corner X lives at the centre of texel X of an (R+1)-texel tile");
        out.line("vec4 penumbra_prefix(vec2 corner, int tile)");
        out.line("{");
        out.line("vec2 uv = (corner + 0.5) / (penumbra_resolution + 1.0);");
        if (config.packing == Packing::atlas)
            out.line("return textureLod(penumbra_satAtlas, vec2((float(tile) + uv.x) * penumbra_invTileCount, uv.y), 0.0);");
        else
            out.line("return textureLod(penumbra_sat, vec3(uv, float(tile)), 0.0);");
        out.line("}");
        out.blank();
        out.line("vec4 penumbra_filtered(vec4 kernel, int tile)");
        out.line("{");
        out.block(R"(
            float side = max(kernel.z * penumbra_resolution, 1.0);
            vec2 lo = clamp(kernel.xy * penumbra_resolution - 0.5 * side, 0.0, penumbra_resolution);
            vec2 hi = clamp(kernel.xy * penumbra_resolution + 0.5 * side, 0.0, penumbra_resolution);
            vec4 sum = penumbra_prefix(hi, tile) - penumbra_prefix(vec2(lo.x, hi.y), tile)
                - penumbra_prefix(vec2(hi.x, lo.y), tile) + penumbra_prefix(lo, tile);
            return clamp(sum / (side * side), 0.0, 1.0);
        )");
        out.line("}");
    } else if (config.packing == Packing::array) {
        const bool nbuffer = config.filter == Filter::nbuffer;
        out.line("vec4 penumbra_filtered(vec4 kernel, int tile)");
        out.line("{");
        out.line("float lo = floor(kernel.w);");
        out.line("float hi = min(lo + 1.0, float(penumbra_maxLevel));");
        out.line("vec2 shiftLo = ", nbuffer ? "vec2((exp2(lo - 1.0) - 0.5) / penumbra_resolution)" : "vec2(0.0)", ";");
        out.line("vec2 shiftHi = ", nbuffer ? "vec2((exp2(hi - 1.0) - 0.5) / penumbra_resolution)" : "vec2(0.0)", ";");
        out.line("float layers = float(penumbra_tileCount);");
        out.line("vec4 texelLo = textureLod(penumbra_levels, vec3(kernel.xy - shiftLo, lo * layers + float(tile)), 0.0);");
        out.line("vec4 texelHi = textureLod(penumbra_levels, vec3(kernel.xy - shiftHi, hi * layers + float(tile)), 0.0);");
        out.line("return mix(texelLo, texelHi, kernel.w - lo);");
        out.line("}");
    } else {
        write_array_read(out, config, "penumbra_volumeTexel", "vec3", "penumbra_volumes", generic_volume_textures);
        out.line("vec4 penumbra_filtered(vec4 kernel, int tile)");
        out.line("{");
        if (config.filter == Filter::nbuffer)
            out.line("vec2 shift = vec2((exp2(kernel.w - 1.0) - 0.5) / penumbra_resolution);");
        else
            out.line("vec2 shift = vec2(0.0);");
        out.line("return penumbra_volumeTexel(tile, vec3(kernel.xy - shift, (kernel.w + 0.5) / float(penumbra_maxLevel + 1)));");
        out.line("}");
    }
    out.blank();
}

// Level texel of an atlas of level images: level `level`, tile `tile`, window anchor for N-buffers.
constexpr void write_generic_level_read(LineWriter& out, const Config& config) {
    out.chunk("level_read");
    write_array_read(out, config, "penumbra_levelTexel", "vec2", "penumbra_levelAtlases", generic_level_textures);
    out.line("vec4 penumbra_atlasLevel(int level, vec4 kernel, int tile)");
    out.line("{");
    out.comment("level-0 texels between two texels of this level (reduced levels: level_reduction)");
    out.line("float spacing = float(1 << max(level - penumbra_levelReduction, 0));");
    if (config.filter == Filter::nbuffer) {
        out.comment("the 2^level-texel window centred at the kernel is anchored 2^(level-1) texels lower;");
        out.comment("a texel's centre lies spacing/2 texels past its anchor");
        out.line("float shift = (0.5 * float(1 << level) - 0.5 * spacing) / penumbra_resolution;");
    } else {
        out.comment("a reduced level's texel j holds the blur at level-0 texel spacing * j");
        out.line("float shift = (0.5 - 0.5 * spacing) / penumbra_resolution;");
    }
    out.line("vec2 uv = vec2(float(tile) * penumbra_invTileCount + (kernel.x - shift) * penumbra_invTileCount, "
             "kernel.y - shift);");
    out.line("return penumbra_levelTexel(level, uv);");
    out.line("}");
    out.blank();
}

// The extent and clustered rules' test: only they pay for the wider window's lookups.
constexpr Text generic_extent_test() {
    return cat("penumbra_fusion == ", format_int(static_cast<int>(Fusion::extent)), " || penumbra_fusion == ",
               format_int(static_cast<int>(Fusion::clustered)));
}

// The clustered rule's test: only it pays for the quadrants' lookups.
constexpr Text generic_clustered_test() {
    return cat("penumbra_fusion == ", format_int(static_cast<int>(Fusion::clustered)));
}

// Clustered fusion: the covered area divided by the occluders counted from the kernel's quadrants, each read
// by `lookup(quadrant)` (a vec4 of the slice's texture, the quadrant's kernel named `quadrant`).
template <class Lookup> constexpr void write_generic_clustered_area(LineWriter& out, Lookup lookup) {
    out.line("if (", generic_clustered_test(), ") {");
    out.line("vec4 penumbra_quadrants;");
    for (int i = 0; i < 4; ++i) {
        out.line("{");
        out.line("vec4 quadrant = penumbra_quadrant(kernel, ", quadrant_corners[i], ");");
        out.line("penumbra_quadrants[", format_int(i), "] = ", lookup("quadrant"), "[s % 4];");
        out.line("}");
    }
    out.line("area /= penumbra_clusterCount(penumbra_quadrants);");
    out.line("}");
}

constexpr void write_generic_fusion(LineWriter& out) {
    out.chunk("fusion_result");
    out.comment("every rule's accumulator is kept; the uniform picks the result (paper §3.3)");
    out.line("float penumbra_fused(float lit, float sum, float maximum, float chain, float correlated, float extent)");
    out.line("{");
    out.comment("clustered fusion is extent fusion over one occluder's area: the same accumulator");
    out.line("if (", generic_extent_test(), ") return clamp(extent, 0.0, 1.0);");
    out.line("if (penumbra_fusion == ", format_int(static_cast<int>(Fusion::correlated)), ") return clamp(correlated, 0.0, 1.0);");
    out.line("if (penumbra_fusion == ", format_int(static_cast<int>(Fusion::chained)), ") return clamp(chain, 0.0, 1.0);");
    out.line("if (penumbra_fusion == ", format_int(static_cast<int>(Fusion::probabilistic)), ") return lit;");
    out.line("if (penumbra_fusion == ", format_int(static_cast<int>(Fusion::additive)), ") return max(0.0, 1.0 - sum);");
    out.line("if (penumbra_fusion == ", format_int(static_cast<int>(Fusion::maximum)), ") return 1.0 - maximum;");
    out.line("return 1.0 - 0.5 * (min(1.0, sum) + maximum);");
    out.line("}");
    out.blank();
}

constexpr void write_generic_accumulate(LineWriter& out) {
    out.line("penumbra_lit *= 1.0 - q;");
    out.line("penumbra_sum += q;");
    out.line("penumbra_max = max(penumbra_max, q);");
    out.comment("chained: neighbours fused by maximum, slices further apart by product");
    out.line("penumbra_chain *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);");
    out.comment("correlated: neighbours between nested and independent by the parallax between their kernels");
    out.line("penumbra_correlated *= penumbra_correlatedStep(q, kernel, penumbra_prev, penumbra_prevKernel);");
    out.comment("extent: the same, the occluder's size from a window twice the kernel's side (clustered: one occluder's)");
    out.line("penumbra_extent *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);");
    out.line("penumbra_prev = q;");
    out.line("penumbra_prevKernel = kernel;");
    out.line("penumbra_prevArea = area;");
}

// A `for` loop over the slices, from the bottom one up to the light, one lookup each.
constexpr void write_generic_slice_loop(LineWriter& out, const Config& config) {
    out.chunk("slice_loop");
    out.line("for (int s = penumbra_sliceCount - 1; s >= 0; --s) {");
    out.line("float zeta = penumbra_sliceDepths.x + float(s + 1) * penumbra_sliceDepths.y;");
    out.line("vec4 kernel = ", kernel_call(config), ";");
    out.comment("texture s / 4 holds the slice, channel s % 4");
    out.line("float fade = penumbra_weight(p.z, zeta);");
    out.line("float coverage = penumbra_filtered(kernel, s / 4)[s % 4];");
    out.line("float q = fade * coverage;");
    out.line("float area = 0.0;");
    out.line("if (", generic_extent_test(), ") {");
    out.line("vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));");
    out.line("area = ", extent_area("fade", "coverage", "penumbra_filtered(penumbra_wide, s / 4)[s % 4]"), ";");
    out.line("}");
    write_generic_clustered_area(out, [](std::string_view quadrant) { return cat("penumbra_filtered(", quadrant, ", s / 4)"); });
    write_generic_accumulate(out);
    out.line("}");
}

// paper Algorithm 2 with `for` over the levels: the slices whose kernel falls in a level are read
// there, each once, from the nearest slice above the point upwards.
constexpr void write_generic_level_loop(LineWriter& out, const Config& config) {
    out.chunk("level_loop");
    out.line("float penumbra_k = clamp(ceil((p.z - penumbra_sliceDepths.x) / penumbra_sliceDepths.y) - 2.0, -1.0, "
             "float(penumbra_sliceCount - 1));");
    out.line("for (int level = 0; level <= penumbra_maxLevel; ++level) {");
    out.line("bool last = level == penumbra_maxLevel;");
    out.line("while (penumbra_k >= 0.0) {");
    out.line("float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;");
    out.line("vec4 kernel = ", kernel_call(config), ";");
    out.line("if (!last && kernel.w >= float(level + 1)) break;");
    out.line("int s = int(penumbra_k);");
    out.line("vec4 texel = penumbra_atlasLevel(level, kernel, s / 4);");
    out.line("if (!last) texel = mix(texel, penumbra_atlasLevel(level + 1, kernel, s / 4), kernel.w - float(level));");
    out.line("float fade = penumbra_weight(p.z, zeta);");
    out.line("float q = fade * texel[s % 4];");
    out.line("float area = 0.0;");
    out.line("if (", generic_extent_test(), ") {");
    out.comment("the doubled window's level lies between this level and two above it (clamped to the last);");
    out.comment("levels indexed from the loop's counter, so the sampler index stays dynamically uniform");
    out.line("float t = penumbra_wideLevel(kernel) - float(level);");
    out.line("vec4 penumbra_lo = penumbra_atlasLevel(level, kernel, s / 4);");
    out.line("vec4 penumbra_hi = penumbra_atlasLevel(min(level + 1, penumbra_maxLevel), kernel, s / 4);");
    out.line("vec4 penumbra_wide = t < 1.0 ? mix(penumbra_lo, penumbra_hi, t)");
    out.line("    : mix(penumbra_hi, penumbra_atlasLevel(min(level + 2, penumbra_maxLevel), kernel, s / 4), t - 1.0);");
    out.line("area = ", extent_area("fade", "texel[s % 4]", "penumbra_wide[s % 4]"), ";");
    out.line("}");
    out.comment("a quadrant's level lies between the level below this one and this one (level 0: level 0)");
    write_generic_clustered_area(out, [](std::string_view quadrant) {
        return cat("mix(penumbra_atlasLevel(max(level - 1, 0), ", quadrant, ", s / 4), penumbra_atlasLevel(level, ", quadrant,
                   ", s / 4), clamp(", quadrant, ".w - float(level - 1), 0.0, 1.0))");
    });
    write_generic_accumulate(out);
    out.line("penumbra_k -= 1.0;");
    out.line("}");
    out.line("}");
}

constexpr Text generic_fragment(const Config& config) {
    LineWriter out;
    write_generic_preamble(out, config, "deferred visibility pass, fragment stage");
    write_generic_params(out, config);
    write_generic_kernel(out, config);
    if (uses_generic_level_loop(config)) write_generic_level_read(out, config);
    else write_generic_lookup(out, config);
    write_correlated_step_function(out);
    write_extent_step_function(out);
    write_wide_level_function(out, config, "penumbra_resolution", "float(penumbra_maxLevel)");
    write_cluster_functions(out, config, "penumbra_resolution", "float(penumbra_maxLevel)");
    write_generic_fusion(out);
    const bool clip = clips_to_tangent_plane(config);
    if (weighs_irradiance(config)) write_irradiance_window_function(out, config);
    out.chunk("visibility");
    if (clip) {
        // as the specialized program: the loop in a function of the part of the light, which the
        // irradiance window runs twice
        out.comment(
            "The fused visibility at light-frame point p of the part of the light that penumbra_clip keeps.");
        out.line("float penumbra_clippedVisibility(vec3 p, vec3 penumbra_clip)");
    } else {
        out.comment("Fraction of the light visible from worldPos: 1 lit, 0 in umbra.");
        out.line("float penumbraVisibility(vec3 worldPos)");
    }
    out.line("{");
    if (!clip) write_light_frame_point(out, config.light);
    out.line("float penumbra_lit = 1.0;");
    out.line("float penumbra_sum = 0.0;");
    out.line("float penumbra_max = 0.0;");
    out.line("float penumbra_chain = 1.0;");
    out.line("float penumbra_correlated = 1.0;");
    out.line("float penumbra_extent = 1.0;");
    out.line("float penumbra_prev = 0.0;");
    out.line("vec4 penumbra_prevKernel = vec4(0.0);");
    out.line("float penumbra_prevArea = 0.0;");
    if (uses_generic_level_loop(config)) write_generic_level_loop(out, config);
    else write_generic_slice_loop(out, config);
    out.line("return penumbra_fused(penumbra_lit, penumbra_sum, penumbra_max, penumbra_chain, penumbra_correlated, penumbra_extent);");
    out.line("}");
    out.blank();
    if (clip) {
        if (weighs_irradiance(config)) write_windowed_visibility_function(out, config);
        out.chunk("visibility");
        out.comment("Fraction of the part of the light above the tangent plane at worldPos that is visible.");
        out.line("float penumbraVisibility(vec3 worldPos, vec3 worldNormal)");
        out.line("{");
        write_light_frame_point(out, config.light);
        write_tangent_clip_setup(out, config,
                                 {Text("penumbra_tangentClipOffset / penumbra_resolution"),
                                  Text("penumbra_tangentClipOffset"), Text("penumbra_clipFootprint"),
                                  cat(format_float(clip_footprint_cap_texels), " / penumbra_resolution")});
        out.line(clipped_visibility_return(config));
        out.line("}");
        out.blank();
    }
    write_deferred_main(out, config, clip);
    return out.take();
}

constexpr Text generic_vertex(const Config& config) {
    LineWriter out;
    write_generic_preamble(out, config, "full-screen triangle, vertex stage (draw 3 vertices, no attributes)");
    write_fullscreen_vertex_main(out, config);
    return out.take();
}

} // namespace penumbra::detail
