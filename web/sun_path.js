// sun_path.js — the sun on its path over a day (occlusion interval maps), a port of
// include/penumbra/sun_path.hpp: points {azimuth, elevation} in degrees evenly spaced in t, great-
// circle arcs between them, and the time window that stands for the sun's disk.
//
//   const towardsSun = sunDirection(points, 0.5);                   // unit vector
//   runner.setUniforms({penumbra_timeWindow: timeWindow(points, 0.5, diameterRadians)});

const MIN_WINDOW_WIDTH = 1e-6; // penumbra::min_window_width

function fromDegrees([azimuth, elevation]) {
    const az = azimuth * Math.PI / 180, el = elevation * Math.PI / 180;
    return [Math.sin(az) * Math.cos(el), Math.sin(el), -Math.cos(az) * Math.cos(el)];
}

const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const angleBetween = (a, b) => Math.atan2(Math.hypot(...cross(a, b)), dot(a, b));

function segment(points, t) {
    const segments = points.length - 1;
    const s = Math.min(Math.max(t, 0), 1) * segments;
    const k = Math.min(Math.floor(s), segments - 1);
    return {k, f: s - k, segments};
}

// Unit vector from the scene towards the sun at t (clamped to [0, 1]).
export function sunDirection(points, t) {
    const {k, f} = segment(points, t);
    const a = fromDegrees(points[k]), b = fromDegrees(points[k + 1]);
    const angle = angleBetween(a, b);
    const d = [0, 1, 2].map((i) => (Math.sin((1 - f) * angle) * a[i] + Math.sin(f * angle) * b[i]) / Math.sin(angle));
    const l = Math.hypot(...d);
    return d.map((x) => x / l);
}

// penumbra_timeWindow at t: (start, end, 1 / width, t), the width being the time the sun takes
// to move by its angular diameter (radians).
export function timeWindow(points, t, angularDiameter) {
    const {k, segments} = segment(points, t);
    const speed = segments * angleBetween(fromDegrees(points[k]), fromDegrees(points[k + 1]));
    const width = Math.max(angularDiameter / speed, MIN_WINDOW_WIDTH);
    return [t - 0.5 * width, t + 0.5 * width, 1 / width, t];
}
