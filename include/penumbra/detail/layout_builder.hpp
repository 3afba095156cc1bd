// penumbra/detail/layout_builder.hpp — how a layout is built (its structs and enums:
// penumbra/layout_types.hpp): declaration groups of parameters turned into bindings and block
// offsets, and the builder with which each technique folder describes its textures and passes
// (detail/<technique>/layout.hpp). Nothing here knows a technique's programs.
//
// A technique's describe_layout(LayoutBuilder& b, const Config& config) adds, in pass order:
//
//   b.texture({.name = "penumbra_moments", .format = TextureFormat::rgba16f, .width = R, .height = R,
//              .min_filter = TextureFilter::linear, .mag_filter = TextureFilter::linear,
//              .purpose = "what a texel holds"});
//   b.pass({.name = "moments", .action = PassAction::draw_scene, .program = "moments",
//           .outputs = {{"penumbra_moments"}}, .viewport_width = R, .viewport_height = R,
//           .state = {.clear_color = std::array<float, 4>{}}});
//   b.pass({.name = "blur", .program = "blur",                  // action fullscreen by default
//           .inputs = {{"penumbra_source", "penumbra_moments"}}, // sampler, texture
//           .outputs = {{"penumbra_blurred"}}, .viewport_width = R, .viewport_height = R});
//
// then, for the screen phase, describe_screen_textures and describe_deferred_pass (below). Every
// field not named keeps the default written next to it in layout_types.hpp (a 2D RGBA8 texture,
// NEAREST, CLAMP_TO_EDGE, fixed size, written by the passes; a fullscreen pass of phase shadow with
// no blending and no depth test). The builder fills each input's binding from the program's
// parameters, and finish_sampling each input's sampling.
#pragma once

#include "../layout_types.hpp"
#include "alpha_test.hpp"
#include "glsl_common.hpp"
#include "target_limits.hpp"

#include <algorithm>
#include <cassert>
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
constexpr TextureFormat level_format(const Config& config) {
    if (config.target == Target::essl300) return TextureFormat::rgba8;
    if (config.technique == Technique::occlusion && config.level_format == LevelFormat::rgba8) return TextureFormat::rgba8;
    return TextureFormat::rgba16f;
}

// The screen-phase result: a format every target can render to. ES 3.0 renders R32F / R16F only
// with EXT_color_buffer_float; R8 is colour-renderable in core ES 3.0 (8 bits of visibility).
constexpr TextureFormat visibility_format(const Config& config) {
    return config.target == Target::essl300 ? TextureFormat::r8 : TextureFormat::r32f;
}

