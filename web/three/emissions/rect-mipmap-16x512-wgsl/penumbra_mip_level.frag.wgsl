// Penumbra 0.1.0 - mip chain of the occlusion textures (WebGPU has no generateMipmap), level n to n+1, fragment stage
// slices 16 | resolution 512x512 | filter mipmap | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.

// @penumbra:parameters
@group(0) @binding(0) var penumbra_source: texture_2d<f32>; // the level being reduced (the pass binds one level)

var<private> penumbra_result: vec4f;
var<private> penumbra_fragCoord: vec4f;

// @penumbra:mip_level_main
// the mean of the 2 x 2 texels of level n under this texel of level n + 1
fn penumbra_main()
{
    let base: vec2i = 2 * vec2i(penumbra_fragCoord.xy);
    penumbra_result = 0.25 * (textureLoad(penumbra_source, base, 0) + textureLoad(penumbra_source, base + vec2i(1, 0), 0)
        + textureLoad(penumbra_source, base + vec2i(0, 1), 0) + textureLoad(penumbra_source, base + vec2i(1, 1), 0));
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
