// babylon_test.mjs — the `babylon` browser test: Penumbra's built-in scenes rebuilt in Babylon.js
// from essl300 target bundles (web/babylon/test/: the same triangles, light and camera, the
// bundle's emission folder), checked as three_test.mjs checks the three.js add-on, with its
// functions and tolerances: the add-on's light frame against the desktop's uniforms, and its
// visibility against the desktop runtime's within 2·bound + q on all interior pixels but 1% of the
// image; the casters placed by a matrix five ways (Mesh, InstancedMesh, thin instance, skeleton,
// morph target) agree within three_test.mjs's tolerance; the StandardMaterial's light term is
// scaled by that visibility (lit-with / lit-without, three_test.mjs's compareRatio); update() after
// dispose() throws. (Several lights, PBR materials: the bundler-* tests and babylon-package.)
// Once, cut-out casters (web/babylon/test/cutout.html; the shipped emissions, which the build
// writes), as three_test.mjs's check 7: a plane whose StandardMaterial's diffuseTexture has a
// transparent hole, alpha-tested, under a RectAreaLight. With the default options the add-on follows
// the cut (info.alphaTest, the shipped "-cut" emission) and the ground under the hole is lit (> 0.8),
// clearly more than with alphaTest: false (< 0.2, no warning); a shipped emission without a cut twin
// draws solid with one console.warn; the texture's offset (0.5: the hole at the edges) is followed; the detection rule (cutOf) on PBR and Standard materials as
// Babylon's glTF loader makes them (MASK, BLEND, OPAQUE).
// --engine webgl2 (the default: Engine, essl300 bundles) or webgpu (WebGPUEngine, WebGPU through
// SwiftShader as three-webgpu; wgsl bundles). Needs web/babylon's npm ci (its @babylonjs/core);
// the page's shared/ modules are served from web/three, where they live.
//
//   node targets/web/babylon_test.mjs --web web [--engine webgl2|webgpu] [--chromium PATH]
//        [--against-webgl2 WGSL_BUNDLE_DIR ESSL300_BUNDLE_DIR]... BUNDLE_DIR...
//
// --against-webgl2 (--engine webgpu): a wgsl bundle whose visibility is checked against the add-on's
// own on Engine (WebGL2) with the essl300 bundle of the same room, in the same Chromium, instead of
// the desktop's (the room: SwiftShader's 4 sub-pixel bits against llvmpipe's 8 put 14 of its 3047
// interior pixels beyond 2·bound + q; the WebGL2 test `babylon` holds that comparison, with its 1%):
// every pixel within 2q, none allowed out (three_test.mjs's bundleMismatch and compareBackends).
// Exit 0 pass, 1 fail, 77 skip (no chromium; no WebGPU adapter only with PENUMBRA_WEBGPU_OPTIONAL=1), 2 bad arguments.
import fs from "node:fs";
import path from "node:path";
import {serve, launchChromium, openPage} from "./harness.mjs";
import {ltcTables, serveLtc} from "./ltc_tables.mjs";
import {PIXELS_ALLOWED, R8_STEP, VARIANT_PIXELS_ALLOWED, backendFailures, bundleMismatch, compareBackends, compareRatio, compareVariants, compareWithDesktop,
        frameError} from "./three_test.mjs";
import {installOffscreenCanvas} from "./offscreen_canvas.mjs";
import {adapterLine, startWebGPU} from "./wgsl_compile.mjs";

const ENGINES = {webgl2: {name: "Engine (WebGL2)", target: "essl300"}, webgpu: {name: "WebGPUEngine", target: "wgsl"}};

const UNIFORM_TOLERANCE = 1e-5; // relative: float32 of the same double-precision formulas

function usage(message) {
    console.error(`error: ${message}\nusage: node babylon_test.mjs --web DIR [--engine webgl2|webgpu] [--chromium PATH] ` +
                  "[--against-webgl2 WGSL_DIR ESSL300_DIR]... BUNDLE_DIR...");
    process.exit(2);
}

