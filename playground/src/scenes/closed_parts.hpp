// playground/src/scenes/closed_parts.hpp — which triangles belong to a closed mesh (solid_casters).
//
// A part is a set of triangles connected through shared corner positions. It is closed when every
// edge of it is used by an even number of its triangles (two for a watertight surface; a duplicated
// face or four faces around one edge still pair up): then every ray from the slicing camera enters and
// leaves it in pairs. Triangles of a cut-out material are never closed (the cut opens them). The
// orientation is not checked: the convention is counter-clockwise outward faces, as glTF's and OBJ's
// (a face wound the other way starts its toggle one slice off).
#pragma once

#include "scene.hpp"

#include <cstdint>
#include <vector>

namespace penumbra::playground {

// One entry per triangle of `mesh`: 1 where its part is closed, else 0.
std::vector<std::uint8_t> closed_triangles(const Mesh& mesh);

} // namespace penumbra::playground
