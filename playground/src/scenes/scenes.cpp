// playground/src/scenes/scenes.cpp — procedural scene generators.
#include "scenes/scenes.hpp"

#include "scenes/deterministic_random.hpp"
#include "scenes/mesh_builder.hpp"
#include "scenes/scene_defaults.hpp"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace penumbra::playground {

namespace {

constexpr float ground_size = 10.0f;

void add_ground(Mesh& mesh) { add_horizontal_rect(mesh, 0.0f, 0.0f, 0.0f, ground_size, ground_size); }

glm::mat4 box_transform(glm::vec3 centre, glm::vec3 size, float yaw = 0.0f) {
    glm::mat4 m = glm::translate(glm::mat4(1.0f), centre);
    m = glm::rotate(m, yaw, glm::vec3(0, 1, 0));
    return glm::scale(m, size);
}

// A box of cross-section `thickness` from `start` along unit `direction` for `length`.
glm::mat4 beam_transform(glm::vec3 start, glm::vec3 direction, float length, float thickness) {
    // Rotate +y onto `direction`; the axis is undefined when they are parallel.
    const glm::vec3 up(0, 1, 0);
    glm::mat4 rotation(1.0f);
    const glm::vec3 axis = glm::cross(up, direction);
    const float s = glm::length(axis);
    if (s > 1e-6f) rotation = glm::rotate(glm::mat4(1.0f), std::atan2(s, glm::dot(up, direction)), axis / s);
    glm::mat4 m = glm::translate(glm::mat4(1.0f), start) * rotation;
    m = glm::translate(m, glm::vec3(0, 0.5f * length, 0));
    return glm::scale(m, glm::vec3(thickness, length, thickness));
}

// Ground plus three horizontal quads at the heights in planes_occluder_heights: each occluder
// is parallel to the light, so shadows on the ground have an exact answer (a box filter of the
// occluders' coverage), and each occluder also shadows the ones below it.
Mesh build_planes() {
    Mesh mesh;
    add_ground(mesh);
    add_horizontal_rect(mesh, -1.5f, planes_occluder_heights[0], 0.5f, 3.0f, 2.0f);
    add_horizontal_rect(mesh, 1.0f, planes_occluder_heights[1], -0.5f, 2.0f, 2.0f);
    add_horizontal_rect(mesh, 0.0f, planes_occluder_heights[2], 1.5f, 1.5f, 1.0f);
    return mesh;
}

// Ground plus a cluster of boxes that intersect each other and partly hover, like the paper's
// Fig. 3: occluders overlap in depth, which is what occluder fusion gets wrong or right.
Mesh build_boxes() {
    Mesh mesh;
    add_ground(mesh);
    DeterministicRandom rng(0x0b0c5e5u);
    for (int i = 0; i < 9; ++i) {
        const glm::vec3 size(rng.uniform(0.6f, 1.8f), rng.uniform(0.5f, 2.0f), rng.uniform(0.6f, 1.8f));
        // Two thirds stand on the ground, one third float (shadows detached from their caster).
        const float base = (i % 3 == 2) ? rng.uniform(0.4f, 1.0f) : 0.0f;
        const glm::vec3 centre(rng.uniform(-2.2f, 2.2f), base + 0.5f * size.y, rng.uniform(-2.2f, 2.2f));
        add_box(mesh, box_transform(centre, size, rng.uniform(0.0f, 0.5f * glm::pi<float>())));
    }
    return mesh;
}

// A trunk, a few branches, and several hundred small randomly oriented leaf quads: many small
// overlapping occluders at many depths (the hard case for slicing).
Mesh build_tree() {
    Mesh mesh;
    add_ground(mesh);
    DeterministicRandom rng(0x7ee5u);
    const float trunk_height = 1.8f;
    add_box(mesh, box_transform({0.0f, 0.5f * trunk_height, 0.0f}, {0.3f, trunk_height, 0.3f}));

    std::vector<glm::vec3> tips{{0.0f, trunk_height, 0.0f}};
    const int branch_count = 6;
    for (int i = 0; i < branch_count; ++i) {
        const float start_y = rng.uniform(1.0f, 1.7f);
        const float yaw = 2.0f * glm::pi<float>() * (static_cast<float>(i) + rng.uniform(0.0f, 0.6f)) / branch_count;
        const float tilt = glm::radians(rng.uniform(35.0f, 60.0f));
        const glm::vec3 dir(std::sin(tilt) * std::cos(yaw), std::cos(tilt), std::sin(tilt) * std::sin(yaw));
        const float length = rng.uniform(0.8f, 1.2f);
        const glm::vec3 start(0.0f, start_y, 0.0f);
        add_box(mesh, beam_transform(start, dir, length, 0.08f));
        tips.push_back(start + length * dir);
    }

    const int leaf_count = 600;
    for (int i = 0; i < leaf_count; ++i) {
        const glm::vec3 tip = tips[rng.below(static_cast<std::uint32_t>(tips.size()))];
        // A point in a ball of radius 0.6 around the tip (rejection sampling stays deterministic).
        glm::vec3 offset;
        do {
            offset = glm::vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        } while (glm::dot(offset, offset) > 1.0f);
        glm::vec3 centre = tip + 0.6f * offset;
        centre.y = std::min(centre.y, 2.95f);
        // A random orientation: leaf normal mostly upward-ish but anything is allowed.
        const float yaw = rng.uniform(0.0f, 2.0f * glm::pi<float>());
        const float pitch = rng.uniform(-1.2f, 1.2f);
        const glm::vec3 across(std::cos(yaw), 0.0f, std::sin(yaw));
        const glm::vec3 flat_along(-std::sin(yaw), 0.0f, std::cos(yaw));
        const glm::vec3 along = std::cos(pitch) * flat_along + std::sin(pitch) * glm::vec3(0, 1, 0);
        const glm::vec3 a = 0.09f * across;
        const glm::vec3 b = 0.06f * along;
        add_quad(mesh, centre - a - b, centre + a - b, centre + a + b, centre - a + b);
    }
    return mesh;
}

// One wing: a fan of triangles, two sheets 5 mm apart with opposite facing (the wing is "a
// couple of triangles thick" and nothing more). Wings this thin fall inside a single slice, so
// they are the test for the paper's leak fix (§3.4.1).
void add_wing(Mesh& mesh, const std::vector<glm::vec3>& outline, glm::vec3 root) {
    const glm::vec3 sheet_gap(0.0f, 0.005f, 0.0f);
    for (std::size_t i = 0; i + 1 < outline.size(); ++i) {
        add_triangle(mesh, root, outline[i], outline[i + 1]);                                     // top, +y
        add_triangle(mesh, root - sheet_gap, outline[i + 1] - sheet_gap, outline[i] - sheet_gap); // bottom, −y
    }
}

Mesh make_butterfly_model() {
    Mesh model;
    // Body along z (head at +z).
    add_box(model, box_transform({0.0f, 0.0f, 0.0f}, {0.12f, 0.12f, 1.3f}));
    // Right wing outlines (x > 0), ordered so that the fan (root, o[i], o[i+1]) faces +y.
    // Wing tips rise slightly (a 10° dihedral), as a resting butterfly's would.
    const float dihedral = std::tan(glm::radians(10.0f));
    auto p = [&](float x, float z) { return glm::vec3(x, dihedral * x, z); };
    const std::vector<glm::vec3> forewing{p(0.06f, 0.45f), p(0.8f, 0.95f), p(1.6f, 1.05f),
                                          p(1.95f, 0.6f),  p(1.5f, 0.1f),  p(0.6f, -0.05f),
                                          p(0.06f, -0.05f)};
    const std::vector<glm::vec3> hindwing{p(0.06f, -0.1f), p(0.9f, -0.3f),  p(1.3f, -0.8f),
                                          p(0.9f, -1.25f), p(0.4f, -1.05f), p(0.06f, -0.55f)};
    Mesh right;
    add_wing(right, forewing, p(0.06f, 0.2f));
    add_wing(right, hindwing, p(0.06f, -0.3f));
    append_mesh(model, right, glm::mat4(1.0f));
    // The left wing is the mirror image (append_mesh fixes the winding of mirrored copies).
    append_mesh(model, right, glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1)));
    return model;
}

