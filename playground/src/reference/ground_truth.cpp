// playground/src/reference/ground_truth.cpp
#include "reference/ground_truth.hpp"

#include "scenes/mesh_builder.hpp"

#include <embree3/rtcore.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>
#include <thread>

namespace penumbra::playground {

namespace {

// "lowbias32" (Chris Wellons' integer hash search): cheap, well mixed, and — unlike
// std::uniform_real_distribution — identical on every platform.
std::uint32_t hash32(std::uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352dU;
    x ^= x >> 15;
    x *= 0x846ca68bU;
    x ^= x >> 16;
    return x;
}

// Maps 24 bits to (0, 1): the +0.5 keeps jitter strictly inside the stratum, so no sample lies
// exactly on a stratum boundary (where an edge aligned with the strata would make the answer
// depend on rounding).
float open_unit(std::uint32_t bits) { return (static_cast<float>(bits >> 8) + 0.5f) * (1.0f / 16777216.0f); }

bool has_nan(glm::vec3 p) { return std::isnan(p.x) || std::isnan(p.y) || std::isnan(p.z); }

// Unit normal turned to face `towards`, or zero when the normal is unusable (then no offset).
glm::vec3 facing_normal(glm::vec3 n, glm::vec3 towards) {
    const float len = glm::length(n);
    if (!(len > 0.0f) || !std::isfinite(len)) return glm::vec3(0.0f);
    n /= len;
    return glm::dot(n, towards) < 0.0f ? -n : n;
}

} // namespace

glm::vec2 stratified_sample(std::uint32_t point, std::uint32_t sample, int samples_per_axis) {
    const auto n = static_cast<std::uint32_t>(samples_per_axis);
    const std::uint32_t h1 = hash32(point * 0x9e3779b1U + hash32(sample + 0x632be5abU));
    const std::uint32_t h2 = hash32(h1 ^ 0x85ebca6bU);
    const float i = static_cast<float>(sample % n);
    const float j = static_cast<float>(sample / n);
    return {(i + open_unit(h1)) / static_cast<float>(n), (j + open_unit(h2)) / static_cast<float>(n)};
}

struct GroundTruth::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    float offset = 0.0f;
    unsigned threads = 1;
    // The mesh's triangles and vertex normals, for the shadow terminator (origin_for()).
    std::vector<glm::vec3> positions, normals;
    std::vector<std::uint32_t> indices;
    // The cut materials, their texture coordinates and the triangles' indices and materials (no
    // positions): what the occlusion filter reads. Empty when nothing cuts.
    Mesh cuts;

    // Embree's occlusion filter: a hit on a cut material where its texture's alpha at the hit's
    // texture coordinate is below the cutoff is no hit (the alpha test of cut-out casters).
    static void pass_cut_out(const RTCFilterFunctionNArguments* args) {
        const Mesh& mesh = *static_cast<const Mesh*>(args->geometryUserPtr);
        for (unsigned i = 0; i < args->N; ++i) {
            if (args->valid[i] != -1) continue;
            const unsigned triangle = RTCHitN_primID(args->hit, args->N, i);
            const float u = RTCHitN_u(args->hit, args->N, i), v = RTCHitN_v(args->hit, args->N, i);
            if (!mesh.solid_at(triangle, u, v)) args->valid[i] = 0;
        }
    }

