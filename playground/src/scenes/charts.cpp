// playground/src/scenes/charts.cpp
#include "scenes/charts.hpp"

#include "scenes/uv_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <utility>

namespace penumbra::playground {

namespace {

// Smallest area ratio (projected / true) a triangle may keep in its chart.
constexpr double min_area_ratio = 0.2;

struct UnionFind {
    std::vector<std::uint32_t> parent;
    explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
    std::uint32_t find(std::uint32_t i) {
        while (parent[i] != i) i = parent[i] = parent[parent[i]];
        return i;
    }
    void join(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }
};

struct Chart {
    glm::dvec3 u{0.0}, v{0.0};            // projection axes
    glm::dvec2 lo{1e300}, hi{-1e300};     // bounds of the projected corners (scene units)
    glm::ivec2 cell{0};                   // packed position (texels)
};

glm::dvec3 face_cross(const Mesh& mesh, std::size_t t) {
    const glm::dvec3 a(mesh.positions[mesh.indices[3 * t]]);
    return glm::cross(glm::dvec3(mesh.positions[mesh.indices[3 * t + 1]]) - a,
                      glm::dvec3(mesh.positions[mesh.indices[3 * t + 2]]) - a);
}

// Axes u, v perpendicular to n, u along `along` (projected), so (u, v, n) is right-handed.
std::pair<glm::dvec3, glm::dvec3> plane_axes(glm::dvec3 n, glm::dvec3 along) {
    n = glm::normalize(n);
    glm::dvec3 u = along - glm::dot(along, n) * n;
    if (glm::length(u) < 1e-12) u = glm::cross(std::abs(n.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0), n);
    u = glm::normalize(u);
    return {u, glm::cross(n, u)};
}

// Longest edge of triangle t.
glm::dvec3 longest_edge(const Mesh& mesh, std::size_t t) {
    glm::dvec3 best(0.0);
    for (int k = 0; k < 3; ++k) {
        const glm::dvec3 e = glm::dvec3(mesh.positions[mesh.indices[3 * t + (k + 1) % 3]]) -
                             glm::dvec3(mesh.positions[mesh.indices[3 * t + k]]);
        if (glm::length(e) > glm::length(best)) best = e;
    }
    return best;
}

// Cell of a chart at `density` texels per scene unit: the chart starts half a texel in, and the
// cell ends at least a texel and a half after it.
glm::ivec2 cell_size(const Chart& c, double density) {
    const glm::dvec2 extent = (c.hi - c.lo) * density;
    return {static_cast<int>(std::floor(0.5 + extent.x)) + 2, static_cast<int>(std::floor(0.5 + extent.y)) + 2};
}

// Shelf packing, tallest first; false when the charts do not fit in resolution².
bool pack(std::vector<Chart>& charts, const std::vector<std::size_t>& order, double density, int resolution) {
    int x = 0, y = 0, row = 0;
    for (std::size_t i : order) {
        const glm::ivec2 size = cell_size(charts[i], density);
        if (size.x > resolution) return false;
        if (x + size.x > resolution) {
            y += row;
            x = 0;
            row = 0;
        }
        if (y + size.y > resolution) return false;
        charts[i].cell = {x, y};
        x += size.x;
        row = std::max(row, size.y);
    }
    return true;
}

} // namespace

std::string generate_charts(Mesh& mesh, int resolution) {
    const std::size_t triangles = mesh.triangle_count();
    if (triangles == 0) return "has no triangles to parameterize";

    // Connected pieces: triangles that share a vertex.
    UnionFind pieces(mesh.positions.size());
    for (std::size_t t = 0; t < triangles; ++t) {
        pieces.join(mesh.indices[3 * t], mesh.indices[3 * t + 1]);
        pieces.join(mesh.indices[3 * t], mesh.indices[3 * t + 2]);
    }
    std::map<std::uint32_t, std::vector<std::size_t>> piece_triangles;
    for (std::size_t t = 0; t < triangles; ++t) piece_triangles[pieces.find(mesh.indices[3 * t])].push_back(t);

    // One chart per piece, or per triangle where the piece's projection would fold or squash.
    std::vector<Chart> charts;
    std::vector<std::uint32_t> chart_of(triangles);
    for (const auto& [root, members] : piece_triangles) {
        glm::dvec3 normal(0.0);
        double area = 0.0;
        std::size_t largest = members.front();
        for (std::size_t t : members) {
            const glm::dvec3 c = face_cross(mesh, t);
            normal += c;
            area += glm::length(c);
            if (glm::length(c) > glm::length(face_cross(mesh, largest))) largest = t;
        }
        bool one_chart = glm::length(normal) > 1e-9 * area;
        if (one_chart) {
            const glm::dvec3 n = glm::normalize(normal);
            for (std::size_t t : members) {
                const glm::dvec3 c = face_cross(mesh, t);
                if (glm::dot(c, n) < min_area_ratio * glm::length(c)) one_chart = false;
            }
        }
        if (one_chart) {
            Chart chart;
            std::tie(chart.u, chart.v) = plane_axes(normal, longest_edge(mesh, largest));
            for (std::size_t t : members) chart_of[t] = static_cast<std::uint32_t>(charts.size());
            charts.push_back(chart);
            continue;
        }
        for (std::size_t t : members) {
            Chart chart;
            const glm::dvec3 c = face_cross(mesh, t);
            std::tie(chart.u, chart.v) = plane_axes(glm::length(c) > 0.0 ? c : glm::dvec3(0, 1, 0), longest_edge(mesh, t));
            chart_of[t] = static_cast<std::uint32_t>(charts.size());
            charts.push_back(chart);
        }
    }

    // Vertices per (chart, original vertex): pieces split into several charts get their own copies.
    Mesh out;
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> vertex_of;
    std::vector<glm::dvec2> local; // projected position of each new vertex (scene units)
    std::vector<std::uint32_t> vertex_chart;
    for (std::size_t t = 0; t < triangles; ++t) {
        Chart& chart = charts[chart_of[t]];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t old = mesh.indices[3 * t + k];
            auto [it, added] = vertex_of.try_emplace({chart_of[t], old}, static_cast<std::uint32_t>(out.positions.size()));
            if (added) {
                const glm::dvec3 p(mesh.positions[old]);
                const glm::dvec2 q(glm::dot(p, chart.u), glm::dot(p, chart.v));
                chart.lo = glm::min(chart.lo, q);
                chart.hi = glm::max(chart.hi, q);
                out.positions.push_back(mesh.positions[old]);
                out.normals.push_back(mesh.normals[old]);
                if (mesh.cuts()) out.material_uvs.push_back(mesh.material_uvs[old]);
                local.push_back(q);
                vertex_chart.push_back(chart_of[t]);
            }
            out.indices.push_back(it->second);
        }
    }

