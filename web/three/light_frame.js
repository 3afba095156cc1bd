// light_frame.js — the light-frame uniforms from a light and the scene's bounds, a port of
// include/penumbra/light_frame.hpp (same formulas, double precision, matrices column-major).
// The bounds must contain every receiver, not only the occluders.
//
//   const u = rectFrame({center, u: [1,0,0], v: [0,0,1], width, height}, boundsMin, boundsMax, slices);
//   runner.setUniforms(u); // penumbra_lightFromWorld, penumbra_sliceClipFromWorld, ...

const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const normalize = (a) => scale(a, 1 / Math.sqrt(dot(a, a)));

// World → frame with rows u, v, n and origin o; column-major 4×4 (m[c * 4 + r]).
function frameMatrix(u, v, n, o) {
    const m = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    [u, v, n].forEach((row, r) => {
        m[0 * 4 + r] = row[0];
        m[1 * 4 + r] = row[1];
        m[2 * 4 + r] = row[2];
        m[3 * 4 + r] = -dot(row, o);
    });
    return m;
}

function multiply(a, b) { // column-major a · b
    const m = new Array(16).fill(0);
    for (let c = 0; c < 4; ++c)
        for (let r = 0; r < 4; ++r)
            for (let k = 0; k < 4; ++k) m[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
    return m;
}

function transformPoint(m, p) {
    return [0, 1, 2].map((r) => m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r]);
}

function boxCorners(lo, hi) {
    const c = [];
    for (let i = 0; i < 8; ++i) c.push([(i & 1) ? hi[0] : lo[0], (i & 2) ? hi[1] : lo[1], (i & 4) ? hi[2] : lo[2]]);
    return c;
}

function depthRangeSlices(zmin, zmax, slices) {
    const pad = 1e-4 * Math.max(zmax - zmin, 1e-6);
    const z0 = zmin - pad, zs = zmax + pad;
    return [z0, (zs - z0) / Math.max(slices, 1)];
}

// The widest half angle of the slicing pyramid and of the shadow-map frustum (penumbra::max_frustum_half_angle,
// 70°): in a room the bounds reach the light's plane beside the light, and a pyramid holding them would open
// to 180°. What lies behind the light's plane casts nothing (the emitted light passes clip it).
export const MAX_FRUSTUM_HALF_ANGLE = 70 * Math.PI / 180;

// Rectangular light: perspective slicing from E = C − d·N, near plane = the light rectangle.
// Returns the uniforms by GLSL name, and `contained`: true when every corner of the bounds lies in front
// of the light and inside the pyramid. False in a room, which is fine: a receiver outside the pyramid is
// shadowed by what lies inside it only (docs/model.md §1.2b).
export function rectFrame(light, boundsMin, boundsMax, slices) {
    const u = normalize(light.u), v = normalize(light.v), n = normalize(cross(u, v));
    const lfw = frameMatrix(u, v, n, light.center);
    const w = light.width, h = light.height;
    const cap = 1000 * Math.max(w, h);
    const floorD = 0.5 * Math.max(w, h) / Math.tan(MAX_FRUSTUM_HALF_ANGLE);
    let d = cap, contained = true, room = false; // room: the bounds reach the light's plane
    let zmin = Infinity, zmax = -Infinity;
    for (const corner of boxCorners(boundsMin, boundsMax)) {
        const p = transformPoint(lfw, corner);
        zmin = Math.min(zmin, p[2]);
        zmax = Math.max(zmax, p[2]);
        if (p[2] <= 0) { // on or behind the light's plane: clipped by the light passes
            room = true;
            continue;
        }
        if (Math.abs(p[0]) > w / 2) d = Math.min(d, (w / 2) * p[2] / (Math.abs(p[0]) - w / 2));
        if (Math.abs(p[1]) > h / 2) d = Math.min(d, (h / 2) * p[2] / (Math.abs(p[1]) - h / 2));
    }
    if (room || d < floorD) { // a room opens the pyramid to the cap, to hold as much of its walls as it can
        d = floorD;
        contained = false;
    }
    // clip = (2·a·d/w, 2·b·d/h, 0, d + z) in light-frame coordinates (a, b, z)
    const clipFromLight = new Array(16).fill(0);
    clipFromLight[0] = 2 * d / w;
    clipFromLight[5] = 2 * d / h;
    clipFromLight[11] = 1;
    clipFromLight[15] = d;
    return {
        uniforms: {
            penumbra_lightFromWorld: lfw,
            penumbra_sliceClipFromWorld: multiply(clipFromLight, lfw),
            penumbra_lightSize: [w, h],
            penumbra_copDistance: d,
            penumbra_sliceDepths: depthRangeSlices(Math.max(zmin, 0), zmax, slices),
            penumbra_windowHalfSize: 0,
            penumbra_tanAngularRadius: 0,
            penumbra_toLight: [...light.center, 1], // the light's centre, w = 1 (uniform_values.hpp)
        },
        contained,
    };
}