    // Embree reports errors through a callback (possibly from its own threads); we record the
    // first one and throw it from our own code, never through Embree's C frames.
    mutable std::mutex error_mutex;
    std::string first_error;

    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }

    static void on_error(void* user, RTCError code, const char* message) {
        auto* self = static_cast<Impl*>(user);
        std::lock_guard<std::mutex> lock(self->error_mutex);
        if (self->first_error.empty())
            self->first_error = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                                (message ? message : "(no message)");
    }

    void throw_if_error(const char* during) const {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!first_error.empty()) throw GroundTruthError(std::string("ground truth: ") + during + ": " + first_error);
    }

    // Runs body(index) for every index in [0, count) on `threads` workers, in chunks.
    template <class Body>
    void parallel_for(std::size_t count, const Body& body) const {
        constexpr std::size_t chunk = 64;
        std::atomic<std::size_t> next{0};
        auto worker = [&] {
            for (;;) {
                const std::size_t begin = next.fetch_add(chunk);
                if (begin >= count) return;
                const std::size_t end = std::min(count, begin + chunk);
                for (std::size_t i = begin; i < end; ++i) body(i);
            }
        };
        const unsigned n = static_cast<unsigned>(std::min<std::size_t>(threads, (count + chunk - 1) / chunk));
        std::vector<std::thread> pool;
        for (unsigned t = 1; t < n; ++t) pool.emplace_back(worker);
        worker();
        for (std::thread& t : pool) t.join();
    }

    // Where the rays of a surface point start: on the smooth surface that the vertex normals
    // describe, then `offset` along n (the normal of the lit side). A triangle mesh with
    // interpolated normals is a polyhedron shaded as if curved: near its terminator, rays above
    // the smooth tangent plane run under the flat triangle's own plane and hit the neighbouring
    // triangles, a dark band along every row of triangles that no renderer shading the same
    // normals would draw (the "shadow terminator" problem). Each corner's tangent plane lifts the
    // point by how far it lies below that plane; the barycentric mean of the three lifts puts it
    // on a curved surface through the corners (Hanika, "Hacking the Shadow Terminator", Ray
    // Tracing Gems II, 2021). Flat triangles (equal normals) keep the point where it is.
    glm::vec3 origin_for(glm::vec3 p, glm::vec3 n) const {
        if (n == glm::vec3(0.0f)) return p;
        const float reach = 8.0f * offset;
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRayHit query{};
        query.ray.org_x = p.x + reach * n.x;
        query.ray.org_y = p.y + reach * n.y;
        query.ray.org_z = p.z + reach * n.z;
        query.ray.dir_x = -n.x;
        query.ray.dir_y = -n.y;
        query.ray.dir_z = -n.z;
        query.ray.tnear = 0.0f;
        query.ray.tfar = 2.0f * reach;
        query.ray.mask = 0xffffffffU;
        query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &query);
        glm::vec3 lifted = p;
        if (query.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            const std::size_t t = 3 * static_cast<std::size_t>(query.hit.primID);
            const float b[3] = {1.0f - query.hit.u - query.hit.v, query.hit.u, query.hit.v};
            for (int k = 0; k < 3; ++k) {
                const std::uint32_t corner = indices[t + k];
                glm::vec3 corner_normal = normals[corner];
                if (glm::dot(corner_normal, n) < 0.0f) corner_normal = -corner_normal; // the lit side's
                const float below = std::min(0.0f, glm::dot(p - positions[corner], corner_normal));
                lifted -= b[k] * below * corner_normal;
            }
        }
        return lifted + offset * n;
    }

    // True if nothing in the scene lies on the segment origin + t·dir, t in (0, tfar).
    bool unoccluded(glm::vec3 origin, glm::vec3 dir, float tfar) const {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        RTCRay ray{};
        ray.org_x = origin.x;
        ray.org_y = origin.y;
        ray.org_z = origin.z;
        ray.tnear = 0.0f;
        ray.dir_x = dir.x;
        ray.dir_y = dir.y;
        ray.dir_z = dir.z;
        ray.time = 0.0f;
        ray.tfar = tfar;
        ray.mask = 0xffffffffU;
        ray.flags = 0;
        rtcOccluded1(scene, &context, &ray);
        return ray.tfar >= 0.0f; // Embree sets tfar to −inf on a hit
    }
};

GroundTruth::GroundTruth(const Mesh& mesh, float ray_offset, unsigned thread_count) : impl_(std::make_unique<Impl>()) {
    if (const std::string problem = validate_mesh(mesh); !problem.empty())
        throw GroundTruthError("ground truth: invalid mesh: " + problem);

    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device)
        throw GroundTruthError("ground truth: rtcNewDevice failed (Embree error " +
                               std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(impl_->device, &Impl::on_error, impl_.get());

    const auto [lo, hi] = compute_bounds(mesh);
    const float diagonal = glm::length(hi - lo);
    impl_->offset = ray_offset >= 0.0f ? ray_offset : 1e-4f * std::max(diagonal, 1e-3f);
    impl_->threads = thread_count ? thread_count : std::max(1u, std::thread::hardware_concurrency());

    impl_->scene = rtcNewScene(impl_->device);
    impl_->throw_if_error("creating the scene");
    // Robust mode: watertight edges, so rays through the shared edge of two occluder triangles
    // cannot slip through (thin occluders are exactly what we test).
    rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);

    if (!mesh.indices.empty()) {
        RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
        impl_->throw_if_error("creating the triangle geometry");
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0,
                                                                      RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                                      mesh.positions.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0,
                                                                        RTC_FORMAT_UINT3, 3 * sizeof(unsigned),
                                                                        mesh.triangle_count()));
        if (!vertices || !indices) {
            rtcReleaseGeometry(geometry);
            impl_->throw_if_error("allocating geometry buffers");
            throw GroundTruthError("ground truth: allocating geometry buffers failed");
        }
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            vertices[3 * i + 0] = mesh.positions[i].x;
            vertices[3 * i + 1] = mesh.positions[i].y;
            vertices[3 * i + 2] = mesh.positions[i].z;
        }
        std::copy(mesh.indices.begin(), mesh.indices.end(), indices);
        impl_->positions = mesh.positions;
        impl_->normals = mesh.normals;
        impl_->indices = mesh.indices;
        if (mesh.cuts()) {
            impl_->cuts.indices = mesh.indices;
            impl_->cuts.material_uvs = mesh.material_uvs;
            impl_->cuts.triangle_materials = mesh.triangle_materials;
            impl_->cuts.cut_materials = mesh.cut_materials;
            rtcSetGeometryUserData(geometry, &impl_->cuts);
            rtcSetGeometryOccludedFilterFunction(geometry, &Impl::pass_cut_out);
            rtcSetGeometryIntersectFilterFunction(geometry, &Impl::pass_cut_out);
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometry(impl_->scene, geometry);
        rtcReleaseGeometry(geometry); // the scene holds its own reference
    }
    rtcCommitScene(impl_->scene);
    impl_->throw_if_error("building the scene");
}