    // The largest density at which the rows fit (bisection; the cells only grow with it).
    std::vector<std::size_t> order(charts.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return charts[a].hi.y - charts[a].lo.y > charts[b].hi.y - charts[b].lo.y;
    });
    if (!pack(charts, order, 0.0, resolution)) {
        int needed = resolution;
        while (needed < (1 << 16) && !pack(charts, order, 0.0, needed)) needed *= 2;
        return std::to_string(charts.size()) + " charts do not fit in " + std::to_string(resolution) + "x" +
               std::to_string(resolution) + " texels (each needs at least 2x2); allowed: resolution " +
               std::to_string(needed) + " or more";
    }
    double lo = 0.0, hi = 1.0;
    while (hi < 1e12 && pack(charts, order, hi, resolution)) hi *= 2.0;
    for (int i = 0; i < 40; ++i) {
        const double mid = 0.5 * (lo + hi);
        (pack(charts, order, mid, resolution) ? lo : hi) = mid;
    }
    pack(charts, order, lo, resolution);

    out.cut_materials = std::move(mesh.cut_materials); // triangles keep their order
    out.triangle_materials = std::move(mesh.triangle_materials);
    out.uvs.resize(out.positions.size());
    for (std::size_t i = 0; i < out.positions.size(); ++i) {
        const Chart& c = charts[vertex_chart[i]];
        const glm::dvec2 texel = glm::dvec2(c.cell) + 0.5 + (local[i] - c.lo) * lo;
        out.uvs[i] = glm::vec2(texel / static_cast<double>(resolution));
    }
    mesh = std::move(out);
    if (std::string problem = find_uv_overlap(mesh, resolution) ? "generated charts overlap (a bug in the packer)" : "";
        !problem.empty())
        return problem;
    return {};
}

} // namespace penumbra::playground
