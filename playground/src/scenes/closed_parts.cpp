// playground/src/scenes/closed_parts.cpp
#include "scenes/closed_parts.hpp"

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <tuple>

namespace penumbra::playground {

namespace {

// The smallest vertex index at each vertex's position: corners that coincide are one corner (meshes
// repeat a position per face for its normals or texture coordinates).
std::vector<std::uint32_t> welded_vertices(const Mesh& mesh) {
    std::vector<std::uint32_t> order(mesh.positions.size());
    std::iota(order.begin(), order.end(), 0u);
    const auto key = [&](std::uint32_t i) {
        const glm::vec3& p = mesh.positions[i];
        return std::make_tuple(p.x, p.y, p.z, i);
    };
    std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return key(a) < key(b); });
    std::vector<std::uint32_t> weld(mesh.positions.size());
    for (std::size_t j = 0; j < order.size(); ++j) {
        const bool same = j > 0 && mesh.positions[order[j]] == mesh.positions[order[j - 1]];
        weld[order[j]] = same ? weld[order[j - 1]] : order[j];
    }
    return weld;
}

std::uint32_t find_root(std::vector<std::uint32_t>& parent, std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
}

} // namespace

std::vector<std::uint8_t> closed_triangles(const Mesh& mesh) {
    const std::size_t triangles = mesh.triangle_count();
    const std::vector<std::uint32_t> weld = welded_vertices(mesh);
    // Parts: triangles joined through their welded corners.
    std::vector<std::uint32_t> parent(mesh.positions.size());
    std::iota(parent.begin(), parent.end(), 0u);
    for (std::size_t t = 0; t < triangles; ++t)
        for (int k = 1; k < 3; ++k) {
            const std::uint32_t a = find_root(parent, weld[mesh.indices[3 * t]]);
            const std::uint32_t b = find_root(parent, weld[mesh.indices[3 * t + k]]);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
    // Every edge of a closed part is used by an even number of its triangles: then every ray crosses it
    // an even number of times, in and out, which is what the slices' XOR needs. Two triangles in the
    // same direction (a duplicated face), or four around one edge, still pair up.
    struct Edge {
        std::uint32_t low, high, part;
        bool operator<(const Edge& o) const { return std::tie(low, high) < std::tie(o.low, o.high); }
        bool operator==(const Edge& o) const { return low == o.low && high == o.high; }
    };
    std::vector<Edge> edges;
    edges.reserve(3 * triangles);
    std::vector<std::uint8_t> open_part(mesh.positions.size(), 0);
    for (std::size_t t = 0; t < triangles; ++t) {
        const std::uint32_t part = find_root(parent, weld[mesh.indices[3 * t]]);
        if (mesh.material_of(t)) open_part[part] = 1; // a cut opens its part
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = weld[mesh.indices[3 * t + k]], b = weld[mesh.indices[3 * t + (k + 1) % 3]];
            if (a == b) open_part[part] = 1; // a degenerate edge
            edges.push_back({std::min(a, b), std::max(a, b), part});
        }
    }
    std::sort(edges.begin(), edges.end());
    for (std::size_t i = 0; i < edges.size();) {
        std::size_t j = i;
        while (j < edges.size() && edges[j] == edges[i]) ++j;
        if ((j - i) % 2 != 0) open_part[edges[i].part] = 1;
        i = j;
    }
    std::vector<std::uint8_t> closed(triangles, 0);
    for (std::size_t t = 0; t < triangles; ++t)
        closed[t] = open_part[find_root(parent, weld[mesh.indices[3 * t]])] ? 0 : 1;
    return closed;
}

} // namespace penumbra::playground
