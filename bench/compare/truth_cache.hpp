// bench/compare/truth_cache.hpp — Embree ground truth cached on disk. The truth depends on the
// pixels (world positions and normals of the G-buffer), the light and the ray count, never on the
// technique, so it is computed once per scene, light and image and read back on later runs.
// The file name is a hash of exactly those inputs: a changed scene, camera or light misses.
#pragma once

#include "app/image_io.hpp"
#include "reference/ground_truth.hpp"

#include <penumbra/light.hpp>

#include <glm/glm.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace penumbra::bench {

// FNV-1a, 64 bits, over raw bytes.
class Hash {
public:
    void add(const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) value_ = (value_ ^ bytes[i]) * 1099511628211ull;
    }
    template <class T> void add_values(std::span<const T> values) { add(values.data(), values.size_bytes()); }
    std::string hex() const {
        char text[17];
        std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value_));
        return text;
    }

private:
    std::uint64_t value_ = 1469598103934665603ull;
};

struct CachedTruth {
    std::vector<float> visibility; // one per pixel, top row first; 1 on background
    std::string file;              // the cache file it was read from or written to
    bool from_cache = false;
    double milliseconds = 0;       // time to compute (0 when read from the cache)
};

// The truth for `light` at the given pixels, from `directory` when a file with the inputs' hash is
// there, else ray-traced with `truth` and written there. nullopt and *error when the file cannot be written.
inline std::optional<CachedTruth> cached_truth(const std::string& directory, const std::string& scene_name,
                                               const playground::GroundTruth& truth, int width, int height,
                                               std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                               const RectLight& light, int samples_per_axis, std::string* error) {
    Hash hash;
    const char version[] = "rect-truth-v1";
    hash.add(version, sizeof version);
    hash.add_values(positions);
    hash.add_values(normals);
    const double light_values[] = {light.center.x, light.center.y, light.center.z, light.u_axis.x, light.u_axis.y,
                                   light.u_axis.z, light.v_axis.x, light.v_axis.y, light.v_axis.z, light.width,
                                   light.height};
    hash.add(light_values, sizeof light_values);
    const int sizes[] = {width, height, samples_per_axis};
    hash.add(sizes, sizeof sizes);

    CachedTruth out;
    out.file = (std::filesystem::path(directory) / (scene_name + "-" + hash.hex() + ".pfm")).string();
    std::string read_error;
    if (std::optional<playground::FloatImage> image = playground::read_pfm(out.file, &read_error);
        image && image->width == width && image->height == height && image->channels == 1) {
        out.visibility = std::move(image->pixels);
        out.from_cache = true;
        return out;
    }
    const auto start = std::chrono::steady_clock::now();
    out.visibility = truth.visibility(positions, normals, light, samples_per_axis);
    out.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    if (!playground::write_pfm(out.file, {width, height, 1, out.visibility}, error)) return std::nullopt;
    return out;
}

} // namespace penumbra::bench
