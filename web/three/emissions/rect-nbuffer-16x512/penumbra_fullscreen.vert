#version 300 es
// Penumbra 0.1.0 - full-screen triangle, vertex stage (draw 3 vertices, no attributes)
// slices 16 | resolution 512x512 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.
// @penumbra:precision
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler3D;

// @penumbra:fullscreen_vertex_main
void main()
{
    int index = gl_VertexID;
    vec2 corner = vec2(float((index << 1) & 2), float(index & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
