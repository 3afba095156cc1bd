// penumbra/detail/occlusion/emit_slicing.hpp — the slicing pass (paper §3.4): the scene seen from the
// slicing camera, each fragment marking the channel of its slice in one of T render targets.
// Blending is MAX, so a texel is 1 where anything in that slice covers it. Beyond 32 slices
// (paper §3.7) each fragment sets the bit of its slice in one RGBA32UI target instead, combined by
// a logical OR, and the unpack pass (emit_unpack.hpp) writes the RGBA occlusion textures.
#pragma once

#include "../alpha_test.hpp"
#include "parameters.hpp"

namespace penumbra::detail {

// solid_casters: the per-draw flag of the slicing program (closed mesh or open casters), after the
// material's parameters.
inline constexpr std::string_view solid_caster_block = "PenumbraCaster";

constexpr std::vector<Param> solid_caster_params(const Config& config) {
    if (!config.solid_casters) return {};
    return {uniform_param(Uniform::caster_closed, config.light)};
}

// The scene seen from the slicing camera, with its depth along the light normal: the vertex stage of
// the slicing pass and of the depth-bin pre-pass (emit_slice_placement.hpp), each declaring its
// program's parameters so the stages agree on the uniform block.
constexpr Text slicing_camera_vertex(const Config& config, std::string_view title, const std::vector<Param>& params,
                                     std::string_view block) {
    LineWriter out;
    write_preamble(out, config, title);
    out.chunk("slicing_inputs");
    out.line(stage_variable(out, config, "in", 0, "vec3", "penumbra_position", true), " // world space (scene units)");
    out.line(stage_variable(out, config, "out", 0, "float", "penumbra_depth", has_varying_locations(config)),
             " // depth along the light normal (scene units)");
    write_alpha_test_vertex_inputs(out, config);
    declare_builtin(out, config, false, "position", "vec4", clip_position(config));
    out.blank();
    int binding = 0;
    write_params(out, config, params, block, binding);
    out.chunk("slicing_vertex_main");
    write_caster_vertex_main(out, config, "penumbra_sliceClipFromWorld", "a slice's");
    return out.take();
}

constexpr Text slicing_vertex(const Config& config) {
    return slicing_camera_vertex(config, "slicing pass, vertex stage", slicing_camera_params(), "PenumbraSlicing");
}

// The slices slicing target t holds, one per channel: vec4(4t, 4t + 1, 4t + 2, 4t + 3).
constexpr Text target_slices(int t) {
    return cat("vec4(", format_float(4 * t), ", ", format_float(4 * t + 1), ", ", format_float(4 * t + 2), ", ",
               format_float(4 * t + 3), ")");
}

// solid_casters, a closed caster's fragment: it toggles (logic op XOR) every slice from its own down, so the
// slices between where the slicing camera's ray enters the mesh and where it leaves it are marked, both ends'
// slices included, and the ones below cancel out. The slicing camera looks along the light normal with the
// light frame's axes, a mirror of OpenGL's eye space: faces towards the light are its back faces.
constexpr void write_closed_caster(LineWriter& out, const Config& config, bool bits) {
    out.comment("solid_casters: a closed mesh toggles (logic op XOR) every slice from where the ray enters it (a face");
    out.comment("towards the light, back-facing in the slicing camera's mirrored frame: from its own slice) or leaves it");
    out.comment("(from the next slice), so the slices between are filled");
    out.line("if (penumbra_casterClosed > 0.5)");
    out.line("{");
    out.line(value(config, "float", "first", "gl_FrontFacing ? k + 1.0 : k"));
    if (bits) {
        out.line("penumbra_sliceBits = penumbra_slicesFrom(first);");
    } else {
        for (int t = 0; t < slicing_targets(config); ++t)
            out.line("penumbra_occlusion", format_int(t), " = ",
                     construct(config, "vec4", compare(config, "greaterThanEqual", target_slices(t), "vec4(first)")), ";");
    }
    out.line("return;");
    out.line("}");
}

// near_field (docs/model.md §1.7.7): the fragment's depth within its own slice, f in [0, 1] from the slice's
// top, stored as 1 - f * 254/255 in the slice's channel of penumbra_nearDepth (0 elsewhere), so the pass's
// MAX keeps the surface nearest the light in each slice and 0 still means empty. No leak fix: the depth is
// the fragment's.
constexpr void write_near_depth(LineWriter& out, const Config& config) {
    out.comment("near field: where in its slice the fragment lies (0 at the slice's top, towards the light); "
                "MAX keeps");
    out.comment("the nearest surface of each slice, 1/255 the deepest, 0 none");
    out.line(
        value(config, "float", "within",
              "clamp((penumbra_depth - penumbra_sliceDepths.x) / penumbra_sliceDepths.y - k, 0.0, 1.0)"));
    out.line(value(config, "float", "near", cat("1.0 - within * ", format_float(254.0 / 255.0))));
    for (int t = 0; t < texture_count(config); ++t)
        out.line("penumbra_nearDepth", format_int(t), " = ",
                 construct(config, "vec4", compare(config, "equal", "vec4(k)", target_slices(t))),
                 " * near;");
}

constexpr Text slicing_fragment(const Config& config) {
    LineWriter out;
    const bool bits = slices_as_bits(config);
    write_preamble(out, config,
                   bits ? "slicing pass, fragment stage: writes slice k as bit k of an RGBA32UI target (logic op OR, "
                          "clear to 0)"
                        : "slicing pass, fragment stage (blend equation MAX, clear to 0)");
    out.chunk("slicing_outputs");
    out.line(stage_variable(out, config, "in", 0, "float", "penumbra_depth", has_varying_locations(config)));
    write_alpha_test_fragment_inputs(out, config);
    if (bits) {
        out.comment("paper §3.7: more slices than colour channels (eight RGBA targets hold 32) from one geometry pass,");
        out.comment("as in bitmask voxelization [ED06a]: bit k % 32 of component k / 32 marks slice k, and the unpack");
        out.comment("pass redistributes the bits into colour channels independently of the scene. Integer targets do");
        out.comment("not blend: the pass combines fragments by a logical OR.");
        out.line("layout(location = 0) out uvec4 penumbra_sliceBits; // slices 0 to ", format_int(config.slices - 1));
    }
    const bool grouped = slicing_passes(config) > 1;
    for (int t = 0; !bits && grouped && t < slicing_targets(config); ++t)
        out.line(stage_variable(out, config, "out", t, "vec4", cat("penumbra_occlusion", format_int(t)), true),
                 " // slices 4 * penumbra_firstTexture + ", format_int(t * 4), " to + ", format_int(t * 4 + 3));
    for (int t = 0; !bits && !grouped && t < texture_count(config); ++t) {
        const int last = t * 4 + 3 < config.slices - 1 ? t * 4 + 3 : config.slices - 1;
        out.line(stage_variable(out, config, "out", t, "vec4", cat("penumbra_occlusion", format_int(t)), true), " // slices ",
                 format_int(t * 4), " to ", format_int(last));
    }
    for (int t = 0; marches_near_field(config) && t < texture_count(config); ++t) {
        const int first = 4 * t, last = first + 3 < config.slices - 1 ? first + 3 : config.slices - 1;
        out.line(stage_variable(out, config, "out", texture_count(config) + t, "vec4",
                                cat("penumbra_nearDepth", format_int(t)), true),
                 " // near field: nearest depth in slices ", format_int(first), " to ", format_int(last));
    }
    out.blank();
    int binding = 0;
    write_params(out, config, slicing_params(config), "PenumbraSlicing", binding);
    write_alpha_test_params(out, config, binding);
    if (config.solid_casters) write_params(out, config, solid_caster_params(config), solid_caster_block, binding);
    if (bits) {
        out.chunk("slice_bit");
        out.comment("the uvec4 with only the bit of slice `slice` set");
        out.line("uvec4 penumbra_sliceBit(float slice)");
        out.line("{");
        out.line("int s = int(slice);");
        out.line("return uvec4(equal(ivec4(s / 32), ivec4(0, 1, 2, 3))) << uint(s % 32);");
        out.line("}");
        out.blank();
        if (config.solid_casters) {
            out.comment("the uvec4 with the bits of slices `first` to 127 set (solid_casters)");
            out.line("uvec4 penumbra_slicesFrom(float first)");
            out.line("{");
            out.line("ivec4 below = clamp(ivec4(first) - ivec4(0, 32, 64, 96), 0, 32); // bits of each component before `first`");
            out.line("return uvec4(notEqual(below, ivec4(32))) * (uvec4(0xffffffffu) << uvec4(min(below, ivec4(31))));");
            out.line("}");
            out.blank();
        }
    }
    if (places_slices_adaptively(config)) write_boundary_function(out, config);
    out.chunk("slicing_fragment_main");
    out.line(main_signature(config));
    out.line("{");
    write_alpha_test_discard(out, config);
    write_light_plane_clip(out, config);
    if (places_slices_adaptively(config)) {
        out.comment("slice k holds the depths in (boundary k, boundary k + 1]: k counts the inner boundaries above");
        write_boundary_search(out, config, "inner", "penumbra_depth", config.slices - 1);
        out.line(value(config, "float", "k", construct(config, "float", "inner")));
    } else {
        out.comment("slice k holds the depths in (z0 + k * thickness, z0 + (k + 1) * thickness]");
        out.line(value(config, "float", "k", uniform_slice_of(config, "penumbra_depth")));
    }
    if (config.solid_casters) write_closed_caster(out, config, bits);
    const int reach = leak_fix_reach(config);
    if (reach == 1) out.comment("paper §3.4.1 leak fix: also mark the next slice away from the light");
    if (reach > 1) {
        out.comment(cat("paper §3.4.1 leak fix, over a constant depth: also mark the next ", format_int(reach),
                        " slices away from the light"));
        out.comment("(one sixteenth of the depth range, as one slice of 16: a sheet that crosses thin slices then has");
        out.comment("all its bands in one slice, which chained fusion's maximum over neighbours needs)");
    }
    if (reach > 0) {
        out.comment("slices k to next are marked");
        out.line(value(config, "float", "next", cat("min(k + ", format_float(reach), ", ", format_float(config.slices - 1), ")")));
    }
    if (bits) {
        out.line("penumbra_sliceBits = penumbra_sliceBit(k);");
        for (int j = 1; j <= reach; ++j)
            out.line("penumbra_sliceBits |= penumbra_sliceBit(min(k + ", format_float(j), ", next));");
    }
    if (grouped) {
        out.comment(cat("this pass writes occlusion textures penumbra_firstTexture to + ", format_int(slicing_targets(config) - 1),
                        " (WebGPU: ", format_int(slicing_targets(config)), " colour targets a pass, no logic op)"));
        out.line(value(config, "float", "base", construct(config, "float", "4 * penumbra_firstTexture")));
    }
    for (int t = 0; !bits && t < slicing_targets(config); ++t) {
        Text first = target_slices(t);
        if (grouped) first = cat("(", first, " + vec4(base))");
        out.line("// texture ", choose(grouped, cat("penumbra_firstTexture + ", format_int(t)), format_int(t)));
        if (reach > 0)
            out.line("penumbra_occlusion", format_int(t), " = ",
                     construct(config, "vec4", compare(config, "greaterThanEqual", first, "vec4(k)")), " * ",
                     construct(config, "vec4", compare(config, "lessThanEqual", first, "vec4(next)")), ";");
        else
            out.line("penumbra_occlusion", format_int(t), " = ", construct(config, "vec4", compare(config, "equal", "vec4(k)", first)),
                     ";");
    }
    if (marches_near_field(config)) write_near_depth(out, config);
    out.line("}");
    write_entry_point(out, config, Stage::fragment);
    return out.take();
}

} // namespace penumbra::detail
