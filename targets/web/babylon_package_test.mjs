// babylon_package_test.mjs — the `babylon-package` test: penumbra-babylon as a TypeScript user and
// as the example's user meet it (the bundler-* tests run its page in four bundlers).
//   1. A fresh project (WORK/app) installs the tarball (pack-web-packages) offline beside
//      @babylonjs/core and typescript from this folder's node_modules, and `tsc --noEmit` checks
//      babylon_package/check.ts against @babylonjs/core's declarations.
//   2. The example (web/babylon/example/, served from the repository with web/babylon/node_modules
//      from `npm ci` there, and shared/ from web/three) in chromium, on each engine (its engine
//      switch: Engine, WebGL2, and WebGPUEngine): its light switch rect → sun → rect, Penumbra's
//      shadows against none after each switch, and screenshots of each into --images.
//   3. The bundler tests' Babylon page (bundle_pages/babylon.js), unbundled (an import map to the
//      repository's package), on WebGPUEngine, checked as bundle_test.mjs checks it: two lights (a
//      RectAreaLight and a sun) on one StandardMaterial, then PBRMaterial, each scaling its own
//      light's term by its visibility, both on the sum of each alone, update() after dispose() an error.
// WebGPU runs through SwiftShader (harness.mjs's WEBGPU_ARGS), its canvas offscreen
// (offscreen_canvas.mjs); without a WebGPU adapter 2 and 3 fail, or are skipped with PENUMBRA_WEBGPU_OPTIONAL=1.
// Babylon's RectAreaLight fetches its LTC tables from Babylon's CDN, which a test cannot reach:
// the page gets the same fit from three's RectAreaLightTexturesLib (bundle_test.mjs's ltcTables).
//
//   node targets/web/babylon_package_test.mjs --tarball FILE --work DIR --web web [--chromium PATH] [--images DIR]
//
// Exit 0 pass, 1 fail, 77 skip (no chromium), 2 bad arguments.
import fs from "node:fs";
import path from "node:path";
import {fileURLToPath} from "node:url";
import {WEBGPU_ARGS, serve, launchChromium, openPage, run} from "./harness.mjs";
import {ltcTables, serveLtc} from "./ltc_tables.mjs";
import {installOffscreenCanvas} from "./offscreen_canvas.mjs";
import {check as checkBundlePage} from "./bundle_test.mjs";

const here = path.dirname(fileURLToPath(import.meta.url));
const modules = path.join(here, "node_modules");

function parseArguments(argv) {
    const out = {tarball: null, work: null, web: null, chromium: "/usr/bin/chromium", images: null};
    for (let i = 0; i < argv.length; i += 2) {
        const key = argv[i].slice(2);
        if (!argv[i].startsWith("--") || !(key in out)) usage(`unknown argument '${argv[i]}'; allowed: --tarball, --work, --web, --chromium, --images`);
        if (argv[i + 1] === undefined) usage(`${argv[i]}: missing value`);
        out[key] = argv[i + 1];
    }
    if (!out.tarball || !out.work || !out.web) usage("--tarball, --work and --web are required");
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node babylon_package_test.mjs --tarball FILE --work DIR --web web [--chromium PATH] [--images DIR]`);
    process.exit(2);
}

// 1. tsc over check.ts in a fresh project
function typecheck(work, tarball) {
    const app = path.join(work, "app");
    fs.rmSync(app, {recursive: true, force: true});
    fs.mkdirSync(app, {recursive: true});
    fs.copyFileSync(path.join(here, "babylon_package", "check.ts"), path.join(app, "check.ts"));
    fs.writeFileSync(path.join(app, "package.json"), JSON.stringify({
        name: "penumbra-babylon-user", private: true, type: "module",
        dependencies: {"penumbra-babylon": `file:${path.resolve(tarball)}`, "@babylonjs/core": `file:${path.join(modules, "@babylonjs/core")}`},
    }, null, 2));
    // (--legacy-peer-deps: as in bundle_test.mjs, npm 11 fails to place a peer met by a linked scoped package)
    run("npm", ["install", "--offline", "--no-audit", "--no-fund", "--loglevel=error", "--legacy-peer-deps"], {cwd: app});
    fs.writeFileSync(path.join(app, "tsconfig.json"), JSON.stringify({
        compilerOptions: {strict: true, noEmit: true, target: "es2022", module: "esnext", moduleResolution: "bundler",
                          lib: ["es2022", "dom"], skipLibCheck: true, types: []},
        files: ["check.ts"],
    }, null, 2));
    const started = Date.now();
    try {
        run(process.execPath, [path.join(modules, "typescript/bin/tsc"), "-p", "tsconfig.json"], {cwd: app});
    } catch (e) {
        return [`tsc against @babylonjs/core's declarations: ${e.message}`];
    } finally {
        console.log(`     tsc --noEmit check.ts: ${((Date.now() - started) / 1000).toFixed(1)} s`);
    }
    return [];
}

