// three_test.mjs — the `three` browser test: one of Penumbra's built-in scenes rebuilt in three.js
// (web/three/test/: the bundle's triangles, light and camera), the add-on (web/three/penumbra_shadows.js)
// attached to its RectAreaLight (or sun), in Debian's chromium (headless, SwiftShader):
//
//   node targets/web/three_test.mjs --web web [--chromium PATH] [--wasm penumbra_emitter.wasm] BUNDLE_DIR...
//
// Each BUNDLE_DIR is written by penumbra-export-bundle --target essl300 (uniforms.json has the camera).
//   1. The add-on's light frame, computed from the three.js light and the scene's bounds, is the
//      desktop runtime's (relative 1e-5).
//   2. Its visibility at the camera's pixels equals the desktop runtime's (visibility_gl.f32) within
//      2·bound + q (both are within the oracle's bound of the model; q = 1/255 for the R8 result) on
//      all interior pixels but 1% of the image's (as browser_test.mjs allows its own slicing; SwiftShader rasterizes triangle edges in the slicing pass
//      unlike llvmpipe, which the bound does not cover; silhouette pixels, where the two cameras
//      may see different surfaces, are counted and left out).
//   3. In MeshStandardMaterial, the RectAreaLight's contribution is multiplied by that visibility:
//      (lit with the add-on) / (lit without it) equals it within 2/255 + 1e-3 wherever the light
//      reaches (unshadowed > 1e-3), on all but 1% of those pixels.
//   4. The scene's mesh moved by a matrix M as a Mesh, an InstancedMesh (instance matrix M), a
//      SkinnedMesh (its bone at M) and a morph target (positions × M): the same visibility within
//      2q (all but 0.2% of the pixels), and unlike the unmoved mesh's.
//   5. Moving the light re-runs the shadow phase; update() without a change does not; dispose()
//      deletes the add-on's textures and programs and restores the materials.
//   6. With --wasm: the bundle's configuration emitted in the page by the WebAssembly emitter
//      (a configuration object as `emission`) gives the same visibility as the bundle's emission
//      folder (within 1e-6).
//   7. Once, cut-out casters (web/three/test/cutout.html; the shipped emissions, which the build
//      writes): a plane whose map has a transparent hole, with alphaTest, under a RectAreaLight.
//      With the default options the add-on follows the cut (info.alphaTest, the shipped "-cut"
//      emission) and the ground under the hole is lit (> 0.8), clearly more than with
//      alphaTest: false (< 0.2, no warning); a shipped emission without a cut twin draws solid
//      with one console.warn.
// Exit 0 pass, 1 fail, 77 skip (no chromium), 2 bad arguments.
// The checks 1-4 and 7 are exported for three_webgpu_test.mjs (the add-on on WebGPURenderer), and 2b
// (a WebGPU visibility against the same add-on's WebGL2 one, for the room) for it and babylon_test.mjs.
import path from "node:path";
import fs from "node:fs";
import {fileURLToPath} from "node:url";
import {serve, launchChromium, openPage, readFloats} from "./harness.mjs";

export const R8_STEP = 1 / 255;
export const UNIFORM_TOLERANCE = 1e-5;
export const PIXELS_ALLOWED = 0.01;
export const VARIANT_PIXELS_ALLOWED = 0.002; // float rounding of M applied on the GPU or the CPU