// Sun: orthographic slicing along the light direction over a square window covering the bounds.
export function sunFrame(sun, boundsMin, boundsMax, slices) {
    const n = normalize(sun.direction);
    const helper = Math.abs(n[1]) < 0.9 ? [0, 1, 0] : [1, 0, 0];
    const u = normalize(cross(helper, n));
    const v = cross(n, u);
    const centre = [0, 1, 2].map((i) => 0.5 * (boundsMin[i] + boundsMax[i]));
    const diagonal = [0, 1, 2].map((i) => boundsMax[i] - boundsMin[i]);
    const radius = Math.max(0.5 * Math.sqrt(dot(diagonal, diagonal)), 1e-3);
    const origin = [0, 1, 2].map((i) => centre[i] - n[i] * radius * 1.1);
    const lfw = frameMatrix(u, v, n, origin);
    let half = 0, zmin = Infinity, zmax = -Infinity;
    for (const corner of boxCorners(boundsMin, boundsMax)) {
        const p = transformPoint(lfw, corner);
        half = Math.max(half, Math.abs(p[0]), Math.abs(p[1]));
        zmin = Math.min(zmin, p[2]);
        zmax = Math.max(zmax, p[2]);
    }
    half = Math.max(half * 1.001, 1e-6);
    const clipFromLight = new Array(16).fill(0);
    clipFromLight[0] = 1 / half;
    clipFromLight[5] = 1 / half;
    clipFromLight[15] = 1;
    return {
        uniforms: {
            penumbra_lightFromWorld: lfw,
            penumbra_sliceClipFromWorld: multiply(clipFromLight, lfw),
            penumbra_lightSize: [0, 0],
            penumbra_copDistance: 0,
            penumbra_sliceDepths: depthRangeSlices(zmin, zmax, slices),
            penumbra_windowHalfSize: half,
            penumbra_tanAngularRadius: Math.tan(0.5 * sun.angularDiameter),
            penumbra_toLight: [-n[0], -n[1], -n[2], 0], // towards the sun, w = 0 (uniform_values.hpp)
        },
        contained: true,
    };
}

// Shadow-map techniques (penumbra::shadow_frame): rectangle — a perspective from the light's
// centre along its normal whose square frustum holds the bounds; sun — the sun's slicing frame.
export function rectShadowFrame(light, boundsMin, boundsMax) {
    const u = normalize(light.u), v = normalize(light.v), n = normalize(cross(u, v));
    const lfw = frameMatrix(u, v, n, light.center);
    const corners = boxCorners(boundsMin, boundsMax).map((c) => transformPoint(lfw, c));
    let zmin = Infinity, zmax = -Infinity;
    for (const p of corners) {
        zmin = Math.min(zmin, p[2]);
        zmax = Math.max(zmax, p[2]);
    }
    const diagonal = [0, 1, 2].map((i) => boundsMax[i] - boundsMin[i]);
    const extent = Math.max(Math.sqrt(dot(diagonal, diagonal)), 1e-6);
    const near = Math.max(zmin, 1e-3 * extent), far = Math.max(zmax, near + 1e-3 * extent) + 0.01 * (zmax - zmin);
    let tanHalf = 1e-6;
    for (const p of corners) {
        if (p[2] <= 0) continue; // behind the light's plane: the depth pass clips it
        tanHalf = Math.max(tanHalf, Math.abs(p[0]) / Math.max(p[2], near), Math.abs(p[1]) / Math.max(p[2], near));
    }
    tanHalf *= 1.001;
    let contained = zmin > 0;
    if (zmin <= 0 || tanHalf > Math.tan(MAX_FRUSTUM_HALF_ANGLE)) { // a room opens the frustum to the cap
        tanHalf = Math.tan(MAX_FRUSTUM_HALF_ANGLE);
        contained = false;
    }
    const clipFromLight = new Array(16).fill(0);
    clipFromLight[0] = 1 / tanHalf;
    clipFromLight[5] = 1 / tanHalf;
    clipFromLight[11] = 1;
    return {
        uniforms: {
            penumbra_lightFromWorld: lfw,
            penumbra_shadowClipFromWorld: multiply(clipFromLight, lfw),
            penumbra_shadowDepthRange: [near, far],
            penumbra_shadowTanHalfFov: tanHalf,
            penumbra_lightSize: [light.width, light.height],
            penumbra_lightSizeUV: [light.width / (2 * tanHalf * near), light.height / (2 * tanHalf * near)],
        },
        contained,
    };
}

export function sunShadowFrame(sun, boundsMin, boundsMax) {
    const slices = sunFrame(sun, boundsMin, boundsMax, 1).uniforms;
    let zmin = Infinity, zmax = -Infinity;
    for (const corner of boxCorners(boundsMin, boundsMax)) {
        const z = transformPoint(slices.penumbra_lightFromWorld, corner)[2];
        zmin = Math.min(zmin, z);
        zmax = Math.max(zmax, z);
    }
    const pad = 1e-4 * Math.max(zmax - zmin, 1e-6);
    const growth = Math.fround(2 * Math.fround(slices.penumbra_tanAngularRadius) / (2 * Math.fround(slices.penumbra_windowHalfSize)));
    return {
        uniforms: {
            penumbra_lightFromWorld: slices.penumbra_lightFromWorld,
            penumbra_shadowClipFromWorld: slices.penumbra_sliceClipFromWorld,
            penumbra_shadowDepthRange: [zmin - pad, zmax + 0.01 * (zmax - zmin) + pad],
            penumbra_windowHalfSize: slices.penumbra_windowHalfSize,
            penumbra_tanAngularRadius: slices.penumbra_tanAngularRadius,
            penumbra_lightSizeUV: [growth, growth],
        },
        contained: true,
    };
}

// Every light uniform any technique reads: the slicing frame's and the shadow map's.
export function lightUniforms(light, boundsMin, boundsMax, slices) {
    const sliced = light.kind === "sun" ? sunFrame(light, boundsMin, boundsMax, slices) : rectFrame(light, boundsMin, boundsMax, slices);
    const shadow = light.kind === "sun" ? sunShadowFrame(light, boundsMin, boundsMax) : rectShadowFrame(light, boundsMin, boundsMax);
    return {uniforms: {...sliced.uniforms, ...shadow.uniforms}, contained: sliced.contained && shadow.contained};
}