Mesh build_butterfly() {
    Mesh mesh;
    add_ground(mesh);
    const Mesh butterfly = make_butterfly_model();
    // A large one hovering flat (wings parallel to the light: the worst case for leaks) ...
    append_mesh(mesh, butterfly, glm::translate(glm::mat4(1.0f), glm::vec3(-0.5f, 1.5f, 0.3f)));
    // ... and a smaller, banked one close to the ground (contact shadow of a thin occluder).
    glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(2.2f, 0.5f, -1.8f));
    m = glm::rotate(m, glm::radians(40.0f), glm::vec3(0, 1, 0));
    m = glm::rotate(m, glm::radians(20.0f), glm::vec3(0, 0, 1));
    m = glm::scale(m, glm::vec3(0.6f));
    append_mesh(mesh, butterfly, m);
    return mesh;
}

// Smooth rolling heightfield plus seeded bumps; no separate "receiver" plane, so every surface
// both casts and receives (docs/model.md §5).
Mesh build_terrain() {
    DeterministicRandom rng(0x7e55a1u);
    struct Bump { glm::vec2 centre; float amplitude, width; };
    std::array<Bump, 7> bumps{};
    for (Bump& b : bumps)
        b = {{rng.uniform(-4.5f, 4.5f), rng.uniform(-4.5f, 4.5f)}, rng.uniform(0.2f, 0.7f), rng.uniform(0.6f, 1.5f)};
    auto height = [&](float x, float z) {
        float h = 0.3f * std::sin(0.9f * x + 0.3f) * std::cos(0.7f * z - 0.4f) + 0.15f * std::sin(1.7f * x + 2.1f * z);
        for (const Bump& b : bumps) {
            const glm::vec2 d = glm::vec2(x, z) - b.centre;
            h += b.amplitude * std::exp(-glm::dot(d, d) / (b.width * b.width));
        }
        return h;
    };

    const int cells = 96;
    Mesh ground;
    float min_height = 1e30f;
    for (int j = 0; j <= cells; ++j) {
        for (int i = 0; i <= cells; ++i) {
            const float x = ground_size * (static_cast<float>(i) / cells - 0.5f);
            const float z = ground_size * (static_cast<float>(j) / cells - 0.5f);
            const float y = height(x, z);
            min_height = std::min(min_height, y);
            ground.positions.emplace_back(x, y, z);
        }
    }
    // Lowest point at y = 0, like the flat grounds of the other scenes.
    for (glm::vec3& p : ground.positions) p.y -= min_height;
    auto vertex = [&](int i, int j) { return static_cast<std::uint32_t>(j * (cells + 1) + i); };
    for (int j = 0; j < cells; ++j) {
        for (int i = 0; i < cells; ++i) {
            // Counter-clockwise seen from +y (x right, z towards the viewer).
            const std::uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1), d = vertex(i, j + 1);
            ground.indices.insert(ground.indices.end(), {a, d, c, a, c, b});
        }
    }
    compute_vertex_normals(ground);

    Mesh mesh = ground;
    auto ground_y = [&](float x, float z) { return height(x, z) - min_height; };
    // An arch standing on the slope: pillars reach 0.3 below the local ground so no gap shows.
    const float arch_top = ground_y(0.0f, 0.0f) + 2.2f;
    for (float px : {-0.9f, 0.9f}) {
        const float bottom = ground_y(px, 0.0f) - 0.3f;
        add_box(mesh, box_transform({px, 0.5f * (bottom + arch_top), 0.0f}, {0.35f, arch_top - bottom, 0.35f}));
    }
    add_box(mesh, box_transform({0.0f, arch_top + 0.15f, 0.0f}, {2.4f, 0.3f, 0.5f}));
    // A few half-buried rocks.
    for (int i = 0; i < 5; ++i) {
        const float x = rng.uniform(-3.5f, 3.5f), z = rng.uniform(-3.5f, 3.5f);
        const float s = rng.uniform(0.3f, 0.7f);
        glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(x, ground_y(x, z), z));
        m = glm::rotate(m, rng.uniform(0.0f, 3.0f), glm::normalize(glm::vec3(rng.uniform(-1, 1), 1.0f, rng.uniform(-1, 1))));
        add_box(mesh, glm::scale(m, glm::vec3(s, 0.8f * s, 1.2f * s)));
    }
    return mesh;
}

