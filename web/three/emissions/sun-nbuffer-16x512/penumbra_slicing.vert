#version 300 es
// Penumbra 0.1.0 - slicing pass, vertex stage
// slices 16 | resolution 512x512 | filter nbuffer | fusion extent | packing atlas | light sun | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.
// @penumbra:precision
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler3D;

// @penumbra:slicing_inputs
layout(location = 0) in vec3 penumbra_position; // world space (scene units)
out float penumbra_depth; // depth along the light normal (scene units)

// @penumbra:parameters
uniform mat4 penumbra_sliceClipFromWorld; // world to clip space of the slicing camera (perspective from the centre of projection, or orthographic)
uniform mat4 penumbra_lightFromWorld; // world to light frame (z = depth along the light normal) (scene units)
uniform vec2 penumbra_sliceDepths; // x: depth z0 of the first slice's top, y: slice thickness (scene units)

// @penumbra:slicing_vertex_main
void main()
{
    vec4 world = vec4(penumbra_position, 1.0);
    penumbra_depth = (penumbra_lightFromWorld * world).z;
    gl_Position = penumbra_sliceClipFromWorld * world;
}
