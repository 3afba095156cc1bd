// Penumbra 0.1.0 - example shading pass, vertex stage
// slices 16 | resolution 256x256 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 4 RGBA occlusion texture(s), filter levels 0 to 8. Generated: edit the configuration, not this file.

// @penumbra:example_vertex_inputs
var<private> penumbra_position: vec3f; // world space (scene units)
var<private> penumbra_normal: vec3f;   // world space
var<private> penumbra_worldPos: vec3f;
var<private> penumbra_worldNormal: vec3f;
var<private> penumbra_clipPosition: vec4f;

// @penumbra:parameters
struct PenumbraCamera {
    penumbra_clipFromWorld: mat4x4f, // world to clip space of the viewer's camera
}
@group(0) @binding(20) var<uniform> penumbraCameraBlock: PenumbraCamera;
var<private> penumbra_clipFromWorld: mat4x4f;
fn penumbra_loadCamera()
{
    penumbra_clipFromWorld = penumbraCameraBlock.penumbra_clipFromWorld;
}

// @penumbra:example_vertex_main
fn penumbra_main()
{
    penumbra_worldPos = penumbra_position;
    penumbra_worldNormal = penumbra_normal;
    penumbra_clipPosition = penumbra_clipFromWorld * vec4(penumbra_position, 1.0);
}

// @penumbra:entry_point
// entry point: the inputs into the globals above, the uniform values loaded, then penumbra_main()
struct PenumbraStageOutput {
    @location(0) penumbra_worldPos: vec3f,
    @location(1) penumbra_worldNormal: vec3f,
    @builtin(position) penumbra_clipPosition: vec4f,
}

@vertex
fn main(@location(0) penumbra_positionIn: vec3f, @location(1) penumbra_normalIn: vec3f) -> PenumbraStageOutput
{
    penumbra_position = penumbra_positionIn;
    penumbra_normal = penumbra_normalIn;
    penumbra_loadCamera();
    penumbra_main();
    return PenumbraStageOutput(penumbra_worldPos, penumbra_worldNormal, penumbra_clipPosition);
}
