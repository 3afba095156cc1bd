// penumbra/detail/occlusion/emit_prefilter_compute.hpp — the compute prefilter (Config::prefilter_stage
// compute, target glsl450): N-buffer levels above the atlas packing pass built by compute dispatches
// instead of one full-screen pass per level. A workgroup loads one block of the level the dispatch
// starts from (and the apron its widest windows reach) into shared memory once, builds the
// dispatch's levels there, and writes each level's texels with imageStore. The values are the
// fragment path's (emit_prefilter.hpp), rounding of the level format included; which dispatch builds
// which levels: compute_dispatches (prefilter_plan.hpp).
#pragma once

#include "emit_prefilter.hpp"
#include "prefilter_plan.hpp"

namespace penumbra::detail {

// Plain uniforms of a dispatch (its int_uniforms) and the level it starts from.
constexpr std::vector<Param> nbuffer_compute_params() {
    return {
        {"penumbra_levels", "int", "levels this dispatch builds, image outputs 0 to penumbra_levels - 1", "", {}, UniformSource::pass},
        {"penumbra_step", "int", "offset between the taps of the first level built, in texels of the source level",
         "texels", {}, UniformSource::pass},
        {"penumbra_sourceTile", "int", "side of one tile of the source level", "texels", {}, UniformSource::pass},
        {"penumbra_sameSize", "int",
         "levels of this dispatch stored at the source level's resolution; each one after it halves it", "", {}, UniformSource::pass},
        {"penumbra_groupsPerTile", "int", "workgroups across one tile of the source level, per axis", "", {}, UniformSource::pass},
        {"penumbra_source", "sampler2D", "filter level the dispatch starts from (atlas)", ""},
    };
}

// Image outputs the program declares: the most levels one dispatch of the configuration builds.
constexpr int compute_image_outputs(const Config& config) {
    int outputs = 1;
    for (const ComputeDispatch& d : compute_dispatches(config)) outputs = outputs > d.levels ? outputs : d.levels;
    return outputs;
}

constexpr Text compute_image_name(int output) { return cat("penumbra_output", format_int(output)); }

// The GLSL image format qualifier of the level storage (level_format).
constexpr std::string_view compute_image_format(const Config& config) {
    return config.level_format == LevelFormat::rgba16f ? "rgba16f" : "rgba8";
}

// "levels 2 to 4 from level 1, 5 to 7 from level 4, …": the dispatches, for the header comment.
constexpr Text describe_compute_dispatches(const Config& config) {
    Text out;
    for (const ComputeDispatch& d : compute_dispatches(config)) {
        if (!out.empty()) out += "; ";
        const int first = d.source_level + 1, last = d.source_level + d.levels;
        out += cat(first == last ? cat("level ", format_int(first)) : cat("levels ", format_int(first), " to ", format_int(last)),
                   " from level ", format_int(d.source_level), " (tile ", format_int(compute_tile_side(config, d)), " x ",
                   format_int(compute_tile_side(config, d)), ")");
    }
    return choose(out.empty(), Text("none (the packing pass writes every level)"), out);
}

constexpr Text nbuffer_levels_compute(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "N-buffer levels from a lower level, several per dispatch, compute stage");
    const int N = compute_group_side, tile = compute_shared_side(config), outputs = compute_image_outputs(config);
    const Text G = format_int(N);
    int binding = 0;
    write_params(out, config, nbuffer_compute_params(), "PenumbraPass", binding);

    out.chunk("compute_outputs");
    out.comment("the levels this dispatch builds, in order: output i holds level (source level + 1 + i)");
    for (int i = 0; i < outputs; ++i)
        out.line("layout(binding = ", format_int(i), ", ", compute_image_format(config), ") writeonly uniform image2D ",
                 compute_image_name(i), ";");
    out.blank();

    out.chunk("compute_tile");
    out.comment(cat("one workgroup: ", G, " x ", G, " invocations over a ", G, " x ", G,
                    " block of the source level; the tile holds the block"));
    out.comment("and the apron the widest window of the dispatch reaches. Dispatches of this configuration:");
    out.comment(describe_compute_dispatches(config));
    out.line("layout(local_size_x = ", G, ", local_size_y = ", G, ") in;");
    out.line("const int PENUMBRA_GROUP = ", G, "; // invocations per side of a workgroup, texels per side of its block");
    out.line("const int PENUMBRA_TILE = ", format_int(tile), "; // texels per side of the largest tile");
    out.line("shared vec4 penumbra_tile[PENUMBRA_TILE * PENUMBRA_TILE];");
    out.blank();

