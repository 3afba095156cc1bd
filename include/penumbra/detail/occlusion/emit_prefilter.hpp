// penumbra/detail/occlusion/emit_prefilter.hpp — full-screen passes that turn the slicing output into the
// filtered storage the shading pass reads (paper §3.2). Mipmaps need no shader of ours on GL: the
// layout description asks for glGenerateMipmap; WebGPU has none, so on WGSL a pass per level builds
// the chain (mip_level_fragment).
#pragma once

#include "../emit_shading.hpp"
#include "prefilter_plan.hpp"

namespace penumbra::detail {

constexpr Param step_param() {
    return {"penumbra_step", "int", "offset between the windows combined by this pass, in texels of the texture it reads", "texels", {}, UniformSource::pass};
}
// Reduced levels (reduces_levels): the previous level's tile side and how many of its texels one
// texel of the level being built steps over (2 where this level halves the resolution, else 1).
constexpr Param source_tile_param() {
    return {"penumbra_sourceTile", "int", "side of one tile of the previous level", "texels", {}, UniformSource::pass};
}
constexpr Param scale_param() {
    return {"penumbra_scale", "int", "texels of the previous level per texel of this one, per axis (1 or 2)", "", {}, UniformSource::pass};
}
constexpr Param layer_param(std::string_view meaning) { return {"penumbra_sourceLayer", "int", meaning, "", {}, UniformSource::pass}; }

// Parameters of a level-building pass (N-buffer or Gaussian): the window step and the source.
constexpr std::vector<Param> level_params(const Config& config) {
    std::vector<Param> params{step_param()};
    if (reduces_levels(config)) {
        params.push_back(source_tile_param());
        params.push_back(scale_param());
    }
    if (config.packing == Packing::atlas)
        params.push_back({"penumbra_source", "sampler2D", "previous filter level (atlas)", "", {}, UniformSource::light, {},
                          /*fetch_only=*/true});
    else if (config.packing == Packing::array) {
        params.push_back(layer_param("layer of the previous level's tile in the source array"));
        params.push_back({"penumbra_source", "sampler2DArray", "filter levels array", "", "penumbra_levels", UniformSource::light,
                          {}, /*fetch_only=*/true});
    } else {
        params.push_back(layer_param("depth index of the previous level in the source volume"));
        params.push_back({"penumbra_source", "sampler3D", "volume of the four slices being filtered", "", {}, UniformSource::light,
                          {}, /*fetch_only=*/true});
    }
    return params;
}

// penumbra_source_texel(origin, local): texel `local` of the previous level's part `size` texels wide
// that starts at `origin`, 0 outside it, so the window sums treat the outside as unoccluded.
// `write_value` declares `value`, the texel, from `origin`, `local` and `size`.
template <class WriteValue>
constexpr void write_source_texel_function(LineWriter& out, const Config& config, std::string_view comment,
                                           const Text& size, WriteValue write_value) {
    const std::string_view ivec2 = type_name(config, "ivec2");
    out.comment(comment);
    out.line(signature(config, "vec4", "penumbra_source_texel", {{"ivec2", "origin"}, {"ivec2", "local"}}));
    out.line("{");
    out.line(value(config, "bool", "inside",
                   cat("all(", compare(config, "greaterThanEqual", "local", cat(ivec2, "(0)")), ") && all(",
                       compare(config, "lessThan", "local", cat(ivec2, "(", size, ")")), ")")));
    write_value();
    out.line("return ", conditional(config, "inside", "value", "vec4(0.0)"), ";");
    out.line("}");
}

// penumbra_source_texel over an atlas level whose tiles are `tile` texels wide (a literal, or a
// uniform where the level's size varies). Shared by the fragment level passes and the compute prefilter.
constexpr void write_atlas_source_texel(LineWriter& out, const Config& config, const Text& tile) {
    const std::string_view ivec2 = type_name(config, "ivec2");
    write_source_texel_function(out, config, "texel `local` of the previous level's tile that starts at `origin`, 0 outside the tile",
                                tile, [&] {
                                    out.line(value(config, "vec4", "value",
                                                   fetch(config, "penumbra_source",
                                                         cat("origin + clamp(local, ", ivec2, "(0), ", ivec2, "(", tile, " - 1))"), "0")));
                                });
}

// Declarations of a level-building pass and the texel read that returns 0 outside the occlusion
// texture's tile (the window sums treat the outside as unoccluded). The read takes the tile's
// origin in the source and a position inside the tile, so a fragment finds its tile once and each
// tap costs an add, a bounds test and a clamp (no integer division per tap: on a CPU rasterizer a
// division by a uniform is scalar, eight per SIMD vector).
constexpr void write_level_source(LineWriter& out, const Config& config) {
    const Text R = format_int(config.resolution);
    const std::vector<Param> params = level_params(config);
    int binding = 0;
    write_params(out, config, params, "PenumbraPass", binding);
    out.line(stage_variable(out, config, "out", 0, "vec4", "penumbra_result", true));
    declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
    out.blank();
    out.chunk("level_source");
    if (config.packing == Packing::atlas) {
        // reduced levels: the previous level's tiles are penumbra_sourceTile texels wide
        write_atlas_source_texel(out, config, choose(reduces_levels(config), Text("penumbra_sourceTile"), R));
        out.blank();
        return;
    }
    const std::string_view ivec2 = type_name(config, "ivec2");
    write_source_texel_function(out, config, "texel `local` of the previous level, 0 outside the texture (origin: always 0)",
                                R, [&] {
        out.line(value(config, "ivec2", "texel",
                       cat("origin + clamp(local, ", ivec2, "(0), ", ivec2, "(", format_int(config.resolution - 1), "))")));
        if (config.packing == Packing::array)
            out.line(value(config, "vec4", "value", fetch_layer(config, "penumbra_source", "texel", "penumbra_sourceLayer", "0")));
        else
            out.line(value(config, "vec4", "value",
                           fetch(config, "penumbra_source", cat(type_name(config, "ivec3"), "(texel, penumbra_sourceLayer)"), "0")));
    });
    out.blank();
}

// The tile origin and the position in it, in the previous level, of this fragment's texel. Reduced
// levels (reduces_levels): a texel of a level at spacing s (texels of level 0) stands for level-0
// texel s·j of its tile, so with penumbra_scale = s / s' it is texel scale·j of the previous level's
// tile (offsets in the previous level's texels: penumbra_step = 2^(l-1) / s').
constexpr void write_level_base(LineWriter& out, const Config& config) {
    const std::string_view ivec2 = type_name(config, "ivec2");
    out.line(value(config, "ivec2", "fragment", construct(config, "ivec2", cat(frag_coord(config), ".xy"))));
    if (config.packing != Packing::atlas) {
        out.line(value(config, "ivec2", "origin", cat(ivec2, "(0)")));
        out.line(value(config, "ivec2", "local", "fragment"));
        return;
    }
    if (!reduces_levels(config)) {
        const Text R = format_int(config.resolution);
        out.line(value(config, "int", "tile", cat("fragment.x / ", R)), " // which occlusion texture");
        out.line(value(config, "ivec2", "origin", cat(ivec2, "(tile * ", R, ", 0)")));
        out.line(value(config, "ivec2", "local", cat(ivec2, "(fragment.x - tile * ", R, ", fragment.y)")));
        return;
    }
    out.line(value(config, "int", "side", conditional(config, "penumbra_scale == 1", "penumbra_sourceTile", "penumbra_sourceTile / 2")),
             " // this level's tile side");
    out.comment("which occlusion texture: fragment.x / side without an integer division (the pixel centre's");
    out.comment("half texel keeps the float quotient at least 0.5 / side off an integer: exact for any side)");
    out.line(value(config, "int", "tile", construct(config, "int", cat(frag_coord(config), ".x / ", construct(config, "float", "side")))));
    out.line(value(config, "ivec2", "origin", cat(ivec2, "(tile * penumbra_sourceTile, 0)")));
    out.line(value(config, "ivec2", "local", cat(ivec2, "(fragment.x - tile * side, fragment.y) * penumbra_scale")));
}

// Décoret 2005: level l at a texel is the mean of the 2^l window anchored there, i.e. of four
// level l-1 windows at offsets 0 and 2^(l-1).
constexpr Text nbuffer_level_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "N-buffer level l from level l-1, fragment stage");
    write_level_source(out, config);
    out.chunk("nbuffer_level_main");
    out.line(main_signature(config));
    out.line("{");
    write_level_base(out, config);
    const std::string_view ivec2 = type_name(config, "ivec2");
    out.line(value(config, "int", "s", "penumbra_step"), " // 2^(l-1) texels of level 0, in texels of the previous level");
    out.line("penumbra_result = 0.25 * (penumbra_source_texel(origin, local) + penumbra_source_texel(origin, local + ", ivec2, "(s, 0))");
    out.line("+ penumbra_source_texel(origin, local + ", ivec2, "(0, s)) + penumbra_source_texel(origin, local + ", ivec2, "(s, s)));");
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

