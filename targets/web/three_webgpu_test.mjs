// three_webgpu_test.mjs — the `three-webgpu` browser test: the three.js add-on on WebGPURenderer
// (web/three/penumbra_shadows.js → penumbra_shadows_webgpu.js) in Debian's chromium (headless,
// WebGPU through SwiftShader), over bundles exported with `penumbra-export-bundle --target wgsl`
// (the desktop GL run of the same configuration; emission/ holds its wgsl emission):
//
//   node targets/web/three_webgpu_test.mjs --web web [--chromium PATH] [--images DIR]
//        [--two-lights RECT_EMISSION_DIR SUN_EMISSION_DIR] [--three THREE_DIR]
//        [--against-webgl2 BUNDLE_DIR[:physical-node] ESSL300_BUNDLE_DIR]... BUNDLE_DIR[:physical-node]...
//
// Each bundle's scene is rebuilt in three.js (web/three/test/webgpu.html: the bundle's triangles,
// light and camera, as the WebGL2 test's page), the add-on attached with PenumbraShadows.load(), and
// the checks of three_test.mjs (its functions, the same tolerances):
//   1. the add-on's light frame is the desktop's (relative 1e-5);
//   2. its visibility equals the desktop run's within 2·bound + q on the interior pixels, all but
//      INTERIOR_PIXELS_ALLOWED (one pixel a bundle); silhouette pixels (where three's rasterization
//      and the desktop's G-buffer may see different surfaces) are counted and reported, left out
//      as in three_test.mjs;
//   3. in the node material the light's term is multiplied by that visibility (rect and sun):
//      lit-with / lit-without equals it within 2q + 1e-3 on all but 1% of the lit pixels;
//   4. the mesh moved as a Mesh, InstancedMesh, SkinnedMesh and morph target: the same visibility;
//   5. moving the light re-runs the shadow phase once, update() without a change does not, no
//      WebGPU validation error, dispose() restores the material;
//   7. once, three_test.mjs's cut-out caster check (web/three/test/cutout_webgpu.html): a plane with
//      a hole in its map's alpha, the shipped "-cut-wgsl" emission picked by default, the ground
//      under the hole lit, and dark with alphaTest: false.
// --against-webgl2: a wgsl bundle whose check 2 is against the same add-on's WebGL2 visibility
// instead of the desktop's (the room: SwiftShader's 4 sub-pixel bits against llvmpipe's 8 move a
// slice texel on a shelf's edge and the rasterized receivers by 1-2 mm, which near contact, in the
// self-shadow fade, moves 14 of 3047 interior pixels beyond 2·bound + q; the WebGL2 test `three`
// holds that comparison, with its 1%): the essl300 bundle of the same room (scene, triangles,
// light, camera, configuration) through web/three/test/index.html (WebGLRenderer) in the same
// Chromium, whose SwiftShader rasterizes both alike; every pixel within 2q, none allowed out, so
// that the WGSL path is shown to compute what the ESSL one does. The desktop's numbers are printed.
// ":physical-node" after a bundle: its receivers get a MeshPhysicalNodeMaterial (else the bundle
// scene's plain MeshStandardMaterial, which WebGPURenderer converts).
// --two-lights: a RectAreaLight and a sun, each with its add-on (the two wgsl emission folders, small
// enough that both fit 16 sampled textures a stage), on one MeshStandardNodeMaterial
// (web/three/test/two_lights_webgpu.html): each light's lit-with / lit-without is its own visibility,
// both lights on is the sum of each alone, and their shadows differ.
// --three: the first bundle again with another three.js build (an npm package folder, e.g. three
// r180, the other end of the peer range), through a page whose import map points there.
// Exit 0 pass, 1 fail, 2 bad arguments, 77 skip (no chromium; no WebGPU adapter only with
// PENUMBRA_WEBGPU_OPTIONAL=1, as wgsl_compile.mjs).
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import {openPage, writeGreyPng} from "./harness.mjs";
import {PIXELS_ALLOWED, R8_STEP, UNIFORM_TOLERANCE, VARIANT_PIXELS_ALLOWED, backendFailures, bundleMismatch, checkCutout, compareBackends, compareRatio,
        compareVariants, compareWithDesktop, frameError} from "./three_test.mjs";
import {adapterLine, startWebGPU} from "./wgsl_compile.mjs";

