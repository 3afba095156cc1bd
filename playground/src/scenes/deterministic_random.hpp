// playground/src/scenes/deterministic_random.hpp — random numbers that are identical everywhere.
//
// std::mt19937's output sequence is fixed by the C++ standard, but std::uniform_*_distribution
// is not: libstdc++, libc++ and MSVC map the engine's bits to floats differently, and libstdc++
// has changed its own mapping between releases. Procedural scenes must be bit-identical on every
// machine (tests compare them, ground-truth images are cached), so we map the bits ourselves.
#pragma once

#include <cstdint>
#include <random>

namespace penumbra::playground {

class DeterministicRandom {
public:
    explicit DeterministicRandom(std::uint32_t seed) : engine_(seed) {}

    // Uniform in [0, 1): the top 24 bits of one 32-bit draw, so every value is an exact float.
    float uniform01() { return static_cast<float>(engine_() >> 8) * (1.0f / 16777216.0f); }

    // Uniform in [lo, hi).
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform01(); }

    // Integer in [0, n) for small n (n ≪ 2^32; the modulo bias is irrelevant here and,
    // more importantly, deterministic).
    std::uint32_t below(std::uint32_t n) { return n == 0 ? 0 : engine_() % n; }

private:
    std::mt19937 engine_;
};

} // namespace penumbra::playground
