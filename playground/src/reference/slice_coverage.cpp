// playground/src/reference/slice_coverage.cpp
#include "reference/slice_coverage.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::playground {

namespace {

// Texture coordinates (texels), depth along the light and clip w of a world point, from docs/model.md §1
// (rect: perspective from E = C − d·N; sun: orthographic along the light), not from the slicing
// camera's matrix.
struct Projected {
    glm::dvec2 texel;
    double depth = 0, w = 1;
};

Projected project(const Config& config, const SliceFrame& frame, glm::dvec3 world) {
    const glm::dvec3 p = glm::dvec3(glm::dmat4(frame.light_from_world) * glm::dvec4(world, 1.0));
    Projected out;
    out.depth = p.z;
    glm::dvec2 uv;
    if (config.light == Light::rect) {
        const double d = frame.cop_distance;
        out.w = d + p.z;
        uv = 0.5 + glm::dvec2(p) * d / (out.w * glm::dvec2(frame.light_size));
    } else {
        uv = 0.5 + glm::dvec2(p) / (2.0 * static_cast<double>(frame.window_half_size));
    }
    out.texel = uv * static_cast<double>(config.resolution);
    return out;
}

// The cut at texture coordinate `uv`: covered, empty, or either when a neighbour within rounding
// of the texture's texel grid decides otherwise.
Coverage cut_at(const CutMaterial& m, glm::dvec2 uv) {
    const double margin_u = 0.01 / m.texture.width, margin_v = 0.01 / m.texture.height;
    const bool solid = m.solid_at(glm::vec2(uv));
    for (const glm::dvec2 d : {glm::dvec2(margin_u, 0), glm::dvec2(-margin_u, 0), glm::dvec2(0, margin_v),
                               glm::dvec2(0, -margin_v)})
        if (m.solid_at(glm::vec2(uv + d)) != solid) return Coverage::either;
    return solid ? Coverage::covered : Coverage::empty;
}

// solid_casters: one fragment of a closed part toggles every slice from `first` down; from `either`
// down (either <= first) it may or may not (a texel at the triangle's edge, a depth on a slice boundary).
struct Toggle {
    int either, first;
    bool certain; // false: the texel centre may be outside the triangle
};

// The slices a closed part's toggles mark (odd count) at one texel, merged into `out`.
void apply_toggles(SliceCoverage& out, int x, int y, const std::vector<Toggle>& toggles) {
    for (int s = 0; s < out.slices; ++s) {
        int parity = 0;
        bool unsure = false;
        for (const Toggle& t : toggles) {
            if (s >= t.first && t.certain) parity ^= 1;
            if (s >= t.either && (!t.certain || s < t.first)) unsure = true;
        }
        const Coverage c = unsure ? Coverage::either : parity ? Coverage::covered : Coverage::empty;
        out.at(s, x, y) = std::max(out.at(s, x, y), c);
    }
}

// A corner of a triangle, or of the part of it in front of the light's plane.
struct Corner {
    glm::dvec3 world;
    glm::dvec2 material_uv{0.0};
};

// Rect light: the part of triangle `corners` in front of the light's plane (light-frame depth > 0), as
// a fan of triangles in the same winding, as the GPU's light passes keep it (docs/model.md §1.2b: they
// discard fragments at depth <= 0; the rasteriser's own clip at w = 0, the centre of projection, lies
// behind the plane). The sun keeps every triangle whole.
std::vector<std::array<Corner, 3>> in_front_of_light(const Config& config, const SliceFrame& frame,
                                                     const std::array<Corner, 3>& corners) {
    if (config.light != Light::rect) return {corners};
    const glm::dmat4 lfw(frame.light_from_world);
    double depth[3];
    int in_front = 0;
    for (int k = 0; k < 3; ++k) in_front += (depth[k] = (lfw * glm::dvec4(corners[k].world, 1.0)).z) > 0.0;
    if (in_front == 3) return {corners};
    if (in_front == 0) return {};
    std::vector<Corner> polygon; // Sutherland–Hodgman against depth > 0
    for (int k = 0; k < 3; ++k) {
        const int next = (k + 1) % 3;
        if (depth[k] > 0.0) polygon.push_back(corners[k]);
        if ((depth[k] > 0.0) != (depth[next] > 0.0)) {
            const double t = depth[k] / (depth[k] - depth[next]);
            polygon.push_back({glm::mix(corners[k].world, corners[next].world, t),
                               glm::mix(corners[k].material_uv, corners[next].material_uv, t)});
        }
    }
    std::vector<std::array<Corner, 3>> fan;
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
        fan.push_back({polygon[0], polygon[k], polygon[k + 1]});
    return fan;
}

} // namespace