// A simple box figure about 1.5 units tall standing on y = 0, facing +z.
Mesh make_figure() {
    Mesh figure;
    add_box(figure, box_transform({-0.1f, 0.35f, 0.0f}, {0.12f, 0.7f, 0.14f}));  // legs
    add_box(figure, box_transform({0.1f, 0.35f, 0.0f}, {0.12f, 0.7f, 0.14f}));
    add_box(figure, box_transform({0.0f, 1.0f, 0.0f}, {0.4f, 0.6f, 0.22f}));     // torso
    add_box(figure, box_transform({0.0f, 1.42f, 0.0f}, {0.22f, 0.24f, 0.22f}));  // head
    add_box(figure, beam_transform({-0.25f, 1.25f, 0.0f}, glm::normalize(glm::vec3(-0.25f, -1.0f, 0.1f)), 0.6f, 0.1f)); // arms
    add_box(figure, beam_transform({0.25f, 1.25f, 0.0f}, glm::normalize(glm::vec3(0.25f, -1.0f, -0.1f)), 0.6f, 0.1f));
    return figure;
}

// Many copies of one figure on a jittered grid: the scaling scene (triangle count, overdraw).
Mesh build_crowd() {
    Mesh mesh;
    add_ground(mesh);
    const Mesh figure = make_figure();
    DeterministicRandom rng(0xc20d0u);
    const int rows = 16;
    const float spacing = 0.56f;
    for (int j = 0; j < rows; ++j) {
        for (int i = 0; i < rows; ++i) {
            const float x = (static_cast<float>(i) - 0.5f * (rows - 1)) * spacing + rng.uniform(-0.1f, 0.1f);
            const float z = (static_cast<float>(j) - 0.5f * (rows - 1)) * spacing + rng.uniform(-0.1f, 0.1f);
            glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.0f, z));
            m = glm::rotate(m, rng.uniform(0.0f, 2.0f * glm::pi<float>()), glm::vec3(0, 1, 0));
            m = glm::scale(m, glm::vec3(rng.uniform(0.85f, 1.15f)));
            append_mesh(mesh, figure, m);
        }
    }
    return mesh;
}