function parseArguments(argv) {
    const out = {web: null, chromium: "/usr/bin/chromium", engine: "webgl2", bundles: [], webgl2: []};
    for (let i = 0; i < argv.length; ++i) {
        if (argv[i] === "--against-webgl2") {
            if (i + 2 >= argv.length) usage("--against-webgl2: needs a wgsl bundle and the essl300 bundle of the same scene");
            out.webgl2[out.bundles.length] = argv[i + 2];
            out.bundles.push(argv[i + 1]);
            i += 2;
        } else if (argv[i] === "--web" || argv[i] === "--chromium" || argv[i] === "--engine") {
            if (i + 1 >= argv.length) usage(`${argv[i]}: missing value`);
            out[argv[i].slice(2)] = argv[++i];
        } else if (argv[i].startsWith("--")) {
            usage(`unknown argument '${argv[i]}'; allowed: --web, --engine, --chromium, --against-webgl2, bundle folders`);
        } else {
            out.bundles.push(argv[i]);
        }
    }
    if (!out.web || !out.bundles.length) usage("--web and at least one bundle folder are required");
    if (!ENGINES[out.engine]) usage(`--engine '${out.engine}': allowed ${Object.keys(ENGINES).join(", ")}`);
    if (out.webgl2.length && out.engine !== "webgpu") usage("--against-webgl2: only with --engine webgpu");
    return out;
}

async function checkBundle(browser, port, index, dir, ltc, engine, webgl2 = null) {
    const bundle = JSON.parse(fs.readFileSync(path.join(dir, "uniforms.json"), "utf8"));
    const c = bundle.config;
    if (c.target !== ENGINES[engine].target) {
        console.log(`FAIL ${dir}: a bundle of target '${c.target}'; ${ENGINES[engine].name} runs ${ENGINES[engine].target} bundles`);
        return 1;
    }
    const label = `${bundle.scene} ${c.light} ${c.filter}/${c.packing} ${c.slices}×${c.resolution}² ${bundle.width}x${bundle.height}`;
    const started = Date.now();
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/web/babylon/test/index.html?bundle=/bundle/${index}/&engine=${engine}`, "penumbraBabylon",
                                            undefined, async (p) => {
        await serveLtc(p, ltc);
        // (headless Chromium loses the WebGPU device when a WebGPU canvas is presented: offscreen_canvas.mjs)
        if (engine === "webgpu") await p.evaluateOnNewDocument(installOffscreenCanvas);
    });
    const failures = [];
    const info = await page.evaluate(() => window.penumbraBabylon.engine());
    if (info.isWebGPU !== (engine === "webgpu")) failures.push(`the page runs ${info.name}, not ${ENGINES[engine].name}`);
    const uniformError = frameError(await page.evaluate(() => window.penumbraBabylon.frameUniforms()));
    if (!(uniformError <= UNIFORM_TOLERANCE)) failures.push(`the add-on's light frame differs from the desktop's by ${uniformError.toExponential(2)} (relative)`);
    const visibility = await page.evaluate(() => window.penumbraBabylon.visibility());
    const v = compareWithDesktop(visibility, dir, bundle);
    // (on WebGPU one pixel a bundle, as three-webgpu; WebGL2's SwiftShader rasterizes the slicing
    // pass's triangle edges unlike llvmpipe: 1% of the image, as three)
    const allowed = engine === "webgpu" ? 1 : PIXELS_ALLOWED * v.pixels;
    let against = "";
    if (webgl2) { // against the add-on's WebGL2 visibility of the same room (the desktop's: the `babylon` test)
        failures.push(...bundleMismatch(dir, webgl2));
        const gl = await openPage(browser, `http://127.0.0.1:${port}/web/babylon/test/index.html?bundle=/webgl2/${index}/&engine=webgl2`, "penumbraBabylon",
                                  undefined, (p) => serveLtc(p, ltc));
        if ((await gl.page.evaluate(() => window.penumbraBabylon.engine())).isWebGPU) failures.push("the WebGL2 page runs a WebGPUEngine");
        const b = compareBackends(visibility, await gl.page.evaluate(() => window.penumbraBabylon.visibility()));
        failures.push(...gl.problems);
        await gl.page.close();
        failures.push(...backendFailures(b, v.pixels));
        against = `\n     visibility vs the add-on on Engine (WebGL2; same room, same chromium): max |Δ| ${b.worst.toExponential(2)}, ` +
                  `${b.outside} of ${b.pixels} pixels outside 2q (${b.shadowed} shadowed)\n     not checked here (\`babylon\` checks the room on WebGL2):`;
    } else if (v.outside > allowed)
        failures.push(`${v.outside} of ${v.geometry} interior pixels differ from the desktop run by more than 2·bound + q (allowed: ${allowed} of the ${v.pixels} pixels)`);
    // the casters placed five ways agree
    const variants = await page.evaluate(() => window.penumbraBabylon.variants());
    const differing = compareVariants(variants);
    differing.thin = variants.thin.reduce((n, x, i) => n + (Math.abs(x - variants.mesh[i]) > 2 * R8_STEP ? 1 : 0), 0);
    for (const name of ["instanced", "thin", "skinned", "morphed"])
        if (differing[name] > VARIANT_PIXELS_ALLOWED * v.pixels) failures.push(`the ${name} caster's shadow differs from the moved Mesh's at ${differing[name]} pixels`);
    if (differing.moved === 0) failures.push("moving the casters changed no pixel: the variants prove nothing");
    // the StandardMaterial's light term times the visibility (after the variants: the casters are back)
    const ratio = compareRatio(await page.evaluate(() => window.penumbraBabylon.materialRatio()), await page.evaluate(() => window.penumbraBabylon.visibility()));
    if (ratio.lit === 0) failures.push("the light lights no pixel");
    if (ratio.outside > PIXELS_ALLOWED * ratio.lit) failures.push(`the lit image is not visibility × unshadowed at ${ratio.outside} of ${ratio.lit} lit pixels`);
    const disposed = await page.evaluate(() => window.penumbraBabylon.dispose());
    if (!disposed.refused) failures.push(`update() after dispose() was not refused with a PenumbraError (${disposed.message ?? "no error"})`);
    failures.push(...problems);
    await page.close();
    console.log(`${failures.length ? "FAIL" : "ok  "} babylon ${info.version} ${info.name} ${label} (${((Date.now() - started) / 1000).toFixed(1)} s)\n` +
                `     light frame vs desktop ${uniformError.toExponential(2)} (relative);${against} visibility vs desktop: mean |Δ| ${v.mean.toExponential(2)}, ` +
                `max ${v.worst.toFixed(4)}, ${v.outside} of ${v.geometry} interior pixels outside 2·bound + q (${v.shadowed} shadowed; ${v.silhouette} silhouette pixels left out)\n` +
                `     casters moved by M changed ${differing.moved} pixels; pixels differing from the moved Mesh: instanced ${differing.instanced}, ` +
                `thin instance ${differing.thin}, skinned ${differing.skinned}, morphed ${differing.morphed}\n` +
                `     material: lit-with / lit-without vs visibility max |Δ| ${ratio.worst.toFixed(4)}, ${ratio.outside} of ${ratio.lit} lit pixels outside 2q + 1e-3; ` +
                `update() after dispose(): ${disposed.refused ? "refused" : "not refused"}`);
    for (const f of failures) console.log(`FAIL ${f}`);
    return failures.length;
}

