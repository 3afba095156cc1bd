#version 300 es
// Penumbra 0.1.0 - example shading pass: Lambert term times penumbraVisibility, fragment stage
// slices 16 | resolution 512x512 | filter mipmap | fusion extent | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
// 4 RGBA occlusion texture(s), filter levels 0 to 9. Generated: edit the configuration, not this file.
// @penumbra:precision
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler3D;

// @penumbra:example_inputs
in vec3 penumbra_worldPos; // scene units
in vec3 penumbra_worldNormal;
layout(location = 0) out vec4 penumbra_color;

// @penumbra:parameters
uniform mat4 penumbra_lightFromWorld; // world to light frame: x, y lateral, z depth along the light normal, origin at the light centre (scene units)
uniform vec2 penumbra_lightSize; // light rectangle width, height (scene units)
uniform float penumbra_copDistance; // distance d of the slicing centre of projection behind the light (scene units)
uniform vec2 penumbra_sliceDepths; // x: depth z0 of the first slice's top, y: slice thickness (scene units)
uniform sampler2D penumbra_occlusionAtlas; // occlusion tiles side by side with a full mip chain, texture unit 0

// @penumbra:kernel
// Kernel on the slice plane at depth zeta, seen from light-frame point p (docs/model.md §1.4, §1.9):
// xy = centre (uv of the slice's texture), z = side (uv), w = filter level.
// clip: the part of the light above the receiver's tangent plane (penumbra_tangentClip)
vec4 penumbra_kernel(vec3 p, float zeta, vec3 clip)
{
    // rays from p to the light rectangle cut the plane in a square; w and h cancel out of its side
    float scale = penumbra_copDistance / (p.z * (penumbra_copDistance + zeta));
    vec2 centre = 0.5 + p.xy * (zeta * scale) / penumbra_lightSize;
    float side = max(p.z - zeta, 0.0) * scale;
    // the light's unit square maps affinely onto the kernel: the clipped part is the square of
    // its shorter side at its centre, so the kernel never reaches behind the tangent plane
    centre += clip.xy * side;
    side *= clip.z;
    // windows narrower than one texel read level 0
    float level = clamp(log2(max(side * 512.0, 1.0)), 0.0, 9.0);
    return vec4(centre, side, level);
}

// @penumbra:fade
// paper §3.4.2: 0 for planes at or below the point, a ramp over 0.25 of the slice above the point, then 1
float penumbra_weight(float zPoint, float zeta)
{
    return clamp((zPoint - zeta) / (penumbra_sliceDepths.y * 0.25), 0.0, 1.0);
}

// @penumbra:lookup
// paper §3.2: hardware trilinear filtering, level chosen explicitly
vec4 penumbra_filtered(vec4 kernel, float tile)
{
    return textureLod(penumbra_occlusionAtlas, vec2((tile + kernel.x) * 0.25, kernel.y), kernel.w);
}

// @penumbra:tangent_clip
// The part of the light above the tangent plane at p (unit normal n, light frame), in the light's
// unit square [-0.5, 0.5]^2: xy = centre of the clipped rectangle, z = its shorter side. The plane
// is cut along the axis it crosses most steeply, at the other axis' centre line (exact for planes
// parallel to a light axis, the same area otherwise), or where that leaves less, in the corner it spares.
vec3 penumbra_tangentClip(vec3 p, vec3 n)
{
    // light point (X w, Y h, 0) is above the plane where n.x X w + n.y Y h > dot(n, p)
    vec2 slopes = n.xy * penumbra_lightSize;
    float level = dot(n, p);
    bool alongX = abs(slopes.x) >= abs(slopes.y);
    float slope = alongX ? slopes.x : slopes.y;
    float safe = slope >= 0.0 ? max(slope, 1e-12) : min(slope, -1e-12);
    float cut = clamp(level / safe, -0.5, 0.5);
    float lo = safe > 0.0 ? cut : -0.5;
    float hi = safe > 0.0 ? 0.5 : cut;
    float mid = 0.5 * (lo + hi);
    vec3 clip = vec3(alongX ? vec2(mid, 0.0) : vec2(0.0, mid), hi - lo);
    // a plane that leaves a corner of the light above it (the centre line may lie wholly below): the
    // largest square in that corner, where it is larger; 0 where the whole light is below the plane
    float slopeSum = abs(slopes.x) + abs(slopes.y);
    float corner = clamp((0.5 * slopeSum - level) / max(slopeSum, 1e-12), 0.0, 1.0);
    if (corner > clip.z) { clip = vec3(sign(slopes) * (0.5 - 0.5 * corner), corner); }
    return clip;
}

