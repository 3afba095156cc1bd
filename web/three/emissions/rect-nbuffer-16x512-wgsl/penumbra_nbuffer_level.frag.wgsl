// Penumbra 0.1.0 - N-buffer level l from level l-1, fragment stage
// slices 16 | resolution 512x512 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.

// @penumbra:parameters
struct PenumbraPass {
    penumbra_step: i32, // offset between the windows combined by this pass, in texels of the texture it reads (texels)
    penumbra_sourceTile: i32, // side of one tile of the previous level (texels)
    penumbra_scale: i32, // texels of the previous level per texel of this one, per axis (1 or 2)
}
@group(0) @binding(0) var<uniform> penumbraPassBlock: PenumbraPass;
var<private> penumbra_step: i32;
var<private> penumbra_sourceTile: i32;
var<private> penumbra_scale: i32;
fn penumbra_loadPass()
{
    penumbra_step = penumbraPassBlock.penumbra_step;
    penumbra_sourceTile = penumbraPassBlock.penumbra_sourceTile;
    penumbra_scale = penumbraPassBlock.penumbra_scale;
}
@group(0) @binding(1) var penumbra_source: texture_2d<f32>; // previous filter level (atlas)

var<private> penumbra_result: vec4f;
var<private> penumbra_fragCoord: vec4f;

// @penumbra:level_source
// texel `local` of the previous level's tile that starts at `origin`, 0 outside the tile
fn penumbra_source_texel(origin: vec2i, local: vec2i) -> vec4f
{
    let inside: bool = all((local >= vec2i(0))) && all((local < vec2i(penumbra_sourceTile)));
    let value: vec4f = textureLoad(penumbra_source, origin + clamp(local, vec2i(0), vec2i(penumbra_sourceTile - 1)), 0);
    return select(vec4(0.0), value, inside);
}

// @penumbra:nbuffer_level_main
fn penumbra_main()
{
    let fragment: vec2i = vec2i(penumbra_fragCoord.xy);
    let side: i32 = select(penumbra_sourceTile / 2, penumbra_sourceTile, penumbra_scale == 1); // this level's tile side
    // which occlusion texture: fragment.x / side without an integer division (the pixel centre's
    // half texel keeps the float quotient at least 0.5 / side off an integer: exact for any side)
    let tile: i32 = i32(penumbra_fragCoord.x / f32(side));
    let origin: vec2i = vec2i(tile * penumbra_sourceTile, 0);
    let local: vec2i = vec2i(fragment.x - tile * side, fragment.y) * penumbra_scale;
    let s: i32 = penumbra_step; // 2^(l-1) texels of level 0, in texels of the previous level
    penumbra_result = 0.25 * (penumbra_source_texel(origin, local) + penumbra_source_texel(origin, local + vec2i(s, 0))
    + penumbra_source_texel(origin, local + vec2i(0, s)) + penumbra_source_texel(origin, local + vec2i(s, s)));
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
    penumbra_loadPass();
    penumbra_main();
    return PenumbraStageOutput(penumbra_result);
}