    out.chunk("compute_source");
    write_atlas_source_texel(out, config, "penumbra_sourceTile");
    out.blank();
    if (config.level_format == LevelFormat::rgba16f) {
        out.comment("what an RGBA16F level stores: half floats, so the next level is built from what the fragment");
        out.comment("path would read back");
        out.line("vec4 penumbra_stored(vec4 value)");
        out.line("{");
        out.line("return vec4(unpackHalf2x16(packHalf2x16(value.xy)), unpackHalf2x16(packHalf2x16(value.zw)));");
        out.line("}");
    } else {
        out.comment("what an RGBA8 level stores: the nearest 1/255, so the next level is built from what the fragment path");
        out.comment("reads back (where the fp32 sum lies on a rounding tie, a driver's conversion may round the other way:");
        out.comment("one unit)");
        out.line("vec4 penumbra_stored(vec4 value)");
        out.line("{");
        out.line("return roundEven(value * 255.0) / 255.0;");
        out.line("}");
    }
    out.blank();
    out.comment("writes texel `texel` of output `index` (a uniform value: one branch per workgroup)");
    out.line("void penumbra_store(int index, ivec2 texel, vec4 value)");
    out.line("{");
    for (int i = 0; i < outputs; ++i) {
        out.line(i == 0 ? "if (index == 0)" : cat("else if (index == ", format_int(i), ")"));
        out.line("{");
        out.line("imageStore(", compute_image_name(i), ", texel, value);");
        out.line("}");
    }
    out.line("}");
    out.blank();

    out.chunk("nbuffer_levels_main");
    out.block(R"(
void main()
{
    // the occlusion texture (tile) this workgroup works in, its block in the tile, this invocation's texel
    int tile = int(gl_WorkGroupID.x) / penumbra_groupsPerTile;
    ivec2 block = ivec2(int(gl_WorkGroupID.x) - tile * penumbra_groupsPerTile, int(gl_WorkGroupID.y)) * PENUMBRA_GROUP;
    ivec2 origin = ivec2(tile * penumbra_sourceTile, 0);
    ivec2 thread = ivec2(gl_LocalInvocationID.xy);

    // 1. Load the block and its apron once: level i's taps are penumbra_step << i texels apart, so the
    // last level's windows reach (2^levels - 1) * penumbra_step texels past the block.
    int span = PENUMBRA_GROUP + ((1 << penumbra_levels) - 1) * penumbra_step;
    for (int y = thread.y; y < span; y += PENUMBRA_GROUP)
    {
        for (int x = thread.x; x < span; x += PENUMBRA_GROUP)
        {
            penumbra_tile[y * PENUMBRA_TILE + x] = penumbra_source_texel(origin, block + ivec2(x, y));
        }
    }
    barrier();

    for (int level = 0; level < penumbra_levels; ++level)
    {
        // 2. This level in place from the one below (Décoret 2005): the mean of four windows of the level
        // below at offsets 0 and s. A position reads positions at or after it only, so the tile is updated
        // in rounds of PENUMBRA_GROUP x PENUMBRA_GROUP positions in row order, every read of a round before
        // its writes; only the positions the levels above this one still read (the block alone for the last).
        int s = penumbra_step << level;
        int extent = PENUMBRA_GROUP + ((1 << penumbra_levels) - (2 << level)) * penumbra_step;
        for (int y0 = 0; y0 < extent; y0 += PENUMBRA_GROUP)
        {
            for (int x0 = 0; x0 < extent; x0 += PENUMBRA_GROUP)
            {
                ivec2 at = ivec2(x0, y0) + thread;
                bool needed = all(lessThan(at, ivec2(extent)));
                int k = at.y * PENUMBRA_TILE + at.x;
                vec4 value = vec4(0.0);
                if (needed)
                {
                    int below = k + s * PENUMBRA_TILE; // the row s texels further
                    value = 0.25 * (penumbra_tile[k] + penumbra_tile[k + s] + penumbra_tile[below] + penumbra_tile[below + s]);
                }
                barrier();
                if (needed)
                {
                    penumbra_tile[k] = penumbra_stored(value);
                }
                barrier();
            }
        }

        // 3. Store this level's texels of the block. A reduced level keeps every 2^shift-th texel of the
        // source level per axis (the window anchored there), in a tile 2^shift times smaller.
        int shift = max(0, level + 1 - penumbra_sameSize);
        ivec2 source = block + thread;
        bool stored = all(equal(source & ivec2((1 << shift) - 1), ivec2(0)));
        if (stored && all(lessThan(source, ivec2(penumbra_sourceTile))))
        {
            int side = penumbra_sourceTile >> shift; // this level's tile side
            penumbra_store(level, ivec2(tile * side, 0) + (source >> shift), penumbra_tile[thread.y * PENUMBRA_TILE + thread.x]);
        }
    }
}
)");
    return out.take();
}

} // namespace penumbra::detail
