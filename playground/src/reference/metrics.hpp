// playground/src/reference/metrics.hpp — how far an estimated visibility is from the truth.
#pragma once

#include <cstddef>
#include <span>

namespace penumbra::playground {

struct ErrorStats {
    double mae = 0, rmse = 0, p95 = 0;
    double bias = 0; // mean signed error, estimate − reference: > 0 too bright, < 0 too dark
    std::size_t count = 0;
};

struct Metrics {
    ErrorStats all;      // over every geometry pixel
    ErrorStats penumbra; // where the reference or the estimate is < 0.98
};

// |estimate − reference| over the pixels where `geometry` is non-zero and the reference is not
// NaN (a fair reference marks pixels that see none of the light so); all three spans have one
// entry per pixel.
Metrics compare(std::span<const float> estimate, std::span<const unsigned char> geometry,
                std::span<const float> reference);

// One estimate against the three references of the ground truth (reference/ground_truth.hpp),
// whatever technique produced it:
//   visibility: the unblocked fraction of the whole light (rays behind the receiver's tangent
//               plane count as blocked), today's metric;
//   oriented:   the visibility of the part of the light above the tangent plane;
//   irradiance: the ray-traced irradiance relative to the unoccluded irradiance from that part.
// A share of wrong pixels: `wrong` of the `pixels` a condition selects.
struct ErrorRate {
    std::size_t wrong = 0, pixels = 0;
    double fraction() const { return pixels ? static_cast<double>(wrong) / pixels : 0.0; }
};

// What a viewer sees at once, which a mean hides, on the pixels the shading lights (some of the light is
// above the surface: the irradiance truth is defined; elsewhere the shading is dark whatever the estimate):
//   false light:  of the pixels that get no light (irradiance truth ≤ .01), those the estimate gives ≥ .05;
//   false shadow: of the pixels fully lit (irradiance truth ≥ .99), those the estimate gives < .95.
// Not the whole-light truth: a face that sees a corner of a large light above it, unblocked, gets under 1 %
// of the whole light and is rightly lit (dimly, as its shading's irradiance is small).
inline constexpr float false_light_truth = 0.01f, false_light_estimate = 0.05f;
inline constexpr float false_shadow_truth = 0.99f, false_shadow_estimate = 0.95f;

// shaded: the irradiance reference's error, each pixel weighed by the unoccluded irradiance it receives
// (GroundTruth::Oriented::unoccluded): the error of the shaded image (albedo × radiance × unoccluded
// irradiance × visibility) in linear light, albedo aside, relative to the mean unoccluded irradiance over the
// same pixels (the unshadowed image's mean). A face
// that gets almost no light weighs almost nothing, the floor under the light the most; where every
// pixel gets the same irradiance it equals the irradiance reference's error. Same pixels as irradiance
// (penumbra: the truth or the estimate < 0.98).
struct QualityMetrics {
    Metrics visibility, oriented, irradiance, shaded;
    ErrorRate false_light, false_shadow;
};

QualityMetrics compare_quality(std::span<const float> estimate, std::span<const unsigned char> geometry,
                               std::span<const float> visibility, std::span<const float> oriented,
                               std::span<const float> irradiance, std::span<const float> unoccluded);

} // namespace penumbra::playground
