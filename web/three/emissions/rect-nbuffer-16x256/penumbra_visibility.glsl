// Penumbra 0.1.0 - penumbra_visibility.glsl: float penumbraVisibility(vec3 worldPos, vec3 worldNormal) (clipped to the tangent plane) and (vec3 worldPos)
// slices 16 | resolution 256x256 | filter nbuffer | fusion chained | packing atlas | light rect | leak fix on | fade on over 0.25 slice | tangent clip on, offset 1.0 texels + footprint | target essl300
// Include after the #version line of a stage for this target. Bindings start at 0.

// @penumbra:precision
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp sampler2DArray;
precision highp sampler3D;
// @penumbra:parameters
uniform mat4 penumbra_lightFromWorld; // world to light frame: x, y lateral, z depth along the light normal, origin at the light centre (scene units)
uniform vec2 penumbra_lightSize; // light rectangle width, height (scene units)
uniform float penumbra_copDistance; // distance d of the slicing centre of projection behind the light (scene units)
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
    float level = clamp(log2(max(side * 256.0, 1.0)), 0.0, 8.0);
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
// parallel to a light axis, the same area otherwise).
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
    return vec3(alongX ? vec2(mid, 0.0) : vec2(0.0, mid), hi - lo);
}

// @penumbra:visibility
// The fused visibility at light-frame point p of the part of the light that penumbra_clip keeps.
float penumbra_clippedVisibility(vec3 p, vec3 penumbra_clip)
{
    // @penumbra:fusion
    // chained fusion: eq. (5) assumes independent slices, but the leak fix (paper §3.4.1) copies every
    // surface into the next slice and a solid covers consecutive slices alike. Neighbours are taken
    // as nested (fused by maximum), slices further apart as independent (product): a chain whose
    // step from the previous slice's q to this one's lets through (1 - max(q, prev)) / (1 - prev).
    float penumbra_lit = 1.0;
    float penumbra_prev = 0.0; // q of the slice visited before (its neighbour)
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
        vec4 texel = mix(textureLod(penumbra_level0, vec2(penumbra_delta + (kernel.x - 0.0) * 0.25, kernel.y - 0.0), 0.0),
            textureLod(penumbra_level1, vec2(penumbra_delta + (kernel.x - 0.001953125) * 0.25, kernel.y - 0.001953125), 0.0), kernel.w - 0.0);
        float q = penumbra_weight(p.z, zeta) * dot(texel, penumbra_i);
        penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);
        penumbra_prev = q;
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
        vec4 texel = mix(textureLod(penumbra_level1, vec2(penumbra_delta + (kernel.x - 0.001953125) * 0.25, kernel.y - 0.001953125), 0.0),
            textureLod(penumbra_level2, vec2(penumbra_delta + (kernel.x - 0.005859375) * 0.25, kernel.y - 0.005859375), 0.0), kernel.w - 1.0);
        float q = penumbra_weight(p.z, zeta) * dot(texel, penumbra_i);
        penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);
        penumbra_prev = q;
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
        vec4 texel = mix(textureLod(penumbra_level2, vec2(penumbra_delta + (kernel.x - 0.005859375) * 0.25, kernel.y - 0.005859375), 0.0),
            textureLod(penumbra_level3, vec2(penumbra_delta + (kernel.x - 0.01171875) * 0.25, kernel.y - 0.01171875), 0.0), kernel.w - 2.0);
        float q = penumbra_weight(p.z, zeta) * dot(texel, penumbra_i);
        penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);
        penumbra_prev = q;
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
        vec4 texel = mix(textureLod(penumbra_level3, vec2(penumbra_delta + (kernel.x - 0.01171875) * 0.25, kernel.y - 0.01171875), 0.0),
            textureLod(penumbra_level4, vec2(penumbra_delta + (kernel.x - 0.0234375) * 0.25, kernel.y - 0.0234375), 0.0), kernel.w - 3.0);
        float q = penumbra_weight(p.z, zeta) * dot(texel, penumbra_i);
        penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);
        penumbra_prev = q;
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
        vec4 texel = mix(textureLod(penumbra_level4, vec2(penumbra_delta + (kernel.x - 0.0234375) * 0.25, kernel.y - 0.0234375), 0.0),
            textureLod(penumbra_level5, vec2(penumbra_delta + (kernel.x - 0.046875) * 0.25, kernel.y - 0.046875), 0.0), kernel.w - 4.0);
        float q = penumbra_weight(p.z, zeta) * dot(texel, penumbra_i);
        penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);
        penumbra_prev = q;
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
        vec4 texel = mix(textureLod(penumbra_level5, vec2(penumbra_delta + (kernel.x - 0.046875) * 0.25, kernel.y - 0.046875), 0.0),
            textureLod(penumbra_level6, vec2(penumbra_delta + (kernel.x - 0.09375) * 0.25, kernel.y - 0.09375), 0.0), kernel.w - 5.0);
        float q = penumbra_weight(p.z, zeta) * dot(texel, penumbra_i);
        penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);
        penumbra_prev = q;
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
        vec4 texel = mix(textureLod(penumbra_level6, vec2(penumbra_delta + (kernel.x - 0.09375) * 0.25, kernel.y - 0.09375), 0.0),
            textureLod(penumbra_level7, vec2(penumbra_delta + (kernel.x - 0.1875) * 0.25, kernel.y - 0.1875), 0.0), kernel.w - 6.0);
        float q = penumbra_weight(p.z, zeta) * dot(texel, penumbra_i);
        penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);
        penumbra_prev = q;
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
        vec4 texel = mix(textureLod(penumbra_level7, vec2(penumbra_delta + (kernel.x - 0.1875) * 0.25, kernel.y - 0.1875), 0.0),
            textureLod(penumbra_level8, vec2(penumbra_delta + (kernel.x - 0.375) * 0.25, kernel.y - 0.375), 0.0), kernel.w - 7.0);
        float q = penumbra_weight(p.z, zeta) * dot(texel, penumbra_i);
        penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);
        penumbra_prev = q;
        // next slice up: the channel rotates; wrapping from r to a moves one tile left
        penumbra_k -= 1.0;
        penumbra_i = penumbra_i.yzwx;
        penumbra_delta -= penumbra_i.w * 0.25;
    }
    // level 8: the remaining slices, windows of 256 texels and more
    while (penumbra_k >= 0.0) {
        float zeta = penumbra_sliceDepths.x + (penumbra_k + 1.0) * penumbra_sliceDepths.y;
        vec4 kernel = penumbra_kernel(p, zeta, penumbra_clip);
        vec4 texel = textureLod(penumbra_level8, vec2(penumbra_delta + (kernel.x - 0.375) * 0.25, kernel.y - 0.375), 0.0);
        float q = penumbra_weight(p.z, zeta) * dot(texel, penumbra_i);
        penumbra_lit *= (1.0 - max(q, penumbra_prev)) / max(1.0 - penumbra_prev, 1e-6);
        penumbra_prev = q;
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
    // footprint of the receiver's own tangent plane in the slice above it, along its normal (scene units)
    float penumbra_across = max(length(n.xy), 1e-6);
    float penumbra_spread = max(n.z / penumbra_across + dot(p.xy, n.xy) / (penumbra_across * (penumbra_copDistance + p.z)), 0.0);
    float penumbra_footprint = penumbra_spread * 2.0 * penumbra_sliceDepths.y;
    float penumbra_cap = max(penumbra_lightSize.x, penumbra_lightSize.y) * (penumbra_copDistance + p.z) / penumbra_copDistance * 0.015625;
    // move the point 1.0 slicing texels sideways along its normal, off its own texels
    p.xy += n.xy * penumbra_lightSize * ((penumbra_copDistance + p.z) / penumbra_copDistance * 0.00390625);
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
