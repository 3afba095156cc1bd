// penumbra/detail/parameters.hpp — the uniforms and samplers of each emitted program.
#pragma once

#include "glsl_common.hpp"

namespace penumbra::detail {

// Filters whose levels are full-resolution images built by a shader, one per level.
constexpr bool has_level_images(const Config& config) {
    return config.filter == Filter::nbuffer || config.filter == Filter::gaussian;
}

// Name of the texture of filter level `level` in the atlas packing.
constexpr Text atlas_level_name(int level) { return cat("penumbra_level", format_int(level)); }
constexpr Text volume_name(int texture) { return cat("penumbra_volume", format_int(texture)); }

// Samplers through which the shading pass reads the filtered occlusion (docs/model.md §3).
constexpr std::vector<Param> storage_samplers(const Config& config) {
    std::vector<Param> samplers;
    const int levels = max_level(config);
    if (config.filter == Filter::mipmap) {
        if (config.packing == Packing::atlas)
            samplers.push_back({"penumbra_occlusionAtlas", "sampler2D",
                                "occlusion tiles side by side with a full mip chain", "", "penumbra_occlusionAtlas"});
        else
            samplers.push_back({"penumbra_occlusion", "sampler2DArray",
                                "one layer per RGBA occlusion texture, full mip chain", "", "penumbra_occlusion"});
    } else if (config.filter == Filter::sat) {
        if (config.packing == Packing::atlas)
            samplers.push_back({"penumbra_satAtlas", "sampler2D",
                                "exclusive summed-area tables, (R+1)-texel tiles side by side", "", "penumbra_satAtlas"});
        else
            samplers.push_back({"penumbra_sat", "sampler2DArray",
                                "exclusive summed-area tables, one (R+1)-texel layer per occlusion texture", "",
                                "penumbra_sat"});
    } else if (config.packing == Packing::atlas) {
        for (int level = 0; level <= levels; ++level)
            samplers.push_back({atlas_level_name(level), "sampler2D", "filter level, occlusion tiles side by side",
                                "", atlas_level_name(level)});
    } else if (config.packing == Packing::array) {
        samplers.push_back({"penumbra_levels", "sampler2DArray", "filter levels, layer = level * T + texture", "",
                            "penumbra_levels"});
    } else {
        for (int t = 0; t < texture_count(config); ++t)
            samplers.push_back({volume_name(t), "sampler3D", "four slices, filter levels along depth", "",
                                volume_name(t)});
    }
    return samplers;
}

// Parameters of penumbraVisibility(): the light frame and the slices, then the storage.
constexpr std::vector<Param> visibility_params(const Config& config) {
    std::vector<Param> params;
    params.push_back({"penumbra_lightFromWorld", "mat4",
                      config.light == Light::rect
                          ? "world to light frame: x, y lateral, z depth along the light normal, origin at the light centre"
                          : "world to light frame: x, y lateral, z depth along the sun's direction, origin above the "
                            "scene on the axis through the bounds' centre",
                      "scene units"});
    if (config.light == Light::rect) {
        params.push_back({"penumbra_lightSize", "vec2", "light rectangle width, height", "scene units"});
        params.push_back({"penumbra_copDistance", "float",
                          "distance d of the slicing centre of projection behind the light", "scene units"});
    } else {
        params.push_back({"penumbra_windowHalfSize", "float",
                          "half side of the square orthographic slicing window", "scene units"});
        params.push_back({"penumbra_tanAngularRadius", "float", "tangent of the sun's angular radius", ""});
    }
    params.push_back({"penumbra_sliceDepths", "vec2", "x: depth z0 of the first slice's top, y: slice thickness",
                      "scene units"});
    for (Param& sampler : storage_samplers(config)) params.push_back(std::move(sampler));
    return params;
}

constexpr std::vector<Param> slicing_params() {
    return {
        {"penumbra_sliceClipFromWorld", "mat4",
         "world to clip space of the slicing camera (perspective from the centre of projection, or orthographic)",
         ""},
        {"penumbra_lightFromWorld", "mat4", "world to light frame (z = depth along the light normal)",
         "scene units"},
        {"penumbra_sliceDepths", "vec2", "x: depth z0 of the first slice's top, y: slice thickness", "scene units"},
    };
}

} // namespace penumbra::detail
