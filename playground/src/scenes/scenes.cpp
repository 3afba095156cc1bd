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

// ---------------------------------------------------------------------------------------------
// Rooms: the light inside a closed room (room_scene_names). The shell's faces are single flat quads
// with their own vertices, wound so that their normals face into the room (they receive from
// inside); furniture is boxes (outward normals). Each builder also places its light and camera.

// The camera at `eye` looking at `target` (OrbitCamera's yaw and pitch from the direction).
OrbitCamera camera_looking(glm::vec3 eye, glm::vec3 target, float fov_y_degrees, float z_near, float z_far) {
    OrbitCamera camera;
    // OrbitCamera: eye = target + distance · (cos p sin y, sin p, cos p cos y).
    const glm::vec3 back = eye - target;
    camera.target = target;
    camera.distance = glm::length(back);
    camera.yaw_radians = std::atan2(back.x, back.z);
    camera.pitch_radians = std::asin(back.y / camera.distance);
    camera.fov_y_radians = glm::radians(fov_y_degrees);
    camera.z_near = z_near;
    camera.z_far = z_far;
    return camera;
}

// The inside of the axis-aligned box [lo, hi]: floor, ceiling and four walls, each one quad whose
// normal faces into the box. Corners counter-clockwise seen from inside.
void add_room_shell(Mesh& mesh, glm::vec3 lo, glm::vec3 hi) {
    // Floor (+y), ceiling (−y).
    add_quad(mesh, {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, lo.y, lo.z}, {lo.x, lo.y, lo.z});
    add_quad(mesh, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
    // Back wall at lo.z (+z), front wall at hi.z (−z).
    add_quad(mesh, {lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z});
    add_quad(mesh, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z});
    // Left wall at lo.x (+x), right wall at hi.x (−x).
    add_quad(mesh, {lo.x, lo.y, hi.z}, {lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z});
    add_quad(mesh, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z});
}

// An axis-aligned box from its lower corner `lo` and its size.
void add_block(Mesh& mesh, glm::vec3 lo, glm::vec3 size) {
    add_box(mesh, box_transform(lo + 0.5f * size, size));
}

// A table: a top of `size` (x, thickness, z) whose upper face is at `height`, four square legs.
void add_table(Mesh& mesh, glm::vec3 centre_on_floor, glm::vec3 size, float height) {
    const float leg = 0.06f, inset = 0.05f;
    add_block(mesh, {centre_on_floor.x - 0.5f * size.x, height - size.y, centre_on_floor.z - 0.5f * size.z},
              size);
    for (float sx : {-1.0f, 1.0f})
        for (float sz : {-1.0f, 1.0f}) {
            const glm::vec3 c(centre_on_floor.x + sx * (0.5f * size.x - inset - 0.5f * leg), 0.0f,
                              centre_on_floor.z + sz * (0.5f * size.z - inset - 0.5f * leg));
            add_block(mesh, {c.x - 0.5f * leg, 0.0f, c.z - 0.5f * leg}, {leg, height - size.y, leg});
        }
}

// A chair: a 0.44 × 0.44 seat at 0.45, four legs, a backrest up to 0.9 on the side `back` (a unit
// vector along x or z, away from where one sits facing).
void add_chair(Mesh& mesh, glm::vec3 centre_on_floor, glm::vec3 back) {
    const float seat = 0.44f, seat_height = 0.45f, seat_thickness = 0.04f, rest = 0.03f, rest_width = 0.36f;
    add_table(mesh, centre_on_floor, {seat, seat_thickness, seat}, seat_height);
    const glm::vec3 c = centre_on_floor + (0.5f * seat - 0.5f * rest) * back;
    const glm::vec3 size =
        std::abs(back.x) > 0.5f ? glm::vec3(rest, 0.45f, rest_width) : glm::vec3(rest_width, 0.45f, rest);
    add_block(mesh, {c.x - 0.5f * size.x, seat_height, c.z - 0.5f * size.z}, size);
}

