// penumbra/detail/occlusion/emit_unpack.hpp — the unpack pass of more than 32 slices (paper §3.7): the
// slicing pass wrote slice k as bit k % 32 of component k / 32 of one RGBA32UI texel; this
// full-screen pass turns the bits back into the RGBA occlusion textures (four slices each) that the
// prefilter passes read. One draw writes as many textures as the target has colour attachments,
// so 128 slices (32 textures) take four draws on OpenGL, eight on Vulkan.
#pragma once

#include "parameters.hpp"
#include "../target_limits.hpp"

namespace penumbra::detail {

// Occlusion textures one unpack draw writes: the target's colour attachments. Eight or four
// textures are 32 or 16 slices, so a draw's slices lie in one 32-bit word of the bit texel.
constexpr int unpack_group(const Config& config) {
    const int attachments = limits(config.target).max_draw_buffers;
    return texture_count(config) < attachments ? texture_count(config) : attachments;
}

// Unpack draws of a configuration that slices as bits: T / unpack_group.
constexpr int unpack_draws(const Config& config) {
    return (texture_count(config) + unpack_group(config) - 1) / unpack_group(config);
}

constexpr std::vector<Param> unpack_params() {
    return {{"penumbra_firstSlice", "int", "first slice this draw unpacks (a multiple of four times the outputs)", "",
             {}, UniformSource::pass},
            {"penumbra_sliceBits", "usampler2D", "slicing output: bit k % 32 of component k / 32 marks slice k", "",
             "penumbra_sliceBits"}};
}

constexpr Text unpack_fragment(const Config& config) {
    LineWriter out;
    write_preamble(out, config, "unpack of the sliced bits into RGBA occlusion textures (paper §3.7), fragment stage");
    int binding = 0;
    write_params(out, config, unpack_params(), "PenumbraPass", binding);
    const int outputs = unpack_group(config);
    for (int i = 0; i < outputs; ++i)
        out.line("layout(location = ", format_int(i), ") out vec4 penumbra_occlusion", format_int(i),
                 "; // slices penumbra_firstSlice + ", format_int(4 * i), " to + ", format_int(4 * i + 3));
    out.blank();
    out.chunk("unpack_main");
    out.line("void main()");
    out.line("{");
    out.line("uvec4 bits = texelFetch(penumbra_sliceBits, ivec2(gl_FragCoord.xy), 0);");
    out.comment("the word holding this draw's slices, shifted so that bit 0 is slice penumbra_firstSlice");
    out.line("uint word = bits[penumbra_firstSlice / 32] >> uint(penumbra_firstSlice % 32);");
    for (int i = 0; i < outputs; ++i) {
        out.line("// output ", format_int(i), ": bits ", format_int(4 * i), " to ", format_int(4 * i + 3), " in r, g, b, a");
        out.line("penumbra_occlusion", format_int(i), " = vec4((uvec4(word) >> uvec4(", format_int(4 * i), "u, ",
                 format_int(4 * i + 1), "u, ", format_int(4 * i + 2), "u, ", format_int(4 * i + 3), "u)) & 1u);");
    }
    out.line("}");
    return out.take();
}

} // namespace penumbra::detail
