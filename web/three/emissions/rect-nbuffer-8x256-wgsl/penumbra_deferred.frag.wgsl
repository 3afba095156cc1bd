// Penumbra 0.1.0 - deferred visibility pass: penumbraVisibility of a G-buffer, fragment stage
// slices 8 | resolution 256x256 | filter nbuffer | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 2 RGBA occlusion texture(s), filter levels 0 to 8. Generated: edit the configuration, not this file.

var<private> penumbra_visibility: vec4f;
var<private> penumbra_fragCoord: vec4f;

// @penumbra:parameters
struct PenumbraVisibility {
    penumbra_lightFromWorld: mat4x4f, // world to light frame: x, y lateral, z depth along the light normal, origin at the light centre (scene units)
    penumbra_lightSize: vec2f, // light rectangle width, height (scene units)
    penumbra_copDistance: f32, // distance d of the slicing centre of projection behind the light (scene units)
    penumbra_sliceDepths: vec2f, // x: depth z0 of the first slice's top, y: slice thickness (scene units)
}
@group(0) @binding(0) var<uniform> penumbraVisibilityBlock: PenumbraVisibility;
var<private> penumbra_lightFromWorld: mat4x4f;
var<private> penumbra_lightSize: vec2f;
var<private> penumbra_copDistance: f32;
var<private> penumbra_sliceDepths: vec2f;
fn penumbra_loadVisibility()
{
    penumbra_lightFromWorld = penumbraVisibilityBlock.penumbra_lightFromWorld;
    penumbra_lightSize = penumbraVisibilityBlock.penumbra_lightSize;
    penumbra_copDistance = penumbraVisibilityBlock.penumbra_copDistance;
    penumbra_sliceDepths = penumbraVisibilityBlock.penumbra_sliceDepths;
}
@group(0) @binding(1) var penumbra_level0: texture_2d<f32>; // filter level, occlusion tiles side by side
@group(0) @binding(2) var penumbra_level0_sampler: sampler;
@group(0) @binding(3) var penumbra_level1: texture_2d<f32>; // filter level, occlusion tiles side by side
@group(0) @binding(4) var penumbra_level1_sampler: sampler;
@group(0) @binding(5) var penumbra_level2: texture_2d<f32>; // filter level, occlusion tiles side by side
@group(0) @binding(6) var penumbra_level2_sampler: sampler;
@group(0) @binding(7) var penumbra_level3: texture_2d<f32>; // filter level, occlusion tiles side by side
@group(0) @binding(8) var penumbra_level3_sampler: sampler;
@group(0) @binding(9) var penumbra_level4: texture_2d<f32>; // filter level, occlusion tiles side by side
@group(0) @binding(10) var penumbra_level4_sampler: sampler;
@group(0) @binding(11) var penumbra_level5: texture_2d<f32>; // filter level, occlusion tiles side by side
@group(0) @binding(12) var penumbra_level5_sampler: sampler;
@group(0) @binding(13) var penumbra_level6: texture_2d<f32>; // filter level, occlusion tiles side by side
@group(0) @binding(14) var penumbra_level6_sampler: sampler;
@group(0) @binding(15) var penumbra_level7: texture_2d<f32>; // filter level, occlusion tiles side by side
@group(0) @binding(16) var penumbra_level7_sampler: sampler;
@group(0) @binding(17) var penumbra_level8: texture_2d<f32>; // filter level, occlusion tiles side by side
@group(0) @binding(18) var penumbra_level8_sampler: sampler;