function parseArguments(argv) {
    const out = {web: null, chromium: "/usr/bin/chromium", wasm: null, bundles: []};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        if (flag === "--web" || flag === "--chromium" || flag === "--wasm") {
            if (i + 1 >= argv.length) usage(`${flag}: missing value`);
            out[flag.slice(2)] = argv[++i];
        } else if (flag.startsWith("--")) usage(`unknown flag '${flag}'; allowed: --web, --chromium, --wasm`);
        else out.bundles.push(flag);
    }
    if (!out.web) usage("--web: missing");
    if (out.bundles.length === 0) usage("no bundle directories");
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node three_test.mjs --web DIR [--chromium PATH] [--wasm penumbra_emitter.wasm] BUNDLE_DIR...`);
    process.exit(2);
}

// Pixels whose 8 neighbours are geometry within 8 pixel footprints of its world position, with its
// normal and on its plane within one footprint (the desktop G-buffers): at the others (silhouettes
// and creases), three's rasterization may see another surface than llvmpipe's. (The plane: in a room,
// a shelf's front edge before its back panel and the wall behind are parallel faces a few footprints
// apart in depth, a silhouette that the normals alone miss.)
export function interiorPixels(positions, normals, bundle) {
    const W = bundle.width, H = bundle.height, eye = bundle.camera.eye;
    const scale = 2 * Math.tan(bundle.camera.fov_y_degrees * Math.PI / 360) / H;
    const out = new Uint8Array(W * H);
    const p = (i, a) => positions[4 * i + a];
    for (let y = 1; y < H - 1; ++y)
        for (let x = 1; x < W - 1; ++x) {
            const i = y * W + x;
            if (p(i, 3) === 0) continue;
            const footprint = Math.hypot(p(i, 0) - eye[0], p(i, 1) - eye[1], p(i, 2) - eye[2]) * scale;
            let ok = true;
            for (let dy = -1; dy <= 1 && ok; ++dy)
                for (let dx = -1; dx <= 1 && ok; ++dx) {
                    const j = i + dy * W + dx;
                    const d = [p(j, 0) - p(i, 0), p(j, 1) - p(i, 1), p(j, 2) - p(i, 2)];
                    ok = p(j, 3) !== 0 && Math.hypot(...d) < 8 * footprint &&
                         normals[4 * j] * normals[4 * i] + normals[4 * j + 1] * normals[4 * i + 1] + normals[4 * j + 2] * normals[4 * i + 2] > 0.99 &&
                         Math.abs(d[0] * normals[4 * i] + d[1] * normals[4 * i + 1] + d[2] * normals[4 * i + 2]) < footprint;
                }
            out[i] = ok ? 1 : 0;
        }
    return out;
}

function relativeDifference(a, b) {
    let worst = 0, scale = 0;
    for (let i = 0; i < b.length; ++i) {
        worst = Math.max(worst, Math.abs(Math.fround(a[i]) - b[i]));
        scale = Math.max(scale, Math.abs(b[i]));
    }
    return worst / Math.max(scale, 1e-30);
}

// 1. The add-on's light frame against the bundle's uniforms: the largest relative difference.
export function frameError(frame) {
    let uniformError = 0;
    for (const [name, value] of Object.entries(frame.bundle)) {
        if (!(name in frame.computed)) continue;
        const a = [].concat(frame.computed[name]), b = [].concat(value);
        uniformError = Math.max(uniformError, relativeDifference(a, b));
    }
    return uniformError;
}

// 2. The add-on's visibility (bottom row first) against the desktop run of bundle `dir`: on the
// interior pixels, how many are outside 2·bound + q (and the largest and mean |Δ|); silhouette
// pixels are counted apart (silhouetteOutside: those of them outside too).
export function compareWithDesktop(visibility, dir, bundle) {
    const gl = readFloats(path.join(dir, "visibility_gl.f32")), bound = readFloats(path.join(dir, "bound.f32"));
    const positions = readFloats(path.join(dir, "positions.f32"));
    const interior = interiorPixels(positions, readFloats(path.join(dir, "normals.f32")), bundle);
    const out = {outside: 0, worst: 0, geometry: 0, shadowed: 0, mean: 0, silhouette: 0, silhouetteOutside: 0, pixels: gl.length,
                 length: visibility.length};
    for (let i = 0; i < gl.length; ++i) {
        if (positions[4 * i + 3] === 0) continue; // background: the desktop leaves 1
        const d = Math.abs(visibility[i] - gl[i]);
        const beyond = d > 2 * bound[i] + R8_STEP + 1e-6;
        if (!interior[i]) { ++out.silhouette; if (beyond) ++out.silhouetteOutside; continue; }
        ++out.geometry;
        if (gl[i] < 0.98) ++out.shadowed;
        out.mean += d;
        out.worst = Math.max(out.worst, d);
        if (beyond) ++out.outside;
    }
    out.mean /= Math.max(out.geometry, 1);
    return out;
}

// 2b. (the WebGPU tests, where the desktop comparison is the WebGL2 test's: the room) a wgsl bundle
// against an essl300 bundle of the same scene: what differs but the target (the scene, its
// triangles, light, camera, size, light-frame uniforms and configuration); none, the two add-ons'
// images are of the same room.
export function bundleMismatch(wgslDir, esslDir) {
    const a = JSON.parse(fs.readFileSync(path.join(wgslDir, "uniforms.json"), "utf8"));
    const b = JSON.parse(fs.readFileSync(path.join(esslDir, "uniforms.json"), "utf8"));
    const out = [];
    if (a.config.target !== "wgsl" || b.config.target !== "essl300") out.push(`targets ${a.config.target} and ${b.config.target} (expected wgsl and essl300)`);
    for (const key of ["scene", "width", "height", "camera", "light", "uniforms"])
        if (JSON.stringify(a[key]) !== JSON.stringify(b[key])) out.push(key);
    if (JSON.stringify({...a.config, target: ""}) !== JSON.stringify({...b.config, target: ""})) out.push("config");
    if (!fs.readFileSync(path.join(wgslDir, "mesh.f32")).equals(fs.readFileSync(path.join(esslDir, "mesh.f32")))) out.push("mesh.f32");
    return out.length ? [`${wgslDir} and ${esslDir} are not bundles of the same room: ${out.join(", ")} differ`] : [];
}

// 2b. The add-on's WebGPU visibility against its WebGL2 visibility of the same bundle (both from
// the same Chromium's SwiftShader, so rasterized alike): pixels beyond 2q (every pixel counts),
// the largest |Δ|, and the pixels below 0.98 in either (the comparison proves nothing without).
export function compareBackends(webgpu, webgl2) {
    const out = {outside: 0, worst: 0, shadowed: 0, pixels: webgl2.length, length: webgpu.length};
    for (let i = 0; i < webgl2.length; ++i) {
        const d = Math.abs(webgpu[i] - webgl2[i]);
        if (!(d <= 2 * R8_STEP)) ++out.outside; // (NaN counts)
        out.worst = Math.max(out.worst, Number.isNaN(d) ? Infinity : d);
        if (webgl2[i] < 0.98 || webgpu[i] < 0.98) ++out.shadowed;
    }
    return out;
}

// What compareBackends found wrong, for `expected` pixels: none may lie outside 2q, and one must be shadowed.
export function backendFailures(b, expected) {
    const failures = [];
    if (b.length !== b.pixels || b.pixels !== expected) failures.push(`${b.length} WebGPU and ${b.pixels} WebGL2 pixels read, expected ${expected}`);
    if (b.outside > 0) failures.push(`${b.outside} of ${b.pixels} pixels differ from the add-on's WebGL2 visibility of the same room by more than 2q (allowed: none)`);
    if (b.shadowed === 0) failures.push("neither visibility has a shadowed pixel: the comparison with WebGL2 would prove nothing");
    return failures;
}

