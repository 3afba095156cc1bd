// penumbra/detail/shadow_map/poisson.hpp — the tap patterns PCF and PCSS bake into their text.
//
// Poisson disk: Mitchell's best-candidate algorithm (Mitchell 1991) with a fixed seed, in constant
// expressions. Each new point is the best of 16 uniform candidates in the unit disk (the one
// farthest from the points so far), so the first k points of the sequence are a Poisson-like
// pattern for every k: the pattern for k taps is the same whatever the largest k in use.
// Grid: N x N taps at the texel-like centres of the square [-1, 1]².
#pragma once

#include <cstdint>
#include <vector>

namespace penumbra::detail {

struct Tap {
    double x, y; // offset in units of the kernel's half-extent: |(x, y)| <= 1 (disk) or max <= 1 (grid)
};

// SplitMix64 (Steele, Lea & Flood 2014): a tiny generator that is the same on every platform.
class SplitMix64 {
public:
    constexpr explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
    constexpr std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    // Uniform in [-1, 1), with 53 random bits.
    constexpr double symmetric() { return static_cast<double>(next() >> 11) * (2.0 / 9007199254740992.0) - 1.0; }

private:
    std::uint64_t state_;
};

// Uniform point in the unit disk by rejection from the square (no square root: constexpr-safe).
constexpr Tap disk_point(SplitMix64& random) {
    for (;;) {
        const double x = random.symmetric(), y = random.symmetric();
        if (x * x + y * y <= 1.0) return {x, y};
    }
}

// Rounds to six decimals, so the baked literals stay short (a millionth of the kernel radius).
constexpr double six_decimals(double value) {
    const double scaled = value * 1e6;
    const long long rounded = static_cast<long long>(scaled < 0 ? scaled - 0.5 : scaled + 0.5);
    return static_cast<double>(rounded) / 1e6;
}

// The first `count` points of the best-candidate sequence in the unit disk.
constexpr std::vector<Tap> poisson_disk(int count, std::uint64_t seed = 0x5EED0F0CC1D3ull) {
    constexpr int candidates = 16;
    SplitMix64 random(seed);
    std::vector<Tap> taps;
    for (int i = 0; i < count; ++i) {
        Tap best = disk_point(random);
        double best_distance = -1.0;
        for (int c = 0; c < candidates && i > 0; ++c) {
            const Tap candidate = c == 0 ? best : disk_point(random);
            double nearest = 1e300;
            for (const Tap& t : taps) {
                const double dx = t.x - candidate.x, dy = t.y - candidate.y;
                const double d = dx * dx + dy * dy;
                nearest = d < nearest ? d : nearest;
            }
            if (nearest > best_distance) {
                best_distance = nearest;
                best = candidate;
            }
        }
        taps.push_back({six_decimals(best.x), six_decimals(best.y)});
    }
    return taps;
}

// N x N taps at ((i + 0.5) / N) * 2 - 1, row by row (y outer).
constexpr std::vector<Tap> grid_taps(int n) {
    std::vector<Tap> taps;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) taps.push_back({(i + 0.5) / n * 2.0 - 1.0, (j + 0.5) / n * 2.0 - 1.0});
    return taps;
}

} // namespace penumbra::detail
