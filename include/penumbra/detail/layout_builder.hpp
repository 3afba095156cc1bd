// penumbra/detail/layout_builder.hpp — how a layout is built (its structs: penumbra/layout_types.hpp):
// declaration groups of parameters turned into bindings and block offsets, and the builder with which each technique folder describes its
// textures and passes (detail/<technique>/layout.hpp). Nothing here knows a technique's programs.
#pragma once

#include "../layout_types.hpp"
#include "alpha_test.hpp"
#include "glsl_common.hpp"
#include "target_limits.hpp"

#include <algorithm>
#include <array>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace penumbra {

namespace detail {

// The filtered levels' format (Config::level_format); ES 3.0 cannot render to half floats. Other
// techniques' screen-sized intermediates (erosion) stay in half floats where the target has them.
constexpr std::string_view level_format(const Config& config) {
    if (config.target == Target::essl300) return "RGBA8";
    if (config.technique == Technique::occlusion && config.level_format == LevelFormat::rgba8) return "RGBA8";
    return "RGBA16F";
}

// The screen-phase result: a format every target can render to. ES 3.0 renders R32F / R16F only
// with EXT_color_buffer_float; R8 is colour-renderable in core ES 3.0 (8 bits of visibility).
constexpr std::string_view visibility_format(const Config& config) {
    return config.target == Target::essl300 ? "R8" : "R32F";
}

inline std::string border_wrap(const Config& config) {
    return limits(config.target).clamp_to_border ? "CLAMP_TO_BORDER" : "CLAMP_TO_EDGE";
}

// One declaration group of a program: a uniform block on Vulkan ("PenumbraSlicing", …) and its
// samplers. The emitters declare the same groups in the same order, so the bindings match.
struct ParamGroup {
    std::string_view block;
    std::vector<Param> params;
};

// The groups of the shading programs every technique ends with: penumbraVisibility()'s parameters,
// then the program's own (shading_example: fragment, then vertex stage; shading_deferred: the G-buffer).
inline std::vector<ParamGroup> shading_param_groups(std::string_view program, std::vector<Param> visibility,
                                                    std::vector<Param> deferred, std::vector<Param> fragment,
                                                    std::vector<Param> vertex) {
    if (program == "shading_example")
        return {{"PenumbraVisibility", std::move(visibility)},
                {"PenumbraExample", std::move(fragment)},
                {"PenumbraCamera", std::move(vertex)}};
    return {{"PenumbraVisibility", std::move(visibility)}, {"PenumbraDeferred", std::move(deferred)}};
}

// The groups of the programs that draw the casters from the light (slicing, depth bins, shadow-map
// depth): the program's own, then with alpha_test the draw's material (detail/alpha_test.hpp).
inline std::vector<ParamGroup> caster_param_groups(const Config& config, std::string_view block,
                                                   std::vector<Param> own) {
    std::vector<ParamGroup> groups{{block, std::move(own)}};
    if (config.alpha_test) groups.push_back({alpha_test_block, alpha_test_params(config)});
    return groups;
}

// The parameters of a program from its declaration groups: blocks and samplers numbered as they appear.
inline std::vector<ParamDesc> describe_params(const Config& config, const std::vector<ParamGroup>& groups) {
    std::vector<ParamDesc> out;
    int next_binding = 0;
    for (const auto& [block, group] : groups) {
        const int block_binding = next_binding;
        const std::vector<int> bindings = param_bindings(config, group, next_binding);
        int offset = 0;
        for (std::size_t i = 0; i < group.size(); ++i) {
            const Param& p = group[i];
            ParamDesc desc;
            desc.name = p.name.str();
            desc.type = std::string(p.type);
            desc.meaning = std::string(p.meaning);
            desc.units = std::string(p.units);
            desc.binding = bindings[i];
            desc.texture = p.texture.str();
            if (!is_sampler(p) || p.source == UniformSource::draw) {
                desc.source = p.source;
                const UniformDef* def = find_uniform(p.name.view());
                desc.compute = p.source == UniformSource::pass ? "the value in int_uniforms of the pass that runs this program"
                               : def ? std::string(def->compute(config.light)) : std::string();
            }
            if (is_sampler(p)) { // completed from the texture by finish_sampling
                desc.sampling.min_filter = desc.sampling.mag_filter = std::string(p.filter);
                if (p.type.ends_with("Shadow")) desc.sampling.compare = std::string(shadow_compare_func);
            }
            if (is_vulkan(config)) desc.set = vulkan_descriptor_set;
            if (!is_sampler(p) && is_vulkan(config)) {
                const std::optional<GlslType> type = parse_enum<GlslType>(p.type);
                const Std140 layout = std140(type.value_or(GlslType::float_)); // std140 layout rules
                offset = (offset + layout.align - 1) / layout.align * layout.align;
                desc.block = std::string(block);
                desc.block_binding = block_binding;
                desc.offset = offset;
                offset += layout.size;
            }
            out.push_back(std::move(desc));
        }
    }
    return out;
}

// find_texture(layout, name): penumbra/layout_types.hpp.

inline int binding_of(const std::vector<ParamDesc>& params, std::string_view name) {
    for (const ParamDesc& p : params)
        if (p.name == name) return p.binding;
    return -1;
}

// Adds textures and passes to a layout whose programs are already described.
struct LayoutBuilder {
    Layout& layout;
    std::string wrap; // the default wrap mode of new textures
    // What the screen phase depends on (layout.phase_inputs); a technique whose screen phase reads a
    // bake instead of the light and the geometry says so.
    std::vector<std::string> screen_inputs{"light", "geometry", "camera", "caller_textures"};