GroundTruth::~GroundTruth() = default;
GroundTruth::GroundTruth(GroundTruth&&) noexcept = default;
GroundTruth& GroundTruth::operator=(GroundTruth&&) noexcept = default;

float GroundTruth::ray_offset() const { return impl_->offset; }

namespace {

void check_inputs(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals, int samples_per_axis) {
    if (normals.size() != positions.size())
        throw GroundTruthError("ground truth: " + std::to_string(normals.size()) + " normals for " +
                               std::to_string(positions.size()) + " positions");
    if (samples_per_axis < 1 || samples_per_axis > 4096)
        throw GroundTruthError("ground truth: samples_per_axis must be in [1, 4096], got " +
                               std::to_string(samples_per_axis));
}

} // namespace

std::vector<float> GroundTruth::visibility(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                           const penumbra::RectLight& light, int samples_per_axis) const {
    check_inputs(positions, normals, samples_per_axis);
    const glm::dvec3 centre = light.center;
    const glm::dvec3 light_normal = light.normal();
    const glm::dvec3 u = glm::normalize(light.u_axis) * light.width;
    const glm::dvec3 v = glm::normalize(light.v_axis) * light.height;
    const auto sample_count = static_cast<std::uint32_t>(samples_per_axis * samples_per_axis);

    std::vector<float> result(positions.size(), 1.0f);
    impl_->parallel_for(positions.size(), [&](std::size_t index) {
        const glm::vec3 p = positions[index];
        if (has_nan(p)) return; // background: fully lit by convention
        const glm::dvec3 pd(p);
        if (glm::dot(pd - centre, light_normal) <= 0.0) {
            result[index] = 0.0f; // behind or in the light's plane: the light emits away from it
            return;
        }
        const glm::vec3 n = facing_normal(normals[index], glm::vec3(centre - pd));
        const glm::vec3 origin = impl_->origin_for(p, n);
        const auto point = static_cast<std::uint32_t>(index);
        std::uint32_t visible = 0;
        for (std::uint32_t s = 0; s < sample_count; ++s) {
            const glm::vec2 xi = stratified_sample(point, s, samples_per_axis);
            const glm::dvec3 target = centre + (static_cast<double>(xi.x) - 0.5) * u + (static_cast<double>(xi.y) - 0.5) * v;
            const glm::dvec3 to_light = target - glm::dvec3(origin);
            const double distance = glm::length(to_light);
            if (!(distance > 0.0)) continue;
            // Stop just short of the light so geometry coplanar with it (a ceiling) does not count.
            if (impl_->unoccluded(origin, glm::vec3(to_light / distance), static_cast<float>(distance * (1.0 - 1e-5))))
                ++visible;
        }
        result[index] = static_cast<float>(visible) / static_cast<float>(sample_count);
    });
    impl_->throw_if_error("tracing rays to the area light");
    return result;
}

namespace {

// Orthonormal frame (t, b, w) around the direction w towards the sun, and the cone's 1 − cos α.
struct SunFrame {
    glm::dvec3 t, b, w;
    double one_minus_cos;