// Gaussian pyramid at full resolution (journal §3.5): level l is level l-1 blurred by the
// [1 2 1]/4 kernel in x and y, its taps 2^(l-1) texels apart (à trous). The variance grows to
// (4^l - 1) / 6 texels², which the shading pass's level bias accounts for.
constexpr Text gaussian_level_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "Gaussian level l from level l-1, fragment stage");
    write_level_source(out, config);
    out.chunk("gaussian_level_main");
    out.line(main_signature(config));
    out.line("{");
    write_level_base(out, config);
    const std::string_view ivec2 = type_name(config, "ivec2");
    out.line(value(config, "int", "s", "penumbra_step"), " // 2^(l-1) texels of level 0, in texels of the previous level");
    out.line(variable(config, "vec4", "sum", "vec4(0.0)"));
    out.comment("3 x 3 taps, weights (1 2 1) x (1 2 1) / 16");
    for (const char* tap : {"1.0 * penumbra_source_texel(origin, local + #(-s, -s))", "2.0 * penumbra_source_texel(origin, local + #(0, -s))",
                            "1.0 * penumbra_source_texel(origin, local + #(s, -s))", "2.0 * penumbra_source_texel(origin, local + #(-s, 0))",
                            "4.0 * penumbra_source_texel(origin, local + #(0, 0))", "2.0 * penumbra_source_texel(origin, local + #(s, 0))",
                            "1.0 * penumbra_source_texel(origin, local + #(-s, s))", "2.0 * penumbra_source_texel(origin, local + #(0, s))",
                            "1.0 * penumbra_source_texel(origin, local + #(s, s))"}) {
        const std::string_view text = tap;
        const std::size_t hash = text.find('#');
        out.line("sum += ", text.substr(0, hash), ivec2, text.substr(hash + 1), ";");
    }
    out.line("penumbra_result = sum / 16.0;");
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

