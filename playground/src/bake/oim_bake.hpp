// playground/src/bake/oim_bake.hpp — the offline bake of occlusion interval maps (Donnelly &
// Demers, GPU Gems ch. 13) with Embree.
//
// Per texel of the mesh's unique parameterization (scenes/uv_coverage.hpp gives the surface point
// and normal), rays towards the sun at `samples` evenly spaced instants t_i = (i + 1/2) / samples
// of its path; each run of visible instants i..j-1 becomes the interval [i/samples, j/samples]
// ("rise" and "fall" times). The sun below the horizon (direction.y ≤ 0) counts as hidden.
// Up to `intervals` intervals per texel, four per RGBA pair of textures; a texel with more has its
// shortest gaps filled or shortest intervals dropped, whichever changes less light, and is counted.
#pragma once

#include "scenes/scene.hpp"

#include <penumbra/sun_path.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace penumbra::playground {

struct OimBakeSettings {
    int resolution = 256;  // texels per side of the maps
    int intervals = 8;     // visibility intervals per texel, a multiple of 4 (one RGBA rise/fall pair per 4)
    int samples = 256;     // instants along the path (the chapter: 256, enough for 8-bit edges)
    penumbra::SunPath path;
};

struct OimBake {
    int resolution = 0, intervals = 0, samples = 0;
    // Per texel (y·R + x), `intervals` edge indices k in 0..samples (time k / samples), ascending;
    // unused intervals are [0, 0].
    std::vector<std::uint16_t> rise, fall;
    std::vector<std::uint8_t> covered; // per texel: 1 where the texel stands for a surface point
    std::size_t merged_texels = 0;     // texels whose visibility had more intervals than stored
    double bake_ms = 0.0;              // wall time of the ray casting
    std::uint64_t rays = 0;

    // Texture `pair` (0-based) as R·R RGBA floats, rises (fall = false) or falls, in times t.
    std::vector<float> texture(int pair, bool fall) const;

    // The chapter's evaluation at one texel for the window [start, end] (Listing 13-1): the sum
    // over intervals of saturate(min(fall, end) − max(rise, start)) / (end − start).
    float visibility(std::size_t texel, double start, double end) const;
};

// Bakes `mesh` (which needs unique texture coordinates, see check_unique_uvs). Throws
// GroundTruthError for Embree failures. `settings.path` must be valid.
OimBake bake_occlusion_intervals(const Mesh& mesh, const OimBakeSettings& settings, unsigned threads = 0);

// Intervals of one texel's visibility along the path (1 = visible) as [rise, fall) sample-index
// pairs, at most `capacity` of them (merged as described above). Exposed for tests.
std::vector<std::pair<int, int>> visibility_runs(const std::vector<std::uint8_t>& visible, int capacity, bool* merged);

// The directions towards the sun at the bake's instants.
std::vector<glm::vec3> sample_directions(const penumbra::SunPath& path, int samples);

} // namespace penumbra::playground
