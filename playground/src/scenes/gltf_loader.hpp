// playground/src/scenes/gltf_loader.hpp — any glTF 2.0 file (.gltf with its buffers, or .glb) as a Scene.
#pragma once

#include "scenes/obj_loader.hpp" // LoadResult

#include <string>

namespace penumbra::playground {

// Loads every triangle primitive (TRIANGLES, TRIANGLE_STRIP, TRIANGLE_FAN; indexed with unsigned
// byte, short or int indices, or not indexed) of every mesh reached from the default scene's nodes
// (scene 0 when the file names none), each placed by its node's world transform (matrix or
// translation × rotation × scale, composed down the node tree). Positions, normals and TEXCOORD_0
// are read (normals transformed by the inverse transpose; computed, smooth, when a primitive has
// none or has unusable ones; texture coordinates kept in mesh.uvs when every primitive has them).
// Materials that cut (alpha test) become mesh.cut_materials: alphaMode MASK (baseColorFactor.a ×
// baseColorTexture.a below alphaCutoff, default 0.5) and BLEND (cast as a cut-out at 0.5), their
// texture's alpha decoded with stb_image (material_textures.hpp) and read at TEXCOORD_0; no other
// image is decoded. A texture that cannot be read leaves the factor alone to cut, with a warning.
// The parser is Debian's libtinygltf; everything it does not check is validated here before any
// data is read: the .glb header and chunk lengths against the file size, every accessor and buffer
// view against its buffer, component types and accessor types, index values against the vertex
// count, finite positions within ±1e9, node cycles, the total size after instancing.
// Compressed geometry is decoded first (scenes/gltf_compression.hpp): KHR_draco_mesh_compression
// with libdraco, EXT_meshopt_compression (with KHR_mesh_quantization) with libmeshoptimizer; a
// stream that does not decode, or whose counts, strides or attribute ids do not match the file,
// is an error.
// Primitives that are points or lines, use sparse accessors, have no buffer data or whose buffer's
// file is missing are skipped, each with a line in `warnings`; a file with nothing left is an error.
// Lights: the first EXT_lights_area light met walking the scene's nodes becomes scene.file_light (a
// "rect" of height `size` and width `size` × `rect.aspect`, at its node's origin, facing the node's −z,
// u along its −x, v along its +y, sized by its scale, as Babylon.js's loader places it; a "disk" the
// square of its area, with a warning: the shadows serve rectangles only), the first KHR_lights_punctual
// directional light's −z scene.file_sun_direction; finish_scene puts them in place of the defaults, so
// the --light-* flags, applied to the loaded scene, still win. More lights of a kind, and point or
// spot lights, are a warning each. A light whose type is not rect or disk, whose size or rect.aspect
// is not a finite number above 0, or a node naming a light the file does not have, is an error.
// Never throws on bad input; every failure is one line in `error` naming the file and the problem.
LoadResult load_gltf_scene(const std::string& path);

} // namespace penumbra::playground
