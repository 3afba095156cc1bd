// bench/compare/truth_cache.hpp — Embree ground truth cached on disk. The truth depends on the
// pixels (world positions and normals of the G-buffer), the light and the ray count, never on the
// technique, so it is computed once per scene, light and image and read back on later runs.
// The file name is a hash of exactly those inputs (pixels, light, camera position, rays, and the
// cut materials of cut-out casters): a changed scene, camera or light misses the cache.
#pragma once

#include "app/image_io.hpp"
#include "rendering/headless_render.hpp"

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
    // visibility, oriented, irradiance, unoccluded; one per pixel, top row first
    playground::References references;
    std::string file; // the cache file it was read from or written to (and unoccluded_file(file))
    bool from_cache = false;
    double milliseconds = 0;           // time to compute (0 when read from the cache)
};

// Where the unoccluded irradiance of the cache file `file` lies: a 1-channel float map beside it.
inline std::string unoccluded_file(const std::string& file) {
    return file.substr(0, file.size() - 4) + ".unoccluded.pfm";
}

// The references (playground::reference_all) for `scene` with its light as it is (the
// rectangle scene.light, or with Light::sun scene.sun), at the pixels of `frame`: from `directory`
// when files with the inputs' hash are there, else ray-traced and written there (a 3-channel float
// map of the three truths, and a 1-channel one of the unoccluded irradiance). nullopt and *error
// when a file cannot be written.
inline std::optional<CachedTruth> cached_truth(const std::string& directory, const playground::Scene& scene,
                                               const playground::HeadlessResult& frame, int samples_per_axis,
                                               std::string* error, Light light_kind = Light::rect) {
    Hash hash;
    // the versions change with what GroundTruth computes (rect v3, sun v2: ray origins lifted onto
    // the smooth surface of the vertex normals), so a cache from before is not read back
    const char rect_version[] = "rect-references-v3", sun_version[] = "sun-references-v2";
    if (light_kind == Light::sun) hash.add(sun_version, sizeof sun_version);
    else hash.add(rect_version, sizeof rect_version);
    hash.add_values(std::span<const glm::vec3>(frame.positions));
    hash.add_values(std::span<const glm::vec3>(frame.normals));
    if (light_kind == Light::sun) {
        const SunLight& sun = scene.sun;
        const double sun_values[] = {sun.direction.x, sun.direction.y, sun.direction.z, sun.angular_diameter};
        hash.add(sun_values, sizeof sun_values);
    } else {
        const RectLight& light = scene.light;
        const double light_values[] = {light.center.x, light.center.y, light.center.z, light.u_axis.x, light.u_axis.y,
                                       light.u_axis.z, light.v_axis.x, light.v_axis.y, light.v_axis.z, light.width,
                                       light.height};
        hash.add(light_values, sizeof light_values);
    }
    const glm::vec3 eye = scene.camera.eye_position(); // the fair references face the camera
    hash.add(&eye, sizeof eye);
    const int sizes[] = {frame.width, frame.height, samples_per_axis};
    hash.add(sizes, sizeof sizes);
    // the truth's rays pass where cut materials are cut (alpha test): those decide it too
    for (const playground::CutMaterial& m : scene.mesh.cut_materials) {
        hash.add(&m.cutoff, sizeof m.cutoff);
        hash.add_values(std::span<const std::uint8_t>(m.texture.alpha));
    }
    hash.add_values(std::span<const glm::vec2>(scene.mesh.material_uvs));
    hash.add_values(std::span<const std::int32_t>(scene.mesh.triangle_materials));

    CachedTruth out;
    out.file = (std::filesystem::path(directory) / (scene.name + (light_kind == Light::sun ? "-sun-" : "-") + hash.hex() + ".pfm")).string();
    const std::size_t n = frame.positions.size();
    std::string read_error;
    std::optional<playground::FloatImage> cached = playground::read_pfm(out.file, &read_error);
    std::optional<playground::FloatImage> unoccluded =
        playground::read_pfm(unoccluded_file(out.file), &read_error);
    if (cached && cached->width == frame.width && cached->height == frame.height && cached->channels == 3 &&
        unoccluded && unoccluded->width == frame.width && unoccluded->height == frame.height &&
        unoccluded->channels == 1) {
        for (std::vector<float>* channel : {&out.references.visibility, &out.references.oriented, &out.references.irradiance})
            channel->resize(n);
        for (std::size_t i = 0; i < n; ++i) {
            out.references.visibility[i] = cached->pixels[3 * i];
            out.references.oriented[i] = cached->pixels[3 * i + 1];
            out.references.irradiance[i] = cached->pixels[3 * i + 2];
        }
        out.references.unoccluded = std::move(unoccluded->pixels);
        out.from_cache = true;
        return out;
    }
    const auto start = std::chrono::steady_clock::now();
    out.references = playground::reference_all(scene, frame, samples_per_axis, light_kind);
    out.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    playground::FloatImage image{frame.width, frame.height, 3, std::vector<float>(3 * n)};
    for (std::size_t i = 0; i < n; ++i) {
        image.pixels[3 * i] = out.references.visibility[i];
        image.pixels[3 * i + 1] = out.references.oriented[i];
        image.pixels[3 * i + 2] = out.references.irradiance[i];
    }
    std::error_code ec;
    std::filesystem::create_directories(directory, ec);
    if (!playground::write_pfm(out.file, image, error) ||
        !playground::write_pfm(unoccluded_file(out.file),
                               {frame.width, frame.height, 1, out.references.unoccluded}, error))
        return std::nullopt;
    return out;
}

} // namespace penumbra::bench
