// Clustered fusion's occluder count (docs/model.md §1.7.3), through the oracle's double-precision twin of
// the emitted penumbra_clusterCount (penumbra-tests-gl checks the GPU against the oracle).
#include "reference/oracle.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

using penumbra::playground::cluster_count;

TEST_CASE("cluster count: an edge and a single occluder count as one") {
    for (double a : {0.1, 0.5, 1.0}) {
        CAPTURE(a);
        // a straight edge along either axis: two quadrants covered alike, two not (no saddle)
        CHECK(cluster_count({a, 0.0, a, 0.0}) == doctest::Approx(1.0));
        CHECK(cluster_count({0.0, 0.0, a, a}) == doctest::Approx(1.0));
        // one occluder inside one quadrant
        CHECK(cluster_count({0.0, 0.0, 0.0, a}) == doctest::Approx(1.0));
    }
    // nothing to count
    CHECK(cluster_count({0.0, 0.0, 0.0, 0.0}) == 1.0);
}

TEST_CASE("cluster count: an even crowd counts as many, a lone one in a quadrant stays one") {
    CHECK(cluster_count({0.30, 0.32, 0.29, 0.31}) > 100.0);
    CHECK(cluster_count({0.30, 0.32, 0.29, 0.31}) > 20.0 * cluster_count({0.6, 0.0, 0.6, 0.02}));
}

// N squares of 4 × 4 texels thrown at random into a 64 × 64 kernel: the median count over many throws
// follows N (the binomial the count is derived from), though the squares may overlap.
TEST_CASE("cluster count: scattered occluders are counted") {
    std::uint32_t state = 12345u;
    auto next = [&](int below) { // a fixed linear congruential sequence: the same throws everywhere
        state = state * 1664525u + 1013904223u;
        return static_cast<int>((state >> 8) % static_cast<std::uint32_t>(below));
    };
    const int R = 64, side = 4;
    for (int n : {1, 4, 16, 64}) {
        std::vector<double> counts;
        for (int trial = 0; trial < 101; ++trial) {
            std::vector<unsigned char> mask(R * R, 0);
            for (int i = 0; i < n; ++i) {
                const int x0 = next(R - side + 1), y0 = next(R - side + 1);
                for (int y = y0; y < y0 + side; ++y)
                    for (int x = x0; x < x0 + side; ++x) mask[y * R + x] = 1;
            }
            glm::dvec4 quadrants(0.0); // lower left, lower right, upper left, upper right
            for (int y = 0; y < R; ++y)
                for (int x = 0; x < R; ++x) quadrants[(y >= R / 2 ? 2 : 0) + (x >= R / 2 ? 1 : 0)] += mask[y * R + x];
            counts.push_back(cluster_count(quadrants / double(R * R / 4)));
        }
        std::nth_element(counts.begin(), counts.begin() + 50, counts.end());
        const double median = counts[50];
        CAPTURE(n);
        CAPTURE(median);
        CHECK(median >= 0.5 * n);
        CHECK(median <= 2.0 * n);
    }
}
