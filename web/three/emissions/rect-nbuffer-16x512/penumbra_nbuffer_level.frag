#version 300 es
// Penumbra 0.1.0 - N-buffer level l from level l-1, fragment stage
// slices 16 | resolution 512x512 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.
// @penumbra:precision
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler3D;

// @penumbra:parameters
uniform int penumbra_step; // offset between the windows combined by this pass, in texels of the texture it reads (texels)
uniform int penumbra_sourceTile; // side of one tile of the previous level (texels)
uniform int penumbra_scale; // texels of the previous level per texel of this one, per axis (1 or 2)
uniform sampler2D penumbra_source; // previous filter level (atlas), texture unit 0

layout(location = 0) out vec4 penumbra_result;

// @penumbra:level_source
// texel `local` of the previous level's tile that starts at `origin`, 0 outside the tile
vec4 penumbra_source_texel(ivec2 origin, ivec2 local)
{
    bool inside = all(greaterThanEqual(local, ivec2(0))) && all(lessThan(local, ivec2(penumbra_sourceTile)));
    vec4 value = texelFetch(penumbra_source, origin + clamp(local, ivec2(0), ivec2(penumbra_sourceTile - 1)), 0);
    return inside ? value : vec4(0.0);
}

// @penumbra:nbuffer_level_main
void main()
{
    ivec2 fragment = ivec2(gl_FragCoord.xy);
    int side = penumbra_scale == 1 ? penumbra_sourceTile : penumbra_sourceTile / 2; // this level's tile side
    // which occlusion texture: fragment.x / side without an integer division (the pixel centre's
    // half texel keeps the float quotient at least 0.5 / side off an integer: exact for any side)
    int tile = int(gl_FragCoord.x / float(side));
    ivec2 origin = ivec2(tile * penumbra_sourceTile, 0);
    ivec2 local = ivec2(fragment.x - tile * side, fragment.y) * penumbra_scale;
    int s = penumbra_step; // 2^(l-1) texels of level 0, in texels of the previous level
    penumbra_result = 0.25 * (penumbra_source_texel(origin, local) + penumbra_source_texel(origin, local + ivec2(s, 0))
    + penumbra_source_texel(origin, local + ivec2(0, s)) + penumbra_source_texel(origin, local + ivec2(s, s)));
}