// The mipmap filter on WGSL (WebGPU has no generateMipmap): level n + 1 of the mip chain from level n,
// the pass binding level n alone (layout.json: the input's level), each texel the mean of the 2 × 2
// texels under it, the box filter generateMipmap applies to power-of-two levels. Of a texture array
// (the array packing, adaptive placement's depth bins) a pass a layer (penumbra_sourceLayer).
constexpr std::vector<Param> mip_chain_params(bool array) {
    if (array)
        return {layer_param("the layer being reduced"),
                {"penumbra_source", "sampler2DArray", "the level being reduced (the pass binds one level)", "", {},
                 UniformSource::light, {}, /*fetch_only=*/true}};
    return {{"penumbra_source", "sampler2D", "the level being reduced (the pass binds one level)", "", {},
             UniformSource::light, {}, /*fetch_only=*/true}};
}
constexpr std::vector<Param> mip_level_params(const Config& config) { return mip_chain_params(config.packing == Packing::array); }

// One texel of the level being reduced, at `texel` (a text expression).
constexpr Text mip_source_texel(const Config& config, bool array, Text texel) {
    if (array) return fetch_layer(config, "penumbra_source", texel, "penumbra_sourceLayer", "0");
    return fetch(config, "penumbra_source", texel, "0");
}

