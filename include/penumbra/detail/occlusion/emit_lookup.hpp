// penumbra/detail/occlusion/emit_lookup.hpp — the reads of penumbraVisibility's loops: the fade across a
// slice, and the filtered occlusion of a kernel in each storage (array, volume, atlas; mipmap, N-buffer,
// Gaussian, summed-area table).
#pragma once

#include "emit_kernel.hpp"

namespace penumbra::detail {

// Adaptive placement with the fade: each plane's ramp runs over the slice below it (the one a point
// crosses while the ramp is active), so the fade takes that thickness. Both loops visit the planes
// from the bottom up and keep the plane below in penumbra_below (one fetch per slice); below the
// last plane lies a virtual one, a last slice's thickness further.
constexpr bool fades_over_own_thickness(const Config& config) {
    return config.self_shadow_fade && places_slices_adaptively(config);
}

// The depth the fade ramps over, Config::fade_ramp of `thickness` (a GLSL expression): `thickness`
// itself for the paper's ramp over the whole slice.
constexpr Text fade_ramp_depth(const Config& config, std::string_view thickness) {
    return choose(config.fade_ramp == 1.0, Text(thickness), cat("(", thickness, " * ", format_float(config.fade_ramp), ")"));
}

constexpr Text fade_ramp_words(const Config& config) {
    return choose(config.fade_ramp == 1.0, Text("the slice"), cat(format_float(config.fade_ramp), " of the slice"));
}

constexpr void write_weight_function(LineWriter& out, const Config& config) {
    out.chunk("fade");
    if (fades_over_own_thickness(config)) {
        out.comment(cat("paper §3.4.2: 0 for planes at or below the point, a ramp over ", fade_ramp_words(config),
                        " below the plane, then 1"));
        out.line(signature(config, "float", "penumbra_weight", {{"float", "zPoint"}, {"float", "zeta"}, {"float", "thickness"}}));
        out.line("{");
        out.line("return clamp((zPoint - zeta) / ", fade_ramp_depth(config, "thickness"), ", 0.0, 1.0);");
    } else if (config.self_shadow_fade) {
        out.comment(cat("paper §3.4.2: 0 for planes at or below the point, a ramp over ", fade_ramp_words(config),
                        " above the point, then 1"));
        out.line(signature(config, "float", "penumbra_weight", {{"float", "zPoint"}, {"float", "zeta"}}));
        out.line("{");
        out.line("return clamp((zPoint - zeta) / ", fade_ramp_depth(config, "penumbra_sliceDepths.y"), ", 0.0, 1.0);");
    } else {
        out.comment("fade off: planes strictly above the point count fully, the others not at all");
        out.line(signature(config, "float", "penumbra_weight", {{"float", "zPoint"}, {"float", "zeta"}}));
        out.line("{");
        out.line("return 1.0 - step(zPoint, zeta);");
    }
    out.line("}");
    out.blank();
}

// penumbra_below before the bottom plane: the virtual plane a last slice's thickness below it, so
// the last plane's ramp runs over the last slice's own thickness.
constexpr void write_virtual_plane(LineWriter& out, const Config& config) {
    const Text S = format_int(config.slices), S1 = format_int(config.slices - 1);
    out.line(variable(config, "float", "penumbra_below",
                      cat("2.0 * penumbra_boundary(", S, ") - penumbra_boundary(", S1, ")")),
             " // below the bottom plane");
}

// How the loops call the fade function.
constexpr Text weight_call(const Config& config) {
    return choose(fades_over_own_thickness(config), "penumbra_weight(p.z, zeta, thickness)", "penumbra_weight(p.z, zeta)");
}

// N-buffer level l stores at a texel the mean of the 2^l-texel window anchored there, so a window
// centred at c is read at c - 2^(l-1) texels, plus half a texel to land on the texel centre. A
// reduced level (level_spacing s > 1) has texel j anchored at level-0 texel s·j, its centre s/2
// texels further: the read moves by 2^(l-1) - s/2.
constexpr Text nbuffer_shift(const Config& config, int level) {
    return format_float((0.5 * (1 << level) - 0.5 * level_spacing(config, level)) / config.resolution);
}

// Where the atlas's level loop reads level `level` for the kernel's centre coordinate `axis`
// ("kernel.x"): N-buffer levels at their window anchor; Gaussian levels at the centre, where a
// reduced level's texel j (the blur at level-0 texel s·j) is read (s - 1)/2 texels further.
constexpr Text level_read_coordinate(const Config& config, int level, std::string_view axis) {
    if (config.filter == Filter::nbuffer) return cat(axis, " - ", nbuffer_shift(config, level));
    const int spacing = level_spacing(config, level);
    if (spacing == 1) return cat(axis, " - 0.0");
    return cat(axis, " + ", format_float(0.5 * (spacing - 1) / config.resolution));
}

// Reads the filtered occlusion of all four channels for a kernel; one function per storage so the
// unrolled part stays one line per slice. Explicit LOD everywhere: the walk of the level loop is
// non-uniform control flow, where implicit derivatives are undefined.
constexpr void write_lookup_function(LineWriter& out, const Config& config) {
    const VisibilityConstants k = constants(config);
    out.chunk("lookup");
    if (config.filter == Filter::mipmap) {
        out.comment("paper §3.2: hardware trilinear filtering, level chosen explicitly");
        out.line(signature(config, "vec4", "penumbra_filtered", {{"vec4", "kernel"}, {"float", "tile"}}));
        out.line("{");
        if (config.packing == Packing::atlas)
            out.line("return ",
                     sample_level(config, "penumbra_occlusionAtlas", cat("vec2((tile + kernel.x) * ", k.inv_T, ", kernel.y)"),
                                  "kernel.w"),
                     ";");
        else
            out.line("return ", sample_layer_level(config, "penumbra_occlusion", "kernel.xy", "tile", "kernel.w"), ";");
        out.line("}");
    } else if (config.filter == Filter::sat) {
        const Text R1 = format_float(config.resolution + 1);
        out.comment("Crow 1984: prefix sum at texel corner X (in texels) lives at the centre of texel X of an");
        out.comment("(R+1)-texel tile; bilinear filtering between corners is exact for box-shaped coverage");
        out.line(signature(config, "vec4", "penumbra_prefix", {{"vec2", "corner"}, {"float", "tile"}}));
        out.line("{");
        if (!binds_samplers_apart(config)) {
            out.line("vec2 uv = (corner + 0.5) / ", R1, ";");
            if (config.packing == Packing::atlas)
                out.line("return textureLod(penumbra_satAtlas, vec2((tile + uv.x) * ", k.inv_T, ", uv.y), 0.0);");
            else
                out.line("return textureLod(penumbra_sat, vec3(uv, tile), 0.0);");
        } else {
            // WebGPU filters no 32-bit float texture without an optional feature: the bilinear read by hand
            const bool atlas = config.packing == Packing::atlas;
            const Text last = format_int(config.resolution); // the tile's last texel
            out.comment("WebGPU filters no 32-bit float texture (without an optional feature): the bilinear read by hand,");
            out.comment("the four texels around the corner (clamped to the tile) weighted by its fraction");
            out.line(value(config, "vec2", "base", "floor(corner)"));
            out.line(value(config, "vec2", "f", "corner - base"));
            const Text tile_index = construct(config, "int", "tile");
            out.line(value(config, "ivec2", "a",
                           cat("min(", construct(config, "ivec2", "base"), ", ",
                               construct(config, "ivec2", last), ")")));
            out.line(value(config, "ivec2", "b",
                           cat("min(a + ", construct(config, "ivec2", "1"), ", ",
                               construct(config, "ivec2", last), ")")));
            const Text offset = choose(
                atlas,
                cat(" + ", construct(config, "ivec2",
                                     cat(tile_index, " * ", format_int(config.resolution + 1), ", 0"))),
                Text());
            auto load = [&](std::string_view x, std::string_view y) {
                const Text texel = cat(construct(config, "ivec2", cat(x, ".x, ", y, ".y")), offset);
                return atlas ? fetch(config, "penumbra_satAtlas", texel, "0")
                             : fetch_layer(config, "penumbra_sat", texel, tile_index, "0");
            };
            out.line(value(config, "vec4", "bottom", cat("mix(", load("a", "a"), ", ", load("b", "a"), ", f.x)")));
            out.line(value(config, "vec4", "top", cat("mix(", load("a", "b"), ", ", load("b", "b"), ", f.x)")));
            out.line("return mix(bottom, top, f.y);");
        }
        out.line("}");
        out.blank();
        out.comment("exact box mean: the window is clipped to the texture, outside counts as unoccluded");
        out.line(signature(config, "vec4", "penumbra_filtered", {{"vec4", "kernel"}, {"float", "tile"}}));
        out.line("{");
        out.line(value(config, "float", "side", cat("max(kernel.z * ", k.R, ", 1.0)")));
        out.line(value(config, "vec2", "lo", clamp_vector(config, "vec2", cat("kernel.xy * ", k.R, " - 0.5 * side"), "0.0", k.R)));
        out.line(value(config, "vec2", "hi", clamp_vector(config, "vec2", cat("kernel.xy * ", k.R, " + 0.5 * side"), "0.0", k.R)));
        out.line(declaration(config, "vec4", "sum"), "penumbra_prefix(hi, tile) - penumbra_prefix(vec2(lo.x, hi.y), tile)");
        out.line("    - penumbra_prefix(vec2(hi.x, lo.y), tile) + penumbra_prefix(lo, tile);");
        out.line("return ", saturate(config, "sum / (side * side)"), ";");
        out.line("}");
    } else if (config.packing == Packing::array) {
        const bool nbuffer = config.filter == Filter::nbuffer;
        out.comment(nbuffer ? "N-buffers: two levels around the kernel's, each read at its window anchor, then a lerp"
                            : "Gaussian levels: two levels around the kernel's, then a lerp");
        out.line(signature(config, "vec4", "penumbra_filtered", {{"vec4", "kernel"}, {"float", "tile"}}));
        out.line("{");
        out.line(value(config, "float", "lo", "floor(kernel.w)"));
        out.line(value(config, "float", "hi", cat("min(lo + 1.0, ", k.L, ")")));
        if (nbuffer) {
            out.line(value(config, "vec2", "shiftLo", cat("vec2((exp2(lo - 1.0) - 0.5) / ", k.R, ")")));
            out.line(value(config, "vec2", "shiftHi", cat("vec2((exp2(hi - 1.0) - 0.5) / ", k.R, ")")));
        } else {
            out.line(value(config, "vec2", "shiftLo", "vec2(0.0)"));
            out.line(value(config, "vec2", "shiftHi", "vec2(0.0)"));
        }
        out.line(value(config, "vec4", "texelLo",
                       sample_layer_level(config, "penumbra_levels", "kernel.xy - shiftLo", cat("lo * ", k.T, " + tile"), "0.0")));
        out.line(value(config, "vec4", "texelHi",
                       sample_layer_level(config, "penumbra_levels", "kernel.xy - shiftHi", cat("hi * ", k.T, " + tile"), "0.0")));
        out.line("return mix(texelLo, texelHi, kernel.w - lo);");
        out.line("}");
    } else if (config.packing == Packing::volume) {
        out.comment("paper §3.7: levels along the depth of a 3D texture, the hardware interpolates between them;");
        out.comment("both levels are read at one position, so the N-buffer anchor follows the fractional level");
        for (int t = 0; t < texture_count(config); ++t) {
            const Text name = cat("penumbra_filtered", format_int(t));
            out.line(signature(config, "vec4", name, {{"vec4", "kernel"}}));
            out.line("{");
            if (config.filter == Filter::nbuffer)
                out.line(value(config, "vec2", "shift", cat("vec2((exp2(kernel.w - 1.0) - 0.5) / ", k.R, ")")));
            else
                out.line(value(config, "vec2", "shift", "vec2(0.0)"));
            out.line("return ",
                     sample_level(config, volume_name(t),
                                  cat("vec3(kernel.xy - shift, (kernel.w + 0.5) / ", format_float(max_level(config) + 1), ")"), "0.0"),
                     ";");
            out.line("}");
        }
    }
    out.blank();
}

} // namespace penumbra::detail
