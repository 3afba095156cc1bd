#version 300 es
// Penumbra 0.1.0 - example shading pass, vertex stage
// slices 16 | resolution 512x512 | filter nbuffer | fusion extent | packing atlas | light sun | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.
// @penumbra:precision
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler3D;

// @penumbra:example_vertex_inputs
layout(location = 0) in vec3 penumbra_position; // world space (scene units)
layout(location = 1) in vec3 penumbra_normal;   // world space
out vec3 penumbra_worldPos;
out vec3 penumbra_worldNormal;

// @penumbra:parameters
uniform mat4 penumbra_clipFromWorld; // world to clip space of the viewer's camera

// @penumbra:example_vertex_main
void main()
{
    penumbra_worldPos = penumbra_position;
    penumbra_worldNormal = penumbra_normal;
    gl_Position = penumbra_clipFromWorld * vec4(penumbra_position, 1.0);
}
