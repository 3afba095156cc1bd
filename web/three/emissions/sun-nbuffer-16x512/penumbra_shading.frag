#version 300 es
// Penumbra 0.1.0 - example shading pass: Lambert term times penumbraVisibility, fragment stage
// slices 16 | resolution 512x512 | filter nbuffer | fusion extent | packing atlas | light sun | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
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
uniform mat4 penumbra_lightFromWorld; // world to light frame: x, y lateral, z depth along the sun's direction, origin above the scene on the axis through the bounds' centre (scene units)
uniform float penumbra_windowHalfSize; // half side of the square orthographic slicing window (scene units)
uniform float penumbra_tanAngularRadius; // tangent of the sun's angular radius
uniform vec2 penumbra_sliceDepths; // x: depth z0 of the first slice's top, y: slice thickness (scene units)
uniform sampler2D penumbra_level0; // filter level, occlusion tiles side by side, texture unit 0
uniform sampler2D penumbra_level1; // filter level, occlusion tiles side by side, texture unit 1
uniform sampler2D penumbra_level2; // filter level, occlusion tiles side by side, texture unit 2
uniform sampler2D penumbra_level3; // filter level, occlusion tiles side by side, texture unit 3
uniform sampler2D penumbra_level4; // filter level, occlusion tiles side by side, texture unit 4
uniform sampler2D penumbra_level5; // filter level, occlusion tiles side by side, texture unit 5
uniform sampler2D penumbra_level6; // filter level, occlusion tiles side by side, texture unit 6
uniform sampler2D penumbra_level7; // filter level, occlusion tiles side by side, texture unit 7
uniform sampler2D penumbra_level8; // filter level, occlusion tiles side by side, texture unit 8
uniform sampler2D penumbra_level9; // filter level, occlusion tiles side by side, texture unit 9

