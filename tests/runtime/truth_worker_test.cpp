// tests/runtime/truth_worker_test.cpp — the background ground truth: progress, exactness against
// one GroundTruth::visibility call, cancellation latency, restart, bad input.
//
// Inputs are CPU-only: receiver points on a grid over the ground of the "planes" scene (y = 0,
// normal +y), with a border of background (NaN) pixels, so no GL context is needed.
#include <doctest/doctest.h>

#include "reference/ground_truth.hpp"
#include "scenes/scenes.hpp"
#include "reference/truth_worker.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <thread>

using namespace penumbra::playground;
using namespace std::chrono_literals;

namespace {

struct Pixels {
    std::vector<glm::vec3> positions, normals;
};

// side × side points over [-4, 4]² on the ground; the outermost ring is background.
Pixels ground_grid(int side) {
    Pixels p;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const bool border = x == 0 || y == 0 || x == side - 1 || y == side - 1;
            const float fx = -4.0f + 8.0f * (x + 0.5f) / side, fz = -4.0f + 8.0f * (y + 0.5f) / side;
            p.positions.push_back(border ? glm::vec3(nan) : glm::vec3(fx, 0.0f, fz));
            p.normals.push_back(border ? glm::vec3(0.0f) : glm::vec3(0.0f, 1.0f, 0.0f));
        }
    return p;
}

struct Fixture {
    Scene scene = *make_scene("planes");
    std::shared_ptr<const Mesh> mesh = std::make_shared<const Mesh>(scene.mesh);
};

TruthJob job_for(const Fixture& f, const Pixels& pixels, TruthLight light, int max_samples) {
    return {.mesh = f.mesh,
            .light = light,
            .positions = pixels.positions,
            .normals = pixels.normals,
            .first_samples_per_axis = 2,
            .max_samples_per_axis = max_samples};
}

// Bitwise equality, NaN-aware (background is 1, never NaN, in both).
bool same(const std::vector<float>& a, const std::vector<float>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i]) return false;
    return true;
}

// Polls until the job is no longer running (or the deadline passes); returns every snapshot seen.
std::vector<TruthSnapshot> follow(const TruthWorker& worker, std::chrono::seconds deadline) {
    std::vector<TruthSnapshot> seen;
    const auto until = std::chrono::steady_clock::now() + deadline;
    std::uint64_t version = 0;
    while (std::chrono::steady_clock::now() < until) {
        if (worker.version() != version) {
            seen.push_back(worker.snapshot());
            version = seen.back().version;
            if (seen.back().state != TruthState::running && seen.back().job > 0) break;
        }
        std::this_thread::sleep_for(1ms);
    }
    return seen;
}

} // namespace

TEST_CASE("truth worker: progress rises monotonically to 1 and the result equals one GroundTruth call") {
    Fixture f;
    const Pixels pixels = ground_grid(32);
    TruthWorker worker({.rays_per_chunk = 4096}); // many small chunks: many snapshots to check
    REQUIRE(worker.start(job_for(f, pixels, f.scene.light, 16)).empty());
    const std::vector<TruthSnapshot> seen = follow(worker, 60s);
    REQUIRE(!seen.empty());
    const TruthSnapshot& last = seen.back();
    REQUIRE_MESSAGE(last.state == TruthState::finished, to_string(last.state), " ", last.error);
    CHECK(last.progress == 1.0);
    CHECK(last.samples_per_axis == 16);
    CHECK(seen.size() > 2);
    for (std::size_t i = 1; i < seen.size(); ++i) {
        CHECK(seen[i].version > seen[i - 1].version);
        CHECK(seen[i].progress >= seen[i - 1].progress);
        CHECK(seen[i].samples_per_axis >= seen[i - 1].samples_per_axis);
        CHECK(seen[i].rays_traced >= seen[i - 1].rays_traced);
    }
    // Passes 2, 4, 8, 16 over the 30×30 traced pixels.
    CHECK(last.rays_traced == std::uint64_t(30 * 30) * (4 + 16 + 64 + 256));

    const GroundTruth truth(f.scene.mesh);
    const std::vector<float> reference =
        truth.visibility(pixels.positions, pixels.normals, f.scene.light, 16);
    CHECK(same(last.visibility, reference));
    // Not a trivial image: the planes cast shadows on the ground.
    int shadowed = 0, lit = 0;
    for (float v : reference) {
        shadowed += v < 0.5f;
        lit += v > 0.99f;
    }
    CHECK(shadowed > 20);
    CHECK(lit > 20);
    std::printf("truth worker 32x32 up to 16x16 rays: %zu snapshots, %.3f s, %u threads\n", seen.size(),
                last.seconds, worker.threads());
}