// An open bookshelf `size` (width along x, height, depth along z) with `shelves` boards between its
// plinth and top: two sides, a top, a plinth and a back panel; its back at z = 0, open towards +z,
// centred on x = 0, standing on y = 0.
Mesh make_shelf(glm::vec3 size, int shelves) {
    Mesh shelf;
    const float t = 0.025f, plinth = 0.08f, x0 = -0.5f * size.x;
    add_block(shelf, {x0, 0.0f, 0.0f}, {t, size.y, size.z}); // sides
    add_block(shelf, {-x0 - t, 0.0f, 0.0f}, {t, size.y, size.z});
    add_block(shelf, {x0 + t, size.y - t, 0.0f}, {size.x - 2 * t, t, size.z});          // top
    add_block(shelf, {x0 + t, 0.0f, 0.0f}, {size.x - 2 * t, plinth, size.z});           // plinth
    add_block(shelf, {x0 + t, plinth, 0.0f}, {size.x - 2 * t, size.y - plinth - t, t}); // back panel
    for (int i = 1; i <= shelves; ++i) {
        const float y =
            plinth + (size.y - plinth - t) * static_cast<float>(i) / static_cast<float>(shelves + 1);
        add_block(shelf, {x0 + t, y - 0.5f * t, t}, {size.x - 2 * t, t, size.z - t});
    }
    return shelf;
}

// `room`: a 6 × 3 × 5 room (x −3…3, y 0…3, z −2.5…2.5) lit by a 1.2 × 0.6 ceiling panel 2 cm under
// the ceiling, facing down; a table with a chair, a bookshelf and a crate against the back wall
// (z = −2.5), a box on the table; the camera inside, by the front wall, looking at them.
void build_room(Scene& scene) {
    Mesh& mesh = scene.mesh;
    const glm::vec3 lo(-3.0f, 0.0f, -2.5f), hi(3.0f, 3.0f, 2.5f);
    add_room_shell(mesh, lo, hi);
    const float wall_gap = 0.01f; // furniture stands 1 cm off the walls: no coplanar faces
    add_table(mesh, {-0.7f, 0.0f, lo.z + wall_gap + 0.4f}, {1.6f, 0.05f, 0.8f}, 0.75f);
    add_block(mesh, {-1.2f, 0.75f, -2.3f}, {0.35f, 0.25f, 0.25f}); // a box on the table
    add_chair(mesh, {-0.5f, 0.0f, -1.45f}, {0.0f, 0.0f, 1.0f});
    append_mesh(mesh, make_shelf({1.1f, 2.0f, 0.35f}, 3),
                glm::translate(glm::mat4(1.0f), {1.6f, 0.0f, lo.z + wall_gap}));
    add_block(mesh, {2.3f, 0.0f, lo.z + wall_gap}, {0.55f, 0.45f, 0.6f}); // a crate
    finish_scene(scene);

    penumbra::RectLight& light = scene.light;
    light.center = glm::dvec3(0.0, 3.0 - 0.02, -0.6);
    light.u_axis = glm::dvec3(1.0, 0.0, 0.0);
    light.v_axis = glm::dvec3(0.0, 0.0, 1.0); // normal() = cross(+x, +z) = −y: down
    light.width = 1.2;
    light.height = 0.6;
    scene.sun = default_sun_light(); // outside: the ceiling hides it
    scene.camera = camera_looking({0.9f, 1.7f, 2.3f}, {0.4f, 0.7f, -2.0f}, 60.0f, 0.02f, 15.0f);
}

