// Penumbra 0.1.0 - atlas packing of the slicing output (paper §3.6) and N-buffer level 1 from it, fragment stage
// slices 8 | resolution 256x256 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 2 RGBA occlusion texture(s), filter levels 0 to 8. Generated: edit the configuration, not this file.

// @penumbra:parameters
@group(0) @binding(0) var penumbra_slices: texture_2d_array<f32>; // slicing output, one layer per RGBA texture

var<private> penumbra_level0: vec4f; // level 0: the slicing output
var<private> penumbra_level1: vec4f; // level 1, same size
var<private> penumbra_fragCoord: vec4f;

// @penumbra:pack_atlas_source
// texel `local` of occlusion texture `layer` of the slicing output, 0 outside its 256 x 256 texels
fn penumbra_slice_texel(layer: i32, local: vec2i) -> vec4f
{
    let inside: bool = all((local >= vec2i(0))) && all((local < vec2i(256)));
    let value: vec4f = textureLoad(penumbra_slices, clamp(local, vec2i(0), vec2i(255)), layer, 0);
    return select(vec4(0.0), value, inside);
}

// @penumbra:pack_atlas_main
fn penumbra_main()
{
    let texel: vec2i = vec2i(penumbra_fragCoord.xy);
    let layer: i32 = texel.x / 256; // which occlusion texture: the tile
    let local: vec2i = vec2i(texel.x - layer * 256, texel.y);
    let level0: vec4f = penumbra_slice_texel(layer, local);
    penumbra_level0 = level0;
    // level 1 (Décoret 2005): the mean of the 2 x 2 window anchored here
    penumbra_level1 = 0.25 * (level0 + penumbra_slice_texel(layer, local + vec2i(1, 0))
        + penumbra_slice_texel(layer, local + vec2i(0, 1)) + penumbra_slice_texel(layer, local + vec2i(1, 1)));
}

// @penumbra:entry_point
// entry point: the inputs into the globals above, the uniform values loaded, then penumbra_main()
struct PenumbraStageOutput {
    @location(0) penumbra_level0: vec4f,
    @location(1) penumbra_level1: vec4f,
}

@fragment
fn main(@builtin(position) penumbra_fragCoordIn: vec4f) -> PenumbraStageOutput
{
    penumbra_fragCoord = penumbra_fragCoordIn;
    penumbra_main();
    return PenumbraStageOutput(penumbra_level0, penumbra_level1);
}
