// playground/src/bake/oim_cache.cpp
#include "bake/oim_cache.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <unistd.h>

namespace penumbra::playground {

namespace {

constexpr char magic[8] = {'P', 'N', 'B', 'R', 'O', 'I', 'M', '1'};

struct Fnv {
    std::uint64_t a = 0xcbf29ce484222325ull, b = 0x84222325cbf29ce4ull;
    void bytes(const void* data, std::size_t size) {
        const auto* p = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) {
            a = (a ^ p[i]) * 0x100000001b3ull;
            b = (b ^ p[i]) * 0x100000001b3ull;
            b ^= b >> 29;
        }
    }
    template <class T> void value(const T& v) { bytes(&v, sizeof v); }
    template <class T> void array(const std::vector<T>& v) {
        value(v.size());
        if (!v.empty()) bytes(v.data(), v.size() * sizeof(T));
    }
};

struct Header {
    char magic[8];
    std::int32_t resolution, intervals, samples, reserved;
    double bake_ms;
    std::uint64_t merged_texels, rays;
};

std::string hex(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

} // namespace

std::string oim_cache_key(const Mesh& mesh, const OimBakeSettings& settings) {
    Fnv h;
    h.bytes(magic, sizeof magic);
    h.array(mesh.positions);
    h.array(mesh.normals);
    h.array(mesh.uvs);
    h.array(mesh.indices);
    if (mesh.cuts()) { // the bake's rays pass where the cut materials are cut
        h.array(mesh.material_uvs);
        h.array(mesh.triangle_materials);
        for (const CutMaterial& m : mesh.cut_materials) {
            h.value(m.cutoff);
            h.value(m.texture.width);
            h.value(m.texture.height);
            h.array(m.texture.alpha);
        }
    }
    h.value(settings.resolution);
    h.value(settings.intervals);
    h.value(settings.samples);
    h.value(settings.path.points.size());
    for (const penumbra::SunPathPoint& p : settings.path.points) {
        h.value(p.azimuth_degrees);
        h.value(p.elevation_degrees);
    }
    return hex(h.a) + hex(h.b);
}

std::filesystem::path default_oim_cache_dir() {
    if (const char* dir = std::getenv("PENUMBRA_CACHE_DIR"); dir && *dir) return std::filesystem::path(dir) / "oim";
    if (const char* dir = std::getenv("XDG_CACHE_HOME"); dir && *dir) return std::filesystem::path(dir) / "penumbra" / "oim";
    if (const char* home = std::getenv("HOME"); home && *home)
        return std::filesystem::path(home) / ".cache" / "penumbra" / "oim";
    return std::filesystem::temp_directory_path() / "penumbra-cache" / "oim";
}

std::optional<OimBake> read_cached_bake(const std::filesystem::path& dir, const std::string& key,
                                        const OimBakeSettings& settings) {
    std::ifstream file(dir / (key + ".bin"), std::ios::binary);
    if (!file) return std::nullopt;
    Header header{};
    if (!file.read(reinterpret_cast<char*>(&header), sizeof header)) return std::nullopt;
    if (std::memcmp(header.magic, magic, sizeof magic) != 0 || header.resolution != settings.resolution ||
        header.intervals != settings.intervals || header.samples != settings.samples)
        return std::nullopt;
    OimBake bake;
    bake.resolution = header.resolution;
    bake.intervals = header.intervals;
    bake.samples = header.samples;
    bake.bake_ms = header.bake_ms;
    bake.merged_texels = header.merged_texels;
    bake.rays = header.rays;
    const std::size_t texels = static_cast<std::size_t>(bake.resolution) * static_cast<std::size_t>(bake.resolution);
    bake.covered.resize(texels);
    bake.rise.resize(texels * static_cast<std::size_t>(bake.intervals));
    bake.fall.resize(bake.rise.size());
    file.read(reinterpret_cast<char*>(bake.covered.data()), static_cast<std::streamsize>(texels));
    file.read(reinterpret_cast<char*>(bake.rise.data()), static_cast<std::streamsize>(bake.rise.size() * 2));
    file.read(reinterpret_cast<char*>(bake.fall.data()), static_cast<std::streamsize>(bake.fall.size() * 2));
    if (!file || file.peek() != std::char_traits<char>::eof()) return std::nullopt;
    return bake;
}

bool write_cached_bake(const std::filesystem::path& dir, const std::string& key, const OimBake& bake,
                       std::string* error) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    const std::filesystem::path final_path = dir / (key + ".bin");
    const std::filesystem::path temp_path = dir / (key + ".bin.tmp" + std::to_string(::getpid()));
    {
        std::ofstream file(temp_path, std::ios::binary | std::ios::trunc);
        Header header{};
        std::memcpy(header.magic, magic, sizeof magic);
        header.resolution = bake.resolution;
        header.intervals = bake.intervals;
        header.samples = bake.samples;
        header.bake_ms = bake.bake_ms;
        header.merged_texels = bake.merged_texels;
        header.rays = bake.rays;
        file.write(reinterpret_cast<const char*>(&header), sizeof header);
        file.write(reinterpret_cast<const char*>(bake.covered.data()), static_cast<std::streamsize>(bake.covered.size()));
        file.write(reinterpret_cast<const char*>(bake.rise.data()), static_cast<std::streamsize>(bake.rise.size() * 2));
        file.write(reinterpret_cast<const char*>(bake.fall.data()), static_cast<std::streamsize>(bake.fall.size() * 2));
        file.close();
        if (!file) {
            std::filesystem::remove(temp_path, ec);
            if (error) *error = "cannot write the bake cache file " + temp_path.string();
            return false;
        }
    }
    std::filesystem::rename(temp_path, final_path, ec);
    if (ec) {
        std::filesystem::remove(temp_path, ec);
        if (error) *error = "cannot rename " + temp_path.string() + " to " + final_path.string();
        return false;
    }
    return true;
}

CachedBake bake_with_cache(const Mesh& mesh, const OimBakeSettings& settings, const std::filesystem::path& dir) {
    CachedBake out;
    const std::string key = oim_cache_key(mesh, settings);
    out.file = dir / (key + ".bin");
    std::error_code ec;
    if (std::optional<OimBake> cached = read_cached_bake(dir, key, settings)) {
        out.bake = std::move(*cached);
        out.from_cache = true;
        out.file_bytes = std::filesystem::file_size(out.file, ec);
        return out;
    }
    out.bake = bake_occlusion_intervals(mesh, settings);
    std::string error;
    if (!write_cached_bake(dir, key, out.bake, &error)) out.warning = error;
    else out.file_bytes = std::filesystem::file_size(out.file, ec);
    return out;
}

} // namespace penumbra::playground
