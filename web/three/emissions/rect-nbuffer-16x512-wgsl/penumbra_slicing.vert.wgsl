// Penumbra 0.1.0 - slicing pass, vertex stage
// slices 16 | resolution 512x512 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.

// @penumbra:slicing_inputs
var<private> penumbra_position: vec3f; // world space (scene units)
var<private> penumbra_depth: f32; // depth along the light normal (scene units)
var<private> penumbra_clipPosition: vec4f;

// @penumbra:parameters
struct PenumbraSlicing {
    penumbra_sliceClipFromWorld: mat4x4f, // world to clip space of the slicing camera (perspective from the centre of projection, or orthographic)
    penumbra_lightFromWorld: mat4x4f, // world to light frame (z = depth along the light normal) (scene units)
    penumbra_sliceDepths: vec2f, // x: depth z0 of the first slice's top, y: slice thickness (scene units)
}
@group(0) @binding(0) var<uniform> penumbraSlicingBlock: PenumbraSlicing;
var<private> penumbra_sliceClipFromWorld: mat4x4f;
var<private> penumbra_lightFromWorld: mat4x4f;
var<private> penumbra_sliceDepths: vec2f;
fn penumbra_loadSlicing()
{
    penumbra_sliceClipFromWorld = penumbraSlicingBlock.penumbra_sliceClipFromWorld;
    penumbra_lightFromWorld = penumbraSlicingBlock.penumbra_lightFromWorld;
    penumbra_sliceDepths = penumbraSlicingBlock.penumbra_sliceDepths;
}

// @penumbra:slicing_vertex_main
fn penumbra_main()
{
    let world: vec4f = vec4(penumbra_position, 1.0);
    penumbra_depth = (penumbra_lightFromWorld * world).z;
    penumbra_clipPosition = penumbra_sliceClipFromWorld * world;
    // WebGPU's framebuffer rows run top down: flipped, a slice's row 0 holds uv.y = 0 as on OpenGL
    penumbra_clipPosition.y = -penumbra_clipPosition.y;
}

// @penumbra:entry_point
// entry point: the inputs into the globals above, the uniform values loaded, then penumbra_main()
struct PenumbraStageOutput {
    @location(0) penumbra_depth: f32,
    @builtin(position) penumbra_clipPosition: vec4f,
}

@vertex
fn main(@location(0) penumbra_positionIn: vec3f) -> PenumbraStageOutput
{
    penumbra_position = penumbra_positionIn;
    penumbra_loadSlicing();
    penumbra_main();
    return PenumbraStageOutput(penumbra_depth, penumbra_clipPosition);
}