// `window`: a 5 × 2.8 × 6 room (x −2.5…2.5, y 0…2.8, z −3…3) lit by a 1.5 × 1.2 window in the −x
// wall: the light lies 1 cm inside the wall's plane, its lower edge 0.9 above the floor, facing +x
// into the room; a table with two chairs in the light's path, a bookshelf against the back wall;
// the camera inside, in the far corner, looking at the window, the table and the floor.
void build_window(Scene& scene) {
    Mesh& mesh = scene.mesh;
    const glm::vec3 lo(-2.5f, 0.0f, -3.0f), hi(2.5f, 2.8f, 3.0f);
    add_room_shell(mesh, lo, hi);
    add_table(mesh, {-0.6f, 0.0f, -0.4f}, {0.9f, 0.05f, 1.4f}, 0.74f);
    add_chair(mesh, {0.15f, 0.0f, -0.7f}, {1.0f, 0.0f, 0.0f});
    add_chair(mesh, {-1.35f, 0.0f, 0.0f}, {-1.0f, 0.0f, 0.0f});
    // A bookshelf against the back wall (−z), across the room from the window.
    append_mesh(mesh, make_shelf({1.0f, 1.8f, 0.35f}, 2),
                glm::translate(glm::mat4(1.0f), {0.4f, 0.0f, lo.z + 0.01f}));
    finish_scene(scene);

    penumbra::RectLight& light = scene.light;
    light.center = glm::dvec3(-2.5 + 0.01, 0.9 + 0.6, -0.4);
    light.u_axis = glm::dvec3(0.0, 0.0, -1.0);
    light.v_axis = glm::dvec3(0.0, 1.0, 0.0); // normal() = cross(−z, +y) = +x: into the room
    light.width = 1.5;
    light.height = 1.2;
    scene.sun = default_sun_light();
    scene.sun.direction =
        glm::normalize(glm::dvec3(1.0, -0.8, 0.25)); // through the window's side (the wall hides it)
    scene.camera = camera_looking({2.2f, 1.65f, 2.7f}, {-0.9f, 0.55f, -0.6f}, 60.0f, 0.02f, 15.0f);
}