// Interior pixels outside 2·bound + q: one a bundle (issue 31's target; the WebGL2 test allows 1%
// of the image: SwiftShader rasterizes the slicing pass's triangle edges unlike llvmpipe).
const INTERIOR_PIXELS_ALLOWED = 1;

function usage(message) {
    console.error(`error: ${message}\nusage: node three_webgpu_test.mjs --web DIR [--chromium PATH] [--images DIR] ` +
                  "[--two-lights RECT_DIR SUN_DIR] [--three THREE_DIR] [--against-webgl2 BUNDLE_DIR[:physical-node] ESSL300_DIR]... " +
                  "BUNDLE_DIR[:physical-node]...");
    process.exit(2);
}

function bundleArgument(flag) {
    const [dir, material = ""] = flag.split(/:(?=[a-z-]+$)/);
    if (material && material !== "physical-node") usage(`${flag}: ':${material}' unknown; allowed: ':physical-node'`);
    if (!fs.existsSync(path.join(dir, "uniforms.json"))) usage(`${dir}: no uniforms.json (a bundle of penumbra-export-bundle --target wgsl)`);
    return {dir, material, webgl2: null};
}

function parseArguments(argv) {
    const out = {web: null, chromium: "/usr/bin/chromium", images: null, bundles: [], twoLights: null, three: null};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        if (flag === "--two-lights") {
            if (i + 2 >= argv.length) usage("--two-lights: needs the rect and the sun emission folders");
            out.twoLights = [argv[++i], argv[++i]];
            for (const dir of out.twoLights) if (!fs.existsSync(path.join(dir, "layout.json"))) usage(`--two-lights: no layout.json in ${dir}`);
        } else if (flag === "--against-webgl2") {
            if (i + 2 >= argv.length) usage("--against-webgl2: needs a wgsl bundle and the essl300 bundle of the same scene");
            const bundle = bundleArgument(argv[++i]);
            bundle.webgl2 = argv[++i];
            if (!fs.existsSync(path.join(bundle.webgl2, "uniforms.json"))) usage(`--against-webgl2: no uniforms.json in ${bundle.webgl2}`);
            out.bundles.push(bundle);
        } else if (flag === "--web" || flag === "--chromium" || flag === "--images" || flag === "--three") {
            if (i + 1 >= argv.length) usage(`${flag}: missing value`);
            out[flag.slice(2)] = argv[++i];
        } else if (flag.startsWith("--")) {
            usage(`unknown flag '${flag}'; allowed: --web, --chromium, --images, --two-lights, --three, --against-webgl2`);
        } else {
            out.bundles.push(bundleArgument(flag));
        }
    }
    if (!out.web) usage("--web: missing (the web/ folder with three/penumbra_shadows.js)");
    if (!fs.existsSync(path.join(out.web, "three/penumbra_shadows_webgpu.js"))) usage(`--web: no three/penumbra_shadows_webgpu.js in ${out.web}`);
    if (out.bundles.length === 0) usage("no bundle directories");
    if (out.three && !fs.existsSync(path.join(out.three, "build/three.webgpu.js"))) usage(`--three: no build/three.webgpu.js in ${out.three}`);
    return out;
}