// The canvas's pixels (RGBA, top row first): on WebGL2 through a 2D canvas, on WebGPU from the
// offscreen canvas's texture; and as a PNG file.
async function canvasPixels(page, file) {
    return page.evaluate(async (file) => {
        const canvas = document.querySelector("canvas");
        const c = document.createElement("canvas");
        c.width = canvas.width;
        c.height = canvas.height;
        const ctx = c.getContext("2d");
        if (window.penumbraOffscreenCanvas) ctx.putImageData(new ImageData(await window.penumbraOffscreenCanvas.read(canvas), c.width, c.height), 0, 0);
        else ctx.drawImage(canvas, 0, 0);
        return {rgba: Array.from(ctx.getImageData(0, 0, c.width, c.height).data), png: file ? c.toDataURL("image/png") : null};
    }, file);
}

// 2. the example's light switch on one engine: Penumbra's mode differs from "none" after each switch
async function checkExample(browser, port, images, engine) {
    const ltc = await ltcTables();
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/web/babylon/example/index.html?size=320x200&engine=${engine}`, "example",
                                            {width: 320, height: 200}, async (p) => {
                                                await serveLtc(p, ltc);
                                                if (engine === "webgpu") await p.evaluateOnNewDocument(installOffscreenCanvas);
                                            });
    await page.evaluate(() => window.example.ready);
    // (on SwiftShader's WebGPU a frame takes longer than the display's: the render loop's frames
    // queue up without bound and a read-back waits behind them all; the test renders each frame itself)
    if (engine === "webgpu") await page.evaluate(() => window.example.scene.getEngine().stopRenderLoop());
    const failures = [], steps = [];
    const shot = async (mode, file) => {
        await page.evaluate(async (m) => {
            await window.example.set({mode: m});
            for (let i = 0; i < 200 && !window.example.scene?.isReady?.(); ++i) await new Promise((r) => requestAnimationFrame(r));
            // (a frame as the render loop makes it: WebGPUEngine submits its commands at endFrame)
            const engine = window.example.scene.getEngine();
            engine.beginFrame();
            window.example.render();
            engine.endFrame();
        }, mode);
        await new Promise((resolve) => setTimeout(resolve, 200));
        const {rgba, png} = await canvasPixels(page, file);
        if (file) fs.writeFileSync(file, Buffer.from(png.slice(png.indexOf(",") + 1), "base64"));
        return rgba;
    };
    if (images) fs.mkdirSync(images, {recursive: true});
    for (const [k, light] of ["rect", "sun", "rect"].entries()) {
        await page.evaluate((l) => window.example.set({light: l}), light);
        await new Promise((resolve) => setTimeout(resolve, 500)); // frames with the new add-on
        const on = await shot("penumbra", images && k < 2 ? path.join(images, `example_${engine}_${light}_penumbra.png`) : null);
        const off = await shot("none", images && k < 2 ? path.join(images, `example_${engine}_${light}_none.png`) : null);
        let differing = 0;
        for (let i = 0; i < on.length; i += 4) if (Math.abs(on[i] - off[i]) + Math.abs(on[i + 1] - off[i + 1]) + Math.abs(on[i + 2] - off[i + 2]) > 12) ++differing;
        const info = await page.evaluate(() => window.example.info());
        if (info.engine !== engine) failures.push(`the example runs ${info.engine}, not ${engine}`);
        steps.push(`${light}: ${differing} of ${on.length / 4} pixels shadowed, ${info.shadows.casters} casters, ${info.shadows.receivers} receivers`);
        if (differing < 0.01 * on.length / 4) failures.push(`after switching to the ${light} light, Penumbra's mode differs from "none" at ${differing} pixels only`);
    }
    failures.push(...problems);
    await page.close();
    console.log(`${failures.length ? "FAIL" : "ok  "} the example on ${engine}: its light switch (rect → sun → rect): ${steps.join("; ")}`);
    return failures;
}

