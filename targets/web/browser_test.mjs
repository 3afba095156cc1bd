// browser_test.mjs — the `browser` test: opens web/index.html in Debian's chromium (headless,
// WebGL2 through SwiftShader), lets the page run each target bundle's essl300 emission with its
// own layout runner, and compares the browser's visibility with the desktop GL runtime's.
//
//   node targets/web/browser_test.mjs --web web [--chromium PATH] [--screenshots DIR] BUNDLE_DIR...
//
// Each BUNDLE_DIR is written by penumbra-export-bundle --target essl300: the desktop runtime ran
// the same essl300 emission. q is one step of the layout's result format (essl300: R8, 1/255).
//   1. With the desktop run's slicing output (slices.f32) in place of the browser's own, every
//      pixel must be within bound + q of the CPU oracle (oracle.f32, bound.f32: texture precision)
//      and within 2·bound + q of the desktop run (visibility_gl.f32: both are within the bound).
//   2. With the browser's own slicing, SwiftShader's rasterization of triangle edges differs from
//      llvmpipe's, which the bound does not cover: at most 5% of the covered slice texels may
//      differ, and at most 1% of the pixels may leave 2·bound + q.
//   3. light_frame.js reproduces the exported light-frame uniforms (relative 1e-5), and moving the
//      light changes the image.
// Exit 0 pass, 1 fail, 77 skip (no chromium), 2 bad arguments.
import fs from "node:fs";
import http from "node:http";
import os from "node:os";
import path from "node:path";

const R8_STEP = 1 / 255;
const UNIFORM_TOLERANCE = 1e-5; // JS light frame vs the exported one, relative to the largest entry
// SwiftShader and llvmpipe rasterize triangle edges differently (the bound does not cover that):
const SLICE_TEXELS_ALLOWED = 0.05; // slicing texels that may differ, of the desktop's covered texels
const OWN_PIXELS_ALLOWED = 0.01;   // pixels of the browser's own run that may leave 2·bound + q

