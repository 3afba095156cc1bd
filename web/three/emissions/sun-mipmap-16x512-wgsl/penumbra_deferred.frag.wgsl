// Penumbra 0.1.0 - deferred visibility pass: penumbraVisibility of a G-buffer, fragment stage
// slices 16 | resolution 512x512 | filter mipmap | fusion extent | packing atlas | light sun | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target wgsl
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.

var<private> penumbra_visibility: vec4f;
var<private> penumbra_fragCoord: vec4f;

// @penumbra:parameters
struct PenumbraVisibility {
    penumbra_lightFromWorld: mat4x4f, // world to light frame: x, y lateral, z depth along the sun's direction, origin above the scene on the axis through the bounds' centre (scene units)
    penumbra_windowHalfSize: f32, // half side of the square orthographic slicing window (scene units)
    penumbra_tanAngularRadius: f32, // tangent of the sun's angular radius
    penumbra_sliceDepths: vec2f, // x: depth z0 of the first slice's top, y: slice thickness (scene units)
}
@group(0) @binding(0) var<uniform> penumbraVisibilityBlock: PenumbraVisibility;
var<private> penumbra_lightFromWorld: mat4x4f;
var<private> penumbra_windowHalfSize: f32;
var<private> penumbra_tanAngularRadius: f32;
var<private> penumbra_sliceDepths: vec2f;
fn penumbra_loadVisibility()
{
    penumbra_lightFromWorld = penumbraVisibilityBlock.penumbra_lightFromWorld;
    penumbra_windowHalfSize = penumbraVisibilityBlock.penumbra_windowHalfSize;
    penumbra_tanAngularRadius = penumbraVisibilityBlock.penumbra_tanAngularRadius;
    penumbra_sliceDepths = penumbraVisibilityBlock.penumbra_sliceDepths;
}
@group(0) @binding(1) var penumbra_occlusionAtlas: texture_2d<f32>; // occlusion tiles side by side with a full mip chain
@group(0) @binding(2) var penumbra_occlusionAtlas_sampler: sampler;

// @penumbra:kernel
// Kernel on the slice plane at depth zeta, seen from light-frame point p (docs/model.md §1.4, §1.9):
// xy = centre (uv of the slice's texture), z = side (uv), w = filter level.
// clip: the part of the light above the receiver's tangent plane (penumbra_tangentClip)
fn penumbra_kernel(p: vec3f, zeta: f32, clip: vec3f) -> vec4f
{
    // journal §3.5: orthographic slicing, the cone towards the sun grows linearly with distance
    var centre: vec2f = 0.5 + p.xy / (2.0 * penumbra_windowHalfSize);
    var side: f32 = max(p.z - zeta, 0.0) * penumbra_tanAngularRadius / penumbra_windowHalfSize;
    // the light's unit square maps affinely onto the kernel: the clipped part is the square of
    // its shorter side at its centre, so the kernel never reaches behind the tangent plane
    centre += clip.xy * side;
    side *= clip.z;
    // windows narrower than one texel read level 0
    let level: f32 = clamp(log2(max(side * 512.0, 1.0)), 0.0, 9.0);
    return vec4(centre, side, level);
}

// @penumbra:fade
// paper §3.4.2: 0 for planes at or below the point, a ramp over 0.25 of the slice above the point, then 1
fn penumbra_weight(zPoint: f32, zeta: f32) -> f32
{
    return clamp((zPoint - zeta) / (penumbra_sliceDepths.y * 0.25), 0.0, 1.0);
}

// @penumbra:lookup
// paper §3.2: hardware trilinear filtering, level chosen explicitly
fn penumbra_filtered(kernel: vec4f, tile: f32) -> vec4f
{
    return textureSampleLevel(penumbra_occlusionAtlas, penumbra_occlusionAtlas_sampler, vec2((tile + kernel.x) * 0.25, kernel.y), kernel.w);
}