// @penumbra:kernel
// Kernel on the slice plane at depth zeta, seen from light-frame point p (docs/model.md §1.4, §1.9):
// xy = centre (uv of the slice's texture), z = side (uv), w = filter level.
// clip: the part of the light above the receiver's tangent plane (penumbra_tangentClip)
vec4 penumbra_kernel(vec3 p, float zeta, vec3 clip)
{
    // journal §3.5: orthographic slicing, the cone towards the sun grows linearly with distance
    vec2 centre = 0.5 + p.xy / (2.0 * penumbra_windowHalfSize);
    float side = max(p.z - zeta, 0.0) * penumbra_tanAngularRadius / penumbra_windowHalfSize;
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

// @penumbra:tangent_clip
// The part of the light above the tangent plane at p (unit normal n, light frame), in the light's
// unit square [-0.5, 0.5]^2: xy = centre of the clipped rectangle, z = its shorter side. The plane
// is cut along the axis it crosses most steeply, at the other axis' centre line (exact for planes
// parallel to a light axis, the same area otherwise), or where that leaves less, in the corner it spares.
vec3 penumbra_tangentClip(vec3 p, vec3 n)
{
    // direction (X, Y) 2 tan(alpha) sideways, 1 up towards the sun is above where its dot with n > 0
    vec2 slopes = n.xy * (2.0 * penumbra_tanAngularRadius);
    float level = n.z;
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
    // @penumbra:level_loop
    // start at the nearest slice above the point; slices below it have weight 0
    float penumbra_k = clamp(ceil((p.z - penumbra_sliceDepths.x) / penumbra_sliceDepths.y) - 2.0, -1.0, 15.0);
    vec4 penumbra_i = vec4(equal(vec4(mod(max(penumbra_k, 0.0), 4.0)), vec4(0.0, 1.0, 2.0, 3.0)));
    float penumbra_delta = floor(max(penumbra_k, 0.0) / 4.0) * 0.25; // horizontal offset of the slice's tile
    // level 0: windows of 1 to 2 texels
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 1.0) break;
        vec4 penumbra_lo = textureLod(penumbra_level0, vec2(penumbra_delta + (kernel.x - 0.0) * 0.25, kernel.y - 0.0), 0.0);
        vec4 penumbra_hi = textureLod(penumbra_level1, vec2(penumbra_delta + (kernel.x - 0.0009765625) * 0.25, kernel.y - 0.0009765625), 0.0);
        vec4 texel = mix(penumbra_lo, penumbra_hi, kernel.w - 0.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        float penumbra_wideAt = penumbra_wideLevel(kernel);
        vec4 penumbra_wide = penumbra_wideAt < 1.0 ? mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 0.0)
            : mix(penumbra_hi, textureLod(penumbra_level2, vec2(penumbra_delta + (kernel.x - 0.0029296875) * 0.25, kernel.y - 0.0029296875), 0.0), penumbra_wideAt - 1.0);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 1: windows of 2 to 4 texels
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 2.0) break;
        vec4 penumbra_lo = textureLod(penumbra_level1, vec2(penumbra_delta + (kernel.x - 0.0009765625) * 0.25, kernel.y - 0.0009765625), 0.0);
        vec4 penumbra_hi = textureLod(penumbra_level2, vec2(penumbra_delta + (kernel.x - 0.0029296875) * 0.25, kernel.y - 0.0029296875), 0.0);
        vec4 texel = mix(penumbra_lo, penumbra_hi, kernel.w - 1.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        float penumbra_wideAt = penumbra_wideLevel(kernel);
        vec4 penumbra_wide = penumbra_wideAt < 2.0 ? mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 1.0)
            : mix(penumbra_hi, textureLod(penumbra_level3, vec2(penumbra_delta + (kernel.x - 0.005859375) * 0.25, kernel.y - 0.005859375), 0.0), penumbra_wideAt - 2.0);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 2: windows of 4 to 8 texels
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 3.0) break;
        vec4 penumbra_lo = textureLod(penumbra_level2, vec2(penumbra_delta + (kernel.x - 0.0029296875) * 0.25, kernel.y - 0.0029296875), 0.0);
        vec4 penumbra_hi = textureLod(penumbra_level3, vec2(penumbra_delta + (kernel.x - 0.005859375) * 0.25, kernel.y - 0.005859375), 0.0);
        vec4 texel = mix(penumbra_lo, penumbra_hi, kernel.w - 2.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        float penumbra_wideAt = penumbra_wideLevel(kernel);
        vec4 penumbra_wide = penumbra_wideAt < 3.0 ? mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 2.0)
            : mix(penumbra_hi, textureLod(penumbra_level4, vec2(penumbra_delta + (kernel.x - 0.01171875) * 0.25, kernel.y - 0.01171875), 0.0), penumbra_wideAt - 3.0);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 3: windows of 8 to 16 texels
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 4.0) break;
        vec4 penumbra_lo = textureLod(penumbra_level3, vec2(penumbra_delta + (kernel.x - 0.005859375) * 0.25, kernel.y - 0.005859375), 0.0);
        vec4 penumbra_hi = textureLod(penumbra_level4, vec2(penumbra_delta + (kernel.x - 0.01171875) * 0.25, kernel.y - 0.01171875), 0.0);
        vec4 texel = mix(penumbra_lo, penumbra_hi, kernel.w - 3.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        float penumbra_wideAt = penumbra_wideLevel(kernel);
        vec4 penumbra_wide = penumbra_wideAt < 4.0 ? mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 3.0)
            : mix(penumbra_hi, textureLod(penumbra_level5, vec2(penumbra_delta + (kernel.x - 0.0234375) * 0.25, kernel.y - 0.0234375), 0.0), penumbra_wideAt - 4.0);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 4: windows of 16 to 32 texels
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 5.0) break;
        vec4 penumbra_lo = textureLod(penumbra_level4, vec2(penumbra_delta + (kernel.x - 0.01171875) * 0.25, kernel.y - 0.01171875), 0.0);
        vec4 penumbra_hi = textureLod(penumbra_level5, vec2(penumbra_delta + (kernel.x - 0.0234375) * 0.25, kernel.y - 0.0234375), 0.0);
        vec4 texel = mix(penumbra_lo, penumbra_hi, kernel.w - 4.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        float penumbra_wideAt = penumbra_wideLevel(kernel);
        vec4 penumbra_wide = penumbra_wideAt < 5.0 ? mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 4.0)
            : mix(penumbra_hi, textureLod(penumbra_level6, vec2(penumbra_delta + (kernel.x - 0.046875) * 0.25, kernel.y - 0.046875), 0.0), penumbra_wideAt - 5.0);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 5: windows of 32 to 64 texels
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 6.0) break;
        vec4 penumbra_lo = textureLod(penumbra_level5, vec2(penumbra_delta + (kernel.x - 0.0234375) * 0.25, kernel.y - 0.0234375), 0.0);
        vec4 penumbra_hi = textureLod(penumbra_level6, vec2(penumbra_delta + (kernel.x - 0.046875) * 0.25, kernel.y - 0.046875), 0.0);
        vec4 texel = mix(penumbra_lo, penumbra_hi, kernel.w - 5.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        float penumbra_wideAt = penumbra_wideLevel(kernel);
        vec4 penumbra_wide = penumbra_wideAt < 6.0 ? mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 5.0)
            : mix(penumbra_hi, textureLod(penumbra_level7, vec2(penumbra_delta + (kernel.x - 0.09375) * 0.25, kernel.y - 0.09375), 0.0), penumbra_wideAt - 6.0);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 6: windows of 64 to 128 texels
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 7.0) break;
        vec4 penumbra_lo = textureLod(penumbra_level6, vec2(penumbra_delta + (kernel.x - 0.046875) * 0.25, kernel.y - 0.046875), 0.0);
        vec4 penumbra_hi = textureLod(penumbra_level7, vec2(penumbra_delta + (kernel.x - 0.09375) * 0.25, kernel.y - 0.09375), 0.0);
        vec4 texel = mix(penumbra_lo, penumbra_hi, kernel.w - 6.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        float penumbra_wideAt = penumbra_wideLevel(kernel);
        vec4 penumbra_wide = penumbra_wideAt < 7.0 ? mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 6.0)
            : mix(penumbra_hi, textureLod(penumbra_level8, vec2(penumbra_delta + (kernel.x - 0.1875) * 0.25, kernel.y - 0.1875), 0.0), penumbra_wideAt - 7.0);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 7: windows of 128 to 256 texels
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 8.0) break;
        vec4 penumbra_lo = textureLod(penumbra_level7, vec2(penumbra_delta + (kernel.x - 0.09375) * 0.25, kernel.y - 0.09375), 0.0);
        vec4 penumbra_hi = textureLod(penumbra_level8, vec2(penumbra_delta + (kernel.x - 0.1875) * 0.25, kernel.y - 0.1875), 0.0);
        vec4 texel = mix(penumbra_lo, penumbra_hi, kernel.w - 7.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        float penumbra_wideAt = penumbra_wideLevel(kernel);
        vec4 penumbra_wide = penumbra_wideAt < 8.0 ? mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 7.0)
            : mix(penumbra_hi, textureLod(penumbra_level9, vec2(penumbra_delta + (kernel.x - 0.375) * 0.25, kernel.y - 0.375), 0.0), penumbra_wideAt - 8.0);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 8: windows of 256 to 512 texels
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        if (kernel.w >= 9.0) break;
        vec4 penumbra_lo = textureLod(penumbra_level8, vec2(penumbra_delta + (kernel.x - 0.1875) * 0.25, kernel.y - 0.1875), 0.0);
        vec4 penumbra_hi = textureLod(penumbra_level9, vec2(penumbra_delta + (kernel.x - 0.375) * 0.25, kernel.y - 0.375), 0.0);
        vec4 texel = mix(penumbra_lo, penumbra_hi, kernel.w - 8.0);
        // the same slice over a window twice the kernel's side: how far the occluder extends
        float penumbra_wideAt = penumbra_wideLevel(kernel);
        vec4 penumbra_wide = mix(penumbra_lo, penumbra_hi, penumbra_wideAt - 8.0);
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 9: the remaining slices, windows of 512 texels and more
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        vec4 penumbra_lo = textureLod(penumbra_level9, vec2(penumbra_delta + (kernel.x - 0.375) * 0.25, kernel.y - 0.375), 0.0);
        vec4 texel = penumbra_lo;
        vec4 penumbra_wide = penumbra_lo; // no wider window than the last level's
        float fade = penumbra_weight(p.z, zeta);
        float coverage = dot(texel, penumbra_i);
        float q = fade * coverage;
        float area = fade * max(coverage, 4.0 * dot(penumbra_wide, penumbra_i)) * kernel.z * kernel.z;
        penumbra_lit *= penumbra_extentStep(q, kernel, area, penumbra_prev, penumbra_prevKernel, penumbra_prevArea);
        penumbra_prev = q;
        penumbra_prevKernel = kernel;
        penumbra_prevArea = area;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
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
    float penumbra_spread = max(n.z / penumbra_across, 0.0);
    float penumbra_footprint = penumbra_spread * 2.0 * penumbra_sliceDepths.y;
    float penumbra_cap = 2.0 * penumbra_windowHalfSize * 0.0078125;
    // move the point 1.0 slicing texels sideways along its normal, off its own texels
    p.xy += n.xy * (2.0 * penumbra_windowHalfSize * 0.001953125);
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
