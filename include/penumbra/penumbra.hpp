// penumbra/penumbra.hpp — Penumbra: specialized GLSL for occlusion-texture soft shadows
// (Eisemann & Décoret, "Occlusion Textures for Plausible Soft Shadows", CGF 27(1), 2008).
//
//   #include <penumbra/penumbra.hpp>
//
//   penumbra::Config config{.slices = 16, .resolution = 512, .filter = penumbra::Filter::nbuffer};
//   auto result = penumbra::emit(config);        // errors as values: result.errors
//   const penumbra::Emission& e = *result.value;
//   e.programs;                                  // slicing, prefilter, shading stages, complete
//   e.snippet.text;                              // float penumbraVisibility(vec3 worldPos)
//   penumbra::to_json(e.layout);                 // textures, parameters, bindings, passes
//
// Uniform values from a light and the scene bounds (which must contain every receiver):
//   penumbra::SliceFrame f = penumbra::slice_frame(light, bounds_min, bounds_max, config.slices); // light_frame.hpp
//   penumbra::uniform_value("penumbra_sliceDepths", {f, config.light});  // by name: uniform_values.hpp
// The derivation: docs/model.md; layout.json's schema: docs/layout.schema.json.
// Techniques (config.technique): occlusion textures (the default; detail/occlusion/) and the
// shadow map family, shadowmap / pcf / pcss (detail/shadow_map/); every one emits the same
// float penumbraVisibility(vec3 worldPos). Texture memory of a layout: penumbra/texture_memory.hpp.
// Only the filter levels a light's kernels reach: config.level_bound = penumbra::kernel_level_bound(f, config)
// (penumbra/level_bound.hpp).
// The same model with uniforms instead of baked constants: penumbra::emit_generic (penumbra/generic.hpp).
// At compile time: penumbra::static_glsl<config, "penumbra_visibility.glsl"> (penumbra/static_glsl.hpp).
// Validation with glslang: penumbra/validation.hpp (target penumbra::validation).
// Every configuration field's JSON key, flag, range and help, and a configuration as layout.json's
// "config" object: penumbra::config_fields(), penumbra::config_to_json (penumbra/config_fields.hpp).
#pragma once

#include "config.hpp"
#include "config_fields.hpp"
#include "emit.hpp"
#include "generic.hpp"
#include "layout.hpp"
#include "level_bound.hpp"
#include "light_frame.hpp"
#include "profiles.hpp"
#include "program.hpp"
#include "static_glsl.hpp"
#include "uniform_values.hpp"
#include "texture_memory.hpp"
#include "validate.hpp"