TEST_CASE("truth worker: the irradiance and oriented jobs (the window's views) equal one "
          "GroundTruth::oriented call") {
    Fixture f;
    Pixels pixels = ground_grid(16);
    // A tilted receiver normal so that part of the light lies below the tangent plane: the
    // references differ from the whole light's there, and from each other (the cosine weighs the light).
    for (glm::vec3& n : pixels.normals)
        if (n != glm::vec3(0.0f)) n = glm::normalize(glm::vec3(1.0f, 0.3f, 0.0f));
    const GroundTruth truth(f.scene.mesh);
    const GroundTruth::Oriented fair = truth.oriented(pixels.positions, pixels.normals, f.scene.light, 8);
    const std::vector<float> whole = truth.visibility(pixels.positions, pixels.normals, f.scene.light, 8);
    int weighed = 0;
    for (const TruthReference reference : {TruthReference::irradiance, TruthReference::oriented}) {
        CAPTURE(to_string(reference));
        TruthWorker worker;
        TruthJob job = job_for(f, pixels, f.scene.light, 8);
        job.reference = reference;
        REQUIRE(worker.start(std::move(job)).empty());
        const std::vector<TruthSnapshot> seen = follow(worker, 60s);
        REQUIRE(!seen.empty());
        REQUIRE(seen.back().state == TruthState::finished);
        const std::vector<float>& expected =
            reference == TruthReference::irradiance ? fair.irradiance : fair.oriented;
        int differ = 0;
        for (std::size_t i = 0; i < expected.size(); ++i) {
            const float got = seen.back().visibility[i];
            CHECK((got == expected[i] || (std::isnan(got) && std::isnan(expected[i]))));
            differ += std::abs(expected[i] - whole[i]) > 0.05f;
            weighed += reference == TruthReference::irradiance &&
                       std::abs(fair.irradiance[i] - fair.oriented[i]) > 0.01f;
        }
        CHECK(differ > 20);
    }
    CHECK(weighed > 20);
}

TEST_CASE("truth worker: an intermediate pass is a coarser estimate of the same image") {
    Fixture f;
    const Pixels pixels = ground_grid(24);
    TruthWorker worker({.rays_per_chunk = 2048});
    REQUIRE(worker.start(job_for(f, pixels, f.scene.light, 32)).empty());
    // Wait for the first pass (2×2) to cover every pixel.
    std::optional<TruthSnapshot> coarse;
    for (int i = 0; i < 20000 && !coarse; ++i) {
        TruthSnapshot s = worker.snapshot();
        if (s.samples_per_axis >= 2)
            coarse = std::move(s);
        else
            std::this_thread::sleep_for(1ms);
    }
    REQUIRE(coarse);
    for (std::size_t i = 0; i < pixels.positions.size(); ++i) CHECK(!std::isnan(coarse->visibility[i]));
    REQUIRE(worker.wait(60000ms));
    const TruthSnapshot fine = worker.snapshot();
    REQUIRE(fine.state == TruthState::finished);
    double mae = 0;
    for (std::size_t i = 0; i < fine.visibility.size(); ++i)
        mae += std::abs(fine.visibility[i] - coarse->visibility[i]);
    mae /= fine.visibility.size();
    CHECK(mae > 0.0);  // refinement changed something
    CHECK(mae < 0.15); // and the coarse pass was already close
}

TEST_CASE("truth worker: cancel during a long job takes effect within a second") {
    Fixture f;
    const Pixels pixels = ground_grid(64);
    TruthWorker worker;
    // 62² pixels × (2² + … + 1024²) rays: minutes of work.
    REQUIRE(worker.start(job_for(f, pixels, f.scene.light, 1024)).empty());
    for (int i = 0; i < 10000 && worker.snapshot().rays_traced == 0; ++i) std::this_thread::sleep_for(1ms);
    std::this_thread::sleep_for(200ms);
    const auto t0 = std::chrono::steady_clock::now();
    worker.cancel();
    const bool stopped = worker.wait(1000ms);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    CHECK(stopped);
    CHECK(seconds < 1.0);
    const TruthSnapshot s = worker.snapshot();
    CHECK(s.state == TruthState::cancelled);
    CHECK(s.progress > 0.0);
    CHECK(s.progress < 1.0);
    std::printf("truth worker: cancel took %.1f ms (progress %.4f)\n", 1e3 * seconds, s.progress);
}