async function checkBundle(browser, port, index, {dir, material, webgl2}, images, page_ = "webgpu.html") {
    const bundle = JSON.parse(fs.readFileSync(path.join(dir, "uniforms.json"), "utf8"));
    const c = bundle.config;
    if (c.target !== "wgsl") return {failures: [`${dir}: a bundle of target '${c.target}'; this test runs wgsl bundles`]};
    const label = `${bundle.scene} ${c.light} ${c.filter}/${c.packing} ${c.slices}×${c.resolution}² ${bundle.width}x${bundle.height}`;
    const started = Date.now();
    const query = `bundle=/bundle/${index}/${material ? `&material=${material}` : ""}`;
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/web/three/test/${page_}?${query}`, "penumbraThree");
    const failures = [];
    const call = (name, ...args) => page.evaluate((n, a) => window.penumbraThree[n](...a), name, args);
    const info = await call("info");
    if (info.backend !== "webgpu" || info.addon !== "PenumbraShadowsWebGPU") failures.push(`the page runs backend ${info.backend} with ${info.addon}`);

    const uniformError = frameError(await call("frameUniforms"));
    if (!(uniformError <= UNIFORM_TOLERANCE)) failures.push(`the add-on's light frame differs from the desktop's by ${uniformError.toExponential(2)} (relative)`);

    const visibility = await call("visibility");
    const v = compareWithDesktop(visibility, dir, bundle);
    if (v.length !== v.pixels) failures.push(`${v.length} pixels read, expected ${v.pixels}`);
    let against = "";
    if (webgl2) { // 2b. against the add-on's WebGL2 visibility of the same room (the desktop's: the `three` test)
        failures.push(...bundleMismatch(dir, webgl2));
        const gl = await openPage(browser, `http://127.0.0.1:${port}/web/three/test/index.html?bundle=/webgl2/${index}/`, "penumbraThree");
        const b = compareBackends(visibility, await gl.page.evaluate(() => window.penumbraThree.visibility()));
        failures.push(...gl.problems);
        await gl.page.close();
        failures.push(...backendFailures(b, v.pixels));
        against = `\n     visibility vs the add-on on WebGLRenderer (same room, same chromium): max |Δ| ${b.worst.toExponential(2)}, ` +
                  `${b.outside} of ${b.pixels} pixels outside 2q (${b.shadowed} shadowed)\n     not checked here (\`three\` checks the room on WebGL2):`;
    } else if (v.outside > INTERIOR_PIXELS_ALLOWED)
        failures.push(`${v.outside} of ${v.geometry} interior pixels differ from the desktop run by more than 2·bound + q (allowed: ${INTERIOR_PIXELS_ALLOWED})`);
    if (v.shadowed === 0) failures.push("the desktop image has no shadowed pixel: the comparison would prove nothing");

    const ratio = compareRatio(await call("materialRatio"), visibility);
    if (ratio.lit === 0) failures.push("the light lights no pixel");
    if (ratio.outside > PIXELS_ALLOWED * ratio.lit) failures.push(`the lit image is not visibility × unshadowed at ${ratio.outside} of ${ratio.lit} lit pixels`);

    const variants = compareVariants(await call("variants"));
    for (const name of ["instanced", "skinned", "morphed"])
        if (variants[name] > VARIANT_PIXELS_ALLOWED * v.pixels) failures.push(`the ${name} casters and receivers differ from the moved Mesh at ${variants[name]} pixels`);
    if (variants.moved === 0) failures.push("moving the mesh changed no pixel: the variants prove nothing");

    const before = await call("shadowUpdates");
    const idle = await call("update");
    const moved = await call("moveLight", 0.25 * (bundle.light.width || 1));
    const after = await call("visibility");
    const changed = after.reduce((n, x, i) => n + (Math.abs(x - visibility[i]) > 2 / 255 ? 1 : 0), 0);
    if (idle !== before) failures.push("update() without a change re-ran the shadow phase");
    if (moved !== before + 1) failures.push("moving the light did not re-run the shadow phase once");
    if (c.light === "rect" && changed === 0) failures.push("moving the light changed no pixel");
    const shadowError = await call("shadowError");
    if (shadowError) failures.push(`WebGPU: ${shadowError}`);
    const disposed = await call("dispose");
    if (!disposed.hooked || !disposed.restored || !disposed.refused)
        failures.push(`dispose(): the material was ${disposed.hooked ? "" : "not "}hooked before and ${disposed.restored ? "" : "not "}restored after; ` +
                      `update() after it was ${disposed.refused ? "" : "not "}refused`);
    failures.push(...problems);
    await page.close();
    if (images) {
        fs.mkdirSync(images, {recursive: true});
        await writeGreyPng(path.join(images, `${index}_${bundle.scene}_${c.light}_webgpu.png`), bundle.width, bundle.height, visibility);
    }
    console.log(`${failures.length ? "FAIL" : "ok  "} three r${info.three} WebGPURenderer ${label} ${info.material} (${((Date.now() - started) / 1000).toFixed(1)} s)\n` +
                `     light frame vs desktop ${uniformError.toExponential(2)} (relative);${against} visibility vs desktop: mean |Δ| ${v.mean.toExponential(2)}, ` +
                `max ${v.worst.toFixed(4)}, ${v.outside} of ${v.geometry} interior pixels outside 2·bound + q (${v.shadowed} shadowed); ` +
                `${v.silhouetteOutside} of ${v.silhouette} silhouette pixels outside (left out)\n` +
                `     material: lit-with / lit-without vs visibility max |Δ| ${ratio.worst.toFixed(4)}, ${ratio.outside} of ${ratio.lit} lit pixels outside 2q + 1e-3; ` +
                `moved light changed ${changed} pixels\n` +
                `     moved mesh changed ${variants.moved} pixels; pixels differing from it: instanced ${variants.instanced}, skinned ${variants.skinned}, morphed ${variants.morphed}`);
    for (const f of failures) console.log(`     ${f}`);
    return {failures};
}