// @penumbra:fusion
// extent fusion: correlated fusion, the occluder's size from a window twice the kernel's side, docs/model.md §1.7.2
float penumbra_extentStep(float q, vec4 kernel, float area, float prev, vec4 prevKernel, float prevArea)
{
    // parallax between the two kernels, RMS over the light's points, per axis (uv)
    vec2 parallax = kernel.xy - prevKernel.xy;
    float grow = kernel.z - prevKernel.z;
    vec2 shift = sqrt(parallax * parallax + vec2(grow * grow / 12.0));
    // the occluder's size (uv): the larger covered area either slice sees around its kernel
    float feature = sqrt(max(area, prevArea));
    vec2 overlap = clamp(1.0 - shift / max(feature, 1e-12), 0.0, 1.0);
    // blocked by both: nested (the smaller) when the occluder overlaps itself, independent (product) when not
    float both = mix(q * prev, min(q, prev), overlap.x * overlap.y);
    return (1.0 - q - prev + both) / max(1.0 - prev, 1e-6);
}

// @penumbra:fusion
// filter level of a window twice the kernel's side (extent fusion)
float penumbra_wideLevel(vec4 kernel)
{
    return clamp(log2(max(2.0 * kernel.z * 512.0, 1.0)), 0.0, 9.0);
}

