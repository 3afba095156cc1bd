#include "reference/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace penumbra::playground {

namespace {

ErrorStats stats(std::vector<double> errors, double signed_sum) {
    ErrorStats s;
    s.count = errors.size();
    if (errors.empty()) return s;
    double sum = 0, sq = 0;
    for (double e : errors) {
        sum += e;
        sq += e * e;
    }
    s.mae = sum / errors.size();
    s.bias = signed_sum / errors.size();
    s.rmse = std::sqrt(sq / errors.size());
    const std::size_t k = std::min(errors.size() - 1, static_cast<std::size_t>(std::ceil(0.95 * errors.size())) - 1);
    std::nth_element(errors.begin(), errors.begin() + static_cast<std::ptrdiff_t>(k), errors.end());
    s.p95 = errors[k];
    return s;
}

} // namespace

Metrics compare(std::span<const float> estimate, std::span<const unsigned char> geometry,
                std::span<const float> reference) {
    std::vector<double> all, pen;
    double signed_all = 0, signed_pen = 0;
    for (std::size_t i = 0; i < estimate.size(); ++i) {
        if (!geometry[i] || std::isnan(reference[i])) continue;
        const double signed_error = static_cast<double>(estimate[i]) - reference[i];
        const double e = std::abs(signed_error);
        all.push_back(e);
        signed_all += signed_error;
        if (reference[i] < 0.98f || estimate[i] < 0.98f) {
            pen.push_back(e);
            signed_pen += signed_error;
        }
    }
    return {stats(std::move(all), signed_all), stats(std::move(pen), signed_pen)};
}

QualityMetrics compare_quality(std::span<const float> estimate, std::span<const unsigned char> geometry,
                               std::span<const float> visibility, std::span<const float> oriented,
                               std::span<const float> irradiance) {
    QualityMetrics q{compare(estimate, geometry, visibility), compare(estimate, geometry, oriented),
                     compare(estimate, geometry, irradiance), {}, {}};
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
