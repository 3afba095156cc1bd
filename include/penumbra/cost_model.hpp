// penumbra/cost_model.hpp — what a layout's passes cost on a GPU, from the layout alone: per pass
// the fragments shaded, the texel fetches, and the bytes read and written. A GPU's prefilter and
// slicing passes are bound by memory bandwidth, so their time follows the bytes; the shading pass
// follows the fetches. Like texture_memory.hpp, it counts what the layout asks for, not what a
// driver does (caches, compression, tiling).
//
//   penumbra::CostModel cost = penumbra::cost_model(layout, width, height);
//   cost.shadow.bytes_read; cost.screen.texel_fetches; cost.passes[i].bytes_written
//
// The counting rules, per pass action:
//   fullscreen     every texel of the viewport once: fragments = viewport area; fetches = the
//                  program's texel reads per fragment (below) × fragments; bytes written = fragments ×
//                  the bytes per texel of every output; bytes read = every input texel once (a cache
//                  holds the neighbourhood the taps share): the input's bytes at the level it reads,
//                  at most the fetches' bytes. A pass that builds a reduced level (int uniform
//                  penumbra_scale = 2: it halves the resolution) reads every second texel of its
//                  source per axis, a quarter of them.
//   draw_scene     the clear of every output (bytes written = its size); the scene's own fragments
//                  depend on the geometry and are not counted (their blended writes go to the same
//                  texels, so the clear's bytes are the least the pass moves).
//   copy           the texel count read and written once.
//   generate_mipmap each level read once and the next written: 4/3 of level 0's bytes read, 1/3 written.
//   dispatch       (the compute prefilter) invocations = the workgroups' invocations; fetches = the
//                  shared tile each workgroup loads (block and apron, one texelFetch per texel) — the
//                  levels are then built from shared memory, not counted as fetches; bytes read = every
//                  texel of the source level once (the aprons overlap the neighbours' blocks: a cache
//                  holds them), at most the fetches' bytes; bytes written = every texel of every image
//                  output once. `fragments` counts the invocations.
// Fetches per fragment come from the technique's descriptor (detail/<technique>/technique.hpp:
// texels_per_fragment): a bilinear fetch counts 4 texels, a trilinear one 8. Occlusion textures: an
// N-buffer level 4 texels, a Gaussian one 9, the shading pass an upper bound (every slice above the
// point looks up); shadow maps: 4 texels per tap.
#pragma once

#include "layout.hpp"
#include "texture_memory.hpp"

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

struct PassCost {
    std::string name, phase;
    long long fragments = 0;     // fragments shaded (fullscreen: the viewport; draw_scene: 0, geometry-dependent;
                                 // dispatch: compute invocations)
    long long texel_fetches = 0; // texels the fragments read (bilinear: 4, trilinear: 8 per fetch)
    long long bytes_read = 0;    // input texels read once each
    long long bytes_written = 0; // output texels written once each (draw_scene: the clear)
};

struct PhaseCost {
    int passes = 0;
    long long fragments = 0, texel_fetches = 0, bytes_read = 0, bytes_written = 0;
    long long bytes() const { return bytes_read + bytes_written; }
};

struct CostModel {
    std::vector<PassCost> passes; // in layout order, phases "shadow" and "screen"
    PhaseCost shadow;             // the passes from the light (slicing, prefilter): when the light or geometry moves
    PhaseCost screen;             // every frame, at the output size
};

namespace detail {

// Texels one fragment of `pass` reads: the technique's descriptor knows its programs' taps.
inline long long texels_per_fragment(const Layout& layout, const PassDesc& pass) {
    return technique_descriptor(layout.config.technique).texels_per_fragment(layout.config, pass);
}

// Bytes of one level (or one layer) of a texture.
inline long long level_bytes(const TextureDesc& t, int level, int output_width, int output_height, bool one_layer) {
    long long w = t.width > 0 ? t.width : output_width, h = t.height > 0 ? t.height : output_height;
    w = std::max(1LL, w >> level);
    h = std::max(1LL, h >> level);
    const long long d = one_layer ? 1 : t.depth;
    return w * h * d * bytes_per_texel(t.internal_format);
}

} // namespace detail

