#version 300 es
// Penumbra 0.1.0 - atlas packing of the slicing output (paper §3.6), fragment stage
// slices 16 | resolution 512x512 | filter mipmap | fusion extent | packing atlas | light sun | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.
// @penumbra:precision
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler3D;

// @penumbra:parameters
uniform sampler2DArray penumbra_slices; // slicing output, one layer per RGBA texture, texture unit 0

layout(location = 0) out vec4 penumbra_result;

// @penumbra:pack_atlas_main
void main()
{
    ivec2 texel = ivec2(gl_FragCoord.xy);
    penumbra_result = texelFetch(penumbra_slices, ivec3(texel.x % 512, texel.y, texel.x / 512), 0);
}
