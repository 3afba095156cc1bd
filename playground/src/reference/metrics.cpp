#include "reference/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace penumbra::playground {

namespace {

// One pixel's error and its weight (1, or the unoccluded irradiance for the shaded reference).
struct WeightedError {
    double error = 0, weight = 1;
};

// Weighted means of |e|, e and e²; p95 the smallest |e| below which 95 % of the weight lies.
ErrorStats stats(std::vector<WeightedError> errors, double signed_sum, double weight_sum) {
    ErrorStats s;
    s.count = errors.size();
    if (errors.empty() || !(weight_sum > 0)) return s;
    double sum = 0, sq = 0;
    for (const WeightedError& e : errors) {
        sum += e.weight * e.error;
        sq += e.weight * e.error * e.error;
    }
    s.mae = sum / weight_sum;
    s.bias = signed_sum / weight_sum;
    s.rmse = std::sqrt(sq / weight_sum);
    std::sort(errors.begin(), errors.end(),
              [](const WeightedError& a, const WeightedError& b) { return a.error < b.error; });
    double below = 0;
    s.p95 = errors.back().error;
    for (const WeightedError& e : errors) {
        below += e.weight;
        if (below >= 0.95 * weight_sum) {
            s.p95 = e.error;
            break;
        }
    }
    return s;
}

// compare(), each pixel weighed by weights[i] (empty: 1); pixels of weight 0 count in neither mean.
Metrics compare_weighted(std::span<const float> estimate, std::span<const unsigned char> geometry,
                         std::span<const float> reference, std::span<const float> weights) {
    std::vector<WeightedError> all, pen;
    double signed_all = 0, signed_pen = 0, weight_all = 0, weight_pen = 0;
    for (std::size_t i = 0; i < estimate.size(); ++i) {
        if (!geometry[i] || std::isnan(reference[i])) continue;
        const double w = weights.empty() ? 1.0 : static_cast<double>(weights[i]);
        if (!(w > 0)) continue;
        const double signed_error = static_cast<double>(estimate[i]) - reference[i];
        const WeightedError e{std::abs(signed_error), w};
        all.push_back(e);
        signed_all += w * signed_error;
        weight_all += w;
        if (reference[i] < 0.98f || estimate[i] < 0.98f) {
            pen.push_back(e);
            signed_pen += w * signed_error;
            weight_pen += w;
        }
    }
    return {stats(std::move(all), signed_all, weight_all), stats(std::move(pen), signed_pen, weight_pen)};
}

} // namespace

Metrics compare(std::span<const float> estimate, std::span<const unsigned char> geometry,
                std::span<const float> reference) {
    return compare_weighted(estimate, geometry, reference, {});
}

QualityMetrics compare_quality(std::span<const float> estimate, std::span<const unsigned char> geometry,
                               std::span<const float> visibility, std::span<const float> oriented,
                               std::span<const float> irradiance, std::span<const float> unoccluded) {
    QualityMetrics q{compare(estimate, geometry, visibility),
                     compare(estimate, geometry, oriented),
                     compare(estimate, geometry, irradiance),
                     compare_weighted(estimate, geometry, irradiance, unoccluded),
                     {},
                     {}};
    for (std::size_t i = 0; i < estimate.size(); ++i) {
        if (!geometry[i] || std::isnan(irradiance[i])) continue; // the shading lights none of it
        if (irradiance[i] <= false_light_truth) {
            ++q.false_light.pixels;
            if (estimate[i] >= false_light_estimate) ++q.false_light.wrong;
        }
        if (irradiance[i] >= false_shadow_truth) {
            ++q.false_shadow.pixels;
            if (estimate[i] < false_shadow_estimate) ++q.false_shadow.wrong;
        }
    }
    return q;
}

} // namespace penumbra::playground