// Cut-out casters on cutout.html (?engine=webgpu on WebGPUEngine): failures, and a line.
async function checkCutout(browser, port, ltc, engine) {
    const started = Date.now();
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/web/babylon/test/cutout.html?engine=${engine}`, "penumbraCut",
                                            undefined, async (p) => {
        await serveLtc(p, ltc);
        if (engine === "webgpu") await p.evaluateOnNewDocument(installOffscreenCanvas);
    });
    const failures = [];
    const run = (options) => page.evaluate((o) => window.penumbraCut.run(o), options);
    const followed = await run({});
    const solid = await run({alphaTest: false});
    const untwinned = await run({emission: "rect-nbuffer-8x256"}); // shipped, no "-cut" twin (the engine picks the essl300 or wgsl one)
    const forced = await run({alphaTest: true});
    const shifted = await page.evaluate(() => window.penumbraCut.run({}, 0.5)); // the texture's offset moves the hole off the middle
    const rule = await page.evaluate(() => window.penumbraCut.rule());
    const renderer = await page.evaluate(() => window.penumbraCut.renderer);
    await page.close();
    for (const [name, r] of Object.entries({followed, solid, untwinned, forced, shifted}))
        if (r.error) failures.push(`${name}: the shadow phase failed: ${r.error}`);
    if (!followed.alphaTest || !followed.emissionCuts || followed.cutDraws !== 1)
        failures.push(`default options: info.alphaTest ${followed.alphaTest}, the emission's alpha_test ${followed.emissionCuts}, ` +
                      `${followed.cutDraws} cut draws (expected on, on, 1): the cut-out caster was not followed`);
    if (!(followed.hole > 0.8)) failures.push(`default options: the ground under the hole has visibility ${followed.hole.toFixed(3)} (expected > 0.8: lit through the hole)`);
    if (!forced.alphaTest || !(forced.hole > 0.8)) failures.push(`alphaTest: true: info.alphaTest ${forced.alphaTest}, under the hole ${forced.hole.toFixed(3)} (expected on, > 0.8)`);
    if (!(shifted.hole < 0.2)) failures.push(`the texture's uOffset, vOffset 0.5: the ground under the plane's middle has visibility ${shifted.hole.toFixed(3)} (expected < 0.2: the hole moved to the edges)`);
    if (solid.alphaTest || solid.emissionCuts || solid.cutDraws !== 0) failures.push("alphaTest: false: the add-on still cuts (info.alphaTest or the emission's alpha_test)");
    if (!(solid.hole < 0.2)) failures.push(`alphaTest: false: the ground under the hole has visibility ${solid.hole.toFixed(3)} (expected < 0.2: the plane drawn solid)`);
    if (!(followed.hole - solid.hole > 0.6)) failures.push(`under the hole, cut ${followed.hole.toFixed(3)} vs solid ${solid.hole.toFixed(3)}: not clearly brighter`);
    for (const [name, r] of Object.entries({solid, followed, forced}))
        if (r.warnings.length) failures.push(`${name} warned: ${r.warnings.join("; ")}`);
    const cutWarnings = untwinned.warnings.filter((w) => /alpha test/.test(w));
    if (untwinned.alphaTest || !(untwinned.hole < 0.2) || cutWarnings.length !== 1)
        failures.push(`a shipped emission without a cut twin: info.alphaTest ${untwinned.alphaTest}, under the hole ${untwinned.hole.toFixed(3)}, ` +
                      `${cutWarnings.length} warnings about the alpha test (expected off, < 0.2, one)`);
    failures.push(...rule, ...problems);
    const line = `${failures.length ? "FAIL" : "ok  "} babylon cut-out caster on ${renderer} (${((Date.now() - started) / 1000).toFixed(1)} s): ` +
                 `under the hole ${followed.hole.toFixed(3)} followed (alpha test on) vs ${solid.hole.toFixed(3)} with alphaTest: false; ` +
                 `the texture offset by 0.5 ${shifted.hole.toFixed(3)}; without a cut twin ${untwinned.hole.toFixed(3)} and ${cutWarnings.length} warning; the detection rule: ${rule.length ? `${rule.length} failures` : "as Babylon draws"}`;
    return {failures, line};
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    const web = path.resolve(args.web);
    for (const need of ["babylon/node_modules/@babylonjs/core/package.json"])
        if (!fs.existsSync(path.join(web, need))) {
            console.log(`error: ${path.join(web, need)} is missing: scripts/setup.sh runs npm ci in web/babylon`);
            process.exit(1);
        }
    // (web/babylon/shared/ served from its one source, web/three/: never a stale copy)
    const roots = {web, "web/babylon/shared": path.join(web, "three")};
    args.bundles.forEach((dir, i) => {
        roots[`bundle/${i}`] = dir;
        if (args.webgl2[i]) roots[`webgl2/${i}`] = args.webgl2[i];
    });
    let browser, port, close;
    if (args.engine === "webgpu") { // (WebGPU's flags; exits 77 or 1 without an adapter, as three-webgpu)
        const gpu = await startWebGPU(args.chromium, roots);
        ({browser, port, close} = gpu);
        console.log(adapterLine(gpu.adapter));
    } else {
        const server = await serve(roots);
        const chromium = await launchChromium(args.chromium);
        browser = chromium.browser;
        port = server.address().port;
        close = async () => {
            await chromium.close();
            server.close();
        };
    }
    let failures = 0;
    try {
        const ltc = await ltcTables(); // (Babylon's RectAreaLight fetches them from its CDN: ltc_tables.mjs)
        for (let i = 0; i < args.bundles.length; ++i) failures += await checkBundle(browser, port, i, args.bundles[i], ltc, args.engine, args.webgl2[i]);
        const cut = await checkCutout(browser, port, ltc, args.engine);
        console.log(cut.line);
        for (const f of cut.failures) console.log(`FAIL ${f}`);
        failures += cut.failures.length;
    } catch (e) {
        console.log(`FAIL ${e.message}`);
        failures += 1;
    } finally {
        await close();
    }
    process.exit(failures ? 1 : 0);
}

main();