// Two add-ons on one material: each scales its own light's term only.
async function checkTwoLights(browser, port) {
    const started = Date.now();
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/web/three/test/two_lights_webgpu.html?rect=/two/rect/&sun=/two/sun/`, "result");
    const r = await page.evaluate(() => window.result);
    await page.close();
    const failures = [...problems, ...r.errors.map((e) => `WebGPU: ${e}`)];
    for (const light of ["rect", "sun"]) {
        const x = r[light];
        if (x.lit === 0 || x.shadowed === 0) failures.push(`${light}: ${x.lit} lit and ${x.shadowed} shadowed pixels: the check would prove nothing`);
        if (!(x.worst <= 2 * R8_STEP + 1e-3)) failures.push(`${light}: lit-with / lit-without differs from its own visibility by ${x.worst}`);
    }
    if (!(r.sum <= 1e-4)) failures.push(`both lights on differ from the sum of each alone by ${r.sum}`);
    if (r.distinct === 0) failures.push("the two lights' visibilities are the same: the check would prove nothing");
    console.log(`${failures.length ? "FAIL" : "ok  "} two add-ons (a RectAreaLight and a sun) on one MeshStandardNodeMaterial (${((Date.now() - started) / 1000).toFixed(1)} s): ` +
                `rect lit-with / lit-without vs its visibility max |Δ| ${r.rect.worst.toExponential(2)} (${r.rect.shadowed} shadowed of ${r.rect.lit} lit), ` +
                `sun ${r.sun.worst.toExponential(2)} (${r.sun.shadowed} of ${r.sun.lit}); both on vs the sum max |Δ| ${r.sum.toExponential(2)}; ` +
                `${r.distinct} pixels where the two visibilities differ`);
    for (const f of failures) console.log(`     ${f}`);
    return failures;
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    const roots = {web: args.web};
    args.bundles.forEach(({dir, webgl2}, i) => {
        roots[`bundle/${i}`] = dir;
        if (webgl2) roots[`webgl2/${i}`] = webgl2;
    });
    if (args.twoLights) [roots["two/rect"], roots["two/sun"]] = args.twoLights;
    // --three: the test page with an import map to that build (served beside webgpu.html, so that
    // its module's relative imports resolve alike)
    const files = {};
    if (args.three) {
        roots["three-alt"] = args.three;
        const html = fs.readFileSync(path.join(args.web, "three/test/webgpu.html"), "utf8").replaceAll("../node_modules/three/", "/three-alt/");
        const file = path.join(fs.mkdtempSync(path.join(os.tmpdir(), "penumbra-three-webgpu-")), "webgpu-alt.html");
        fs.writeFileSync(file, html);
        files["/web/three/test/webgpu-alt.html"] = file;
    }
    const {browser, port, adapter, close} = await startWebGPU(args.chromium, roots, files);
    console.log(adapterLine(adapter));
    let failures = 0;
    try {
        for (let i = 0; i < args.bundles.length; ++i) failures += (await checkBundle(browser, port, i, args.bundles[i], args.images)).failures.length;
        if (args.twoLights) failures += (await checkTwoLights(browser, port)).length;
        const cut = await checkCutout(browser, `http://127.0.0.1:${port}/web/three/test/cutout_webgpu.html`);
        console.log(cut.line);
        for (const f of cut.failures) console.log(`     ${f}`);
        failures += cut.failures.length;
        if (args.three) failures += (await checkBundle(browser, port, 0, args.bundles[0], null, "webgpu-alt.html")).failures.length;
    } catch (e) {
        console.log(`FAIL ${e.message}`);
        failures += 1;
    } finally {
        await close();
    }
    process.exit(failures ? 1 : 0);
}

main();