// 3. the bundler tests' Babylon page on WebGPUEngine, unbundled: an import map to the repository's package
async function checkBundlePageWebGPU(browser, port) {
    const ltc = await ltcTables();
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/bundle-page-webgpu.html`, "bundleCheck", undefined, async (p) => {
        await serveLtc(p, ltc);
        await p.evaluateOnNewDocument(installOffscreenCanvas);
    });
    const failures = [];
    for (const material of await page.evaluate(() => window.bundleCheck.materials)) {
        const r = await page.evaluate((m) => window.bundleCheck.run(m, "webgpu"), material);
        if (r.error) {
            failures.push(`${material} on WebGPUEngine: ${r.error}`);
            continue;
        }
        const c = checkBundlePage(r);
        console.log(`${c.failures.length ? "FAIL" : "ok  "} two add-ons on one material (bundle_pages/babylon.js, unbundled): ${c.summary}`);
        failures.push(...c.failures);
    }
    failures.push(...problems);
    await page.close();
    return failures;
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    if (!fs.existsSync(args.chromium)) {
        console.log(`skip: no chromium at ${args.chromium} (scripts/setup.sh installs Debian's chromium)`);
        process.exit(77);
    }
    const web = path.resolve(args.web);
    for (const need of [path.join(modules, "typescript/bin/tsc"), path.join(modules, "@babylonjs/core/package.json"),
                        path.join(web, "babylon/node_modules/@babylonjs/core/package.json")])
        if (!fs.existsSync(need)) {
            console.log(`error: ${need} is missing: scripts/setup.sh runs npm ci in targets/web and in web/babylon`);
            process.exit(1);
        }
    const work = path.resolve(args.work);
    fs.mkdirSync(work, {recursive: true});
    const failures = typecheck(work, args.tarball);
    console.log(`${failures.length ? "FAIL" : "ok  "} npm install --offline of the tarball into a fresh project; tsc --noEmit of check.ts against @babylonjs/core's declarations`);
    const {browser, close} = await launchChromium(args.chromium, WEBGPU_ARGS);
    // (web/babylon/shared/ served from its one source, web/three/: never a stale copy; the bundle
    // page beside an HTML page whose import map points at the repository's package)
    const page = path.join(work, "bundle-page-webgpu.html");
    fs.writeFileSync(page, `<!doctype html><html lang="en"><head><meta charset="utf-8"><link rel="icon" href="data:,">
<script type="importmap">{"imports": {"penumbra-babylon": "/web/babylon/penumbra_babylon.js", "@babylonjs/core/": "/web/babylon/node_modules/@babylonjs/core/"}}</script>
</head><body style="margin:0"><script type="module" src="/pages/babylon.js"></script></body></html>\n`);
    const server = await serve({web, "web/babylon/shared": path.join(web, "three"), pages: path.join(here, "bundle_pages")},
                               {"/bundle-page-webgpu.html": page, "/webgpu.html": path.join(here, "webgpu_page.html")});
    try {
        const port = server.address().port;
        failures.push(...(await checkExample(browser, port, args.images, "webgl2")));
        const webgpu = await hasWebGPU(browser, port);
        if (webgpu === true) {
            failures.push(...(await checkExample(browser, port, args.images, "webgpu")));
            failures.push(...(await checkBundlePageWebGPU(browser, port)));
        } else if (process.env.PENUMBRA_WEBGPU_OPTIONAL === "1") {
            console.log(`skip: the WebGPU checks (${webgpu}; PENUMBRA_WEBGPU_OPTIONAL=1)`);
        } else {
            failures.push(`no WebGPU adapter in chromium (${webgpu}): set PENUMBRA_WEBGPU_OPTIONAL=1 to skip the WebGPU checks instead of failing`);
        }
    } catch (e) {
        failures.push(e.message);
    } finally {
        await close();
        server.close();
    }
    for (const f of failures) console.log(`FAIL ${f}`);
    process.exit(failures.length ? 1 : 0);
}

// true, or why not
async function hasWebGPU(browser, port) {
    const page = await browser.newPage();
    await page.goto(`http://127.0.0.1:${port}/webgpu.html`);
    const r = await page.evaluate(async () => (!navigator.gpu ? "navigator.gpu is undefined" : (await navigator.gpu.requestAdapter()) ? true : "no adapter"));
    await page.close();
    return r;
}

main();
