// playground/src/reference/ground_truth.hpp — reference visibility by ray casting (Embree 3).
//
// This answers docs/model.md §4 question 2 ("how good is the model?"): the fraction of an area light
// (or of the sun's disk) that a surface point actually sees, estimated with N×N stratified,
// deterministically jittered samples against the scene's exact triangles.
#pragma once

#include "scenes/scene.hpp"

#include <penumbra/light.hpp>

#include <glm/glm.hpp>

#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

namespace penumbra::playground {

// Thrown for any Embree failure (device creation, scene build, ...) and for malformed meshes.
class GroundTruthError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class GroundTruth {
public:
    // Builds the acceleration structure over `mesh` (copied into Embree's buffers). Its cut materials
    // cut (an occlusion filter): a ray passes where the texture's alpha at the hit's texture
    // coordinate is below the cutoff (the truth of cut-out casters; without_cuts() for solid ones).
    // `ray_offset`: distance by which ray origins are pushed off the surface along the normal to
    // avoid self-intersection; a negative value selects 1e-4 × the mesh's bounding-box diagonal.
    // `thread_count` 0 uses std::thread::hardware_concurrency().
    explicit GroundTruth(const Mesh& mesh, float ray_offset = -1.0f, unsigned thread_count = 0);
    ~GroundTruth();
    GroundTruth(GroundTruth&&) noexcept;
    GroundTruth& operator=(GroundTruth&&) noexcept;
    GroundTruth(const GroundTruth&) = delete;
    GroundTruth& operator=(const GroundTruth&) = delete;

    float ray_offset() const;

    // Per point: the unblocked fraction of samples_per_axis² stratified rays from the point to
    // the light rectangle. The origin is position + ray_offset·n, where n is the normal flipped,
    // if needed, to face the light's centre (so both sides of a thin sheet are handled). The
    // light rectangle itself is not an occluder. A point not strictly in front of the light
    // (depth along the light's normal ≤ 0) receives nothing: 0. A point whose position has a NaN
    // component (a background pixel of a G-buffer) gets 1. `normals` must be as long as
    // `positions`; a zero or non-finite normal means "no offset".
    std::vector<float> visibility(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                  const penumbra::RectLight& light, int samples_per_axis = 32) const;

    // Same for the sun: samples_per_axis² directions stratified over the cone of half-angle
    // angular_diameter/2 around −direction (uniform in solid angle), rays to infinity.
    std::vector<float> visibility(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                  const penumbra::SunLight& sun, int samples_per_axis = 32) const;

    // The fair references (what a viewer sees), per point, for the side of the surface that
    // `normals` points to (the caller orients them, e.g. towards the camera):
    //   oriented:   of the light's samples above the point's tangent plane, the fraction that is
    //               unoccluded — the visibility of the part of the light the surface can receive;
    //   irradiance: the ray-traced irradiance over the unoccluded irradiance from that (clipped)
    //               light, both cosine-weighted at the receiver and, for the rectangle, at the
    //               light (cos θ_P · cos θ_L / r²); an estimated visibility V times the unoccluded
    //               irradiance is then off by |V − irradiance| relative to the unoccluded value.
    //   unoccluded: the irradiance that clipped light sends the point with nothing in between, for a
    //               light of radiance 1 (the rectangle: ∫ cos θ_P · cos θ_L / r² dA / π; the sun:
    //               ∫ cos θ_P dω / π over its disk): how bright the shaded image is there, so how
    //               much a visibility error there shows (metrics.hpp's shaded reference).
    // oriented and irradiance are NaN where the point sees none of the light (every sample below its
    // tangent plane, behind the light's plane, or a zero normal), unoccluded 0 there; all three are 1
    // on background points (NaN position).
    struct Oriented {
        std::vector<float> oriented;
        std::vector<float> irradiance;
        std::vector<float> unoccluded;
    };
    Oriented oriented(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                      const penumbra::RectLight& light, int samples_per_axis = 32) const;
    Oriented oriented(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                      const penumbra::SunLight& sun, int samples_per_axis = 32) const;

    // A light made of directions (unit vectors towards it, at infinity), e.g. the sun's path over
    // a window of time sampled at several instants: per point and direction, 1 where the ray is
    // unblocked. Row-major: element p·directions.size() + d. The origin is offset along the normal
    // turned towards that direction. A point with a NaN component sees everything (1).
    std::vector<std::uint8_t> unoccluded(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                         std::span<const glm::vec3> directions) const;

    // Per point: the unblocked fraction of `directions` (same rules as unoccluded()).
    std::vector<float> visibility(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                  std::span<const glm::vec3> directions) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// The stratified sample position in [0,1)² for sample `sample` (row-major in an n×n grid) of
// point `point`: the stratum's corner plus a jitter from a fixed integer hash, strictly inside
// the stratum. Exposed so tests can reason about the estimator.
glm::vec2 stratified_sample(std::uint32_t point, std::uint32_t sample, int samples_per_axis);

} // namespace penumbra::playground