inline CostModel cost_model(const Layout& layout, int output_width, int output_height) {
    using detail::find_texture;
    CostModel model;
    for (const PassDesc& pass : layout.passes) {
        if (pass.phase != "shadow" && pass.phase != "screen") continue;
        PassCost cost{pass.name, pass.phase};
        const bool screen = pass.phase == "screen";
        const long long w = screen ? output_width : pass.viewport_width, h = screen ? output_height : pass.viewport_height;
        auto output_bytes = [&](const AttachmentDesc& a) {
            const TextureDesc* t = find_texture(layout, a.texture);
            return t ? detail::level_bytes(*t, a.level, output_width, output_height, true) : 0LL;
        };
        if (pass.action == "fullscreen") {
            cost.fragments = w * h;
            cost.texel_fetches = cost.fragments * detail::texels_per_fragment(layout, pass);
            long long per_texel_written = 0;
            for (const AttachmentDesc& a : pass.outputs)
                if (const TextureDesc* t = find_texture(layout, a.texture)) per_texel_written += bytes_per_texel(t->internal_format);
            cost.bytes_written = cost.fragments * per_texel_written;
            // a pass with penumbra_sourceLayer reads one layer (array) or depth slice (volume) of its source
            bool one_layer = false;
            long long scale = 1; // reduced levels: every scale-th texel of the source per axis
            for (const auto& [name, value] : pass.int_uniforms) {
                one_layer = one_layer || name == "penumbra_sourceLayer";
                if (name == "penumbra_scale" && value > 1) scale = value;
            }
            long long fetched_bytes = 0, inputs = 0;
            for (const BindingDesc& in : pass.inputs) {
                const TextureDesc* t = find_texture(layout, in.texture);
                if (!t) continue;
                inputs += detail::level_bytes(*t, std::max(in.level, 0), output_width, output_height, one_layer) /
                          (scale * scale);
                fetched_bytes = std::max<long long>(fetched_bytes, bytes_per_texel(t->internal_format));
            }
            // every input texel once, but never more than the fetches bring in
            cost.bytes_read = std::min(inputs, cost.texel_fetches * fetched_bytes);
        } else if (pass.action == "draw_scene") {
            for (const AttachmentDesc& a : pass.outputs) cost.bytes_written += output_bytes(a);
            for (const BindingDesc& in : pass.inputs)
                if (const TextureDesc* t = find_texture(layout, in.texture))
                    cost.bytes_read += detail::level_bytes(*t, 0, output_width, output_height, false);
        } else if (pass.action == "copy") {
            const long long bytes = pass.outputs.empty() ? 0 : output_bytes(pass.outputs.front());
            cost.bytes_read = cost.bytes_written = bytes;
            cost.fragments = w * h;
        } else if (pass.action == "dispatch" && pass.dispatch) {
            const DispatchDesc& d = *pass.dispatch;
            const long long groups = 1LL * d.groups[0] * d.groups[1] * d.groups[2];
            cost.fragments = groups * d.local_size[0] * d.local_size[1] * d.local_size[2];
            // the tile a workgroup loads: its block (local_size) and the apron of its last level's windows
            int levels = 0, step = 0;
            for (const auto& [name, value] : pass.int_uniforms) {
                if (name == "penumbra_levels") levels = value;
                if (name == "penumbra_step") step = value;
            }
            const long long apron = ((1LL << levels) - 1) * step;
            cost.texel_fetches = groups * (d.local_size[0] + apron) * (d.local_size[1] + apron);
            long long fetched_bytes = 0, inputs = 0;
            for (const BindingDesc& in : pass.inputs)
                if (const TextureDesc* t = find_texture(layout, in.texture)) {
                    inputs += detail::level_bytes(*t, std::max(in.level, 0), output_width, output_height, true);
                    fetched_bytes = std::max<long long>(fetched_bytes, bytes_per_texel(t->internal_format));
                }
            cost.bytes_read = std::min(inputs, cost.texel_fetches * fetched_bytes);
            for (const ImageBindingDesc& image : pass.image_outputs)
                if (const TextureDesc* t = find_texture(layout, image.texture))
                    cost.bytes_written += detail::level_bytes(*t, image.level, output_width, output_height, true);
        } else if (pass.action == "generate_mipmap") {
            if (!pass.outputs.empty())
                if (const TextureDesc* t = find_texture(layout, pass.outputs.front().texture)) {
                    const long long base = detail::level_bytes(*t, 0, output_width, output_height, false);
                    cost.bytes_read = base * 4 / 3;
                    cost.bytes_written = base / 3;
                }
        }
        PhaseCost& phase = screen ? model.screen : model.shadow;
        ++phase.passes;
        phase.fragments += cost.fragments;
        phase.texel_fetches += cost.texel_fetches;
        phase.bytes_read += cost.bytes_read;
        phase.bytes_written += cost.bytes_written;
        model.passes.push_back(std::move(cost));
    }
    return model;
}

} // namespace penumbra
