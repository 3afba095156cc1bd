// playground/src/bake/oim_bake.cpp
#include "bake/oim_bake.hpp"

#include "reference/ground_truth.hpp"
#include "scenes/uv_coverage.hpp"

#include <algorithm>
#include <chrono>

namespace penumbra::playground {

std::vector<glm::vec3> sample_directions(const penumbra::SunPath& path, int samples) {
    std::vector<glm::vec3> directions(static_cast<std::size_t>(samples));
    for (int i = 0; i < samples; ++i)
        directions[static_cast<std::size_t>(i)] = glm::vec3(penumbra::sun_direction(path, (i + 0.5) / samples));
    return directions;
}

std::vector<std::pair<int, int>> visibility_runs(const std::vector<std::uint8_t>& visible, int capacity, bool* merged) {
    std::vector<std::pair<int, int>> runs;
    const int n = static_cast<int>(visible.size());
    for (int i = 0; i < n;) {
        if (!visible[static_cast<std::size_t>(i)]) {
            ++i;
            continue;
        }
        int j = i;
        while (j < n && visible[static_cast<std::size_t>(j)]) ++j;
        runs.push_back({i, j});
        i = j;
    }
    if (merged) *merged = static_cast<int>(runs.size()) > capacity;
    while (static_cast<int>(runs.size()) > capacity) {
        // The cheapest change: fill the shortest gap (adds light) or drop the shortest run (removes it).
        std::size_t gap = 0, run = 0;
        for (std::size_t k = 1; k < runs.size(); ++k)
            if (runs[k].first - runs[k - 1].second < runs[gap + 1].first - runs[gap].second) gap = k - 1;
        for (std::size_t k = 0; k < runs.size(); ++k)
            if (runs[k].second - runs[k].first < runs[run].second - runs[run].first) run = k;
        if (runs[gap + 1].first - runs[gap].second <= runs[run].second - runs[run].first) {
            runs[gap].second = runs[gap + 1].second;
            runs.erase(runs.begin() + static_cast<std::ptrdiff_t>(gap) + 1);
        } else {
            runs.erase(runs.begin() + static_cast<std::ptrdiff_t>(run));
        }
    }
    return runs;
}

OimBake bake_occlusion_intervals(const Mesh& mesh, const OimBakeSettings& settings, unsigned threads) {
    const auto start = std::chrono::steady_clock::now();
    const int R = settings.resolution, S = settings.samples, I = settings.intervals;
    OimBake bake;
    bake.resolution = R;
    bake.intervals = I;
    bake.samples = S;
    const std::size_t texel_count = static_cast<std::size_t>(R) * static_cast<std::size_t>(R);
    bake.rise.assign(texel_count * static_cast<std::size_t>(I), 0);
    bake.fall.assign(bake.rise.size(), 0);
    bake.covered.assign(texel_count, 0);

    const std::vector<TexelSample> texels = texel_samples(mesh, R);
    const std::vector<glm::vec3> all_directions = sample_directions(settings.path, S);
    // Only instants with the sun above the horizon are traced; the others stay hidden.
    std::vector<glm::vec3> directions;
    std::vector<int> instant;
    for (int i = 0; i < S; ++i)
        if (all_directions[static_cast<std::size_t>(i)].y > 0.0f) {
            directions.push_back(all_directions[static_cast<std::size_t>(i)]);
            instant.push_back(i);
        }

    const GroundTruth truth(mesh, -1.0f, threads);
    std::vector<std::size_t> chunk;
    std::vector<glm::vec3> positions, normals;
    auto flush = [&] {
        if (chunk.empty()) return;
        const std::vector<std::uint8_t> open = truth.unoccluded(positions, normals, directions);
        bake.rays += static_cast<std::uint64_t>(open.size());
        std::vector<std::uint8_t> visible(static_cast<std::size_t>(S));
        for (std::size_t c = 0; c < chunk.size(); ++c) {
            std::fill(visible.begin(), visible.end(), 0);
            for (std::size_t d = 0; d < directions.size(); ++d)
                visible[static_cast<std::size_t>(instant[d])] = open[c * directions.size() + d];
            bool merged = false;
            const std::vector<std::pair<int, int>> runs = visibility_runs(visible, I, &merged);
            bake.merged_texels += merged;
            const std::size_t base = chunk[c] * static_cast<std::size_t>(I);
            for (std::size_t k = 0; k < runs.size(); ++k) {
                bake.rise[base + k] = static_cast<std::uint16_t>(runs[k].first);
                bake.fall[base + k] = static_cast<std::uint16_t>(runs[k].second);
            }
        }
        chunk.clear();
        positions.clear();
        normals.clear();
    };
    for (std::size_t i = 0; i < texel_count; ++i) {
        if (texels[i].triangle < 0) continue;
        bake.covered[i] = 1;
        chunk.push_back(i);
        positions.push_back(texels[i].position);
        normals.push_back(texels[i].normal);
        if (chunk.size() == 4096) flush();
    }
    flush();
    bake.bake_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return bake;
}

std::vector<float> OimBake::texture(int pair, bool falls) const {
    const std::size_t texel_count = static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution);
    const std::vector<std::uint16_t>& edges = falls ? fall : rise;
    std::vector<float> rgba(4 * texel_count);
    for (std::size_t i = 0; i < texel_count; ++i)
        for (int c = 0; c < 4; ++c)
            rgba[4 * i + static_cast<std::size_t>(c)] =
                static_cast<float>(edges[i * static_cast<std::size_t>(intervals) + static_cast<std::size_t>(4 * pair + c)]) /
                static_cast<float>(samples);
    return rgba;
}

float OimBake::visibility(std::size_t texel, double start, double end) const {
    double sum = 0.0;
    for (int k = 0; k < intervals; ++k) {
        const std::size_t e = texel * static_cast<std::size_t>(intervals) + static_cast<std::size_t>(k);
        const double r = static_cast<double>(rise[e]) / samples, f = static_cast<double>(fall[e]) / samples;
        sum += std::clamp(std::min(f, end) - std::max(r, start), 0.0, 1.0);
    }
    return static_cast<float>(sum / (end - start));
}

} // namespace penumbra::playground