// @penumbra:kernel
// Kernel on the slice plane at depth zeta, seen from light-frame point p (docs/model.md §1.4, §1.9):
// xy = centre (uv of the slice's texture), z = side (uv), w = filter level.
// clip: the part of the light above the receiver's tangent plane (penumbra_tangentClip)
fn penumbra_kernel(p: vec3f, zeta: f32, clip: vec3f) -> vec4f
{
    // rays from p to the light rectangle cut the plane in a square; w and h cancel out of its side
    let scale: f32 = penumbra_copDistance / (p.z * (penumbra_copDistance + zeta));
    var centre: vec2f = 0.5 + p.xy * (zeta * scale) / penumbra_lightSize;
    var side: f32 = max(p.z - zeta, 0.0) * scale;
    // the light's unit square maps affinely onto the kernel: the clipped part is the square of
    // its shorter side at its centre, so the kernel never reaches behind the tangent plane
    centre += clip.xy * side;
    side *= clip.z;
    // windows narrower than one texel read level 0
    let level: f32 = clamp(log2(max(side * 256.0, 1.0)), 0.0, 8.0);
    return vec4(centre, side, level);
}

// @penumbra:fade
// paper §3.4.2: 0 for planes at or below the point, a ramp over 0.25 of the slice above the point, then 1
fn penumbra_weight(zPoint: f32, zeta: f32) -> f32
{
    return clamp((zPoint - zeta) / (penumbra_sliceDepths.y * 0.25), 0.0, 1.0);
}

// @penumbra:tangent_clip
// The part of the light above the tangent plane at p (unit normal n, light frame), in the light's
// unit square [-0.5, 0.5]^2: xy = centre of the clipped rectangle, z = its shorter side. The plane
// is cut along the axis it crosses most steeply, at the other axis' centre line (exact for planes
// parallel to a light axis, the same area otherwise), or where that leaves less, in the corner it spares.
fn penumbra_tangentClip(p: vec3f, n: vec3f) -> vec3f
{
    // light point (X w, Y h, 0) is above the plane where n.x X w + n.y Y h > dot(n, p)
    let slopes: vec2f = n.xy * penumbra_lightSize;
    let level: f32 = dot(n, p);
    let alongX: bool = abs(slopes.x) >= abs(slopes.y);
    let slope: f32 = select(slopes.y, slopes.x, alongX);
    let safe: f32 = select(min(slope, -1e-12), max(slope, 1e-12), slope >= 0.0);
    let cut: f32 = clamp(level / safe, -0.5, 0.5);
    let lo: f32 = select(-0.5, cut, safe > 0.0);
    let hi: f32 = select(cut, 0.5, safe > 0.0);
    let mid: f32 = 0.5 * (lo + hi);
    var clip: vec3f = vec3(select(vec2(0.0, mid), vec2(mid, 0.0), alongX), hi - lo);
    // a plane that leaves a corner of the light above it (the centre line may lie wholly below): the
    // largest square in that corner, where it is larger; 0 where the whole light is below the plane
    let slopeSum: f32 = abs(slopes.x) + abs(slopes.y);
    let corner: f32 = clamp((0.5 * slopeSum - level) / max(slopeSum, 1e-12), 0.0, 1.0);
    if (corner > clip.z) { clip = vec3(sign(slopes) * (0.5 - 0.5 * corner), corner); }
    return clip;
}

// @penumbra:fusion
// extent fusion: correlated fusion, the occluder's size from a window twice the kernel's side, docs/model.md §1.7.2
fn penumbra_extentStep(q: f32, kernel: vec4f, area: f32, prev: f32, prevKernel: vec4f, prevArea: f32) -> f32
{
    // parallax between the two kernels, RMS over the light's points, per axis (uv)
    let parallax: vec2f = kernel.xy - prevKernel.xy;
    let grow: f32 = kernel.z - prevKernel.z;
    let shift: vec2f = sqrt(parallax * parallax + vec2(grow * grow / 12.0));
    // the occluder's size (uv): the larger covered area either slice sees around its kernel
    let feature: f32 = sqrt(max(area, prevArea));
    let overlap: vec2f = saturate(1.0 - shift / max(feature, 1e-12));
    // blocked by both: nested (the smaller) when the occluder overlaps itself, independent (product) when not
    let both: f32 = mix(q * prev, min(q, prev), overlap.x * overlap.y);
    return (1.0 - q - prev + both) / max(1.0 - prev, 1e-6);
}