// 3. (rect) lit-with / lit-without against the visibility, where the light reaches.
export function compareRatio({ratio, unshadowed}, visibility) {
    const out = {outside: 0, lit: 0, worst: 0};
    for (let i = 0; i < ratio.length; ++i) {
        if (!(unshadowed[i] > 1e-3)) continue;
        ++out.lit;
        const d = Math.abs(ratio[i] - visibility[i]);
        out.worst = Math.max(out.worst, d);
        if (!(d <= 2 * R8_STEP + 1e-3)) ++out.outside;
    }
    return out;
}

// 4. The variants against the moved Mesh: pixels differing by more than 2q, by name; and how many
// pixels moving the mesh changed.
export function compareVariants(variants) {
    const differing = (a, b, tolerance) => a.reduce((n, v, i) => n + (Math.abs(v - b[i]) > tolerance ? 1 : 0), 0);
    const out = {moved: differing(variants.mesh, variants.unmoved, 2 * R8_STEP)};
    for (const name of ["instanced", "skinned", "morphed"]) out[name] = differing(variants[name], variants.mesh, 2 * R8_STEP);
    return out;
}

// 7. Cut-out casters on the page `url` (cutout.html or cutout_webgpu.html): failures, and a line.
export async function checkCutout(browser, url) {
    const started = Date.now();
    const {page, problems} = await openPage(browser, url, "penumbraCut");
    const failures = [];
    const run = (options) => page.evaluate((o) => window.penumbraCut.run(o), options);
    const followed = await run({});
    const solid = await run({alphaTest: false});
    const untwinned = await run({emission: "rect-nbuffer-8x256"}); // shipped, no "-cut" twin
    const renderer = await page.evaluate(() => window.penumbraCut.renderer);
    await page.close();
    for (const [name, r] of Object.entries({followed, solid, untwinned}))
        if (r.error) failures.push(`${name}: the shadow phase failed: ${r.error}`);
    if (!followed.alphaTest || !followed.emissionCuts || followed.cutDraws !== 1)
        failures.push(`default options: info.alphaTest ${followed.alphaTest}, the emission's alpha_test ${followed.emissionCuts}, ` +
                      `${followed.cutDraws} cut draws (expected on, on, 1): the cut-out caster was not followed`);
    if (!(followed.hole > 0.8)) failures.push(`default options: the ground under the hole has visibility ${followed.hole.toFixed(3)} (expected > 0.8: lit through the hole)`);
    if (solid.alphaTest || solid.emissionCuts || solid.cutDraws !== 0) failures.push("alphaTest: false: the add-on still cuts (info.alphaTest or the emission's alpha_test)");
    if (!(solid.hole < 0.2)) failures.push(`alphaTest: false: the ground under the hole has visibility ${solid.hole.toFixed(3)} (expected < 0.2: the plane drawn solid)`);
    if (!(followed.hole - solid.hole > 0.6)) failures.push(`under the hole, cut ${followed.hole.toFixed(3)} vs solid ${solid.hole.toFixed(3)}: not clearly brighter`);
    if (solid.warnings.length) failures.push(`alphaTest: false warned: ${solid.warnings.join("; ")}`);
    if (followed.warnings.length) failures.push(`default options warned: ${followed.warnings.join("; ")}`);
    const cutWarnings = untwinned.warnings.filter((w) => /alpha test/.test(w));
    if (untwinned.alphaTest || !(untwinned.hole < 0.2) || cutWarnings.length !== 1)
        failures.push(`a shipped emission without a cut twin: info.alphaTest ${untwinned.alphaTest}, under the hole ${untwinned.hole.toFixed(3)}, ` +
                      `${cutWarnings.length} warnings about the alpha test (expected off, < 0.2, one)`);
    failures.push(...problems);
    const line = `${failures.length ? "FAIL" : "ok  "} cut-out caster on ${renderer} (${((Date.now() - started) / 1000).toFixed(1)} s): ` +
                 `under the hole ${followed.hole.toFixed(3)} followed (alpha test on) vs ${solid.hole.toFixed(3)} with alphaTest: false; ` +
                 `without a cut twin ${untwinned.hole.toFixed(3)} and ${cutWarnings.length} warning`;
    return {failures, line};
}