SliceCoverage cpu_slice_coverage(const Mesh& mesh, const Config& config, const SliceFrame& frame, int reach,
                                 bool cut) {
    const int R = config.resolution, S = config.slices;
    SliceCoverage out{R, S, std::vector<Coverage>(static_cast<std::size_t>(S) * R * R, Coverage::empty)};
    const double z0 = frame.slice_depths.x, thickness = frame.slice_depths.y;
    std::vector<std::vector<Toggle>> toggles(config.solid_casters ? static_cast<std::size_t>(R) * R : 0);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const bool closed = config.solid_casters && mesh.closed(t);
        const CutMaterial* material = cut ? mesh.material_of(t) : nullptr;
        std::array<Corner, 3> whole;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t index = mesh.indices[3 * t + k];
            whole[k] = {glm::dvec3(mesh.positions[index]),
                        material ? glm::dvec2(mesh.material_uvs[index]) : glm::dvec2(0.0)};
        }
        for (const std::array<Corner, 3>& part : in_front_of_light(config, frame, whole)) {
            Projected v[3];
            for (int k = 0; k < 3; ++k) v[k] = project(config, frame, part[k].world);
            // Signed edge functions in texels; the triangle's orientation does not matter.
            const glm::dvec2 a0 = v[0].texel, a1 = v[1].texel, a2 = v[2].texel;
            const double area = (a1.x - a0.x) * (a2.y - a0.y) - (a2.x - a0.x) * (a1.y - a0.y);
            if (std::abs(area) < 1e-12) continue;
            const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a0.x, a1.x, a2.x}))) - 1);
            const int x1 = std::min(R - 1, static_cast<int>(std::ceil(std::max({a0.x, a1.x, a2.x}))) + 1);
            const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a0.y, a1.y, a2.y}))) - 1);
            const int y1 = std::min(R - 1, static_cast<int>(std::ceil(std::max({a0.y, a1.y, a2.y}))) + 1);
            for (int y = y0; y <= y1; ++y)
                for (int x = x0; x <= x1; ++x) {
                    const glm::dvec2 c(x + 0.5, y + 0.5);
                    double barycentric[3], nearest_edge = 1e30;
                    for (int k = 0; k < 3; ++k) {
                        const glm::dvec2 a = v[(k + 1) % 3].texel, b = v[(k + 2) % 3].texel;
                        const double edge = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
                        barycentric[k] = edge / area;
                        nearest_edge = std::min(nearest_edge, std::abs(edge) / glm::length(b - a));
                    }
                    const bool inside = barycentric[0] >= 0 && barycentric[1] >= 0 && barycentric[2] >= 0;
                    if (!inside && nearest_edge >= 1.0) continue;
                    Coverage mark = inside && nearest_edge >= 1.0 ? Coverage::covered : Coverage::either;
                    // Perspective-correct weights (the rasteriser divides by clip w).
                    double weight[3], sum = 0;
                    for (int k = 0; k < 3; ++k) sum += weight[k] = barycentric[k] / v[k].w;
                    for (double& w : weight) w /= sum;
                    if (material) {
                        glm::dvec2 uv(0.0);
                        for (int k = 0; k < 3; ++k) uv += weight[k] * part[k].material_uv;
                        const Coverage alpha = cut_at(*material, uv);
                        if (alpha == Coverage::empty) continue; // the alpha test discards the fragment
                        if (alpha == Coverage::either) mark = Coverage::either;
                    }
                    const double z = weight[0] * v[0].depth + weight[1] * v[1].depth + weight[2] * v[2].depth;
                    // on the light's plane the GPU's fp32 depth may fall on either side of its discard
                    if (config.light == Light::rect && z < 1e-5 * thickness) mark = Coverage::either;
                    const double position = (z - z0) / thickness;
                    const int slice = std::clamp(static_cast<int>(std::ceil(position)) - 1, 0, S - 1);
                    // within rounding of plane n, the GPU's fp32 depth may fall in slice n − 1 or n,
                    // whichever side of it the exact depth is
                    const double plane = std::round(position);
                    const bool on_boundary = std::abs(position - plane) < 1e-4;
                    const int upper = on_boundary ? std::clamp(static_cast<int>(plane) - 1, 0, S - 1) : slice;
                    const int lower = on_boundary ? std::clamp(static_cast<int>(plane), 0, S - 1) : slice;
                    if (closed) {
                        // The slicing camera mirrors OpenGL's eye space, so a face towards the light winds
                        // clockwise in texel space (area < 0): the ray enters there and toggles from its own
                        // slice; where it leaves (area > 0), from the next one.
                        const int exit = area > 0 ? 1 : 0;
                        toggles[static_cast<std::size_t>(y) * R + x].push_back({std::min(upper + exit, S),
                                                                                std::min(lower + exit, S),
                                                                                mark == Coverage::covered});
                        continue;
                    }
                    for (int s = upper; s <= lower; ++s) {
                        const Coverage m = on_boundary ? Coverage::either : mark;
                        // paper §3.4.1 leak fix: a fragment of slice k also marks slices k+1 to k+reach
                        for (int j = 0; j <= reach && s + j < S; ++j)
                            out.at(s + j, x, y) = std::max(out.at(s + j, x, y), m);
                    }
                }
        }
    }
    for (int y = 0; y < R && !toggles.empty(); ++y)
        for (int x = 0; x < R; ++x)
            if (const auto& list = toggles[static_cast<std::size_t>(y) * R + x]; !list.empty())
                apply_toggles(out, x, y, list);
    return out;
}

} // namespace penumbra::playground