// The wrap of textures whose outside reads the border colour where the target has one.
constexpr Wrap border_wrap(const Config& config) {
    return limits(config.target).clamp_to_border ? Wrap::clamp_to_border : Wrap::clamp_to_edge;
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
            if (is_sampler(p) && !p.filter.empty()) { // the sampling: from the texture, by finish_sampling
                desc.filter = parse_enum<TextureFilter>(p.filter);
                assert(desc.filter && "Param::filter names a TextureFilter");
            }
            if (is_vulkan(config) || binds_samplers_apart(config)) desc.set = vulkan_descriptor_set;
            if (is_sampler(p) && binds_samplers_apart(config)) {
                desc.sampler_binding = binds_wgsl_sampler(p) ? desc.binding + 1 : -1;
                desc.texture_type = is_hlsl(config) ? hlsl_texture_type(p).str() : wgsl_texture_type(p).str();
            }
            if (!is_sampler(p) && (is_vulkan(config) || binds_samplers_apart(config))) {
                const std::optional<GlslType> type = parse_enum<GlslType>(p.type);
                // std140 layout rules (WGSL's uniform address space places these types the same)
                const Std140 layout = std140(type.value_or(GlslType::float_));
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

inline int binding_of(const std::vector<ParamDesc>& params, std::string_view name) {
    for (const ParamDesc& p : params)
        if (p.name == name) return p.binding;
    return -1;
}

// Adds textures and passes to a layout whose programs are already described (see the top of this file).
struct LayoutBuilder {
    Layout& layout;
    // What the screen phase depends on (layout.phase_inputs); a technique whose screen phase reads a
    // bake instead of the light and the geometry says so.
    std::vector<std::string> screen_inputs{"light", "geometry", "camera", "caller_textures"};

    const std::vector<ParamDesc>& params_of(std::string_view program) const {
        for (const ProgramDesc& p : layout.programs)
            if (p.name == program) return p.parameters;
        return layout.programs.front().parameters;
    }
    // Adds a texture; the reference stays valid until the next texture is added.
    TextureDesc& texture(TextureDesc t) {
        layout.textures.push_back(std::move(t));
        return layout.textures.back();
    }
    // Adds a pass, each input's binding that of its sampler in the pass's program.
    PassDesc& pass(PassDesc p) {
        for (BindingDesc& b : p.inputs)
            if (!p.program.empty()) b.binding = binding_of(params_of(p.program), b.sampler);
        layout.passes.push_back(std::move(p));
        return layout.passes.back();
    }
    // The inputs of a pass running `program` over its samplers' own textures (every sampler parameter
    // with a binding, reading the texture the parameter names).
    std::vector<BindingDesc> own_inputs(std::string_view program) const {
        std::vector<BindingDesc> in;
        for (const ParamDesc& p : params_of(program))
            if (p.binding >= 0) in.push_back({p.name, p.texture, p.binding});
        return in;
    }
};

// How a sampler parameter reads `texture`: the texture's own filters and wrap unless the parameter
// asks for another filter (ParamDesc::filter); a shadow sampler compares (shadow_compare_func).
inline Sampling sampling_of(const ParamDesc* param, const TextureDesc& texture) {
    Sampling s{texture.min_filter, texture.mag_filter, texture.wrap, texture.border_color, std::nullopt};
    if (param && param->filter) s.min_filter = s.mag_filter = *param->filter;
    if (param && param->type.ends_with("Shadow")) s.compare = shadow_compare_func;
    return s;
}

// Every sampler parameter's and every pass input's sampling, from the textures they read and what
// their parameter says.
inline void finish_sampling(Layout& layout) {
    auto param_of = [&](std::string_view program, std::string_view sampler) -> const ParamDesc* {
        for (const ProgramDesc& p : layout.programs)
            if (p.name == program)
                for (const ParamDesc& param : p.parameters)
                    if (param.name == sampler) return &param;
        return nullptr;
    };
    for (PassDesc& pass : layout.passes)
        for (BindingDesc& in : pass.inputs)
            if (const TextureDesc* t = find_texture(layout, in.texture))
                in.sampling = sampling_of(param_of(pass.program, in.sampler), *t);
    // a parameter without a texture of its own (a level pass's source, bound per pass): its first pass's;
    // a draw's sampler (the caller's texture) has none
    for (ProgramDesc& program : layout.programs)
        for (ParamDesc& param : program.parameters) {
            if (param.binding < 0 || param.source == UniformSource::draw) continue;
            if (const TextureDesc* t = find_texture(layout, param.texture)) {
                param.sampling = sampling_of(&param, *t);
                continue;
            }
            for (const PassDesc& pass : layout.passes)
                for (const BindingDesc& in : pass.inputs)
                    if (pass.program == program.name && in.sampler == param.name && !param.sampling &&
                        find_texture(layout, in.texture))
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
    b.texture({.name = std::move(gbuffer), .format = TextureFormat::rgba32f, .size = TextureSize::output,
               .source = TextureSource::caller, .purpose = std::move(gbuffer_purpose)});
    if (reads_receiver_normal(config))
        b.texture({.name = "penumbra_worldNormals", .format = TextureFormat::rgba32f, .size = TextureSize::output,
                   .source = TextureSource::caller,
                   .purpose = "G-buffer filled by the engine every frame: xyz the unit normal of the side the viewer "
                              "sees (tangent clip, normal offset); read with texelFetch (no filtering)"});
    b.texture({.name = "penumbra_visibility", .format = visibility_format(config), .size = TextureSize::output,
               .purpose = "visibility of each output pixel, 0 shadowed to 1 lit"});
    b.layout.result = "penumbra_visibility";
}

// The screen phase of most techniques: shading_deferred over the caller's G-buffer into the result.
inline void describe_deferred_pass(LayoutBuilder& b) {
    b.pass({.name = "shading",
            .program = "shading_deferred",
            .inputs = b.own_inputs("shading_deferred"),
            .outputs = {{b.layout.result}},
            .phase = Phase::screen});
}

} // namespace detail
} // namespace penumbra
