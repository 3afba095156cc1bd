// tests/runtime/fair_reference_test.cpp — the fair references (GroundTruth::oriented) against
// geometry whose answer is known: where today's visibility and the oriented one must differ, and
// where they must agree. Label "runtime".
//
// Light: 2×2 at height 4 facing down, centred over the origin. With N (even) samples per axis
// the strata boundaries include the light's centre lines, so "the half of the light with x > 0"
// holds exactly N²/2 samples.
#include <doctest/doctest.h>

#include "reference/ground_truth.hpp"
#include "reference/metrics.hpp"
#include "scenes/mesh_builder.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>

using namespace penumbra::playground;

namespace {

penumbra::RectLight test_light() {
    penumbra::RectLight light;
    light.center = {0.0, 4.0, 0.0};
    light.u_axis = {1.0, 0.0, 0.0};
    light.v_axis = {0.0, 0.0, 1.0};
    light.width = 2.0;
    light.height = 2.0;
    return light;
}

// A solid box spanning [lo, hi].
Mesh solid(glm::vec3 lo, glm::vec3 hi) {
    Mesh mesh;
    add_box(mesh, glm::scale(glm::translate(glm::mat4(1.0f), 0.5f * (lo + hi)), hi - lo));
    return mesh;
}

// Irradiance at ground point (px, 0, 0) from the part of the light with x in [x0, x1]
// (cos at the receiver × cos at the light / r², midpoint rule on a fine grid).
double irradiance(double px, double x0, double x1) {
    const int n = 400;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const double x = x0 + (i + 0.5) * (x1 - x0) / n - px, z = -1.0 + (j + 0.5) * 2.0 / n;
            const double r2 = 16.0 + x * x + z * z;
            sum += 16.0 / (r2 * r2); // (4/r)·(4/r)/r²
        }
    return sum * (x1 - x0) / n * 2.0 / n;
}

} // namespace

TEST_CASE("fair reference: a vertical face lit from a light partly behind its plane") {
    // The box fills x in [-2, 0]; its +x face (normal +x) at x = 0 is under the light's centre
    // line: the half of the light with x < 0 is behind the face's tangent plane.
    const GroundTruth gt(solid({-2.0f, 0.0f, -1.0f}, {0.0f, 1.0f, 1.0f}));
    const std::vector<glm::vec3> points{{0.0f, 0.5f, 0.0f}, {-2.0f, 0.5f, 0.0f}};
    const std::vector<glm::vec3> normals{{1, 0, 0}, {-1, 0, 0}};
    const int n = 16;
    const std::vector<float> old = gt.visibility(points, normals, test_light(), n);
    const GroundTruth::Oriented fair = gt.oriented(points, normals, test_light(), n);
    // Today's truth: the rays towards the half behind the plane enter the box, so they count as
    // blocked although no renderer would light the face from there (its cosine is negative).
    CHECK(old[0] == doctest::Approx(0.5).epsilon(1e-6));
    // The fair truth: everything the face can receive reaches it.
    CHECK(fair.oriented[0] == 1.0f);
    CHECK(fair.irradiance[0] == 1.0f);
    // The -x face sees none of the light: left out (NaN), where today's truth says 0.
    CHECK(old[1] == 0.0f);
    CHECK(std::isnan(fair.oriented[1]));
    CHECK(std::isnan(fair.irradiance[1]));
}

TEST_CASE("fair reference: agrees with today's on a receiver facing the whole light") {
    // A ground point at x = 1 and an occluder at height 2 whose edge at x = 0.5 projects onto
    // the light's centre line: the half of the light with x < 0 is blocked.
    Mesh occluder;
    add_horizontal_rect(occluder, -2.25f, 2.0f, 0.0f, 5.5f, 6.0f); // x in [-5, 0.5]
    const GroundTruth gt(occluder);
    const std::vector<glm::vec3> points{{1.0f, 0.0f, 0.0f}, {3.0f, 0.0f, 0.0f}};
    const std::vector<glm::vec3> normals{{0, 1, 0}, {0, 1, 0}};
    const int n = 16;
    const std::vector<float> old = gt.visibility(points, normals, test_light(), n);
    const GroundTruth::Oriented fair = gt.oriented(points, normals, test_light(), n);
    // The whole light is above the tangent plane: the same rays, the same answer.
    CHECK(old[0] == fair.oriented[0]);
    CHECK(old[1] == fair.oriented[1]);
    CHECK(fair.oriented[0] == doctest::Approx(0.5).epsilon(1e-6));
    // Cosine weighting: the blocked half is the farther one, so it carries less irradiance.
    const double expected = irradiance(1.0, 0.0, 1.0) / irradiance(1.0, -1.0, 1.0);
    CHECK(expected > 0.55);
    CHECK(fair.irradiance[0] == doctest::Approx(expected).epsilon(0.02));
    CHECK(fair.irradiance[1] == 1.0f);
}

