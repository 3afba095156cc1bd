#version 300 es
// Penumbra 0.1.0 - atlas packing of the slicing output (paper §3.6) and N-buffer level 1 from it, fragment stage
// slices 16 | resolution 256x256 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
// 4 RGBA occlusion texture(s), filter levels 0 to 8. Generated: edit the configuration, not this file.
// @penumbra:precision
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler3D;

// @penumbra:parameters
uniform sampler2DArray penumbra_slices; // slicing output, one layer per RGBA texture, texture unit 0

layout(location = 0) out vec4 penumbra_level0; // level 0: the slicing output
layout(location = 1) out vec4 penumbra_level1; // level 1, same size

// @penumbra:pack_atlas_source
// texel `local` of occlusion texture `layer` of the slicing output, 0 outside its 256 x 256 texels
vec4 penumbra_slice_texel(int layer, ivec2 local)
{
    bool inside = all(greaterThanEqual(local, ivec2(0))) && all(lessThan(local, ivec2(256)));
    vec4 value = texelFetch(penumbra_slices, ivec3(clamp(local, ivec2(0), ivec2(255)), layer), 0);
    return inside ? value : vec4(0.0);
}

// @penumbra:pack_atlas_main
void main()
{
    ivec2 texel = ivec2(gl_FragCoord.xy);
    int layer = texel.x / 256; // which occlusion texture: the tile
    ivec2 local = ivec2(texel.x - layer * 256, texel.y);
    vec4 level0 = penumbra_slice_texel(layer, local);
    penumbra_level0 = level0;
    // level 1 (Décoret 2005): the mean of the 2 x 2 window anchored here
    penumbra_level1 = 0.25 * (level0 + penumbra_slice_texel(layer, local + ivec2(1, 0))
        + penumbra_slice_texel(layer, local + ivec2(0, 1)) + penumbra_slice_texel(layer, local + ivec2(1, 1)));
}