// One axis-aligned box (1.2 × 1.5 × 1.2) on the ground, off the light's axis: the simplest solid. Its top is
// parallel to the light; each vertical face sees only the part of the light on its own side, so
// the fair references (tangent-plane clipped light) and today's (whole light) differ there.
Mesh build_box() {
    Mesh mesh;
    add_ground(mesh);
    add_box(mesh, box_transform({0.3f, 0.75f, -0.2f}, {1.2f, 1.5f, 1.2f}));
    return mesh;
}

// Alpha textures of the cut-out scene, generated in code (v = 0 is row 0).
// A grille cell: solid bars along the edges of the texture, a square hole in the middle; repeated
// over a panel it is a lattice of square holes.
AlphaTexture grille_texture() {
    AlphaTexture t{32, 32, std::vector<std::uint8_t>(32 * 32, 0)};
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const bool bar = x < 6 || x >= 26 || y < 6 || y >= 26;
            t.alpha[static_cast<std::size_t>(y * 32 + x)] = bar ? 255 : 0;
        }
    return t;
}

// A fence: one picket per texture width (the middle half of it) and a rail across the lower third;
// alpha ramps linearly at the picket's sides, so the cutoff decides where the picket ends.
AlphaTexture fence_texture() {
    AlphaTexture t{32, 32, std::vector<std::uint8_t>(32 * 32, 0)};
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const float across = std::abs((static_cast<float>(x) + 0.5f) / 32.0f - 0.5f); // 0 at the picket's middle
            const float picket = std::clamp((0.3f - across) / 0.1f, 0.0f, 1.0f);
            const bool rail = y >= 20 && y < 24;
            t.alpha[static_cast<std::size_t>(y * 32 + x)] =
                static_cast<std::uint8_t>(std::lround(255.0f * (rail ? 1.0f : picket)));
        }
    return t;
}

// A leaf card: an ellipse with a notch along its midrib, alpha falling to 0 at its rim.
AlphaTexture leaf_texture() {
    AlphaTexture t{64, 64, std::vector<std::uint8_t>(64 * 64, 0)};
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            const float u = (static_cast<float>(x) + 0.5f) / 32.0f - 1.0f, v = (static_cast<float>(y) + 0.5f) / 32.0f - 1.0f;
            const float r = std::sqrt(u * u / 0.36f + v * v);                         // the ellipse: r < 1
            const float inside = std::clamp((1.0f - r) / 0.2f, 0.0f, 1.0f);
            const bool midrib_gap = std::abs(u) < 0.04f && v > -0.2f && v < 0.6f; // a slit along the midrib
            t.alpha[static_cast<std::size_t>(y * 64 + x)] =
                static_cast<std::uint8_t>(std::lround(255.0f * (midrib_gap ? 0.0f : inside)));
        }
    return t;
}

