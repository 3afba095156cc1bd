// Penumbra 0.1.0 - atlas packing of the slicing output (paper §3.6), fragment stage
// slices 16 | resolution 512x512 | filter mipmap | fusion extent | packing atlas | light sun | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.

// @penumbra:parameters
@group(0) @binding(0) var penumbra_slices: texture_2d_array<f32>; // slicing output, one layer per RGBA texture

var<private> penumbra_result: vec4f;
var<private> penumbra_fragCoord: vec4f;

// @penumbra:pack_atlas_main
fn penumbra_main()
{
    let texel: vec2i = vec2i(penumbra_fragCoord.xy);
    penumbra_result = textureLoad(penumbra_slices, vec2i(texel.x % 512, texel.y), texel.x / 512, 0);
}

// @penumbra:entry_point
// entry point: the inputs into the globals above, the uniform values loaded, then penumbra_main()
struct PenumbraStageOutput {
    @location(0) penumbra_result: vec4f,
}

@fragment
fn main(@builtin(position) penumbra_fragCoordIn: vec4f) -> PenumbraStageOutput
{
    penumbra_fragCoord = penumbra_fragCoordIn;
    penumbra_main();
    return PenumbraStageOutput(penumbra_result);
}
