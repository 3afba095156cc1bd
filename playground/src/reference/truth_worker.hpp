// playground/src/reference/truth_worker.hpp — ground truth computed in the background, refined progressively.
//
// The playground's "ground truth" and "error heatmap" views need Embree visibility at every
// pixel, which takes seconds to minutes; the window must keep rendering meanwhile and restart the
// computation whenever the view or the light moves. TruthWorker owns one thread that runs
// GroundTruth::visibility in passes of increasing sample count (first×first, then doubling, up to
// max×max rays per pixel), each pass over all pixels, and publishes what it has after every chunk.
//
//   TruthWorker worker;                              // thread starts idle
//   worker.start({.mesh = mesh_ptr, .light = scene.light, .positions = p, .normals = n});
//   ... each frame:
//   if (worker.version() != shown) { TruthSnapshot s = worker.snapshot(); shown = s.version;
//   upload(s.visibility); }
//
// The final pass of a finished job is bit-identical to GroundTruth::visibility(positions, normals,
// light, max_samples_per_axis) computed in one call (same per-pixel jitter, see truth_worker.cpp).
#pragma once

#include "reference/ground_truth.hpp"
#include "scenes/scene.hpp"

#include <penumbra/light.hpp>

#include <glm/glm.hpp>

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <variant>
#include <vector>

namespace penumbra::playground {

using TruthLight = std::variant<penumbra::RectLight, penumbra::SunLight>;

// Which visibility the truth traces (GroundTruth): what the shaded image needs first.
enum class TruthReference {
    irradiance,  // the irradiance-weighted visibility of the light's part above the tangent plane: the
                 // shaded image's own relative error (the light term times it); NaN where no light is above
    oriented,    // the fraction of the light's samples above the tangent plane that reach it; NaN likewise
    whole_light, // the fraction of all of the light's samples that reach the point, its orientation aside
};
inline constexpr int truth_reference_count = 3;
const char* to_string(TruthReference reference);

struct TruthJob {
    // Shared so that a new job for the same mesh (the light or the camera moved) reuses the
    // acceleration structure: it is rebuilt only when this pointer changes.
    std::shared_ptr<const Mesh> mesh;
    TruthLight light;
    // Per pixel, any order (the result uses the same order). NaN position: background, result 1.
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals; // as many as positions; zero = no ray offset
    int first_samples_per_axis = 2; // rays per axis of the first pass; 1 to max_samples_per_axis
    int max_samples_per_axis = 32;  // rays per axis of the last pass; 1 to 4096
    // irradiance and oriented (GroundTruth::oriented) weigh the part of the light above each point's
    // tangent plane, `normals` pointing to the side seen; whole_light ignores the normals but for the
    // rays' offset.
    TruthReference reference = TruthReference::whole_light;
};

enum class TruthState { idle, running, finished, cancelled, failed };

struct TruthSnapshot {
    std::uint64_t version = 0; // increases with every publication (compare with version())
    std::uint64_t job = 0;     // which start() produced it: 1 for the first job, then 2, ...
    TruthState state = TruthState::idle;
    std::vector<float> visibility; // latest estimate per pixel; NaN where no pass has reached it yet
    int samples_per_axis = 0;      // finest pass completed over all pixels (0: none yet)
    int pass_samples_per_axis = 0; // pass in progress (equal to samples_per_axis when finished)
    std::uint64_t rays_traced = 0; // rays cast so far by this job (background pixels cast none)
    double progress = 0.0;         // rays_traced / rays of all passes, 0 to 1; 1 exactly when finished
    double seconds = 0.0;          // time spent on this job so far
    std::string error;             // state == failed: what went wrong (invalid mesh, Embree error)
};

struct TruthWorkerOptions {
    // Threads tracing rays (the worker's own thread included). 0: hardware threads − 1, at least
    // 1, leaving a core to the render thread (llvmpipe renders on the CPU too).
    unsigned threads = 0;
    // Rays per chunk: the worker publishes and checks for cancellation after each chunk, so this
    // bounds the latency of cancel() and restart (2^18 rays ≈ 0.1 s on one core for our scenes).
    std::uint64_t rays_per_chunk = 1u << 18;
};

class TruthWorker {
public:
    explicit TruthWorker(TruthWorkerOptions options = {});
    ~TruthWorker(); // cancels the job and joins the thread
    TruthWorker(const TruthWorker&) = delete;
    TruthWorker& operator=(const TruthWorker&) = delete;

    // Cancels the running job, if any, and starts `job`. Returns an empty string, or — without
    // touching the running job — a one-line message for invalid input (no mesh, sizes that
    // differ, sample counts out of range). Mesh problems and Embree errors are reported later
    // in the snapshot (state failed), since the acceleration structure is built on the thread.
    std::string start(TruthJob job);

    // Stops the running job after its current chunk; returns at once. The snapshot keeps what
    // was computed, with state cancelled.
    void cancel();

    // Waits until no job is running (idle, finished, cancelled or failed), at most `timeout`.
    // True if that happened in time.
    bool wait(std::chrono::milliseconds timeout) const;

    TruthSnapshot snapshot() const; // a copy, safe to call from any thread
    std::uint64_t version() const;  // cheap: has anything changed since a snapshot?
    unsigned threads() const { return threads_; }

private:
    void run();
    void compute(const TruthJob& job, std::uint64_t job_id);
    bool should_stop(std::uint64_t job_id) const;

    const unsigned threads_;
    const std::uint64_t rays_per_chunk_;

    mutable std::mutex mutex_;
    mutable std::condition_variable changed_;
    std::optional<TruthJob> pending_; // next job, taken by the thread
    std::uint64_t requested_job_ = 0; // id of the newest start(); a running job with another id stops
    bool cancel_requested_ = false;
    bool busy_ = false; // the thread is running a job
    bool quit_ = false;
    TruthSnapshot published_;

    // Touched by the worker thread only: the acceleration structure of the last mesh.
    std::shared_ptr<const Mesh> traced_mesh_;
    std::unique_ptr<GroundTruth> truth_;

    std::thread thread_; // last member: starts after everything above exists
};

const char* to_string(TruthState state);

} // namespace penumbra::playground