// Cut-out casters under a wide light (the alpha test, Config::alpha_test): a horizontal grille
// panel of square holes at two heights, a fence of pickets standing on the ground, and a bush of
// leaf cards: quads whose shadows are their textures' alpha, not their rectangles.
Mesh build_cutout() {
    Mesh mesh;
    add_ground(mesh);
    mesh.cut_materials = {{"grille", grille_texture(), 0.5f}, {"fence", fence_texture(), 0.5f},
                          {"leaf", leaf_texture(), 0.5f}};
    complete_cut_materials(mesh);
    // The grille: 3 x 2 units at height 1.4, 0.5-unit cells (texture repeated 6 x 4 times).
    add_cut_quad(mesh, {-3.0f, 1.4f, 1.6f}, {0.0f, 1.4f, 1.6f}, {0.0f, 1.4f, -0.4f}, {-3.0f, 1.4f, -0.4f}, 0,
                 {0.0f, 0.0f}, {6.0f, 0.0f}, {6.0f, 4.0f}, {0.0f, 4.0f});
    // A smaller, finer grille above it (a second cut-out layer over the first).
    add_cut_quad(mesh, {-2.4f, 2.6f, 1.0f}, {-1.0f, 2.6f, 1.0f}, {-1.0f, 2.6f, -0.2f}, {-2.4f, 2.6f, -0.2f}, 0,
                 {0.0f, 0.0f}, {5.6f, 0.0f}, {5.6f, 4.8f}, {0.0f, 4.8f});
    // The fence: 4 units long, 1.6 tall, along x at z = -1.8, eight pickets; both sides face out.
    add_cut_quad(mesh, {-1.0f, 0.0f, -1.8f}, {3.0f, 0.0f, -1.8f}, {3.0f, 1.6f, -1.8f}, {-1.0f, 1.6f, -1.8f}, 1,
                 {0.0f, 1.0f}, {8.0f, 1.0f}, {8.0f, 0.0f}, {0.0f, 0.0f});
    // The bush: leaf cards in a ball around (1.6, 2.0, 0.9), randomly oriented.
    DeterministicRandom rng(0xc07u);
    for (int i = 0; i < 120; ++i) {
        glm::vec3 offset;
        do {
            offset = glm::vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        } while (glm::dot(offset, offset) > 1.0f);
        const glm::vec3 centre = glm::vec3(1.6f, 2.0f, 0.9f) + glm::vec3(0.9f, 0.6f, 0.9f) * offset;
        const float yaw = rng.uniform(0.0f, 2.0f * glm::pi<float>());
        const float pitch = rng.uniform(-0.9f, 0.9f);
        const glm::vec3 across(std::cos(yaw), 0.0f, std::sin(yaw));
        const glm::vec3 flat_along(-std::sin(yaw), 0.0f, std::cos(yaw));
        const glm::vec3 along = std::cos(pitch) * flat_along + std::sin(pitch) * glm::vec3(0, 1, 0);
        const glm::vec3 a = 0.22f * across, b = 0.22f * along;
        add_cut_quad(mesh, centre - a - b, centre + a - b, centre + a + b, centre - a + b, 2, {0.0f, 0.0f},
                     {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f});
    }
    // A trunk under the bush (solid).
    add_box(mesh, box_transform({1.6f, 0.75f, 0.9f}, {0.15f, 1.5f, 0.15f}));
    complete_cut_materials(mesh);
    return mesh;
}

struct SceneEntry {
    std::string_view name;
    Mesh (*build)();
};

constexpr std::array<SceneEntry, 8> scene_table{{
    {"planes", build_planes},
    {"boxes", build_boxes},
    {"tree", build_tree},
    {"butterfly", build_butterfly},
    {"terrain", build_terrain},
    {"crowd", build_crowd},
    {"box", build_box},
    {"cutout", build_cutout},
}};

} // namespace

std::vector<std::string_view> scene_names() {
    std::vector<std::string_view> names;
    for (const SceneEntry& e : scene_table) names.push_back(e.name);
    return names;
}

std::optional<Scene> make_scene(std::string_view name) {
    for (const SceneEntry& e : scene_table) {
        if (e.name != name) continue;
        Scene scene;
        scene.name = std::string(name);
        scene.mesh = e.build();
        scene.generated_charts = true;
        finish_scene(scene);
        return scene;
    }
    return std::nullopt;
}

} // namespace penumbra::playground