    explicit SunFrame(const penumbra::SunLight& sun) {
        w = -glm::normalize(sun.direction);
        const glm::dvec3 helper = std::abs(w.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
        t = glm::normalize(glm::cross(helper, w));
        b = glm::cross(w, t);
        one_minus_cos = 1.0 - std::cos(0.5 * sun.angular_diameter);
    }
    // Uniform in solid angle over the cone: cos θ uniform in [cos α, 1], φ uniform.
    glm::dvec3 direction(glm::vec2 xi) const {
        const double cos_theta = 1.0 - static_cast<double>(xi.x) * one_minus_cos;
        const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
        const double phi = 2.0 * glm::pi<double>() * static_cast<double>(xi.y);
        return cos_theta * w + sin_theta * (std::cos(phi) * t + std::sin(phi) * b);
    }
};

// Accumulates one point's fair references over its light samples.
struct OrientedSums {
    std::uint32_t above = 0, visible = 0;
    double weight = 0.0, visible_weight = 0.0;

    void add(bool unoccluded, double w) {
        ++above;
        weight += w;
        if (!unoccluded) return;
        ++visible;
        visible_weight += w;
    }
    // NaN where no sample was above the tangent plane (or all weights vanish). `sample_measure`: the
    // light's area (rectangle) or solid angle (sun) over π, over the number of samples, so that the
    // mean weight becomes the unoccluded irradiance of a light of radiance 1.
    void store(GroundTruth::Oriented& out, std::size_t index, double sample_measure) const {
        const float nan = std::numeric_limits<float>::quiet_NaN();
        out.oriented[index] = above ? static_cast<float>(visible) / static_cast<float>(above) : nan;
        out.irradiance[index] = weight > 0.0 ? static_cast<float>(visible_weight / weight) : nan;
        out.unoccluded[index] = static_cast<float>(weight * sample_measure);
    }
};

GroundTruth::Oriented background_ones(std::size_t count) {
    return {std::vector<float>(count, 1.0f), std::vector<float>(count, 1.0f),
            std::vector<float>(count, 1.0f)};
}

// Unit normal or zero (unusable), without turning it.
glm::vec3 unit_or_zero(glm::vec3 n) {
    const float len = glm::length(n);
    return len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f);
}

} // namespace

GroundTruth::Oriented GroundTruth::oriented(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                            const penumbra::RectLight& light, int samples_per_axis) const {
    check_inputs(positions, normals, samples_per_axis);
    const glm::dvec3 centre = light.center;
    const glm::dvec3 light_normal = light.normal();
    const glm::dvec3 u = glm::normalize(light.u_axis) * light.width;
    const glm::dvec3 v = glm::normalize(light.v_axis) * light.height;
    const auto sample_count = static_cast<std::uint32_t>(samples_per_axis * samples_per_axis);
    const double sample_measure = light.width * light.height / glm::pi<double>() / sample_count;
    Oriented result = background_ones(positions.size());
    impl_->parallel_for(positions.size(), [&](std::size_t index) {
        const glm::vec3 p = positions[index];
        if (has_nan(p)) return;
        OrientedSums sums;
        const glm::vec3 n = unit_or_zero(normals[index]);
        const glm::dvec3 pd(p);
        // Behind the light's plane or without a normal: sees none of the light (sums stay empty).
        if (glm::dot(pd - centre, light_normal) > 0.0 && n != glm::vec3(0.0f)) {
            const glm::vec3 origin = impl_->origin_for(p, n);
            for (std::uint32_t s = 0; s < sample_count; ++s) {
                const glm::vec2 xi = stratified_sample(static_cast<std::uint32_t>(index), s, samples_per_axis);
                const glm::dvec3 target = centre + (static_cast<double>(xi.x) - 0.5) * u + (static_cast<double>(xi.y) - 0.5) * v;
                const glm::dvec3 to_light = target - pd;
                const double distance = glm::length(to_light);
                if (!(distance > 0.0)) continue;
                const glm::dvec3 dir = to_light / distance;
                const double cos_receiver = glm::dot(dir, glm::dvec3(n));
                if (cos_receiver <= 0.0) continue; // below the tangent plane: the surface cannot receive it
                const double cos_light = std::max(0.0, -glm::dot(dir, light_normal));
                const glm::dvec3 from_origin = target - glm::dvec3(origin);
                const double length = glm::length(from_origin);
                sums.add(impl_->unoccluded(origin, glm::vec3(from_origin / length), static_cast<float>(length * (1.0 - 1e-5))),
                         cos_receiver * cos_light / (distance * distance));
            }
        }
        sums.store(result, index, sample_measure);
    });
    impl_->throw_if_error("tracing rays to the area light");
    return result;
}

