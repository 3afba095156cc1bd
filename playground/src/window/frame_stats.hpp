// playground/src/window/frame_stats.hpp — frame and per-pass times: the last few hundred values
// for the running plot, and every value for the medians printed at exit.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace penumbra::playground {

// The median of `values` (0 for none).
double median(std::vector<double> values);

class TimeSeries {
public:
    static constexpr int plot_length = 240;

    void add(double milliseconds);
    const std::vector<float>& plot() const { return plot_; } // oldest first, at most plot_length
    double last() const { return all_.empty() ? 0.0 : all_.back(); }
    double median() const { return penumbra::playground::median(all_); }
    std::size_t count() const { return all_.size(); }

private:
    std::vector<float> plot_;
    std::vector<double> all_;
};

// Frame time plus one series per named pass, in the order passes first appeared.
struct FrameStats {
    TimeSeries frame;
    std::vector<std::string> pass_order;
    std::map<std::string, TimeSeries> passes;

    void add_pass(const std::string& name, double milliseconds);
};

} // namespace penumbra::playground
