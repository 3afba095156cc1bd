// The one translation unit that compiles Penumbra's run-time emitter, for a program built with
// PENUMBRA_SEPARATE_IMPLEMENTATION (penumbra/detail/api.hpp); main.cpp only declares emit().
#define PENUMBRA_IMPLEMENTATION
#include <penumbra/emit.hpp>