// `cornell`: the Cornell box as measured, from Cornell University Program of Computer Graphics,
// "Cornell Box Data" (https://www.graphics.cornell.edu/online/box/data.html). Coordinates in
// millimetres as published (each quad's corners in the published order, which winds its normal into
// the box, or out of a block), converted to metres; the front (z = 0) stays open, as published.
// Not in the data: the blocks' bottoms, added on the floor (unseen) so that each block is a closed
// solid (solid_casters, docs/model.md §1.3b).
void build_cornell(Scene& scene) {
    using Quad = std::array<glm::dvec3, 4>; // millimetres
    // Floor, ceiling, back wall, right wall (green, x = 0), left wall (red, x ≈ 556).
    const std::array<Quad, 5> shell{{
        {{{552.8, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 559.2}, {549.6, 0.0, 559.2}}},
        {{{556.0, 548.8, 0.0}, {556.0, 548.8, 559.2}, {0.0, 548.8, 559.2}, {0.0, 548.8, 0.0}}},
        {{{549.6, 0.0, 559.2}, {0.0, 0.0, 559.2}, {0.0, 548.8, 559.2}, {556.0, 548.8, 559.2}}},
        {{{0.0, 0.0, 559.2}, {0.0, 0.0, 0.0}, {0.0, 548.8, 0.0}, {0.0, 548.8, 559.2}}},
        {{{552.8, 0.0, 0.0}, {549.6, 0.0, 559.2}, {556.0, 548.8, 559.2}, {556.0, 548.8, 0.0}}},
    }};
    // The short block (165 mm) and the tall block (330 mm): top, then four sides.
    const std::array<Quad, 5> short_block{{
        {{{130.0, 165.0, 65.0}, {82.0, 165.0, 225.0}, {240.0, 165.0, 272.0}, {290.0, 165.0, 114.0}}},
        {{{290.0, 0.0, 114.0}, {290.0, 165.0, 114.0}, {240.0, 165.0, 272.0}, {240.0, 0.0, 272.0}}},
        {{{130.0, 0.0, 65.0}, {130.0, 165.0, 65.0}, {290.0, 165.0, 114.0}, {290.0, 0.0, 114.0}}},
        {{{82.0, 0.0, 225.0}, {82.0, 165.0, 225.0}, {130.0, 165.0, 65.0}, {130.0, 0.0, 65.0}}},
        {{{240.0, 0.0, 272.0}, {240.0, 165.0, 272.0}, {82.0, 165.0, 225.0}, {82.0, 0.0, 225.0}}},
    }};
    const std::array<Quad, 5> tall_block{{
        {{{423.0, 330.0, 247.0}, {265.0, 330.0, 296.0}, {314.0, 330.0, 456.0}, {472.0, 330.0, 406.0}}},
        {{{423.0, 0.0, 247.0}, {423.0, 330.0, 247.0}, {472.0, 330.0, 406.0}, {472.0, 0.0, 406.0}}},
        {{{472.0, 0.0, 406.0}, {472.0, 330.0, 406.0}, {314.0, 330.0, 456.0}, {314.0, 0.0, 456.0}}},
        {{{314.0, 0.0, 456.0}, {314.0, 330.0, 456.0}, {265.0, 330.0, 296.0}, {265.0, 0.0, 296.0}}},
        {{{265.0, 0.0, 296.0}, {265.0, 330.0, 296.0}, {423.0, 330.0, 247.0}, {423.0, 0.0, 247.0}}},
    }};
    // The light: 130 × 105 mm, x 213…343, z 227…332, published at the ceiling's height (548.8).
    const double light_x0 = 213.0, light_x1 = 343.0, light_z0 = 227.0, light_z1 = 332.0;
    const double light_y = 548.7; // 0.1 mm under the ceiling, as renderers of the box usually put it
    // The camera: at (278, 273, −800) looking along +z, up +y; a 35 mm lens over a 25 × 25 mm film:
    // a vertical field of view of 2 · atan(12.5 / 35) = 39.3°.
    const glm::dvec3 camera_position(278.0, 273.0, -800.0);
    const double focal_length = 35.0, film_size = 25.0;

    const double mm = 0.001; // to metres
    Mesh& mesh = scene.mesh;
    auto metres = [&](const glm::dvec3& p) { return glm::vec3(mm * p); };
    auto add = [&](const Quad& q) { add_quad(mesh, metres(q[0]), metres(q[1]), metres(q[2]), metres(q[3])); };
    for (const Quad& q : shell) add(q);
    for (const std::array<Quad, 5>* block : {&short_block, &tall_block}) {
        for (const Quad& q : *block) add(q);
        // The bottom: the top's corners on the floor, wound the other way (facing −y).
        const Quad& top = (*block)[0];
        add({glm::dvec3(top[3].x, 0.0, top[3].z), glm::dvec3(top[2].x, 0.0, top[2].z),
             glm::dvec3(top[1].x, 0.0, top[1].z), glm::dvec3(top[0].x, 0.0, top[0].z)});
    }
    finish_scene(scene);

    penumbra::RectLight& light = scene.light;
    light.center = mm * glm::dvec3(0.5 * (light_x0 + light_x1), light_y, 0.5 * (light_z0 + light_z1));
    light.u_axis = glm::dvec3(1.0, 0.0, 0.0);
    light.v_axis = glm::dvec3(0.0, 0.0, 1.0);  // normal() = cross(+x, +z) = −y: down
    light.width = mm * (light_x1 - light_x0);  // 0.130
    light.height = mm * (light_z1 - light_z0); // 0.105
    scene.sun = default_sun_light();           // outside: the ceiling hides it
    // Looking along +z at the middle of the box's depth (the eye is what is published).
    const glm::vec3 eye = metres(camera_position);
    const float fov_y_degrees =
        static_cast<float>(glm::degrees(2.0 * std::atan(0.5 * film_size / focal_length)));
    scene.camera =
        camera_looking(eye, {eye.x, eye.y, metres({0.0, 0.0, 0.5 * 559.2}).z}, fov_y_degrees, 0.01f, 5.0f);
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

struct RoomEntry {
    std::string_view name;
    void (*build)(Scene&); // the mesh, finish_scene, then the light, sun and camera
};

constexpr std::array<RoomEntry, 3> room_table{{
    {"room", build_room},
    {"window", build_window},
    {"cornell", build_cornell},
}};

} // namespace

std::vector<std::string_view> scene_names() {
    std::vector<std::string_view> names;
    for (const SceneEntry& e : scene_table) names.push_back(e.name);
    return names;
}

std::vector<std::string_view> room_scene_names() {
    std::vector<std::string_view> names;
    for (const RoomEntry& e : room_table) names.push_back(e.name);
    return names;
}

std::string allowed_scene_names() {
    std::string allowed;
    for (std::string_view name : scene_names()) allowed += (allowed.empty() ? "" : ", ") + std::string(name);
    for (std::string_view name : room_scene_names()) allowed += ", " + std::string(name);
    return allowed;
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
    for (const RoomEntry& e : room_table) {
        if (e.name != name) continue;
        Scene scene;
        scene.name = std::string(name);
        scene.generated_charts = true;
        e.build(scene);
        return scene;
    }
    return std::nullopt;
}

} // namespace penumbra::playground
