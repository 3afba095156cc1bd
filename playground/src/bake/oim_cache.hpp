// playground/src/bake/oim_cache.hpp — occlusion interval maps cached on disk, keyed by the scene
// (a content hash of the mesh: positions, normals, texture coordinates, triangles), the sun's path,
// the resolution, interval count and sample count.
//
// Folder: the one given (penumbra-playground --bake-cache DIR), else $PENUMBRA_CACHE_DIR/oim, else
// $XDG_CACHE_HOME/penumbra/oim, else ~/.cache/penumbra/oim. Files are <key>.bin, written to a
// temporary name in the same folder and renamed, so a reader never sees half a file; a file that
// does not match its key's settings or is truncated is ignored and baked again.
#pragma once

#include "bake/oim_bake.hpp"

#include <filesystem>
#include <optional>
#include <string>

namespace penumbra::playground {

// 32 hex digits (two independent 64-bit FNV-1a hashes of the key's bytes).
std::string oim_cache_key(const Mesh& mesh, const OimBakeSettings& settings);

std::filesystem::path default_oim_cache_dir();

// The cached bake for `key`, or nothing (missing, unreadable, or not these settings).
std::optional<OimBake> read_cached_bake(const std::filesystem::path& dir, const std::string& key,
                                        const OimBakeSettings& settings);

// Writes atomically (temporary file + rename); false with *error on failure.
bool write_cached_bake(const std::filesystem::path& dir, const std::string& key, const OimBake& bake,
                       std::string* error);

struct CachedBake {
    OimBake bake;
    bool from_cache = false;
    std::filesystem::path file;   // where it was read or written
    std::uintmax_t file_bytes = 0;
    std::string warning;          // the cache could not be written (the bake is still usable)
};

// Reads the cache or bakes and writes it.
CachedBake bake_with_cache(const Mesh& mesh, const OimBakeSettings& settings, const std::filesystem::path& dir);

} // namespace penumbra::playground