    const std::vector<ParamDesc>& params_of(std::string_view program) const {
        for (const ProgramDesc& p : layout.programs)
            if (p.name == program) return p.parameters;
        return layout.programs.front().parameters;
    }
    TextureDesc& texture(std::string name, std::string target, std::string format, int w, int h, int d, int mips,
                         std::string min, std::string mag, std::string purpose) {
        TextureDesc t;
        t.name = std::move(name);
        t.target = std::move(target);
        t.internal_format = std::move(format);
        t.width = w;
        t.height = h;
        t.depth = d;
        t.mip_levels = mips;
        t.min_filter = std::move(min);
        t.mag_filter = std::move(mag);
        t.wrap = wrap;
        t.purpose = std::move(purpose);
        layout.textures.push_back(std::move(t));
        return layout.textures.back();
    }
    void pass(std::string name, std::string action, std::string program, std::vector<BindingDesc> inputs,
              std::vector<AttachmentDesc> outputs, std::vector<std::pair<std::string, int>> ints, int w, int h,
              RenderState state = {}, std::string phase = "shadow") {
        for (BindingDesc& b : inputs)
            if (!program.empty()) b.binding = binding_of(params_of(program), b.sampler);
        PassDesc p;
        p.name = std::move(name);
        p.action = std::move(action);
        p.program = std::move(program);
        p.inputs = std::move(inputs);
        p.outputs = std::move(outputs);
        p.int_uniforms = std::move(ints);
        p.viewport_width = w;
        p.viewport_height = h;
        p.state = std::move(state);
        p.phase = std::move(phase);
        if (p.action == "copy" && !p.inputs.empty() && !p.outputs.empty())
            p.copy = CopyDesc{std::max(p.inputs[0].level, 0), -1, p.outputs[0].level, p.outputs[0].layer, w, h};
        if (p.action == "generate_mipmap" && !p.outputs.empty())
            if (const TextureDesc* t = find_texture(layout, p.outputs[0].texture))
                p.mipmap = MipmapDesc{p.outputs[0].level, t->mip_levels - p.outputs[0].level};
        layout.passes.push_back(std::move(p));
    }
    // Full-screen passes: no blending, no depth test, an empty vertex array, 3 vertices.
    void fullscreen(std::string name, std::string program, std::vector<BindingDesc> inputs, AttachmentDesc output,
                    std::vector<std::pair<std::string, int>> ints, int w, int h) {
        pass(std::move(name), "fullscreen", std::move(program), std::move(inputs), {std::move(output)}, std::move(ints),
             w, h);
    }
};

// How a binding reads `texture`: the texture's own filters and wrap, unless the sampler parameter
// asks for another filter; `partial` holds what describe_params knew (filter override, compare).
inline Sampling complete_sampling(const Sampling& partial, const TextureDesc& texture) {
    Sampling s = partial;
    if (s.min_filter.empty()) s.min_filter = texture.min_filter;
    if (s.mag_filter.empty()) s.mag_filter = texture.mag_filter;
    s.wrap = texture.wrap;
    s.border_color = texture.border_color;
    return s;
}

// Every sampler parameter's and every pass input's "sampling", from the textures they read and what
// their parameter says; the initial contents of textures that the engine provides.
inline void finish_sampling(Layout& layout) {
    for (TextureDesc& t : layout.textures)
        if (t.source != "passes") t.initial = t.source;
    for (PassDesc& pass : layout.passes)
        for (BindingDesc& in : pass.inputs) {
            Sampling partial;
            for (const ProgramDesc& program : layout.programs)
                if (program.name == pass.program)
                    for (const ParamDesc& param : program.parameters)
                        if (param.name == in.sampler) partial = param.sampling;
            if (const TextureDesc* t = find_texture(layout, in.texture)) in.sampling = complete_sampling(partial, *t);
        }
    // a parameter without a texture of its own (a level pass's source, bound per pass): its first pass's
    for (ProgramDesc& program : layout.programs)
        for (ParamDesc& param : program.parameters) {
            if (param.binding < 0) continue;
            if (const TextureDesc* t = find_texture(layout, param.texture)) {
                param.sampling = complete_sampling(param.sampling, *t);
                continue;
            }
            for (const PassDesc& pass : layout.passes)
                for (const BindingDesc& in : pass.inputs)
                    if (pass.program == program.name && in.sampler == param.name && param.sampling.wrap.empty())
                        param.sampling = in.sampling;
        }
}

// The screen phase's textures: the caller's G-buffer (`gbuffer`: world positions, or what the
// technique reads instead), its normals where penumbraVisibility uses them, and the visibility
// result at the output size.
inline void describe_screen_textures(
    LayoutBuilder& b, const Config& config, std::string gbuffer = "penumbra_worldPositions",
    std::string gbuffer_purpose = "G-buffer filled by the engine every frame: xyz world position, w = 1 on geometry, "
                                  "0 on the background; read with texelFetch (no filtering)") {
    TextureDesc& world =
        b.texture(std::move(gbuffer), "2D", "RGBA32F", 0, 0, 1, 1, "NEAREST", "NEAREST", std::move(gbuffer_purpose));
    world.wrap = "CLAMP_TO_EDGE";
    world.size = "output";
    world.source = "caller";
    if (reads_receiver_normal(config)) {
        TextureDesc& normals = b.texture("penumbra_worldNormals", "2D", "RGBA32F", 0, 0, 1, 1, "NEAREST", "NEAREST",
                                         "G-buffer filled by the engine every frame: xyz the unit normal of the "
                                         "side the viewer sees (tangent clip, normal offset); read with texelFetch "
                                         "(no filtering)");
        normals.wrap = "CLAMP_TO_EDGE";
        normals.size = "output";
        normals.source = "caller";
    }
    TextureDesc& visibility = b.texture("penumbra_visibility", "2D", std::string(visibility_format(config)), 0, 0, 1, 1,
                                        "NEAREST", "NEAREST", "visibility of each output pixel, 0 shadowed to 1 lit");
    visibility.wrap = "CLAMP_TO_EDGE";
    visibility.size = "output";
    b.layout.result = visibility.name;
}

// The screen phase of most techniques: shading_deferred over the caller's G-buffer into the result.
inline void describe_deferred_pass(LayoutBuilder& b) {
    std::vector<BindingDesc> deferred_inputs;
    for (const ParamDesc& p : b.params_of("shading_deferred"))
        if (p.binding >= 0) deferred_inputs.push_back({p.name, p.texture, p.binding});
    b.pass("shading", "fullscreen", "shading_deferred", deferred_inputs, {{b.layout.result, 0, -1}}, {}, 0, 0, {},
           "screen");
}

} // namespace detail
} // namespace penumbra
