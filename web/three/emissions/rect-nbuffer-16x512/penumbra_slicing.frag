#version 300 es
// Penumbra 0.1.0 - slicing pass, fragment stage (blend equation MAX, clear to 0)
// slices 16 | resolution 512x512 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.
// @penumbra:precision
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler3D;

// @penumbra:slicing_outputs
in float penumbra_depth;
layout(location = 0) out vec4 penumbra_occlusion0; // slices 0 to 3
layout(location = 1) out vec4 penumbra_occlusion1; // slices 4 to 7
layout(location = 2) out vec4 penumbra_occlusion2; // slices 8 to 11
layout(location = 3) out vec4 penumbra_occlusion3; // slices 12 to 15

// @penumbra:parameters
uniform mat4 penumbra_sliceClipFromWorld; // world to clip space of the slicing camera (perspective from the centre of projection, or orthographic)
uniform mat4 penumbra_lightFromWorld; // world to light frame (z = depth along the light normal) (scene units)
uniform vec2 penumbra_sliceDepths; // x: depth z0 of the first slice's top, y: slice thickness (scene units)

// @penumbra:slicing_fragment_main
void main()
{
    // slice k holds the depths in (z0 + k * thickness, z0 + (k + 1) * thickness]
    float k = clamp(ceil((penumbra_depth - penumbra_sliceDepths.x) / penumbra_sliceDepths.y) - 1.0, 0.0, 15.0);
    // paper §3.4.1 leak fix: also mark the next slice away from the light
    // slices k to next are marked
    float next = min(k + 1.0, 15.0);
    // texture 0
    penumbra_occlusion0 = vec4(greaterThanEqual(vec4(0.0, 1.0, 2.0, 3.0), vec4(k))) * vec4(lessThanEqual(vec4(0.0, 1.0, 2.0, 3.0), vec4(next)));
    // texture 1
    penumbra_occlusion1 = vec4(greaterThanEqual(vec4(4.0, 5.0, 6.0, 7.0), vec4(k))) * vec4(lessThanEqual(vec4(4.0, 5.0, 6.0, 7.0), vec4(next)));
    // texture 2
    penumbra_occlusion2 = vec4(greaterThanEqual(vec4(8.0, 9.0, 10.0, 11.0), vec4(k))) * vec4(lessThanEqual(vec4(8.0, 9.0, 10.0, 11.0), vec4(next)));
    // texture 3
    penumbra_occlusion3 = vec4(greaterThanEqual(vec4(12.0, 13.0, 14.0, 15.0), vec4(k))) * vec4(lessThanEqual(vec4(12.0, 13.0, 14.0, 15.0), vec4(next)));
}