function parseArguments(argv) {
    const out = {web: null, chromium: "/usr/bin/chromium", screenshots: null, bundles: []};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        if (flag === "--web" || flag === "--chromium" || flag === "--screenshots") {
            if (i + 1 >= argv.length) usage(`${flag}: missing value`);
            out[flag.slice(2)] = argv[++i];
        } else if (flag.startsWith("--")) {
            usage(`unknown flag '${flag}'`);
        } else {
            out.bundles.push(flag);
        }
    }
    if (!out.web) usage("--web: missing");
    if (out.bundles.length === 0) usage("no bundle directories");
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node browser_test.mjs --web DIR [--chromium PATH] [--screenshots DIR] BUNDLE_DIR...`);
    process.exit(2);
}

const CONTENT_TYPES = {".html": "text/html", ".js": "text/javascript", ".json": "application/json"};

// Serves /web/... from the page folder and /bundle/<i>/... from the i-th bundle, on localhost only.
function serve(webDir, bundles) {
    const roots = {web: path.resolve(webDir)};
    bundles.forEach((dir, i) => (roots[`bundle/${i}`] = path.resolve(dir)));
    const server = http.createServer((request, response) => {
        const url = decodeURIComponent(new URL(request.url, "http://localhost").pathname);
        for (const [prefix, root] of Object.entries(roots)) {
            if (!url.startsWith(`/${prefix}/`)) continue;
            const file = path.join(root, url.slice(prefix.length + 2));
            if (!file.startsWith(root) || !fs.existsSync(file) || !fs.statSync(file).isFile()) break;
            response.writeHead(200, {"Content-Type": CONTENT_TYPES[path.extname(file)] || "application/octet-stream",
                                     "Cache-Control": "no-store"});
            fs.createReadStream(file).pipe(response);
            return;
        }
        response.writeHead(404);
        response.end();
    });
    return new Promise((resolve) => server.listen(0, "127.0.0.1", () => resolve(server)));
}

function readFloats(file) {
    const bytes = fs.readFileSync(file);
    return new Float32Array(bytes.buffer, bytes.byteOffset, bytes.length / 4);
}

function largestDifference(a, b) {
    let worst = 0, scale = 0;
    for (let i = 0; i < a.length; ++i) {
        worst = Math.max(worst, Math.abs(a[i] - b[i]));
        scale = Math.max(scale, Math.abs(b[i]));
    }
    return worst / Math.max(scale, 1e-30);
}

// Per-pixel agreement of `visibility` with the model (oracle.f32, within bound + q) and with the
// desktop run (visibility_gl.f32, within 2·bound + q).
function compare(visibility, reference, q) {
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

async function checkBundle(browser, port, index, dir, screenshots) {
    const bundle = JSON.parse(fs.readFileSync(path.join(dir, "uniforms.json"), "utf8"));
    const c = bundle.config;
    const label = `${bundle.scene} ${c.filter}/${c.packing}/${c.light}/${c.fusion}${c.tangent_clip ? " tangent-clip" : ""} ` +
                  `${c.slices}×${c.resolution}² ${bundle.width}x${bundle.height}`;
    const page = await browser.newPage();
    await page.setViewport({width: 1000, height: 700});
    const problems = [];
    page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
    page.on("console", (m) => m.type() === "error" && problems.push(`console: ${m.text()}`));
    const started = Date.now();
    await page.goto(`http://127.0.0.1:${port}/web/index.html?bundle=/bundle/${index}/`);
    await page.waitForFunction(() => window.penumbra !== undefined, {timeout: 60000});
    const error = await page.evaluate(() => window.penumbra.error);
    if (error) throw new Error(`${label}: the page failed: ${error}`);
    const info = await page.evaluate(() => window.penumbra.info());
    const q = info.resultFormat === "R8" || info.resultFormat === "RGBA8" ? R8_STEP : 0;

    // The page's own light frame (light_frame.js) against the desktop runtime's.
    const uniforms = await page.evaluate(() => window.penumbra.uniforms());
    let uniformError = 0;
    for (const [name, value] of Object.entries(uniforms.bundle)) {
        const computed = uniforms.computed[name];
        const a = typeof computed === "number" ? [computed] : computed, b = typeof value === "number" ? [value] : value;
        uniformError = Math.max(uniformError, largestDifference(a.map(Math.fround), b));
    }

    const reference = {gl: readFloats(path.join(dir, "visibility_gl.f32")), oracle: readFloats(path.join(dir, "oracle.f32")),
                       bound: readFloats(path.join(dir, "bound.f32"))};
    let shadowed = 0, worstBound = 0;
    for (let i = 0; i < reference.gl.length; ++i) {
        if (reference.gl[i] < 0.98) ++shadowed;
        worstBound = Math.max(worstBound, reference.bound[i]);
    }
    const read = async () => {
        const v = Float32Array.from(await page.evaluate(() => Array.from(window.penumbra.readVisibility())));
        if (v.length !== reference.gl.length) throw new Error(`${label}: ${v.length} pixels read, expected ${reference.gl.length}`);
        return v;
    };

    // 1. Everything in the browser (its own slicing), with the desktop run's exact uniforms.
    await page.evaluate(() => window.penumbra.useBundleUniforms(true));
    const own = compare(await read(), reference, q);
    const slices = await page.evaluate(() => window.penumbra.compareSlices());
    // 2. The same with the desktop run's slicing output: the oracle's bound applies to every pixel.
    await page.evaluate(() => window.penumbra.useBundleSlices(true));
    const injected = compare(await read(), reference, q);
    await page.evaluate(() => window.penumbra.useBundleSlices(false));

    // 3. Moving the light moves the shadows (the page recomputes the uniforms in JavaScript).
    await page.evaluate(() => window.penumbra.useBundleUniforms(false));
    const before = await read();
    const moved = bundle.light.kind === "sun"
        ? {direction: [bundle.light.direction[0] + 0.3, bundle.light.direction[1], bundle.light.direction[2]]}
        : {center: [bundle.light.center[0] + 0.25 * bundle.light.width, bundle.light.center[1], bundle.light.center[2]]};
    await page.evaluate((m) => window.penumbra.setLight(m), moved);
    const after = await read();
    let changed = 0;
    for (let i = 0; i < after.length; ++i) if (Math.abs(after[i] - before[i]) > 2 * R8_STEP) ++changed;
    if (screenshots) {
        fs.mkdirSync(screenshots, {recursive: true});
        await page.screenshot({path: path.join(screenshots, `${index}_${c.filter}_${c.packing}${c.tangent_clip ? "_clip" : ""}.png`)});
    }
    await page.close();

    const pixels = reference.gl.length;
    const failures = [...problems];
    if (injected.outsideOracle > 0)
        failures.push(`with the desktop slices, ${injected.outsideOracle} pixels differ from the oracle by more than bound + ${q.toFixed(4)}`);
    if (injected.outsideGl > 0)
        failures.push(`with the desktop slices, ${injected.outsideGl} pixels differ from the desktop run by more than 2·bound + ${q.toFixed(4)}`);
    if (slices.differing > SLICE_TEXELS_ALLOWED * slices.covered)
        failures.push(`the browser's slicing covers ${slices.differing} texels differently (more than ${100 * SLICE_TEXELS_ALLOWED}% of ${slices.covered} covered)`);
    if (own.outsideGl > OWN_PIXELS_ALLOWED * pixels)
        failures.push(`with its own slicing, ${own.outsideGl} pixels differ from the desktop run by more than 2·bound + ${q.toFixed(4)} (allowed ${OWN_PIXELS_ALLOWED * 100}%)`);
    if (uniformError > UNIFORM_TOLERANCE) failures.push(`light_frame.js differs from the exported uniforms by ${uniformError.toExponential(2)} (relative)`);
    if (shadowed === 0) failures.push("the desktop image has no shadowed pixel: the comparison would prove nothing");
    if (changed === 0) failures.push("moving the light changed no pixel");
    console.log(`${failures.length ? "FAIL" : "ok  "} ${label} (${info.resultFormat} result, ${shadowed} shadowed, max bound ${worstBound.toExponential(2)}, ` +
                `${((Date.now() - started) / 1000).toFixed(1)} s)\n` +
                `     desktop slices: max |browser − desktop| ${injected.worstGl.toExponential(2)}, max |browser − oracle| ${injected.worstOracle.toExponential(2)}, ` +
                `${injected.outsideOracle} pixels outside bound + q\n` +
                `     own slicing:    max |browser − desktop| ${own.worstGl.toExponential(2)}, ${own.outsideGl} of ${pixels} pixels outside 2·bound + q; ` +
                `slicing texels differing ${slices.differing} of ${slices.covered} covered\n` +
                `     light_frame.js vs exported uniforms ${uniformError.toExponential(2)} (relative); moved light changed ${changed} pixels`);
    for (const f of failures) console.log(`     ${f}`);
    return {failures: failures.length, renderer: info.renderer};
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    if (!fs.existsSync(args.chromium)) {
        console.log(`skip: no chromium at ${args.chromium} (scripts/setup.sh installs Debian's chromium)`);
        process.exit(77);
    }
    let puppeteer;
    try {
        ({default: puppeteer} = await import("puppeteer-core"));
    } catch (e) {
        console.log(`error: puppeteer-core is not installed next to this script (scripts/setup.sh runs npm ci in targets/web): ${e.message}`);
        process.exit(1);
    }
    const server = await serve(args.web, args.bundles);
    const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "penumbra-chromium-"));
    const browser = await puppeteer.launch({
        executablePath: args.chromium,
        headless: true,
        userDataDir,
        args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-background-networking",
               "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-quic", "--disable-extensions",
               "--disable-dev-shm-usage"], // containers often have a tiny /dev/shm
    });
    let failures = 0;
    try {
        console.log(`chromium ${await browser.version()}`);
        for (let i = 0; i < args.bundles.length; ++i) {
            const result = await checkBundle(browser, server.address().port, i, args.bundles[i], args.screenshots);
            if (i === 0) console.log(`WebGL2 renderer: ${result.renderer}`);
            failures += result.failures;
        }
    } catch (e) {
        console.log(`FAIL ${e.message}`);
        failures += 1;
    } finally {
        await browser.close();
        server.close();
        fs.rmSync(userDataDir, {recursive: true, force: true});
    }
    process.exit(failures ? 1 : 0);
}

main();
