// Penumbra 0.1.0 - slicing pass, fragment stage (blend equation MAX, clear to 0)
// slices 16 | resolution 512x512 | filter mipmap | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.

// @penumbra:slicing_outputs
var<private> penumbra_depth: f32;
var<private> penumbra_occlusion0: vec4f; // slices 0 to 3
var<private> penumbra_occlusion1: vec4f; // slices 4 to 7
var<private> penumbra_occlusion2: vec4f; // slices 8 to 11
var<private> penumbra_occlusion3: vec4f; // slices 12 to 15

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

// @penumbra:slicing_fragment_main
fn penumbra_main()
{
    // slice k holds the depths in (z0 + k * thickness, z0 + (k + 1) * thickness]
    let k: f32 = clamp(ceil((penumbra_depth - penumbra_sliceDepths.x) / penumbra_sliceDepths.y) - 1.0, 0.0, 15.0);
    // paper §3.4.1 leak fix: also mark the next slice away from the light
    // slices k to next are marked
    let next: f32 = min(k + 1.0, 15.0);
    // texture 0
    penumbra_occlusion0 = vec4f((vec4(0.0, 1.0, 2.0, 3.0) >= vec4(k))) * vec4f((vec4(0.0, 1.0, 2.0, 3.0) <= vec4(next)));
    // texture 1
    penumbra_occlusion1 = vec4f((vec4(4.0, 5.0, 6.0, 7.0) >= vec4(k))) * vec4f((vec4(4.0, 5.0, 6.0, 7.0) <= vec4(next)));
    // texture 2
    penumbra_occlusion2 = vec4f((vec4(8.0, 9.0, 10.0, 11.0) >= vec4(k))) * vec4f((vec4(8.0, 9.0, 10.0, 11.0) <= vec4(next)));
    // texture 3
    penumbra_occlusion3 = vec4f((vec4(12.0, 13.0, 14.0, 15.0) >= vec4(k))) * vec4f((vec4(12.0, 13.0, 14.0, 15.0) <= vec4(next)));
}

// @penumbra:entry_point
// entry point: the inputs into the globals above, the uniform values loaded, then penumbra_main()
struct PenumbraStageOutput {
    @location(0) penumbra_occlusion0: vec4f,
    @location(1) penumbra_occlusion1: vec4f,
    @location(2) penumbra_occlusion2: vec4f,
    @location(3) penumbra_occlusion3: vec4f,
}

@fragment
fn main(@location(0) penumbra_depthIn: f32) -> PenumbraStageOutput
{
    penumbra_depth = penumbra_depthIn;
    penumbra_loadSlicing();
    penumbra_main();
    return PenumbraStageOutput(penumbra_occlusion0, penumbra_occlusion1, penumbra_occlusion2, penumbra_occlusion3);
}
