#include "frame_stats.hpp"

#include <algorithm>

namespace penumbra::playground {

double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    const std::size_t middle = values.size() / 2;
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle), values.end());
    if (values.size() % 2) return values[middle];
    const double upper = values[middle];
    const double lower =
        *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(middle));
    return 0.5 * (lower + upper);
}

void TimeSeries::add(double milliseconds) {
    all_.push_back(milliseconds);
    plot_.push_back(static_cast<float>(milliseconds));
    if (plot_.size() > plot_length) plot_.erase(plot_.begin());
}

void FrameStats::add_pass(const std::string& name, double milliseconds) {
    if (!passes.count(name)) pass_order.push_back(name);
    passes[name].add(milliseconds);
}

} // namespace penumbra::playground
