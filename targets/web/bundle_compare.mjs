// bundle_compare.mjs — what the browser tests share: a localhost server for the page and the
// bundles, the per-pixel comparison with a bundle's desktop run and CPU oracle, and Debian's
// chromium started headless (WebGL2 through SwiftShader).
import fs from "node:fs";
import path from "node:path";
import {CHROMIUM_ARGS, readFloats, serve as serveRoots} from "./harness.mjs";

export {readFloats};

export const R8_STEP = 1 / 255;
export const UNIFORM_TOLERANCE = 1e-5; // JS light frame vs the exported one, relative to the largest entry
// SwiftShader and llvmpipe rasterize triangle edges differently (the bound does not cover that):
export const SLICE_TEXELS_ALLOWED = 0.05; // slicing texels that may differ, of the desktop's covered texels
export const OWN_PIXELS_ALLOWED = 0.01;   // pixels of the browser's own run that may leave 2·bound + q

// Serves /web/... from the page folder, /bundle/<i>/... from the i-th bundle and each URL path of
// `files` from its file (the WebAssembly module from the build folder), on localhost only.
export function serve(webDir, bundles, files = {}) {
    const roots = {web: webDir};
    bundles.forEach((dir, i) => (roots[`bundle/${i}`] = dir));
    return serveRoots(roots, files);
}

export function largestDifference(a, b) {
    let worst = 0, scale = 0;
    for (let i = 0; i < a.length; ++i) {
        worst = Math.max(worst, Math.abs(a[i] - b[i]));
        scale = Math.max(scale, Math.abs(b[i]));
    }
    return worst / Math.max(scale, 1e-30);
}

// Per-pixel agreement of `visibility` with the model (oracle.f32, within bound + q) and with the
// desktop run (visibility_gl.f32, within 2·bound + q).
export function compare(visibility, reference, q) {
    const {oracle, gl, bound} = reference;
    const out = {worstGl: 0, worstOracle: 0, outsideOracle: 0, outsideGl: 0};
    for (let i = 0; i < gl.length; ++i) {
        const toOracle = Math.abs(visibility[i] - oracle[i]), toGl = Math.abs(visibility[i] - gl[i]);
        out.worstGl = Math.max(out.worstGl, toGl);
        out.worstOracle = Math.max(out.worstOracle, toOracle);
        if (toOracle > bound[i] + q + 1e-6) ++out.outsideOracle;
        if (toGl > 2 * bound[i] + q + 1e-6) ++out.outsideGl;
    }
    return out;
}

// The bundle's reference images: the desktop run, and where it has them (occlusion textures) the
// oracle and its bound, and the ray-traced truth (--reference).
export function readReference(dir) {
    const optional = (name) => (fs.existsSync(path.join(dir, name)) ? readFloats(path.join(dir, name)) : null);
    return {gl: readFloats(path.join(dir, "visibility_gl.f32")), oracle: optional("oracle.f32"), bound: optional("bound.f32"),
            truth: optional("truth.f32")};
}

// For techniques the oracle does not model: how far a run is from the desktop run's image.
export function difference(visibility, gl) {
    const out = {worst: 0, mean: 0, over: 0}; // over: pixels more than TECHNIQUE_PIXEL_STEP apart
    for (let i = 0; i < gl.length; ++i) {
        const d = Math.abs(visibility[i] - gl[i]);
        out.worst = Math.max(out.worst, d);
        out.mean += d / gl.length;
        if (d > TECHNIQUE_PIXEL_STEP) ++out.over;
    }
    return out;
}
// No bound exists for the shadow-map techniques and oim: SwiftShader and llvmpipe rasterize the
// depth pass and round the comparisons differently, which moves taps across shadow edges
// (measured on boxes 64x64: shadowmap, erosion, oim 0 pixels apart; pcf 3x3 grid 17 and pcss 8/8
// 75 of 4096 pixels above 0.1, the rotated taps landing on the other side of an edge).
export const TECHNIQUE_PIXEL_STEP = 0.1;
export const TECHNIQUE_PIXELS_ALLOWED = 0.03; // of the pixels, more than TECHNIQUE_PIXEL_STEP apart
export const TECHNIQUE_MEAN_ALLOWED = 0.01;   // mean |browser − desktop|

// puppeteer-core (targets/web/node_modules, scripts/setup.sh) driving `chromium` headless.
export async function launchChromium(chromium, userDataDir) {
    let puppeteer;
    try {
        ({default: puppeteer} = await import("puppeteer-core"));
    } catch (e) {
        console.log(`error: puppeteer-core is not installed next to this script (scripts/setup.sh runs npm ci in targets/web): ${e.message}`);
        process.exit(1);
    }
    return puppeteer.launch({
        executablePath: chromium,
        headless: true,
        userDataDir,
        args: CHROMIUM_ARGS,
    });
}