async function checkBundle(browser, port, index, dir, wasm) {
    const bundle = JSON.parse(fs.readFileSync(path.join(dir, "uniforms.json"), "utf8"));
    const c = bundle.config;
    const label = `${bundle.scene} ${c.light} ${c.filter}/${c.packing} ${c.slices}×${c.resolution}² ${bundle.width}x${bundle.height}`;
    const started = Date.now();
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/web/three/test/index.html?bundle=/bundle/${index}/`, "penumbraThree");
    const failures = [];
    const info = await page.evaluate(() => window.penumbraThree.info());

    // 1. light frame
    const uniformError = frameError(await page.evaluate(() => window.penumbraThree.frameUniforms()));
    if (uniformError > UNIFORM_TOLERANCE) failures.push(`the add-on's light frame differs from the desktop's by ${uniformError.toExponential(2)} (relative)`);

    // 2. visibility against the desktop runtime
    const visibility = await page.evaluate(() => window.penumbraThree.visibility());
    const v = compareWithDesktop(visibility, dir, bundle);
    const {outside, worst, geometry, shadowed, silhouette} = v, gl = {length: v.pixels};
    if (visibility.length !== gl.length) failures.push(`${visibility.length} pixels read, expected ${gl.length}`);
    if (outside > PIXELS_ALLOWED * gl.length)
        failures.push(`${outside} of ${geometry} interior pixels differ from the desktop run by more than 2·bound + q (allowed: ${100 * PIXELS_ALLOWED}% of the ${gl.length} pixels)`);
    if (shadowed === 0) failures.push("the desktop image has no shadowed pixel: the comparison would prove nothing");

    // 3. the material hook
    let ratioOutside = 0, lit = 0, ratioWorst = 0;
    if (c.light === "rect") {
        ({outside: ratioOutside, lit, worst: ratioWorst} = compareRatio(await page.evaluate(() => window.penumbraThree.materialRatio()), visibility));
        if (lit === 0) failures.push("the RectAreaLight lights no pixel");
        if (ratioOutside > PIXELS_ALLOWED * lit) failures.push(`the lit image is not visibility × unshadowed at ${ratioOutside} of ${lit} lit pixels`);
    }

    // 4. the same casters as a moved Mesh, an InstancedMesh, a SkinnedMesh and a morph target
    const variants = compareVariants(await page.evaluate(() => window.penumbraThree.variants()));
    const variantText = [];
    for (const name of ["instanced", "skinned", "morphed"]) {
        const n = variants[name];
        variantText.push(`${name} ${n}`);
        if (n > VARIANT_PIXELS_ALLOWED * gl.length) failures.push(`the ${name} casters and receivers differ from the moved Mesh at ${n} pixels`);
    }
    const movedPixels = variants.moved;
    if (movedPixels === 0) failures.push("moving the mesh changed no pixel: the variants prove nothing");

    // 5. updates and dispose
    const before = await page.evaluate(() => window.penumbraThree.shadowUpdates());
    const idle = await page.evaluate(() => window.penumbraThree.update());
    const moved = await page.evaluate((dx) => window.penumbraThree.moveLight(dx), 0.25 * (bundle.light.width || 1));
    const after = await page.evaluate(() => window.penumbraThree.visibility());
    let changed = 0;
    for (let i = 0; i < after.length; ++i) if (Math.abs(after[i] - visibility[i]) > 2 * R8_STEP) ++changed;
    if (idle !== before) failures.push("update() without a change re-ran the shadow phase");
    if (moved !== before + 1) failures.push("moving the light did not re-run the shadow phase once");
    if (c.light === "rect" && changed === 0) failures.push("moving the light changed no pixel");
    const disposed = await page.evaluate(() => window.penumbraThree.dispose());
    if (disposed.texturesAlive || disposed.programsAlive || !disposed.restored || !disposed.textures)
        failures.push(`dispose() left ${disposed.texturesAlive} of ${disposed.textures} textures and ${disposed.programsAlive} of ${disposed.programs} programs` +
                      (disposed.restored ? "" : ", and did not restore the material"));
    failures.push(...problems);
    await page.close();

    // 6. the same configuration through the WebAssembly emitter
    let emitterText = "";
    if (wasm) {
        const query = `bundle=/bundle/${index}/&wasm=/wasm/penumbra_emitter.wasm&config=${encodeURIComponent(JSON.stringify(c))}`;
        const emitted = await openPage(browser, `http://127.0.0.1:${port}/web/three/test/index.html?${query}`, "penumbraThree");
        const v = await emitted.page.evaluate(() => window.penumbraThree.visibility());
        let worstEmitted = 0;
        for (let i = 0; i < v.length; ++i) worstEmitted = Math.max(worstEmitted, Math.abs(v[i] - visibility[i]));
        if (!(worstEmitted <= 1e-6)) failures.push(`through the WebAssembly emitter the visibility differs from the emission folder's by ${worstEmitted}`);
        failures.push(...emitted.problems);
        await emitted.page.close();
        emitterText = `; WebAssembly emitter vs emission folder: max |Δ| ${worstEmitted.toExponential(2)}`;
    }
    console.log(`${failures.length ? "FAIL" : "ok  "} three r${info.three} ${label} (${((Date.now() - started) / 1000).toFixed(1)} s)\n` +
                `     light frame vs desktop ${uniformError.toExponential(2)} (relative); visibility vs desktop: mean |Δ| ${v.mean.toExponential(2)}, ` +
                `max ${worst.toFixed(4)}, ${outside} of ${geometry} interior pixels outside 2·bound + q (${shadowed} shadowed; ${silhouette} silhouette pixels left out)\n` +
                `     material: lit-with / lit-without vs visibility max |Δ| ${ratioWorst.toFixed(4)}, ${ratioOutside} of ${lit} lit pixels outside 2q + 1e-3; ` +
                `moved light changed ${changed} pixels\n` +
                `     moved mesh changed ${movedPixels} pixels; pixels differing from it: ${variantText.join(", ")}${emitterText}`);
    for (const f of failures) console.log(`     ${f}`);
    return {failures: failures.length, renderer: info.renderer};
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    const {browser, close} = await launchChromium(args.chromium);
    const roots = {web: args.web};
    args.bundles.forEach((dir, i) => (roots[`bundle/${i}`] = dir));
    if (args.wasm) roots.wasm = path.dirname(path.resolve(args.wasm));
    if (args.wasm && path.basename(args.wasm) !== "penumbra_emitter.wasm") usage("--wasm: the file must be named penumbra_emitter.wasm");
    const server = await serve(roots);
    let failures = 0;
    try {
        for (let i = 0; i < args.bundles.length; ++i) {
            const result = await checkBundle(browser, server.address().port, i, args.bundles[i], args.wasm);
            if (i === 0) console.log(`WebGL2 renderer: ${result.renderer}`);
            failures += result.failures;
        }
        const cut = await checkCutout(browser, `http://127.0.0.1:${server.address().port}/web/three/test/cutout.html`);
        console.log(cut.line);
        for (const f of cut.failures) console.log(`     ${f}`);
        failures += cut.failures.length;
    } catch (e) {
        console.log(`FAIL ${e.message}`);
        failures += 1;
    } finally {
        await close();
        server.close();
    }
    process.exit(failures ? 1 : 0);
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) main();
