// playground/src/reference/truth_worker.cpp
#include "reference/truth_worker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace penumbra::playground {

namespace {

using Clock = std::chrono::steady_clock;

bool is_background(glm::vec3 p) { return std::isnan(p.x) || std::isnan(p.y) || std::isnan(p.z); }

// Samples per axis of each pass: first, doubling, then max (the last pass may be less than double).
std::vector<int> pass_sizes(int first, int max) {
    std::vector<int> sizes;
    for (int n = first; n < max; n *= 2) sizes.push_back(n);
    sizes.push_back(max);
    return sizes;
}

std::vector<float> trace(const GroundTruth& truth, std::span<const glm::vec3> positions,
                         std::span<const glm::vec3> normals, const TruthLight& light, int samples_per_axis,
                         TruthReference reference) {
    return std::visit(
        [&](const auto& l) {
            if (reference == TruthReference::whole_light)
                return truth.visibility(positions, normals, l, samples_per_axis);
            GroundTruth::Oriented fair = truth.oriented(positions, normals, l, samples_per_axis);
            return reference == TruthReference::irradiance ? std::move(fair.irradiance)
                                                           : std::move(fair.oriented);
        },
        light);
}

} // namespace

const char* to_string(TruthReference reference) {
    switch (reference) {
    case TruthReference::irradiance: return "irradiance";
    case TruthReference::oriented: return "oriented";
    case TruthReference::whole_light: return "whole light";
    }
    return "?";
}

const char* to_string(TruthState state) {
    switch (state) {
    case TruthState::idle: return "idle";
    case TruthState::running: return "running";
    case TruthState::finished: return "finished";
    case TruthState::cancelled: return "cancelled";
    case TruthState::failed: return "failed";
    }
    return "?";
}

TruthWorker::TruthWorker(TruthWorkerOptions options)
    : threads_(options.threads ? options.threads : std::max(2u, std::thread::hardware_concurrency()) - 1),
      rays_per_chunk_(std::max<std::uint64_t>(options.rays_per_chunk, 1)) {
    thread_ = std::thread([this] { run(); });
}

TruthWorker::~TruthWorker() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        quit_ = true;
        pending_.reset();
    }
    changed_.notify_all();
    thread_.join();
}

std::string TruthWorker::start(TruthJob job) {
    if (!job.mesh) return "truth worker: the job has no mesh";
    if (job.normals.size() != job.positions.size())
        return "truth worker: " + std::to_string(job.normals.size()) + " normals for " +
               std::to_string(job.positions.size()) + " positions; give one normal per position";
    if (job.max_samples_per_axis < 1 || job.max_samples_per_axis > 4096)
        return "truth worker: max_samples_per_axis must be in [1, 4096], got " +
               std::to_string(job.max_samples_per_axis);
    if (job.first_samples_per_axis < 1 || job.first_samples_per_axis > job.max_samples_per_axis)
        return "truth worker: first_samples_per_axis must be in [1, max_samples_per_axis = " +
               std::to_string(job.max_samples_per_axis) + "], got " +
               std::to_string(job.first_samples_per_axis);
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_ = std::move(job);
        ++requested_job_;
        cancel_requested_ = false;
    }
    changed_.notify_all();
    return {};
}

void TruthWorker::cancel() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        pending_.reset();
        cancel_requested_ = true;
    }
    changed_.notify_all();
}

bool TruthWorker::wait(std::chrono::milliseconds timeout) const {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] { return !busy_ && !pending_; });
}

TruthSnapshot TruthWorker::snapshot() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return published_;
}

std::uint64_t TruthWorker::version() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return published_.version;
}

bool TruthWorker::should_stop(std::uint64_t job_id) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return quit_ || cancel_requested_ || requested_job_ != job_id;
}

void TruthWorker::run() {
    for (;;) {
        TruthJob job;
        std::uint64_t job_id = 0;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait(lock, [&] { return quit_ || pending_.has_value(); });
            if (quit_) break;
            job = std::move(*pending_);
            pending_.reset();
            job_id = requested_job_;
            busy_ = true;
            published_.job = job_id;
            published_.state = TruthState::running;
            published_.visibility.assign(job.positions.size(), std::numeric_limits<float>::quiet_NaN());
            published_.samples_per_axis = 0;
            published_.pass_samples_per_axis = job.first_samples_per_axis;
            published_.rays_traced = 0;
            published_.progress = 0.0;
            published_.seconds = 0.0;
            published_.error.clear();
            ++published_.version;
        }
        changed_.notify_all();
        compute(job, job_id);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            busy_ = false;
        }
        changed_.notify_all();
    }
    // Embree objects live and die on this thread only (its own worker threads sync with it).
    truth_.reset();
    traced_mesh_.reset();
}

