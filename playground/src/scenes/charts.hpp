// playground/src/scenes/charts.hpp — unique texture coordinates for the procedural scenes, which
// occlusion interval maps need (GPU Gems ch. 13: "the objects' texture coordinates cannot overlap").
//
// One chart per connected piece of the mesh (triangles sharing vertices: a box face, a leaf, the
// terrain's heightfield), projected along the piece's mean normal; a piece that this projection
// would fold or squash (any triangle keeping under a fifth of its area) becomes one chart per
// triangle. Charts keep their proportions (one texel density for the whole mesh, as large as fits)
// and are packed in rows, each starting half a texel into its cell and followed by at least a
// texel and a half of gutter, so at `resolution` no texel is touched by two charts.
#pragma once

#include "scenes/scene.hpp"

#include <string>

namespace penumbra::playground {

// Replaces mesh.uvs (vertices shared by pieces that become separate charts are duplicated; the
// geometry is unchanged). Empty on success; otherwise one line, e.g. when the charts cannot fit
// at this resolution, naming the smallest resolution that would hold them.
std::string generate_charts(Mesh& mesh, int resolution);

} // namespace penumbra::playground