// @penumbra:fusion
// filter level of a window twice the kernel's side (extent fusion)
fn penumbra_wideLevel(kernel: vec4f) -> f32
{
    return clamp(log2(max(2.0 * kernel.z * 256.0, 1.0)), 0.0, 8.0);
}

// @penumbra:visibility
// The fused visibility at light-frame point p of the part of the light that penumbra_clip keeps.
fn penumbra_clippedVisibility(p: vec3f, penumbra_clip: vec3f) -> f32
{
    // @penumbra:fusion
    // extent fusion: correlated fusion, the occluder's size from the covered area in a window twice
    // the kernel's side, so an edge of a solid that crosses the kernel stays nested
    var penumbra_lit: f32 = 1.0;
    var penumbra_prev: f32 = 0.0; // q of the slice visited before (its neighbour)
    var penumbra_prevKernel: vec4f = vec4(0.0); // its kernel
    var penumbra_prevArea: f32 = 0.0; // and its covered area
    // @penumbra:level_loop
    // start at the nearest slice above the point; slices below it have weight 0
    var penumbra_k: f32 = clamp(ceil((p.z - penumbra_sliceDepths.x) / penumbra_sliceDepths.y) - 2.0, -1.0, 7.0);
    var penumbra_i: vec4f = vec4f((vec4((max(penumbra_k, 0.0) % 4.0)) == vec4(0.0, 1.0, 2.0, 3.0)));
    var penumbra_delta: f32 = floor(max(penumbra_k, 0.0) / 4.0) * 0.5; // horizontal offset of the slice's tile
    // level 0: windows of 1 to 2 texels
    while (penumbra_k >= 0.0) {
        let zeta: f32 = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 1.0) { break; }
        let penumbra_lo: vec4f = textureSampleLevel(penumbra_level0, penumbra_level0_sampler, vec2(penumbra_delta + (kernel.x - 0.0) * 0.5, kernel.y - 0.0), 0.0);
        let penumbra_hi: vec4f = textureSampleLevel(penumbra_level1, penumbra_level1_sampler, vec2(penumbra_delta + (kernel.x - 0.001953125) * 0.5, kernel.y - 0.001953125), 0.0);
        let texel: vec4f = mix(penumbra_lo, penumbra_hi, kernel.w - 0.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wideAt: f32 = penumbra_wideLevel(kernel);
        let penumbra_wide: vec4f = select(mix(penumbra_hi, textureSampleLevel(penumbra_level2, penumbra_level2_sampler, vec2(penumbra_delta + (kernel.x - 0.005859375) * 0.5, kernel.y - 0.005859375), 0.0), penumbra_wideAt - 1.0), mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 0.0), penumbra_wideAt < 1.0);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(texel, penumbra_i);
        let q: f32 = fade * coverage;
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.5;
    }
    // level 1: windows of 2 to 4 texels
    while (penumbra_k >= 0.0) {
        let zeta: f32 = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 2.0) { break; }
        let penumbra_lo: vec4f = textureSampleLevel(penumbra_level1, penumbra_level1_sampler, vec2(penumbra_delta + (kernel.x - 0.001953125) * 0.5, kernel.y - 0.001953125), 0.0);
        let penumbra_hi: vec4f = textureSampleLevel(penumbra_level2, penumbra_level2_sampler, vec2(penumbra_delta + (kernel.x - 0.005859375) * 0.5, kernel.y - 0.005859375), 0.0);
        let texel: vec4f = mix(penumbra_lo, penumbra_hi, kernel.w - 1.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wideAt: f32 = penumbra_wideLevel(kernel);
        let penumbra_wide: vec4f = select(mix(penumbra_hi, textureSampleLevel(penumbra_level3, penumbra_level3_sampler, vec2(penumbra_delta + (kernel.x - 0.01171875) * 0.5, kernel.y - 0.01171875), 0.0), penumbra_wideAt - 2.0), mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 1.0), penumbra_wideAt < 2.0);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(texel, penumbra_i);
        let q: f32 = fade * coverage;
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.5;
    }
    // level 2: windows of 4 to 8 texels
    while (penumbra_k >= 0.0) {
        let zeta: f32 = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 3.0) { break; }
        let penumbra_lo: vec4f = textureSampleLevel(penumbra_level2, penumbra_level2_sampler, vec2(penumbra_delta + (kernel.x - 0.005859375) * 0.5, kernel.y - 0.005859375), 0.0);
        let penumbra_hi: vec4f = textureSampleLevel(penumbra_level3, penumbra_level3_sampler, vec2(penumbra_delta + (kernel.x - 0.01171875) * 0.5, kernel.y - 0.01171875), 0.0);
        let texel: vec4f = mix(penumbra_lo, penumbra_hi, kernel.w - 2.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wideAt: f32 = penumbra_wideLevel(kernel);
        let penumbra_wide: vec4f = select(mix(penumbra_hi, textureSampleLevel(penumbra_level4, penumbra_level4_sampler, vec2(penumbra_delta + (kernel.x - 0.0234375) * 0.5, kernel.y - 0.0234375), 0.0), penumbra_wideAt - 3.0), mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 2.0), penumbra_wideAt < 3.0);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(texel, penumbra_i);
        let q: f32 = fade * coverage;
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.5;
    }
    // level 3: windows of 8 to 16 texels
    while (penumbra_k >= 0.0) {
        let zeta: f32 = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 4.0) { break; }
        let penumbra_lo: vec4f = textureSampleLevel(penumbra_level3, penumbra_level3_sampler, vec2(penumbra_delta + (kernel.x - 0.01171875) * 0.5, kernel.y - 0.01171875), 0.0);
        let penumbra_hi: vec4f = textureSampleLevel(penumbra_level4, penumbra_level4_sampler, vec2(penumbra_delta + (kernel.x - 0.0234375) * 0.5, kernel.y - 0.0234375), 0.0);
        let texel: vec4f = mix(penumbra_lo, penumbra_hi, kernel.w - 3.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wideAt: f32 = penumbra_wideLevel(kernel);
        let penumbra_wide: vec4f = select(mix(penumbra_hi, textureSampleLevel(penumbra_level5, penumbra_level5_sampler, vec2(penumbra_delta + (kernel.x - 0.046875) * 0.5, kernel.y - 0.046875), 0.0), penumbra_wideAt - 4.0), mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 3.0), penumbra_wideAt < 4.0);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(texel, penumbra_i);
        let q: f32 = fade * coverage;
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.5;
    }
    // level 4: windows of 16 to 32 texels
    while (penumbra_k >= 0.0) {
        let zeta: f32 = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 5.0) { break; }
        let penumbra_lo: vec4f = textureSampleLevel(penumbra_level4, penumbra_level4_sampler, vec2(penumbra_delta + (kernel.x - 0.0234375) * 0.5, kernel.y - 0.0234375), 0.0);
        let penumbra_hi: vec4f = textureSampleLevel(penumbra_level5, penumbra_level5_sampler, vec2(penumbra_delta + (kernel.x - 0.046875) * 0.5, kernel.y - 0.046875), 0.0);
        let texel: vec4f = mix(penumbra_lo, penumbra_hi, kernel.w - 4.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wideAt: f32 = penumbra_wideLevel(kernel);
        let penumbra_wide: vec4f = select(mix(penumbra_hi, textureSampleLevel(penumbra_level6, penumbra_level6_sampler, vec2(penumbra_delta + (kernel.x - 0.09375) * 0.5, kernel.y - 0.09375), 0.0), penumbra_wideAt - 5.0), mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 4.0), penumbra_wideAt < 5.0);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(texel, penumbra_i);
        let q: f32 = fade * coverage;
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.5;
    }
    // level 5: windows of 32 to 64 texels
    while (penumbra_k >= 0.0) {
        let zeta: f32 = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 6.0) { break; }
        let penumbra_lo: vec4f = textureSampleLevel(penumbra_level5, penumbra_level5_sampler, vec2(penumbra_delta + (kernel.x - 0.046875) * 0.5, kernel.y - 0.046875), 0.0);
        let penumbra_hi: vec4f = textureSampleLevel(penumbra_level6, penumbra_level6_sampler, vec2(penumbra_delta + (kernel.x - 0.09375) * 0.5, kernel.y - 0.09375), 0.0);
        let texel: vec4f = mix(penumbra_lo, penumbra_hi, kernel.w - 5.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wideAt: f32 = penumbra_wideLevel(kernel);
        let penumbra_wide: vec4f = select(mix(penumbra_hi, textureSampleLevel(penumbra_level7, penumbra_level7_sampler, vec2(penumbra_delta + (kernel.x - 0.1875) * 0.5, kernel.y - 0.1875), 0.0), penumbra_wideAt - 6.0), mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 5.0), penumbra_wideAt < 6.0);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(texel, penumbra_i);
        let q: f32 = fade * coverage;
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.5;
    }
    // level 6: windows of 64 to 128 texels
    while (penumbra_k >= 0.0) {
        let zeta: f32 = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 7.0) { break; }
        let penumbra_lo: vec4f = textureSampleLevel(penumbra_level6, penumbra_level6_sampler, vec2(penumbra_delta + (kernel.x - 0.09375) * 0.5, kernel.y - 0.09375), 0.0);
        let penumbra_hi: vec4f = textureSampleLevel(penumbra_level7, penumbra_level7_sampler, vec2(penumbra_delta + (kernel.x - 0.1875) * 0.5, kernel.y - 0.1875), 0.0);
        let texel: vec4f = mix(penumbra_lo, penumbra_hi, kernel.w - 6.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wideAt: f32 = penumbra_wideLevel(kernel);
        let penumbra_wide: vec4f = select(mix(penumbra_hi, textureSampleLevel(penumbra_level8, penumbra_level8_sampler, vec2(penumbra_delta + (kernel.x - 0.375) * 0.5, kernel.y - 0.375), 0.0), penumbra_wideAt - 7.0), mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 6.0), penumbra_wideAt < 7.0);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(texel, penumbra_i);
        let q: f32 = fade * coverage;
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.5;
    }
    // level 7: windows of 128 to 256 texels
    while (penumbra_k >= 0.0) {
        let zeta: f32 = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 8.0) { break; }
        let penumbra_lo: vec4f = textureSampleLevel(penumbra_level7, penumbra_level7_sampler, vec2(penumbra_delta + (kernel.x - 0.1875) * 0.5, kernel.y - 0.1875), 0.0);
        let penumbra_hi: vec4f = textureSampleLevel(penumbra_level8, penumbra_level8_sampler, vec2(penumbra_delta + (kernel.x - 0.375) * 0.5, kernel.y - 0.375), 0.0);
        let texel: vec4f = mix(penumbra_lo, penumbra_hi, kernel.w - 7.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wideAt: f32 = penumbra_wideLevel(kernel);
        let penumbra_wide: vec4f = mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 7.0);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(texel, penumbra_i);
        let q: f32 = fade * coverage;
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.5;
    }
    // level 8: the remaining slices, windows of 256 texels and more
    while (penumbra_k >= 0.0) {
        let zeta: f32 = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let penumbra_lo: vec4f = textureSampleLevel(penumbra_level8, penumbra_level8_sampler, vec2(penumbra_delta + (kernel.x - 0.375) * 0.5, kernel.y - 0.375), 0.0);
        let texel: vec4f = penumbra_lo;
        let penumbra_wide: vec4f = penumbra_lo; // no wider window than the last level's
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(texel, penumbra_i);
        let q: f32 = fade * coverage;
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.5;
    }
    // @penumbra:fusion_result
    return clamp(penumbra_lit, 0.0, 1.0);
}

