// tests/runtime/ground_truth_test.cpp — the Embree reference against closed-form visibility.
//
// Setting: a square light of side L at height H facing down, one axis-aligned rectangular
// occluder parallel to it at height h, a receiver point O at height e. Seen from O, the occluder
// projects onto the light's plane as the axis-aligned rectangle x ↦ O + (x − O)·(H − e)/(h − e),
// so the unblocked fraction is 1 − area(projection ∩ light)/L², in closed form.
//
// Error bound of the estimator. In the light's unit parameter square the blocked set is an
// axis-aligned rectangle R; the N×N stratified estimate puts one sample in each stratum of area
// 1/N². A stratum entirely inside or outside R contributes exactly its area, so the error is at
// most (number of strata that straddle the boundary of R)/N² — at most 4N/N² = 4/N, typically
// far less because the straddling strata's errors have zero mean and are independent. The test
// computes that count per point and checks the deterministic bound; when the projected edges fall
// on stratum boundaries, no stratum straddles and the estimate must be exact (within 1/(2N²),
// i.e. not a single sample may be wrong).
#include <doctest/doctest.h>

#include "reference/ground_truth.hpp"
#include "scenes/mesh_builder.hpp"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace penumbra::playground;

namespace {

constexpr double light_height = 4.0;
constexpr double light_size = 2.0;
constexpr double occluder_height = 2.0;

penumbra::RectLight test_light() {
    penumbra::RectLight light;
    light.center = {0.0, light_height, 0.0};
    light.u_axis = {1.0, 0.0, 0.0};
    light.v_axis = {0.0, 0.0, 1.0};
    light.width = light_size;
    light.height = light_size;
    return light;
}

struct Interval {
    double lo, hi;
};

// The occluder's footprint on the light, in the light's parameter u ∈ [0, 1] along one axis.
Interval projected(double origin, double origin_height, Interval occluder) {
    const double k = (light_height - origin_height) / (occluder_height - origin_height);
    auto to_u = [&](double x) { return (origin + (x - origin) * k) / light_size + 0.5; };
    return {to_u(occluder.lo), to_u(occluder.hi)};
}

double overlap(Interval a) { return std::max(0.0, std::min(a.hi, 1.0) - std::max(a.lo, 0.0)); }

// Strata (of N per axis) that straddle an end of the interval a ∩ [0, 1] along one axis, and the
// ones that merely touch the interval.
int touching(Interval a, int n) {
    const double lo = std::max(a.lo, 0.0), hi = std::min(a.hi, 1.0);
    if (hi <= lo) return 0;
    return std::min(n, static_cast<int>(std::ceil(hi * n - 1e-9))) - std::max(0, static_cast<int>(std::floor(lo * n + 1e-9)));
}
int inside(Interval a, int n) {
    const double lo = std::max(a.lo, 0.0), hi = std::min(a.hi, 1.0);
    if (hi <= lo) return 0;
    return std::max(0, static_cast<int>(std::floor(hi * n + 1e-9)) - static_cast<int>(std::ceil(lo * n - 1e-9)));
}

struct Expected {
    double visible;   // closed form
    double max_error; // deterministic bound of the stratified estimate
};

Expected analytic(glm::dvec3 origin, Interval occ_x, Interval occ_z, int n) {
    const Interval px = projected(origin.x, origin.y, occ_x);
    const Interval pz = projected(origin.z, origin.y, occ_z);
    const int straddling = touching(px, n) * touching(pz, n) - inside(px, n) * inside(pz, n);
    return {1.0 - overlap(px) * overlap(pz), straddling / double(n * n) + 0.5 / double(n * n)};
}

Mesh occluder_mesh(Interval x, Interval z, bool with_ground) {
    Mesh mesh;
    if (with_ground) add_horizontal_rect(mesh, 0.0f, 0.0f, 0.0f, 20.0f, 20.0f);
    add_horizontal_rect(mesh, float(0.5 * (x.lo + x.hi)), float(occluder_height), float(0.5 * (z.lo + z.hi)),
                        float(x.hi - x.lo), float(z.hi - z.lo));
    return mesh;
}

} // namespace

