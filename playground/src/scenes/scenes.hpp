// playground/src/scenes/scenes.hpp — the procedural test scenes of docs/model.md §5.
//
// The scenes of scene_names() share one frame: a ground about 10×10 units around the origin at
// y = 0, objects up to about 3 units tall, a 2×2 area light facing down at y ≈ 7 and a slightly
// tilted sun. The rooms of room_scene_names() have their own (the light inside a closed room). Every
// scene is generated from a fixed seed and is bit-identical from run to run and machine to
// machine (see deterministic_random.hpp).
#pragma once

#include "scenes/scene.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::playground {

// "planes", "boxes", "tree", "butterfly", "terrain", "crowd", "box", "cutout" (cut-out casters: a
// grille, a fence and leaf cards whose materials cut, for the alpha test).
std::vector<std::string_view> scene_names();

// The rooms, kept out of scene_names() (whose scenes the tests, benchmarks and tables iterate): the
// light inside a closed room, for when a scene is named. "room" (a ceiling panel over furniture),
// "window" (a light in a wall's plane, facing into the room), "cornell" (the Cornell box as measured,
// in metres, its front open). Each places its own light, sun and camera (inside, or in front of the
// Cornell box's opening).
std::vector<std::string_view> room_scene_names();

// Every name make_scene knows, comma-separated (scene_names(), then room_scene_names()): for
// "allowed: ..." in messages.
std::string allowed_scene_names();

// The named scene (of scene_names() or room_scene_names()), or nullopt for an unknown name.
std::optional<Scene> make_scene(std::string_view name);

// Heights of the planar occluders in the "planes" scene (each parallel to the light, facing +y),
// exposed so tests and analyses can place slices or probes relative to them.
inline constexpr float planes_occluder_heights[] = {1.0f, 2.0f, 3.0f};

} // namespace penumbra::playground
