// browser_test.mjs — the `browser` test: opens web/index.html in Debian's chromium (headless,
// WebGL2 through SwiftShader), lets the page run each target bundle's essl300 emission with its
// own layout runner, and compares the browser's visibility with the desktop GL runtime's.
//
//   node browser_test.mjs --web DIR --chromium PATH [--screenshots DIR] BUNDLE_DIR...
//
// Each BUNDLE_DIR is written by penumbra-export-bundle --target essl300. Per pixel the browser
// must agree with visibility_gl.f32 within  2·bound + 1/255:  both runs are within the CPU
// oracle's bound (bound.f32) of the same model, and the layout's essl300 result texture is R8
// (visibility rounded to 8 bits; the desktop runtime keeps R32F). Exit 0 pass, 1 fail, 77 skip
// (no chromium), 2 bad arguments.
import fs from "node:fs";
import http from "node:http";
import os from "node:os";
import path from "node:path";

const R8_STEP = 1 / 255;
const UNIFORM_TOLERANCE = 1e-5; // JS light frame vs the exported one, relative to the largest entry

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

async function checkBundle(browser, port, index, dir, screenshots) {
    const bundle = JSON.parse(fs.readFileSync(path.join(dir, "uniforms.json"), "utf8"));
    const c = bundle.config;
    const label = `${bundle.scene} ${c.filter}/${c.packing}/${c.light} ${c.slices}×${c.resolution}² ${bundle.width}x${bundle.height}`;
    const page = await browser.newPage();
    const problems = [];
    page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
    page.on("console", (m) => m.type() === "error" && problems.push(`console: ${m.text()}`));
    const started = Date.now();
    await page.goto(`http://127.0.0.1:${port}/web/index.html?bundle=/bundle/${index}/`);
    await page.waitForFunction(() => window.penumbra !== undefined, {timeout: 60000});
    const error = await page.evaluate(() => window.penumbra.error);
    if (error) throw new Error(`${label}: the page failed: ${error}`);
    const info = await page.evaluate(() => window.penumbra.info());

    // The page's own light frame (light_frame.js) against the desktop runtime's.
    const uniforms = await page.evaluate(() => window.penumbra.uniforms());
    let uniformError = 0;
    for (const [name, value] of Object.entries(uniforms.bundle)) {
        const computed = uniforms.computed[name];
        const a = typeof computed === "number" ? [computed] : computed, b = typeof value === "number" ? [value] : value;
        uniformError = Math.max(uniformError, largestDifference(a.map(Math.fround), b));
    }

    // The visibility with the desktop runtime's exact uniforms, against the desktop runtime's.
    await page.evaluate(() => window.penumbra.useBundleUniforms(true));
    const visibility = Float32Array.from(await page.evaluate(() => Array.from(window.penumbra.readVisibility())));
    if (process.env.PENUMBRA_DUMP) fs.writeFileSync(path.join(process.env.PENUMBRA_DUMP, `${index}.f32`), Buffer.from(visibility.buffer));
    const gl = readFloats(path.join(dir, "visibility_gl.f32"));
    const bound = readFloats(path.join(dir, "bound.f32"));
    if (visibility.length !== gl.length) throw new Error(`${label}: ${visibility.length} pixels read, expected ${gl.length}`);
    let worst = 0, worstExcess = -Infinity, outside = 0, beyondOneBound = 0, worstBound = 0, shadowed = 0;
    for (let i = 0; i < gl.length; ++i) {
        const difference = Math.abs(visibility[i] - gl[i]);
        const allowed = 2 * bound[i] + R8_STEP;
        worst = Math.max(worst, difference);
        worstBound = Math.max(worstBound, bound[i]);
        worstExcess = Math.max(worstExcess, difference - allowed);
        if (difference > allowed) ++outside;
        if (difference > bound[i] + R8_STEP) ++beyondOneBound;
        if (gl[i] < 0.98) ++shadowed;
    }

    // Moving the light moves the shadows (the page recomputes the uniforms in JavaScript).
    await page.evaluate(() => window.penumbra.useBundleUniforms(false));
    const before = await page.evaluate(() => Array.from(window.penumbra.readVisibility()));
    const moved = bundle.light.kind === "sun"
        ? {direction: [bundle.light.direction[0] + 0.3, bundle.light.direction[1], bundle.light.direction[2]]}
        : {center: [bundle.light.center[0] + 0.25 * bundle.light.width, bundle.light.center[1], bundle.light.center[2]]};
    const ms = await page.evaluate((m) => { window.penumbra.setLight(m); return window.penumbra.render(); }, moved);
    const after = await page.evaluate(() => Array.from(window.penumbra.readVisibility()));
    let changed = 0;
    for (let i = 0; i < after.length; ++i) if (Math.abs(after[i] - before[i]) > 2 * R8_STEP) ++changed;
    if (screenshots) {
        fs.mkdirSync(screenshots, {recursive: true});
        await page.screenshot({path: path.join(screenshots, `${index}_${c.filter}_${c.packing}.png`)});
    }
    await page.close();

    const failures = [...problems];
    if (outside > 0)
        failures.push(`${outside} pixels differ from the desktop runtime by more than 2·bound + 1/255 (worst excess ${worstExcess.toExponential(2)})`);
    if (uniformError > UNIFORM_TOLERANCE) failures.push(`light_frame.js differs from the exported uniforms by ${uniformError.toExponential(2)} (relative)`);
    if (shadowed === 0) failures.push("the desktop image has no shadowed pixel: the comparison would prove nothing");
    if (changed === 0) failures.push("moving the light changed no pixel");
    console.log(`${failures.length ? "FAIL" : "ok  "} ${label}: max |browser − desktop| = ${worst.toExponential(3)} ` +
                `(max bound ${worstBound.toExponential(3)}; ${beyondOneBound} of ${gl.length} pixels beyond bound + 1/255; ` +
                `${shadowed} shadowed); light frame rel. error ${uniformError.toExponential(2)}; moved light: ${changed} pixels ` +
                `changed, ${ms.toFixed(0)} ms; ${info.resultFormat} result, extensions [${info.extensions.join(", ")}]; ` +
                `${((Date.now() - started) / 1000).toFixed(1)} s`);
    for (const f of failures) console.log(`     ${f}`);
    return {failures: failures.length, renderer: info.renderer};
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    if (!fs.existsSync(args.chromium)) {
        console.log(`skip: no chromium at ${args.chromium} (scripts/setup.sh installs Debian's chromium)`);
        process.exit(77);
    }
    const {default: puppeteer} = await import("puppeteer-core");
    const server = await serve(args.web, args.bundles);
    const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "penumbra-chromium-"));
    const browser = await puppeteer.launch({
        executablePath: args.chromium,
        headless: true,
        userDataDir,
        args: ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--disable-background-networking",
               "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-quic", "--disable-extensions"],
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