// @penumbra:visibility
// The fused visibility at light-frame point p of the part of the light that penumbra_clip keeps.
float penumbra_clippedVisibility(vec3 p, vec3 penumbra_clip)
{
    // @penumbra:fusion
    // extent fusion: correlated fusion, the occluder's size from the covered area in a window twice
    // the kernel's side, so an edge of a solid that crosses the kernel stays nested
    float penumbra_lit = 1.0;
    float penumbra_prev = 0.0; // q of the slice visited before (its neighbour)
    vec4 penumbra_prevKernel = vec4(0.0); // its kernel
    float penumbra_prevArea = 0.0; // and its covered area
    // @penumbra:slice_loop
    // static loop over the slices, unrolled; i selects the slice's channel
    vec4 penumbra_i = vec4(0.0, 0.0, 0.0, 1.0);
    // slice 15: texture 3, channel a, bottom plane at z0 + 16 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 16.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 3.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 3.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 14: texture 3, channel b, bottom plane at z0 + 15 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 15.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 3.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 3.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 13: texture 3, channel g, bottom plane at z0 + 14 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 14.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 3.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 3.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 12: texture 3, channel r, bottom plane at z0 + 13 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 13.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 3.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 3.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 11: texture 2, channel a, bottom plane at z0 + 12 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 12.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 2.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 2.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 10: texture 2, channel b, bottom plane at z0 + 11 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 11.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 2.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 2.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 9: texture 2, channel g, bottom plane at z0 + 10 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 10.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 2.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 2.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 8: texture 2, channel r, bottom plane at z0 + 9 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 9.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 2.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 2.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 7: texture 1, channel a, bottom plane at z0 + 8 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 8.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 1.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 1.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 6: texture 1, channel b, bottom plane at z0 + 7 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 7.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 1.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 1.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 5: texture 1, channel g, bottom plane at z0 + 6 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 6.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 1.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 1.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 4: texture 1, channel r, bottom plane at z0 + 5 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 5.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 1.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 1.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 3: texture 0, channel a, bottom plane at z0 + 4 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 4.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 0.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 0.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 2: texture 0, channel b, bottom plane at z0 + 3 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 3.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 0.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 0.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 1: texture 0, channel g, bottom plane at z0 + 2 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 2.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 0.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 0.0), penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
    }
    penumbra_i = penumbra_i.yzwx;
    // slice 0: texture 0, channel r, bottom plane at z0 + 1 * thickness
    {
        float zeta = penumbra_sliceDepths.x + 1.0 * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(penumbra_filtered(kernel, 0.0), penumbra_i);
        float q = fade * coverage;
        // the same slice over a window twice the kernel's side: how far the occluder extends
        vec4 penumbra_wide = vec4(kernel.xy, 2.0 * kernel.z, penumbra_wideLevel(kernel));
        float area = fade * max(coverage, 4.0 * dot(penumbra_filtered(penumbra_wide, 0.0), penumbra_i)) * kernel.z * kernel.z;
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
float penumbraVisibility(vec3 worldPos, vec3 worldNormal)
{
    vec3 p = (penumbra_lightFromWorld * vec4(worldPos, 1.0)).xyz;
    p.z = max(p.z, 1e-6); // points on or behind the light plane
    vec3 n = mat3(penumbra_lightFromWorld) * worldNormal;
    n *= inversesqrt(max(dot(n, n), 1e-20));
    vec3 penumbra_clip = penumbra_tangentClip(p, n);
    // a receiver turned away from all of the light receives none of it: its lookups would read the
    // occluders beside it, or none, and light it
    if (penumbra_clip.z <= 0.0) { return 0.0; }
    // footprint of the receiver's own tangent plane in the slice above it, along its normal (scene units)
    float penumbra_across = max(length(n.xy), 1e-6);
    float penumbra_spread = max(n.z / penumbra_across + dot(p.xy, n.xy) / (penumbra_across * (penumbra_copDistance + p.z)), 0.0);
    float penumbra_footprint = penumbra_spread * 2.0 * penumbra_sliceDepths.y;
    float penumbra_cap = max(penumbra_lightSize.x, penumbra_lightSize.y) * (penumbra_copDistance + p.z) / penumbra_copDistance * 0.0078125;
    // move the point 1.0 slicing texels sideways along its normal, off its own texels
    p.xy += n.xy * penumbra_lightSize * ((penumbra_copDistance + p.z) / penumbra_copDistance * 0.001953125);
    // and off its own footprint
    p.xy += n.xy / penumbra_across * min(penumbra_footprint, penumbra_cap);
    return penumbra_clippedVisibility(p, penumbra_clip);
}

// Without a normal: the fraction of the whole light that is visible (the paper's kernels, no clip),
// for shaders written against penumbraVisibility(vec3 worldPos) of every technique.
float penumbraVisibility(vec3 worldPos)
{
    vec3 p = (penumbra_lightFromWorld * vec4(worldPos, 1.0)).xyz;
    p.z = max(p.z, 1e-6); // points on or behind the light plane
    return penumbra_clippedVisibility(p, vec3(0.0, 0.0, 1.0));
}

// @penumbra:parameters
uniform vec4 penumbra_toLight; // light for the Lambert term: xyz position and w = 1, or xyz direction towards the light and w = 0 (scene units)

// @penumbra:example_main
void main()
{
    vec3 toLight = normalize(penumbra_toLight.xyz - penumbra_worldPos * penumbra_toLight.w);
    float lambert = max(dot(normalize(penumbra_worldNormal), toLight), 0.0);
    // the tangent clip and the normal offset need the normal of the side the viewer sees
    float visibility = penumbraVisibility(penumbra_worldPos, gl_FrontFacing ? penumbra_worldNormal : -penumbra_worldNormal);
    vec3 albedo = vec3(0.8);
    vec3 color = albedo * (0.15 + 0.85 * lambert * visibility);
    penumbra_color = vec4(color, 1.0);
}
