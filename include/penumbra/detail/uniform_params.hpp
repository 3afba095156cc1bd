// penumbra/detail/uniform_params.hpp — a registry uniform (penumbra/uniforms.hpp) as a parameter of
// an emitted program: name, type, units and source always from its row, so a program cannot declare
// it differently from what layout.json and uniform_value say.
#pragma once

#include "../uniforms.hpp"
#include "glsl_common.hpp"

namespace penumbra::detail {

// The uniform as its row describes it for `light`.
constexpr Param uniform_param(Uniform u, Light light) {
    const UniformDef& def = uniform_def(u);
    return {Text(def.name), to_string(def.type), def.meaning(light), def.units(light), {}, def.source};
}

// The uniform as one program reads it, where that program's role narrows the row's meaning (the
// slicing camera's light frame, the shadow map's window): the declaration comment and layout.json's
// "meaning" say so; `units` replaces the row's only when given.
constexpr Param uniform_param(Uniform u, std::string_view meaning) {
    Param p = uniform_param(u, Light::rect);
    p.meaning = meaning;
    return p;
}
constexpr Param uniform_param(Uniform u, std::string_view meaning, std::string_view units) {
    Param p = uniform_param(u, meaning);
    p.units = units;
    return p;
}

} // namespace penumbra::detail
