// penumbra/detail/api.hpp — header-only by default; optionally one translation unit holds the
// run-time emitter (in the style of stb and sokol), so that the other files that call emit() do
// not compile it:
//
//   PENUMBRA_SEPARATE_IMPLEMENTATION   defined for the whole program (target_compile_definitions):
//                                      emit.hpp and layout.hpp declare emit(), describe_layout()
//                                      and to_json() without their definitions;
//   PENUMBRA_IMPLEMENTATION            defined in one .cpp before including <penumbra/emit.hpp>:
//                                      that file defines them (not inline).
//
// Compile-time use (static_glsl.hpp, validate.hpp, the constexpr emitters) is header-only either way.
#pragma once

#if defined(PENUMBRA_SEPARATE_IMPLEMENTATION) && !defined(PENUMBRA_IMPLEMENTATION)
#define PENUMBRA_DECLARATIONS_ONLY 1
#else
#define PENUMBRA_DECLARATIONS_ONLY 0
#endif

// The run-time entry points: inline when header-only, defined once with a separate implementation
// (a function declared inline in one translation unit must be inline in all of them).
#if defined(PENUMBRA_SEPARATE_IMPLEMENTATION)
#define PENUMBRA_ENTRY_POINT
#else
#define PENUMBRA_ENTRY_POINT inline
#endif