TEST_CASE("truth worker: restart with new input replaces a running job and gives the new result") {
    Fixture f;
    const Pixels pixels = ground_grid(32);
    TruthWorker worker;
    REQUIRE(worker.start(job_for(f, pixels, f.scene.light, 1024)).empty()); // long: will be replaced
    std::this_thread::sleep_for(100ms);
    penumbra::RectLight moved = f.scene.light;
    moved.center += glm::dvec3(2.0, 0.0, 1.0);
    const auto t0 = std::chrono::steady_clock::now();
    REQUIRE(worker.start(job_for(f, pixels, moved, 8)).empty());
    REQUIRE(worker.wait(30000ms));
    const TruthSnapshot s = worker.snapshot();
    std::printf("truth worker: restart to a finished 8x8 job in %.1f ms\n",
                1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    CHECK(s.job == 2);
    REQUIRE(s.state == TruthState::finished);
    const GroundTruth truth(f.scene.mesh);
    CHECK(same(s.visibility, truth.visibility(pixels.positions, pixels.normals, moved, 8)));
    CHECK(!same(s.visibility, truth.visibility(pixels.positions, pixels.normals, f.scene.light, 8)));

    // And the sun, through the same worker (the acceleration structure is reused).
    REQUIRE(worker.start(job_for(f, pixels, f.scene.sun, 8)).empty());
    REQUIRE(worker.wait(30000ms));
    const TruthSnapshot sun = worker.snapshot();
    CHECK(sun.job == 3);
    REQUIRE(sun.state == TruthState::finished);
    CHECK(same(sun.visibility, truth.visibility(pixels.positions, pixels.normals, f.scene.sun, 8)));
}

TEST_CASE("truth worker: the destructor stops a long job promptly") {
    Fixture f;
    const Pixels pixels = ground_grid(64);
    std::chrono::steady_clock::time_point t0;
    {
        TruthWorker worker;
        REQUIRE(worker.start(job_for(f, pixels, f.scene.light, 1024)).empty());
        std::this_thread::sleep_for(200ms);
        t0 = std::chrono::steady_clock::now();
    }
    CHECK(std::chrono::steady_clock::now() - t0 < 1s);
}

TEST_CASE("truth worker: bad input is refused with a message, a bad mesh fails in the snapshot") {
    Fixture f;
    const Pixels pixels = ground_grid(8);
    TruthWorker worker;
    TruthJob no_mesh = job_for(f, pixels, f.scene.light, 4);
    no_mesh.mesh.reset();
    CHECK(worker.start(no_mesh) == "truth worker: the job has no mesh");
    TruthJob short_normals = job_for(f, pixels, f.scene.light, 4);
    short_normals.normals.pop_back();
    CHECK(worker.start(short_normals) ==
          "truth worker: 63 normals for 64 positions; give one normal per position");
    CHECK(worker.start(job_for(f, pixels, f.scene.light, 0)) ==
          "truth worker: max_samples_per_axis must be in [1, 4096], got 0");
    TruthJob first_too_big = job_for(f, pixels, f.scene.light, 4);
    first_too_big.first_samples_per_axis = 8;
    CHECK(worker.start(first_too_big) ==
          "truth worker: first_samples_per_axis must be in [1, max_samples_per_axis = 4], got 8");
    CHECK(worker.snapshot().job == 0); // nothing was started

    Mesh broken = f.scene.mesh;
    broken.indices.back() = static_cast<std::uint32_t>(broken.positions.size()); // out of range
    TruthJob bad = job_for(f, pixels, f.scene.light, 4);
    bad.mesh = std::make_shared<const Mesh>(broken);
    REQUIRE(worker.start(bad).empty());
    REQUIRE(worker.wait(10000ms));
    const TruthSnapshot s = worker.snapshot();
    CHECK(s.state == TruthState::failed);
    CHECK(s.error.find("invalid mesh") != std::string::npos);
    MESSAGE(s.error);
}