constexpr Text mip_chain_fragment(const Config& config, bool array, Text title) {
    LineWriter out;
    write_preamble(out, config, title);
    int binding = 0;
    write_params(out, config, mip_chain_params(array), "PenumbraPass", binding);
    out.line(stage_variable(out, config, "out", 0, "vec4", "penumbra_result", true));
    declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
    out.blank();
    out.chunk("mip_level_main");
    out.comment("the mean of the 2 x 2 texels of level n under this texel of level n + 1");
    out.line(main_signature(config));
    out.line("{");
    const std::string_view ivec2 = type_name(config, "ivec2");
    out.line(value(config, "ivec2", "base", cat("2 * ", construct(config, "ivec2", cat(frag_coord(config), ".xy")))));
    out.line("penumbra_result = 0.25 * (", mip_source_texel(config, array, "base"), " + ",
             mip_source_texel(config, array, cat("base + ", ivec2, "(1, 0)")));
    out.line("    + ", mip_source_texel(config, array, cat("base + ", ivec2, "(0, 1)")), " + ",
             mip_source_texel(config, array, cat("base + ", ivec2, "(1, 1)")), ");");
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

constexpr Text mip_level_fragment(const Config& config) {
    return mip_chain_fragment(config, config.packing == Packing::array,
                              "mip chain of the occlusion textures (WebGPU has no generateMipmap), level n to n+1, fragment stage");
}

// Adaptive slice placement's depth bins on WGSL: their mip chain (layout.hpp), as mip_level_fragment.
constexpr Text depth_bins_level_fragment(const Config& config) {
    return mip_chain_fragment(config, true,
                              "adaptive slice placement: mip chain of the depth bins (WebGPU has no generateMipmap), level n to "
                              "n+1, fragment stage");
}

constexpr Param slices_param() {
    return {"penumbra_slices", "sampler2DArray", "slicing output, one layer per RGBA texture", "", "penumbra_slices",
            UniformSource::light, {}, /*fetch_only=*/true};
}
constexpr std::vector<Param> pack_atlas_params() { return {slices_param()}; }

// The atlas's level 0: the slicing output (a T-layer array) laid out as tiles side by side; with
// packed_level 1 also level 1, from the same texels as the level pass would read from level 0 (the
// same sums in the same order: the same values, in RGBA8 too).
constexpr Text pack_atlas_fragment(const Config& config) {
    LineWriter out;
    const int packed = packed_level(config);
    const bool gaussian = config.filter == Filter::gaussian;
    write_preamble(out, config,
                   packed == 0 ? Text("atlas packing of the slicing output (paper §3.6), fragment stage")
                               : cat("atlas packing of the slicing output (paper §3.6) and ",
                                     gaussian ? "Gaussian" : "N-buffer", " level 1 from it, fragment stage"));
    int binding = 0;
    write_params(out, config, pack_atlas_params(), "PenumbraPass", binding);
    const Text R = format_int(config.resolution);
    const std::string_view ivec2 = type_name(config, "ivec2");
    if (packed == 0) {
        out.line(stage_variable(out, config, "out", 0, "vec4", "penumbra_result", true));
        declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
        out.blank();
        out.chunk("pack_atlas_main");
        out.line(main_signature(config));
        out.line("{");
        out.line(value(config, "ivec2", "texel", construct(config, "ivec2", cat(frag_coord(config), ".xy"))));
        if (binds_samplers_apart(config))
            out.line("penumbra_result = ",
                     fetch_layer(config, "penumbra_slices", cat(ivec2, "(texel.x % ", R, ", texel.y)"), cat("texel.x / ", R), "0"), ";");
        else
            out.line("penumbra_result = texelFetch(penumbra_slices, ivec3(texel.x % ", R, ", texel.y, texel.x / ", R, "), 0);");
        out.line("}");
        write_entry_point(out, config, Stage::fragment);
        return out.take();
    }
    out.line(stage_variable(out, config, "out", 0, "vec4", "penumbra_level0", true), " // level 0: the slicing output");
    out.line(stage_variable(out, config, "out", 1, "vec4", "penumbra_level1", true), " // level 1, same size");
    declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
    out.blank();
    out.chunk("pack_atlas_source");
    out.comment(cat("texel `local` of occlusion texture `layer` of the slicing output, 0 outside its ", R, " x ", R,
                    " texels"));
    out.line(signature(config, "vec4", "penumbra_slice_texel", {{"int", "layer"}, {"ivec2", "local"}}));
    out.line("{");
    out.line(value(config, "bool", "inside",
                   cat("all(", compare(config, "greaterThanEqual", "local", cat(ivec2, "(0)")), ") && all(",
                       compare(config, "lessThan", "local", cat(ivec2, "(", R, ")")), ")")));
    out.line(value(config, "vec4", "value",
                   fetch_layer(config, "penumbra_slices",
                               cat("clamp(local, ", ivec2, "(0), ", ivec2, "(", format_int(config.resolution - 1), "))"), "layer",
                               "0")));
    out.line("return ", conditional(config, "inside", "value", "vec4(0.0)"), ";");
    out.line("}");
    out.blank();
    out.chunk("pack_atlas_main");
    out.line(main_signature(config));
    out.line("{");
    out.line(value(config, "ivec2", "texel", construct(config, "ivec2", cat(frag_coord(config), ".xy"))));
    out.line(value(config, "int", "layer", cat("texel.x / ", R)), " // which occlusion texture: the tile");
    out.line(value(config, "ivec2", "local", cat(ivec2, "(texel.x - layer * ", R, ", texel.y)")));
    out.line(value(config, "vec4", "level0", "penumbra_slice_texel(layer, local)"));
    out.line("penumbra_level0 = level0;");
    if (!gaussian) {
        out.comment("level 1 (Décoret 2005): the mean of the 2 x 2 window anchored here");
        out.line("penumbra_level1 = 0.25 * (level0 + penumbra_slice_texel(layer, local + ", ivec2, "(1, 0))");
        out.line("    + penumbra_slice_texel(layer, local + ", ivec2, "(0, 1)) + penumbra_slice_texel(layer, local + ", ivec2,
                 "(1, 1)));");
    } else {
        out.comment("level 1: level 0 blurred by [1 2 1] / 4 in x and y, 3 x 3 taps, weights (1 2 1) x (1 2 1) / 16");
        out.line(variable(config, "vec4", "sum", "vec4(0.0)"));
        const int weights[3] = {1, 2, 1};
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const Text w = cat(format_int(weights[dx + 1] * weights[dy + 1]), ".0");
                if (dx == 0 && dy == 0)
                    out.line("sum += ", w, " * level0;");
                else
                    out.line("sum += ", w, " * penumbra_slice_texel(layer, local + ", ivec2, "(", format_int(dx), ", ",
                             format_int(dy), "));");
            }
        out.line("penumbra_level1 = sum / 16.0;");
    }
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

constexpr std::vector<Param> sat_shift_params(const Config& config) {
    if (config.packing == Packing::atlas) return {slices_param()};
    return {layer_param("occlusion texture (layer) being shifted"), slices_param()};
}

constexpr std::vector<Param> sat_pass_params(const Config& config) {
    std::vector<Param> params{step_param(), {"penumbra_vertical", "int", "0: pass along x, 1: pass along y", "", {}, UniformSource::pass}};
    if (config.packing == Packing::atlas) {
        params.push_back({"penumbra_source", "sampler2D", "partial sums of the previous pass", "", {}, UniformSource::light, {},
                          /*fetch_only=*/true});
    } else {
        params.push_back(layer_param("layer being summed"));
        params.push_back({"penumbra_source", "sampler2DArray", "partial sums of the previous pass", "", {}, UniformSource::light,
                          {}, /*fetch_only=*/true});
    }
    return params;
}

// Summed-area tables (Crow 1984), built by recursive doubling (Hensley et al. 2005). Each
// occlusion texture gets an (R+1)-texel tile whose texel X holds the sum over texels < X
// (exclusive), so texel 0 is 0 and a box read needs no special case at the border.
constexpr Text sat_shift_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "summed-area table, exclusive shift of the slicing output, fragment stage");
    int binding = 0;
    write_params(out, config, sat_shift_params(config), "PenumbraPass", binding);
    out.line(stage_variable(out, config, "out", 0, "vec4", "penumbra_result", true));
    declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
    out.blank();
    out.chunk("sat_shift_main");
    const Text R1 = format_int(config.resolution + 1);
    const std::string_view ivec2 = type_name(config, "ivec2");
    out.line(main_signature(config));
    out.line("{");
    out.line(value(config, "ivec2", "texel", construct(config, "ivec2", cat(frag_coord(config), ".xy"))));
    if (config.packing == Packing::atlas) {
        out.line(value(config, "int", "tile", cat("texel.x / ", R1)));
        out.line(value(config, "ivec2", "source", cat(ivec2, "(texel.x % ", R1, ", texel.y) - 1")));
    } else {
        out.line(value(config, "int", "tile", "penumbra_sourceLayer"));
        out.line(value(config, "ivec2", "source", "texel - 1"));
    }
    out.line(value(config, "vec4", "value", fetch_layer(config, "penumbra_slices", cat("max(source, ", ivec2, "(0))"), "tile", "0")));
    out.line("penumbra_result = ",
             conditional(config, cat("all(", compare(config, "greaterThanEqual", "source", cat(ivec2, "(0)")), ")"), "value", "vec4(0.0)"),
             ";");
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

