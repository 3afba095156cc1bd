// playground/src/scenes/uv_coverage.cpp
#include "scenes/uv_coverage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace penumbra::playground {

namespace {

using Vec2 = glm::dvec2;

double cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

// Corners of triangle `t` in texel units.
std::array<Vec2, 3> texel_corners(const Mesh& mesh, std::size_t t, int resolution) {
    std::array<Vec2, 3> c;
    for (int k = 0; k < 3; ++k) c[k] = Vec2(mesh.uvs[mesh.indices[3 * t + k]]) * static_cast<double>(resolution);
    return c;
}

// Barycentric coordinates of the point of triangle abc closest to p (Ericson, Real-Time Collision
// Detection §5.1.5, in 2D).
glm::dvec3 closest_barycentric(Vec2 p, Vec2 a, Vec2 b, Vec2 c) {
    const Vec2 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
    const Vec2 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    const Vec2 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    const double denom = 1.0 / (va + vb + vc);
    const double v = vb * denom, w = vc * denom;
    return {1 - v - w, v, w};
}

// Texels whose centres can be within `reach` texels of the triangle: the inclusive range.
struct TexelRange {
    int x0, y0, x1, y1;
};

TexelRange texel_range(const std::array<Vec2, 3>& c, double reach, int resolution) {
    const double lo_x = std::min({c[0].x, c[1].x, c[2].x}) - reach, hi_x = std::max({c[0].x, c[1].x, c[2].x}) + reach;
    const double lo_y = std::min({c[0].y, c[1].y, c[2].y}) - reach, hi_y = std::max({c[0].y, c[1].y, c[2].y}) + reach;
    auto clamp_texel = [&](double v) { return static_cast<int>(std::clamp(v, -1.0, static_cast<double>(resolution))); };
    return {std::max(clamp_texel(std::floor(lo_x - 0.5)), 0), std::max(clamp_texel(std::floor(lo_y - 0.5)), 0),
            std::min(clamp_texel(std::ceil(hi_x - 0.5)), resolution - 1),
            std::min(clamp_texel(std::ceil(hi_y - 0.5)), resolution - 1)};
}

// Top-left rule for a counter-clockwise triangle with y up: the interior lies left of each edge;
// left edges go down, top edges go towards −x.
bool top_left(Vec2 a, Vec2 b) {
    const Vec2 d = b - a;
    return d.y < 0 || (d.y == 0 && d.x < 0);
}

bool covers_centre(std::array<Vec2, 3> c, Vec2 p) {
    if (cross2(c[1] - c[0], c[2] - c[0]) < 0) std::swap(c[1], c[2]);
    for (int k = 0; k < 3; ++k) {
        const Vec2 a = c[k], b = c[(k + 1) % 3];
        const double e = cross2(b - a, p - a);
        if (e < 0 || (e == 0 && !top_left(a, b))) return false;
    }
    return true;
}

} // namespace

std::vector<TexelSample> texel_samples(const Mesh& mesh, int resolution) {
    const auto R = static_cast<std::size_t>(resolution);
    std::vector<TexelSample> texels(R * R);
    std::vector<double> best(R * R, 0.5 + 1e-9); // squared half diagonal: the texel square can touch the triangle
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const std::array<Vec2, 3> c = texel_corners(mesh, t, resolution);
        const TexelRange r = texel_range(c, 0.75, resolution);
        for (int y = r.y0; y <= r.y1; ++y)
            for (int x = r.x0; x <= r.x1; ++x) {
                const Vec2 centre(x + 0.5, y + 0.5);
                const glm::dvec3 w = closest_barycentric(centre, c[0], c[1], c[2]);
                const Vec2 q = w.x * c[0] + w.y * c[1] + w.z * c[2];
                const double d2 = glm::dot(q - centre, q - centre);
                const std::size_t i = static_cast<std::size_t>(y) * R + static_cast<std::size_t>(x);
                if (!(d2 < best[i])) continue;
                best[i] = d2;
                const std::uint32_t* v = &mesh.indices[3 * t];
                TexelSample& s = texels[i];
                s.triangle = static_cast<std::int32_t>(t);
                s.position = glm::vec3(w.x * glm::dvec3(mesh.positions[v[0]]) + w.y * glm::dvec3(mesh.positions[v[1]]) +
                                       w.z * glm::dvec3(mesh.positions[v[2]]));
                const glm::vec3 n = static_cast<float>(w.x) * mesh.normals[v[0]] +
                                    static_cast<float>(w.y) * mesh.normals[v[1]] + static_cast<float>(w.z) * mesh.normals[v[2]];
                const float len = glm::length(n);
                s.normal = len > 0.0f ? n / len : mesh.normals[v[0]];
            }
    }
    return texels;
}

std::optional<UvOverlap> find_uv_overlap(const Mesh& mesh, int resolution) {
    const auto R = static_cast<std::size_t>(resolution);
    std::vector<std::int64_t> owner(R * R, -1);
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const std::array<Vec2, 3> c = texel_corners(mesh, t, resolution);
        const TexelRange r = texel_range(c, 0.0, resolution);
        for (int y = r.y0; y <= r.y1; ++y)
            for (int x = r.x0; x <= r.x1; ++x) {
                if (!covers_centre(c, Vec2(x + 0.5, y + 0.5))) continue;
                std::int64_t& o = owner[static_cast<std::size_t>(y) * R + static_cast<std::size_t>(x)];
                if (o >= 0) return UvOverlap{static_cast<std::size_t>(o), t, x, y};
                o = static_cast<std::int64_t>(t);
            }
    }
    return std::nullopt;
}

std::string check_unique_uvs(const Mesh& mesh, int resolution) {
    std::ostringstream out;
    if (mesh.uvs.empty()) return "has no texture coordinates (occlusion interval maps need a unique parameterization)";
    for (std::size_t i = 0; i < mesh.uvs.size(); ++i) {
        const glm::vec2 uv = mesh.uvs[i];
        if (!(uv.x >= 0.0f && uv.x <= 1.0f && uv.y >= 0.0f && uv.y <= 1.0f)) {
            out << "texture coordinate (" << uv.x << ", " << uv.y << ") of vertex " << i
                << " lies outside [0,1]² (tiled coordinates repeat, so they are not unique); allowed: a unique "
                   "parameterization inside [0,1]²";
            return out.str();
        }
    }
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
        const std::array<Vec2, 3> c = texel_corners(mesh, t, resolution);
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]];
        const bool has_area = glm::length(glm::cross(mesh.positions[mesh.indices[3 * t + 1]] - a,
                                                     mesh.positions[mesh.indices[3 * t + 2]] - a)) > 0.0f;
        if (has_area && cross2(c[1] - c[0], c[2] - c[0]) == 0.0) {
            out << "triangle " << t << " has no area in texture space (its points would share texels); allowed: "
                << "a unique parameterization";
            return out.str();
        }
    }
    if (const std::optional<UvOverlap> o = find_uv_overlap(mesh, resolution)) {
        out << "texture coordinates overlap: triangles " << o->first << " and " << o->second << " both cover texel ("
            << o->x << ", " << o->y << ") at resolution " << resolution
            << "; occlusion interval maps need non-overlapping texture coordinates (one texel, one surface point)";
        return out.str();
    }
    return {};
}

} // namespace penumbra::playground