// @penumbra:tangent_clip
// The part of the light above the tangent plane at p (unit normal n, light frame), in the light's
// unit square [-0.5, 0.5]^2: xy = centre of the clipped rectangle, z = its shorter side. The plane
// is cut along the axis it crosses most steeply, at the other axis' centre line (exact for planes
// parallel to a light axis, the same area otherwise), or where that leaves less, in the corner it spares.
fn penumbra_tangentClip(p: vec3f, n: vec3f) -> vec3f
{
    // direction (X, Y) 2 tan(alpha) sideways, 1 up towards the sun is above where its dot with n > 0
    let slopes: vec2f = n.xy * (2.0 * penumbra_tanAngularRadius);
    let level: f32 = n.z;
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
    return clamp(log2(max(2.0 * kernel.z * 512.0, 1.0)), 0.0, 9.0);
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
    // @penumbra:slice_loop
    // static loop over the slices, unrolled; i selects the slice's channel
    var penumbra_i: vec4f = vec4(0.0, 0.0, 0.0, 1.0);
    // slice 15: texture 3, channel a, bottom plane at z0 + 16 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 16.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 3.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 3.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 14: texture 3, channel b, bottom plane at z0 + 15 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 15.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 3.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 3.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 13: texture 3, channel g, bottom plane at z0 + 14 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 14.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 3.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 3.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 12: texture 3, channel r, bottom plane at z0 + 13 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 13.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 3.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 3.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 11: texture 2, channel a, bottom plane at z0 + 12 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 12.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 2.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 2.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 10: texture 2, channel b, bottom plane at z0 + 11 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 11.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 2.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 2.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 9: texture 2, channel g, bottom plane at z0 + 10 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 10.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 2.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 2.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 8: texture 2, channel r, bottom plane at z0 + 9 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 9.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 2.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 2.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 7: texture 1, channel a, bottom plane at z0 + 8 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 8.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 1.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 1.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 6: texture 1, channel b, bottom plane at z0 + 7 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 7.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 1.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 1.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 5: texture 1, channel g, bottom plane at z0 + 6 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 6.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 1.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 1.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 4: texture 1, channel r, bottom plane at z0 + 5 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 5.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 1.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 1.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 3: texture 0, channel a, bottom plane at z0 + 4 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 4.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 0.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 0.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 2: texture 0, channel b, bottom plane at z0 + 3 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 3.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 0.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 0.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 1: texture 0, channel g, bottom plane at z0 + 2 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 2.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 0.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 0.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 0: texture 0, channel r, bottom plane at z0 + 1 * thickness
    {
        let zeta: f32 = penumbra_sliceDepths.x + 1.0 * penumbra_sliceDepths.y;
        let kernel: vec4f = penumbra_kernel(p, zeta, penumbra_clip);
        let fade: f32 = penumbra_weight(p.z, zeta);
        let coverage: f32 = dot(penumbra_filtered(kernel, 0.0), penumbra_i);
        let q: f32 = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        let penumbra_wide: vec4f = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        let area: f32 = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 0.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
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
    let penumbra_spread: f32 = max(n.z / penumbra_across, 0.0);
    let penumbra_footprint: f32 = penumbra_spread * 2.0 * penumbra_sliceDepths.y;
    let penumbra_cap: f32 = 2.0 * penumbra_windowHalfSize * 0.0078125;
    // move the point 1.0 slicing texels sideways along its normal, off its own texels
    p.xy += n.xy * (2.0 * penumbra_windowHalfSize * 0.001953125);
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
@group(0) @binding(3) var penumbra_worldPositions: texture_2d<f32>; // G-buffer: xyz world position, w = 1 where there is geometry and 0 for the background (scene units)
@group(0) @binding(4) var penumbra_worldNormals: texture_2d<f32>; // G-buffer: xyz world normal of the side the viewer sees (tangent clip, normal offset)

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