TEST_CASE("fair reference: metrics leave out pixels that see none of the light") {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<float> estimate{0.5f, 0.2f, 1.0f, 0.0f};
    const std::vector<unsigned char> geometry{1, 1, 1, 0};
    const std::vector<float> truth{0.5f, nan, 0.9f, 1.0f};
    const Metrics m = compare(estimate, geometry, truth);
    CHECK(m.all.count == 2);
    CHECK(m.all.mae == doctest::Approx(0.05));
    CHECK(m.penumbra.count == 2);
    CHECK(m.all.bias == doctest::Approx(0.05)); // signed: estimate − truth, 0 and +0.1
    CHECK(compare(std::vector<float>{0.2f, 1.0f}, std::vector<unsigned char>{1, 1}, std::vector<float>{0.6f, 1.0f})
              .penumbra.bias == doctest::Approx(-0.4)); // too dark; the lit pixel is no penumbra pixel
    const std::vector<float> unoccluded{1.0f, 0.0f, 1.0f, 1.0f};
    const QualityMetrics q = compare_quality(estimate, geometry, estimate, truth, truth, unoccluded);
    CHECK(q.visibility.all.mae == 0.0);
    CHECK(q.visibility.all.count == 3);
    CHECK(q.oriented.all.count == 2);
    CHECK(q.shaded.all.count == 2);
    CHECK(q.shaded.all.mae == doctest::Approx(0.05)); // equal weights: the irradiance reference's error
}

TEST_CASE("fair reference: the shaded reference weighs each pixel by the light it receives") {
    // Two penumbra pixels equally wrong in visibility (0.2), one receiving nine times the light of the
    // other, and one pixel that is right: the shaded image's error is where the light is.
    const std::vector<float> estimate{0.6f, 0.3f, 0.5f};
    const std::vector<unsigned char> geometry{1, 1, 1};
    const std::vector<float> truth{0.4f, 0.5f, 0.5f};
    const std::vector<float> unoccluded{0.9f, 0.1f, 1.0f};
    const QualityMetrics q = compare_quality(estimate, geometry, truth, truth, truth, unoccluded);
    CHECK(q.irradiance.penumbra.mae == doctest::Approx(0.4 / 3));
    CHECK(q.irradiance.penumbra.bias == doctest::Approx(0.0).epsilon(1e-6));
    CHECK(q.shaded.penumbra.mae == doctest::Approx((0.9 * 0.2 + 0.1 * 0.2) / 2.0));
    CHECK(q.shaded.penumbra.bias ==
          doctest::Approx((0.9 * 0.2 - 0.1 * 0.2) / 2.0)); // the bright pixel too bright
    CHECK(q.shaded.penumbra.p95 == doctest::Approx(0.2));
}

TEST_CASE("fair reference: the unoccluded irradiance of a small rectangle is its form factor") {
    // A 0.2 × 0.2 light (test_light() scaled down) 2 above a point facing it: E ≈ A cos θ cos θ' / (π r²).
    Mesh nothing;
    add_horizontal_rect(nothing, 50.0f, -5.0f, 50.0f, 1.0f, 1.0f); // far away, below: blocks no ray
    const GroundTruth gt(nothing);
    penumbra::RectLight light = test_light();
    light.width = light.height = 0.2;
    const glm::vec3 below(light.center + 2.0 * light.normal()); // the light faces its normal: down
    const glm::vec3 up(-light.normal());
    const std::vector<glm::vec3> points{below, below + glm::vec3(2.0f, 0.0f, 0.0f)};
    const std::vector<glm::vec3> normals{up, up};
    const GroundTruth::Oriented fair = gt.oriented(points, normals, light, 8);
    CHECK(fair.unoccluded[0] == doctest::Approx(0.04 / (glm::pi<double>() * 4.0)).epsilon(0.01));
    // 45° off the axis: both cosines 1/√2, the distance √8
    CHECK(fair.unoccluded[1] == doctest::Approx(0.04 * 0.5 / (glm::pi<double>() * 8.0)).epsilon(0.02));
}
