// Penumbra 0.1.0 - full-screen triangle, vertex stage (draw 3 vertices, no attributes)
// slices 8 | resolution 256x256 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 2 RGBA occlusion texture(s), filter levels 0 to 8. Generated: edit the configuration, not this file.

var<private> penumbra_vertexIndex: i32;
var<private> penumbra_clipPosition: vec4f;
// @penumbra:fullscreen_vertex_main
fn penumbra_main()
{
    let index: i32 = penumbra_vertexIndex;
    let corner: vec2f = vec2(f32((index << 1u) & 2), f32(index & 2));
    penumbra_clipPosition = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}

// @penumbra:entry_point
// entry point: the inputs into the globals above, the uniform values loaded, then penumbra_main()
struct PenumbraStageOutput {
    @builtin(position) penumbra_clipPosition: vec4f,
}

@vertex
fn main(@builtin(vertex_index) penumbra_vertexIndexIn: u32) -> PenumbraStageOutput
{
    penumbra_vertexIndex = i32(penumbra_vertexIndexIn);
    penumbra_main();
    return PenumbraStageOutput(penumbra_clipPosition);
}
