// bundle_compare.mjs — what the browser tests share: a localhost server for the page and the
// bundles, the per-pixel comparison with a bundle's desktop run and CPU oracle, and Debian's
// chromium started headless (WebGL2 through SwiftShader).
import fs from "node:fs";
import http from "node:http";
import path from "node:path";

export const R8_STEP = 1 / 255;
export const UNIFORM_TOLERANCE = 1e-5; // JS light frame vs the exported one, relative to the largest entry
// SwiftShader and llvmpipe rasterize triangle edges differently (the bound does not cover that):
export const SLICE_TEXELS_ALLOWED = 0.05; // slicing texels that may differ, of the desktop's covered texels
export const OWN_PIXELS_ALLOWED = 0.01;   // pixels of the browser's own run that may leave 2·bound + q

const CONTENT_TYPES = {".html": "text/html", ".js": "text/javascript", ".mjs": "text/javascript", ".json": "application/json",
                       ".wasm": "application/wasm"};

// Serves /web/... from the page folder, /bundle/<i>/... from the i-th bundle and each URL path of
// `files` from its file (the WebAssembly module from the build folder), on localhost only.
export function serve(webDir, bundles, files = {}) {
    const roots = {web: path.resolve(webDir)};
    bundles.forEach((dir, i) => (roots[`bundle/${i}`] = path.resolve(dir)));
    const send = (response, file) => {
        response.writeHead(200, {"Content-Type": CONTENT_TYPES[path.extname(file)] || "application/octet-stream", "Cache-Control": "no-store"});
        fs.createReadStream(file).pipe(response);
    };
    const server = http.createServer((request, response) => {
        const url = decodeURIComponent(new URL(request.url, "http://localhost").pathname);
        if (files[url]) return send(response, files[url]);
        for (const [prefix, root] of Object.entries(roots)) {
            if (!url.startsWith(`/${prefix}/`)) continue;
            const file = path.join(root, url.slice(prefix.length + 2));
            if (!file.startsWith(root) || !fs.existsSync(file) || !fs.statSync(file).isFile()) break;
            return send(response, file);
        }
        response.writeHead(404);
        response.end();
    });
    return new Promise((resolve) => server.listen(0, "127.0.0.1", () => resolve(server)));
}

export function readFloats(file) {
    const bytes = fs.readFileSync(file);
    return new Float32Array(bytes.buffer, bytes.byteOffset, bytes.length / 4);
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

// The bundle's reference images: the desktop run, the oracle and its bound.
export function readReference(dir) {
    return {gl: readFloats(path.join(dir, "visibility_gl.f32")), oracle: readFloats(path.join(dir, "oracle.f32")),
            bound: readFloats(path.join(dir, "bound.f32"))};
}

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
        args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-background-networking",
               "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-quic", "--disable-extensions",
               "--disable-dev-shm-usage"], // containers often have a tiny /dev/shm
    });
}