TEST_CASE("ground truth: centred square occluder at half height is exact when edges align with strata") {
    // Occluder [−¼, ¼]² at h = H/2 above the point: the projection scale is H/h = 2, so its
    // footprint on the light ([−1, 1]²) is [−½, ½]², half the light's side: a quarter is blocked.
    const Interval occ{-0.25, 0.25};
    const GroundTruth gt(occluder_mesh(occ, occ, false), /*ray_offset=*/0.0f);
    const glm::vec3 p(0.0f, 0.0f, 0.0f), n(0.0f, 1.0f, 0.0f);
    for (int samples : {8, 16, 32}) {
        CAPTURE(samples);
        const Expected e = analytic(glm::dvec3(p), occ, occ, samples);
        CHECK(e.visible == doctest::Approx(0.75));
        // Footprint [0.25, 0.75] in light parameters: on stratum boundaries for N divisible by 4.
        CHECK(e.max_error == doctest::Approx(0.5 / (samples * samples)));
        // The bound says "exact"; the extra tolerance of one sample (1/N²) is for a sample that
        // grazes an edge closer than Embree's floating-point precision.
        const std::vector<float> v = gt.visibility(std::span(&p, 1), std::span(&n, 1), test_light(), samples);
        CHECK(std::abs(v[0] - e.visible) <= 1.5 / (samples * samples)); // at most one grazing sample
    }
}

TEST_CASE("ground truth: area light, off-centre points and penumbrae against the closed form") {
    // Footprint 2.4 × 2.4 from directly below: wider than the light, so there is an umbra.
    const Interval occ_x{-0.7, 0.5}, occ_z{-0.4, 0.8};
    const int samples = 32;
    for (bool with_ground : {false, true}) {
        CAPTURE(with_ground);
        // With a ground plane the points lie on it and the default ray offset lifts the origins:
        // the closed form then uses the lifted origin, so the comparison stays exact.
        const GroundTruth gt(occluder_mesh(occ_x, occ_z, with_ground), with_ground ? -1.0f : 0.0f);
        const float lift = with_ground ? gt.ray_offset() : 0.0f;
        CHECK(lift >= 0.0f);
        CHECK(lift < 0.01f);

        std::vector<glm::vec3> points, normals;
        for (float x = -2.0f; x <= 2.0f; x += 0.25f)
            for (float z = -2.0f; z <= 2.0f; z += 0.25f) {
                points.emplace_back(x, 0.0f, z);
                normals.emplace_back(0.0f, 1.0f, 0.0f);
            }
        const std::vector<float> v = gt.visibility(points, normals, test_light(), samples);
        REQUIRE(v.size() == points.size());
        double worst_slack = 1.0, sum_error = 0.0, sum_squared = 0.0;
        int penumbra_points = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
            const glm::dvec3 origin(points[i].x, lift, points[i].z);
            const Expected e = analytic(origin, occ_x, occ_z, samples);
            const double error = v[i] - e.visible;
            CAPTURE(points[i].x);
            CAPTURE(points[i].z);
            CHECK(std::abs(error) <= e.max_error);
            worst_slack = std::min(worst_slack, e.max_error - std::abs(error));
            if (e.visible > 0.0 && e.visible < 1.0) {
                ++penumbra_points;
                sum_error += error;
                sum_squared += error * error;
            }
        }
        // The set exercises umbra, penumbra and lit points; stratification keeps the errors
        // unbiased and small (RMS well below the 1/N worst case).
        CHECK(penumbra_points > 50);
        CHECK(std::abs(sum_error / penumbra_points) < 0.25 / samples);
        CHECK(std::sqrt(sum_squared / penumbra_points) < 0.5 / samples);
        CHECK(*std::min_element(v.begin(), v.end()) == 0.0f);  // some points are in the umbra
        CHECK(*std::max_element(v.begin(), v.end()) == 1.0f);  // some are fully lit
    }
}