// @penumbra:visibility
// Fraction of the part of the light above the tangent plane at worldPos (worldNormal: the normal of
// the side being lit, any length but not zero) that is visible: 1 lit, 0 in umbra.
fn penumbraVisibilityWithNormal(worldPos: vec3f, worldNormal: vec3f) -> f32
{
    var p: vec3f = (penumbra_lightFromWorld * vec4(worldPos, 1.0)).xyz;
    p.z = max(p.z, 1e-6); // points on or behind the light plane
    var n: vec3f = mat3x3f(penumbra_lightFromWorld[0].xyz, penumbra_lightFromWorld[1].xyz, penumbra_lightFromWorld[2].xyz) * worldNormal;
    n *= inverseSqrt(max(dot(n, n), 1e-20));
    let penumbra_clip: vec3f = penumbra_tangentClip(p, n);
    // a receiver turned away from all of the light receives none of it: its lookups would read the
    // occluders beside it, or none, and light it
    if (penumbra_clip.z <= 0.0) { return 0.0; }
    // footprint of the receiver's own tangent plane in the slice above it, along its normal (scene units)
    let penumbra_across: f32 = max(length(n.xy), 1e-6);
    let penumbra_spread: f32 = max(n.z / penumbra_across + dot(p.xy, n.xy) / (penumbra_across * (penumbra_copDistance + p.z)), 0.0);
    let penumbra_footprint: f32 = penumbra_spread * 2.0 * penumbra_sliceDepths.y;
    let penumbra_cap: f32 = max(penumbra_lightSize.x, penumbra_lightSize.y) * (penumbra_copDistance + p.z) / penumbra_copDistance * 0.015625;
    // move the point 1.0 slicing texels sideways along its normal, off its own texels
    p.xy += n.xy * penumbra_lightSize * ((penumbra_copDistance + p.z) / penumbra_copDistance * 0.00390625);
    // and off its own footprint
    p.xy += n.xy / penumbra_across * min(penumbra_footprint, penumbra_cap);
    return penumbra_clippedVisibility(p, penumbra_clip);
}