constexpr Text sat_pass_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "summed-area table, one recursive-doubling pass, fragment stage");
    int binding = 0;
    write_params(out, config, sat_pass_params(config), "PenumbraPass", binding);
    out.line(stage_variable(out, config, "out", 0, "vec4", "penumbra_result", true));
    declare_builtin(out, config, true, "position", "vec4", frag_coord(config));
    out.blank();
    out.chunk("sat_pass_main");
    const Text R1 = format_int(config.resolution + 1);
    const std::string_view ivec2 = type_name(config, "ivec2");
    const std::string_view self = is_wgsl(config) ? "here" : "self"; // `self` is reserved in WGSL
    out.line(main_signature(config));
    out.line("{");
    out.line(value(config, "ivec2", "texel", construct(config, "ivec2", cat(frag_coord(config), ".xy"))));
    out.line(value(config, "ivec2", "offset",
                   conditional(config, "penumbra_vertical == 0", cat(ivec2, "(penumbra_step, 0)"), cat(ivec2, "(0, penumbra_step)"))));
    if (config.packing == Packing::atlas) {
        out.line(value(config, "ivec2", "local", cat(ivec2, "(texel.x % ", R1, ", texel.y) - offset")), " // partner within the tile");
        out.line(value(config, "vec4", self, fetch(config, "penumbra_source", "texel", "0")));
        out.line(value(config, "vec4", "partner", fetch(config, "penumbra_source", cat("max(texel - offset, ", ivec2, "(0))"), "0")));
    } else {
        out.line(value(config, "ivec2", "local", "texel - offset"));
        out.line(value(config, "vec4", self, fetch_layer(config, "penumbra_source", "texel", "penumbra_sourceLayer", "0")));
        out.line(value(config, "vec4", "partner",
                       fetch_layer(config, "penumbra_source", cat("max(local, ", ivec2, "(0))"), "penumbra_sourceLayer", "0")));
    }
    out.line("penumbra_result = ", self, " + (",
             conditional(config, cat("all(", compare(config, "greaterThanEqual", "local", cat(ivec2, "(0)")), ")"), "partner", "vec4(0.0)"),
             ");");
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

} // namespace penumbra::detail
