// playground/src/reference/metrics.hpp — how far an estimated visibility is from the truth.
#pragma once

#include <cstddef>
#include <span>

namespace penumbra::playground {

struct ErrorStats {
    double mae = 0, rmse = 0, p95 = 0;
    std::size_t count = 0;
};

struct Metrics {
    ErrorStats all;      // over every geometry pixel
    ErrorStats penumbra; // where the reference or the estimate is < 0.98
};

// |estimate − reference| over the pixels where `geometry` is non-zero; all three spans have one
// entry per pixel.
Metrics compare(std::span<const float> estimate, std::span<const unsigned char> geometry,
                std::span<const float> reference);

} // namespace penumbra::playground