// Without a normal: the fraction of the whole light that is visible (the paper's kernels, no clip),
// for shaders written against penumbraVisibility(vec3 worldPos) of every technique.
fn penumbraVisibility(worldPos: vec3f) -> f32
{
    var p: vec3f = (penumbra_lightFromWorld * vec4(worldPos, 1.0)).xyz;
    p.z = max(p.z, 1e-6); // points on or behind the light plane
    return penumbra_clippedVisibility(p, vec3(0.0, 0.0, 1.0));
}

// @penumbra:parameters
@group(0) @binding(19) var penumbra_worldPositions: texture_2d<f32>; // G-buffer: xyz world position, w = 1 where there is geometry and 0 for the background (scene units)
@group(0) @binding(20) var penumbra_worldNormals: texture_2d<f32>; // G-buffer: xyz world normal of the side the viewer sees (tangent clip, normal offset)

// @penumbra:deferred_main
fn penumbra_main()
{
    let world: vec4f = textureLoad(penumbra_worldPositions, vec2i(penumbra_fragCoord.xy), 0);
    // A real branch, not a select: the background must not pay for the whole slice loop.
    if (world.w < 0.5)
    {
        penumbra_visibility = vec4(1.0);
        return;
    }
    let normal: vec3f = textureLoad(penumbra_worldNormals, vec2i(penumbra_fragCoord.xy), 0).xyz;
    penumbra_visibility = vec4(vec3(penumbraVisibilityWithNormal(world.xyz, normal)), 1.0);
}

// @penumbra:entry_point
// entry point: the inputs into the globals above, the uniform values loaded, then penumbra_main()
struct PenumbraStageOutput {
    @location(0) penumbra_visibility: vec4f,
}

@fragment
fn main(@builtin(position) penumbra_fragCoordIn: vec4f) -> PenumbraStageOutput
{
    penumbra_fragCoord = penumbra_fragCoordIn;
    penumbra_loadVisibility();
    penumbra_main();
    return PenumbraStageOutput(penumbra_visibility);
}