TEST_CASE("ground truth: a point with nothing above sees the whole light; conventions") {
    Mesh ground;
    add_horizontal_rect(ground, 0.0f, 0.0f, 0.0f, 10.0f, 10.0f);
    // A box off to the side, not between the points and the light.
    add_box(ground, glm::translate(glm::mat4(1.0f), glm::vec3(4.0f, 0.5f, 4.0f)));
    const GroundTruth gt(ground);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<glm::vec3> points{{0, 0, 0}, {1, 0, -1}, {nan, nan, nan}, {0, 5, 0}, {0.5f, 0, 0.5f}};
    const std::vector<glm::vec3> normals{{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, -1, 0}};
    const std::vector<float> v = gt.visibility(points, normals, test_light(), 16);
    CHECK(v[0] == 1.0f);
    CHECK(v[1] == 1.0f);
    CHECK(v[2] == 1.0f); // background pixel
    CHECK(v[3] == 0.0f); // above the light: it emits downwards only
    CHECK(v[4] == 1.0f); // normal facing away is flipped towards the light, not self-shadowed

    // Results do not depend on the number of threads (per-point jitter is a hash of the index).
    Mesh occluder = occluder_mesh({-0.6, 0.4}, {-0.3, 0.7}, true);
    std::vector<glm::vec3> many(500), up(500, glm::vec3(0, 1, 0));
    for (std::size_t i = 0; i < many.size(); ++i) many[i] = glm::vec3(-2.0f + 0.008f * float(i), 0.0f, 0.1f);
    const auto one = GroundTruth(occluder, -1.0f, 1).visibility(many, up, test_light(), 8);
    const auto four = GroundTruth(occluder, -1.0f, 4).visibility(many, up, test_light(), 8);
    CHECK(one == four);

    CHECK_THROWS_AS(gt.visibility(points, std::span(normals).first(2), test_light()), GroundTruthError);
    Mesh broken = ground;
    broken.indices.push_back(99999);
    CHECK_THROWS_AS(GroundTruth{broken}, GroundTruthError);
}

TEST_CASE("ground truth: sun visibility across a straight shadow edge") {
    // A half-plane occluder (x > 0) at height 2; the sun straight down. The cone's footprint on
    // the occluder plane is (to O(α²)) a disk of radius r = h·tan α centred above the point.
    Mesh mesh;
    add_horizontal_rect(mesh, 5.0f, 2.0f, 0.0f, 10.0f, 20.0f);
    const GroundTruth gt(mesh, 0.0f);
    penumbra::SunLight sun;
    sun.direction = {0.0, -1.0, 0.0};
    sun.angular_diameter = 0.0093 * 5;
    const double r = 2.0 * std::tan(0.5 * sun.angular_diameter);
    // Fraction of a disk of radius r beyond a chord at signed distance d from its centre.
    auto disk_fraction_beyond = [&](double d) {
        const double c = std::clamp(d / r, -1.0, 1.0);
        return (std::acos(c) - c * std::sqrt(1.0 - c * c)) / glm::pi<double>();
    };
    const std::vector<glm::vec3> points{{-0.5f, 0, 0}, {0.5f, 0, 0}, {0.0f, 0, 0}, {float(-0.5 * r), 0, 0}, {float(0.3 * r), 0, 0}};
    const std::vector<glm::vec3> normals(points.size(), glm::vec3(0, 1, 0));
    const int samples = 64;
    const std::vector<float> v = gt.visibility(points, normals, sun, samples);
    CHECK(v[0] == 1.0f); // well outside the shadow
    CHECK(v[1] == 0.0f); // well inside
    // Exactly on the edge: half the disk by symmetry. The edge is the line φ = 0/π in the
    // (cos θ, φ) sample square, a stratum boundary for even N, so this is exact.
    // (Tolerance: one sample, for a ray grazing the edge within floating-point precision.)
    CHECK(std::abs(v[2] - 0.5) <= 1.0 / (samples * samples));
    // Part of the disk: the blocked fraction is the circular segment beyond x = 0, at signed
    // distance −x from the footprint's centre (statistical and O(α²) projection errors together
    // are far below 0.01 at N = 64).
    CHECK(std::abs(v[3] - (1.0 - disk_fraction_beyond(0.5 * r))) < 0.01);
    CHECK(std::abs(v[4] - (1.0 - disk_fraction_beyond(-0.3 * r))) < 0.01);
}