// Each chunk [begin, end) is traced by GroundTruth::visibility over the prefix [0, end) of a copy
// of the positions in which every pixel outside the chunk is NaN (background: skipped at the
// cost of a comparison). Ground truth jitters the samples of a point by its index in the span, so
// every pixel gets exactly the rays it would get from one call over the whole image: progressive
// and one-shot results agree bit for bit, and the O(end) scan per chunk is negligible next to
// the rays (a chunk holds rays_per_chunk of them).
void TruthWorker::compute(const TruthJob& job, std::uint64_t job_id) {
    const Clock::time_point began = Clock::now();
    auto publish = [&](auto&& update) {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            update(published_);
            published_.seconds = std::chrono::duration<double>(Clock::now() - began).count();
            ++published_.version;
        }
        changed_.notify_all();
    };
    auto fail = [&](const std::string& message) {
        publish([&](TruthSnapshot& s) {
            s.state = TruthState::failed;
            s.error = message;
        });
    };
    auto stop_if_asked = [&] {
        if (!should_stop(job_id)) return false;
        publish([](TruthSnapshot& s) { s.state = TruthState::cancelled; });
        return true;
    };

    try {
        if (job.mesh != traced_mesh_ || !truth_) {
            truth_.reset();
            traced_mesh_.reset();
            truth_ = std::make_unique<GroundTruth>(*job.mesh, -1.0f, threads_);
            traced_mesh_ = job.mesh;
        }
    } catch (const std::exception& e) {
        fail(e.what());
        return;
    }
    if (stop_if_asked()) return;

    const std::size_t count = job.positions.size();
    const std::size_t traced_pixels = static_cast<std::size_t>(std::count_if(
        job.positions.begin(), job.positions.end(), [](glm::vec3 p) { return !is_background(p); }));
    const std::vector<int> passes = pass_sizes(job.first_samples_per_axis, job.max_samples_per_axis);
    std::uint64_t total_rays = 0;
    for (int n : passes) total_rays += static_cast<std::uint64_t>(n) * n * traced_pixels;

    std::vector<glm::vec3> masked(count, glm::vec3(std::numeric_limits<float>::quiet_NaN()));
    std::uint64_t rays = 0;
    for (std::size_t pass = 0; pass < passes.size(); ++pass) {
        const int n = passes[pass];
        const std::uint64_t rays_per_pixel = static_cast<std::uint64_t>(n) * n;
        const std::size_t chunk =
            static_cast<std::size_t>(std::max<std::uint64_t>(1, rays_per_chunk_ / rays_per_pixel));
        publish([&](TruthSnapshot& s) { s.pass_samples_per_axis = n; });
        for (std::size_t begin = 0; begin < count; begin += chunk) {
            if (stop_if_asked()) return;
            const std::size_t end = std::min(count, begin + chunk);
            std::copy(job.positions.begin() + begin, job.positions.begin() + end, masked.begin() + begin);
            std::vector<float> result;
            try {
                result = trace(*truth_, std::span(masked.data(), end), std::span(job.normals.data(), end),
                               job.light, n, job.reference);
            } catch (const std::exception& e) {
                fail(e.what());
                return;
            }
            std::fill(masked.begin() + begin, masked.begin() + end,
                      glm::vec3(std::numeric_limits<float>::quiet_NaN()));
            for (std::size_t i = begin; i < end; ++i)
                if (!is_background(job.positions[i])) rays += rays_per_pixel;
            publish([&](TruthSnapshot& s) {
                std::copy(result.begin() + begin, result.begin() + end, s.visibility.begin() + begin);
                s.rays_traced = rays;
                s.progress = total_rays ? std::min(1.0, static_cast<double>(rays) / total_rays) : 1.0;
            });
        }
        publish([&](TruthSnapshot& s) { s.samples_per_axis = n; });
    }
    publish([&](TruthSnapshot& s) {
        s.state = TruthState::finished;
        s.progress = 1.0;
    });
}

} // namespace penumbra::playground