GroundTruth::Oriented GroundTruth::oriented(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                            const penumbra::SunLight& sun, int samples_per_axis) const {
    check_inputs(positions, normals, samples_per_axis);
    const SunFrame frame(sun);
    const auto sample_count = static_cast<std::uint32_t>(samples_per_axis * samples_per_axis);
    // the disk's solid angle 2π(1 − cos α), which SunFrame samples uniformly
    const double sample_measure = 2.0 * frame.one_minus_cos / sample_count;
    Oriented result = background_ones(positions.size());
    impl_->parallel_for(positions.size(), [&](std::size_t index) {
        const glm::vec3 p = positions[index];
        if (has_nan(p)) return;
        OrientedSums sums;
        const glm::vec3 n = unit_or_zero(normals[index]);
        if (n != glm::vec3(0.0f)) {
            const glm::vec3 origin = impl_->origin_for(p, n);
            for (std::uint32_t s = 0; s < sample_count; ++s) {
                const glm::dvec3 dir = frame.direction(stratified_sample(static_cast<std::uint32_t>(index), s, samples_per_axis));
                const double cos_receiver = glm::dot(dir, glm::dvec3(n));
                if (cos_receiver <= 0.0) continue;
                sums.add(impl_->unoccluded(origin, glm::vec3(dir), std::numeric_limits<float>::infinity()), cos_receiver);
            }
        }
        sums.store(result, index, sample_measure);
    });
    impl_->throw_if_error("tracing rays to the sun");
    return result;
}

std::vector<float> GroundTruth::visibility(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                           const penumbra::SunLight& sun, int samples_per_axis) const {
    check_inputs(positions, normals, samples_per_axis);
    const SunFrame frame(sun);
    const glm::dvec3 w = frame.w;
    const auto sample_count = static_cast<std::uint32_t>(samples_per_axis * samples_per_axis);

    std::vector<float> result(positions.size(), 1.0f);
    impl_->parallel_for(positions.size(), [&](std::size_t index) {
        const glm::vec3 p = positions[index];
        if (has_nan(p)) return;
        const glm::vec3 n = facing_normal(normals[index], glm::vec3(w));
        const glm::vec3 origin = impl_->origin_for(p, n);
        const auto point = static_cast<std::uint32_t>(index);
        std::uint32_t visible = 0;
        for (std::uint32_t s = 0; s < sample_count; ++s) {
            const glm::dvec3 dir = frame.direction(stratified_sample(point, s, samples_per_axis));
            if (impl_->unoccluded(origin, glm::vec3(dir), std::numeric_limits<float>::infinity())) ++visible;
        }
        result[index] = static_cast<float>(visible) / static_cast<float>(sample_count);
    });
    impl_->throw_if_error("tracing rays to the sun");
    return result;
}

std::vector<std::uint8_t> GroundTruth::unoccluded(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                                  std::span<const glm::vec3> directions) const {
    check_inputs(positions, normals, 1);
    const std::size_t count = directions.size();
    std::vector<std::uint8_t> result(positions.size() * count, 1);
    impl_->parallel_for(positions.size(), [&](std::size_t index) {
        const glm::vec3 p = positions[index];
        if (has_nan(p)) return;
        // the normal turns towards each direction, so it is one of two sides: lift each once
        const glm::vec3 front = facing_normal(normals[index], normals[index]);
        const glm::vec3 origins[2] = {impl_->origin_for(p, front), impl_->origin_for(p, -front)};
        for (std::size_t d = 0; d < count; ++d) {
            const glm::vec3 origin = origins[glm::dot(front, directions[d]) < 0.0f ? 1 : 0];
            result[index * count + d] =
                impl_->unoccluded(origin, directions[d], std::numeric_limits<float>::infinity()) ? 1 : 0;
        }
    });
    impl_->throw_if_error("tracing rays along directions");
    return result;
}

std::vector<float> GroundTruth::visibility(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                                           std::span<const glm::vec3> directions) const {
    if (directions.empty()) throw GroundTruthError("ground truth: a light of no directions");
    const std::vector<std::uint8_t> open = unoccluded(positions, normals, directions);
    std::vector<float> result(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) {
        std::size_t visible = 0;
        for (std::size_t d = 0; d < directions.size(); ++d) visible += open[i * directions.size() + d];
        result[i] = static_cast<float>(visible) / static_cast<float>(directions.size());
    }
    return result;
}

} // namespace penumbra::playground