TEST_CASE("ground truth: a coarse smooth-shaded sphere has no shadow terminator") {
    // A UV sphere of 8 × 6 faces with shared corners and smooth normals: a polyhedron shaded as if
    // round. Nothing else is in the scene, so a point on it sees all of the light above its
    // (smooth) tangent plane. Rays that start on the flat face run under the face's own plane near
    // the terminator and hit the neighbouring faces; the truth lifts the origin onto the smooth
    // surface (GroundTruth's origin_for), which must leave every point fully lit.
    constexpr int segments = 8, rings = 6;
    constexpr float radius = 0.5f;
    const glm::vec3 centre(0.0f, 1.0f, 0.0f);
    Mesh sphere;
    sphere.positions.push_back(centre + glm::vec3(0.0f, radius, 0.0f)); // north pole: 0
    for (int r = 1; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const float theta = glm::pi<float>() * float(r) / rings, phi = 2.0f * glm::pi<float>() * float(s) / segments;
            sphere.positions.push_back(
                centre + radius * glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
        }
    sphere.positions.push_back(centre - glm::vec3(0.0f, radius, 0.0f)); // south pole: last
    const auto south = static_cast<std::uint32_t>(sphere.positions.size() - 1);
    auto corner = [](int r, int s) { return static_cast<std::uint32_t>(1 + (r - 1) * segments + s % segments); };
    // counter-clockwise seen from outside, so that the normals point out
    for (int s = 0; s < segments; ++s) {
        sphere.indices.insert(sphere.indices.end(), {0, corner(1, s + 1), corner(1, s)});
        for (int r = 1; r + 1 < rings; ++r)
            sphere.indices.insert(sphere.indices.end(), {corner(r, s), corner(r, s + 1), corner(r + 1, s + 1),
                                                         corner(r, s), corner(r + 1, s + 1), corner(r + 1, s)});
        sphere.indices.insert(sphere.indices.end(), {south, corner(rings - 1, s), corner(rings - 1, s + 1)});
    }
    compute_vertex_normals(sphere);
    for (std::size_t i = 0; i < sphere.positions.size(); ++i)
        REQUIRE(glm::dot(sphere.normals[i], sphere.positions[i] - centre) > 0.0f);

    // Points inside every face below the equator's row and above the bottom (where some of the
    // light is above the tangent plane), with the interpolated normal a G-buffer would hold.
    std::vector<glm::vec3> points, normals;
    for (std::size_t t = 0; t < sphere.indices.size(); t += 3)
        for (const glm::vec3 b : {glm::vec3(0.6f, 0.2f, 0.2f), glm::vec3(0.2f, 0.6f, 0.2f), glm::vec3(0.2f, 0.2f, 0.6f),
                                  glm::vec3(1.0f / 3.0f)}) {
            glm::vec3 p(0.0f), n(0.0f);
            for (int k = 0; k < 3; ++k) {
                p += b[k] * sphere.positions[sphere.indices[t + k]];
                n += b[k] * sphere.normals[sphere.indices[t + k]];
            }
            points.push_back(p);
            normals.push_back(glm::normalize(n));
        }
    const GroundTruth gt(sphere);
    const GroundTruth::Oriented fair = gt.oriented(points, normals, test_light(), 16);
    int lit_points = 0, terminator_points = 0;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (std::isnan(fair.oriented[i])) continue; // none of the light above the tangent plane
        ++lit_points;
        if (normals[i].y < 0.2f) ++terminator_points;
        CAPTURE(i);
        CAPTURE(normals[i].y);
        CHECK(fair.oriented[i] == doctest::Approx(1.0f));
    }
    CHECK(lit_points > 100);
    CHECK(terminator_points > 20); // points near the terminator, where the faces shadow each other
}
