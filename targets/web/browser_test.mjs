// browser_test.mjs — the `browser` test: opens the playground (web/index.html) in Debian's
// chromium (headless, WebGL2 through SwiftShader) over each target bundle, reaches the bundle's
// configuration through the page's panel only (the page starts from the emitter's defaults; every
// field is set as a user would: selects, checkboxes, typed text), so that the WebAssembly emitter
// re-emits and the page re-renders, and compares the browser's visibility with the desktop GL
// runtime's run of that configuration.
//
//   node targets/web/browser_test.mjs --web web --wasm build/wasm/penumbra_emitter.wasm
//        [--chromium PATH] [--screenshots DIR] BUNDLE_DIR...
//
// Each BUNDLE_DIR is written by penumbra-export-bundle --target essl300: the desktop runtime ran
// the essl300 emission of its configuration. q is one step of the layout's result format (essl300: R8, 1/255).
//   0. Every panel change re-emits (the page's emission count grows), the emitted layout's config
//      is then the bundle's, and the image changed from the page's first configuration.
//   1. With the desktop run's slicing output (slices.f32) in place of the browser's own, every
//      pixel must be within bound + q of the CPU oracle (oracle.f32, bound.f32: texture precision)
//      and within 2·bound + q of the desktop run (visibility_gl.f32: both are within the bound).
//   2. With the browser's own slicing, SwiftShader's rasterization of triangle edges differs from
//      llvmpipe's, which the bound does not cover: at most 5% of the covered slice texels may
//      differ, and at most 1% of the pixels may leave 2·bound + q.
//   3. light_frame.js reproduces the exported light-frame uniforms (relative 1e-5), and moving the
//      light changes the image.
// A bundle of another technique (shadowmap, pcf, pcss, erosion, evsm, smrt, oim with its bake) has no oracle:
// its image is compared with the desktop run's (TECHNIQUE_* in bundle_compare.mjs). A bundle with a
// ray-traced truth (--reference) checks the error view's MAE.
// On the first bundle also: an invalid value typed in the panel shows the emitter's message
// (penumbra-gen's line) and keeps nothing running; every shadow-map technique (shadowmap, pcf,
// pcss, erosion, evsm) selected in the panel runs and shadows; oim says why it cannot run; the split
// view runs a second configuration.
// Exit 0 pass, 1 fail, 77 skip (no chromium), 2 bad arguments.
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import {serve, readFloats, largestDifference, compare, difference, readReference, launchChromium, R8_STEP, UNIFORM_TOLERANCE,
        SLICE_TEXELS_ALLOWED, OWN_PIXELS_ALLOWED, TECHNIQUE_PIXEL_STEP, TECHNIQUE_PIXELS_ALLOWED,
        TECHNIQUE_MEAN_ALLOWED} from "./bundle_compare.mjs";

// The occlusion fields a bundle fixes (its uniforms.json config), in the order the panel sets them.
// The panel shows (and the test sets) only the fields the selected technique reads.
const PANEL_FIELDS = ["technique", "light", "target"];
const TECHNIQUE_FIELDS = {
    occlusion: ["slices", "resolution", "filter", "fusion", "packing", "leak_fix", "self_shadow_fade", "tangent_clip", "slice_placement"],
    shadowmap: ["shadow_map.resolution", "shadow_map.constant_bias", "shadow_map.slope_bias"],
    pcf: ["shadow_map.resolution", "shadow_map.constant_bias", "shadow_map.slope_bias", "pcf.pattern", "pcf.grid_size",
          "pcf.poisson_taps", "pcf.radius", "pcf.rotate"],
    pcss: ["shadow_map.resolution", "shadow_map.constant_bias", "shadow_map.slope_bias", "pcss.blocker_samples",
           "pcss.filter_samples", "pcss.max_filter_texels", "pcss.rotate"],
    erosion: ["shadow_map.resolution", "shadow_map.constant_bias", "shadow_map.slope_bias", "erosion.max_search_radius",
              "erosion.edge_threshold", "erosion.search_taps", "erosion.blur_taps"],
    evsm: ["shadow_map.resolution", "shadow_map.constant_bias", "shadow_map.slope_bias", "evsm.positive_exponent",
           "evsm.negative_exponent", "evsm.light_bleeding_reduction", "evsm.variance_bias", "evsm.blur_fraction",
           "evsm.blur_taps", "evsm.max_blur_texels"],
    smrt: ["shadow_map.resolution", "shadow_map.constant_bias", "shadow_map.slope_bias", "smrt.rays", "smrt.samples",
           "smrt.extrapolate_max_slope", "smrt.max_slope_bias", "smrt.texel_dither", "smrt.frame"],
    oim: ["oim.resolution", "oim.intervals", "oim.samples"],
};
const valueAt = (object, key) => key.split(".").reduce((o, k) => (o === undefined ? undefined : o[k]), object);

// One field of the panel `side` ("left", "right") set as a user would: a select picks the option,
// a checkbox is clicked, a text field is cleared, typed into and left with Tab (its change event).
async function setField(page, side, key, value) {
    const selector = `#${side} [data-key="${key}"]`;
    const kind = await page.$eval(selector, (e) => (e.tagName === "SELECT" ? "select" : e.type));
    if (kind === "select") {
        await page.select(selector, String(value));
    } else if (kind === "checkbox") {
        if ((await page.$eval(selector, (e) => e.checked)) !== value) await page.click(selector);
    } else {
        await page.click(selector, {clickCount: 3});
        await page.keyboard.press("Backspace");
        await page.type(selector, String(value));
        await page.keyboard.press("Tab");
    }
}

// What field `key` of the panel `side` shows now, as the configuration's value (number, boolean or name).
async function panelValue(page, side, key) {
    return page.$eval(`#${side} [data-key="${key}"]`, (e) => {
        if (e.tagName === "SELECT") return e.value;
        if (e.type === "checkbox") return e.checked;
        return Number(e.value);
    });
}

// The panel beyond the bundle's configuration: messages, the other techniques, the split view.
async function checkPanel(page, label) {
    const failures = [];
    const state = () => page.evaluate(() => ({ok: window.penumbra.emission().ok, error: window.penumbra.emission().error,
                                              shown: document.querySelector('#left [data-role="error"]').textContent,
                                              running: window.penumbra.running(), reason: window.penumbra.reason()}));
    const slices = await page.$eval('#left [data-key="slices"]', (e) => e.value);
    // An invalid value: the emitter's message (penumbra-gen's error line) on the page, nothing runs.
    await setField(page, "left", "slices", "40");
    const refused = await state();
    const expected = await page.evaluate(() => window.penumbra.emitter.emit(window.penumbra.config()).error);
    if (refused.ok || refused.running) failures.push("slices 40 typed in the panel was not refused");
    if (!refused.shown.startsWith("error: slices: 40 ") || refused.shown !== expected)
        failures.push(`slices 40: the page shows '${refused.shown}', the emitter says '${expected}'`);
    await setField(page, "left", "slices", slices);
    // A profile picked in the panel shows the fields it sets as its preset has them (the table's
    // profile_sets, through the WebAssembly module); picking the default's gives the defaults back.
    const profileFields = ["slices", "resolution", "fusion", "irradiance_window", "irradiance_quadrants"];
    const before = {};
    for (const key of [...profileFields, "profile"]) before[key] = await panelValue(page, "left", key);
    for (const [profile, expected] of [
        ["fast", {slices: 8, resolution: 128, fusion: "chained", irradiance_window: false, irradiance_quadrants: false}],
        ["large", {slices: 16, resolution: 512, fusion: "extent", irradiance_window: true, irradiance_quadrants: true}],
        ["balanced", {slices: 16, resolution: 512, fusion: "extent", irradiance_window: true, irradiance_quadrants: false}]]) {
        await setField(page, "left", "profile", profile);
        for (const key of profileFields) {
            const shown = await panelValue(page, "left", key);
            if (shown !== expected[key]) failures.push(`profile ${profile}: the panel shows ${key} ${shown}, the preset has ${expected[key]}`);
        }
    }
    for (const key of ["profile", ...profileFields])
        if ((await panelValue(page, "left", key)) !== before[key]) await setField(page, "left", key, before[key]);
    // Every filter × packing × light (and adaptive placement) through the panel: what the emitter
    // accepts for essl300 runs and shadows; what it refuses shows its message.
    let ran = 0, refusedCount = 0;
    const resolution = await page.$eval('#left [data-key="resolution"]', (e) => e.value);
    await setField(page, "left", "resolution", "64"); // test time: the sweep is about running, not precision
    for (const light of ["rect", "sun"])
        for (const filter of ["mipmap", "nbuffer", "sat", "gaussian"])
            for (const packing of ["atlas", "array", "volume"])
                for (const placement of ["uniform", "adaptive"]) {
                    if (placement === "adaptive" && packing !== "atlas") continue;
                    for (const [key, value] of [["light", light], ["filter", filter], ["packing", packing], ["slice_placement", placement]])
                        if ((await page.$eval(`#left [data-key="${key}"]`, (e) => e.value)) !== value) await setField(page, "left", key, value);
                    const s = await state();
                    const name = `${light}/${filter}/${packing}/${placement}`;
                    if (!s.ok) {
                        ++refusedCount;
                        if (!s.shown.startsWith("error: ")) failures.push(`${name}: refused without the emitter's message`);
                        continue;
                    }
                    const v = await page.evaluate(() => { try { return Array.from(window.penumbra.readVisibility()); } catch (e) { return e.message; } });
                    if (typeof v === "string") failures.push(`${name}: emitted but does not run: ${v}`);
                    else if (!v.some((x) => x < 0.5)) failures.push(`${name}: no shadowed pixel`);
                    else ++ran;
                }
    for (const [key, value] of [["light", "rect"], ["filter", "nbuffer"], ["packing", "atlas"], ["slice_placement", "uniform"],
                                ["resolution", resolution]])
        await setField(page, "left", key, value);
    // Every technique WebGL2 can run, selected in the panel: it runs and shadows, unlike the others.
    const images = {};
    for (const technique of ["shadowmap", "pcf", "pcss", "erosion", "evsm", "occlusion"]) {
        await setField(page, "left", "technique", technique);
        const s = await state();
        if (!s.running) {
            failures.push(`technique ${technique} selected in the panel does not run: ${s.reason || s.error}`);
            continue;
        }
        images[technique] = Float32Array.from(await page.evaluate(() => Array.from(window.penumbra.readVisibility())));
        const shadowed = images[technique].filter((v) => v < 0.5).length;
        if (shadowed === 0) failures.push(`technique ${technique}: no shadowed pixel`);
    }
    for (const [a, b] of [["shadowmap", "pcss"], ["pcf", "pcss"], ["erosion", "occlusion"], ["pcss", "occlusion"], ["evsm", "pcss"]]) {
        if (!images[a] || !images[b]) continue;
        let differing = 0;
        for (let i = 0; i < images[a].length; ++i) if (Math.abs(images[a][i] - images[b][i]) > 2 * R8_STEP) ++differing;
        if (differing === 0) failures.push(`techniques ${a} and ${b} give the same image`);
    }
    await setField(page, "left", "technique", "oim");
    const oim = await state();
    if (oim.running || !oim.reason.includes("baked offline")) failures.push(`oim: the page does not say why it cannot run (${oim.reason})`);
    await setField(page, "left", "technique", "occlusion");
    // The split view: a second configuration (PCSS) on the right half, with its own panel.
    await page.click("#split");
    const right = await page.evaluate(() => ({running: window.penumbra.running(1), technique: window.penumbra.emission(1).layoutConfig.technique,
                                              visible: !document.getElementById("right").hidden}));
    if (!right.running || right.technique !== "pcss" || !right.visible) failures.push(`split view: ${JSON.stringify(right)}`);
    await page.click("#split");
    console.log(`     panel (${label}): refused slices 40 with "${refused.shown}"; filter × packing × light × placement: ` +
                `${ran} ran and shadowed, ${refusedCount} refused for essl300 with the emitter's message; ran ${Object.keys(images).join(", ")}; ` +
                `oim: ${oim.reason.slice(0, 60)}…; split ran ${right.technique} on the right`);
    return failures;
}

function parseArguments(argv) {
    const out = {web: null, wasm: null, chromium: "/usr/bin/chromium", screenshots: null, bundles: []};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        if (flag === "--web" || flag === "--wasm" || flag === "--chromium" || flag === "--screenshots") {
            if (i + 1 >= argv.length) usage(`${flag}: missing value`);
            out[flag.slice(2)] = argv[++i];
        } else if (flag.startsWith("--")) {
            usage(`unknown flag '${flag}'`);
        } else {
            out.bundles.push(flag);
        }
    }
    if (!out.web) usage("--web: missing");
    if (!out.wasm) usage("--wasm: missing (build/wasm/penumbra_emitter.wasm)");
    if (out.bundles.length === 0) usage("no bundle directories");
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node browser_test.mjs --web DIR --wasm MODULE [--chromium PATH] [--screenshots DIR] BUNDLE_DIR...`);
    process.exit(2);
}

// A bundle of a technique the oracle does not model: the browser's run against the desktop run's
// image (TECHNIQUE_* in bundle_compare.mjs), the light frame, and moving the light.
async function finishTechnique({page, bundle, label, reference, read, failures, problems, changes, rerendered, uniformError, shadowed, started, info}) {
    await page.evaluate(() => window.penumbra.useBundleUniforms(false));
    const d = difference(await read(), reference.gl);
    const pixels = reference.gl.length;
    if (d.over > TECHNIQUE_PIXELS_ALLOWED * pixels)
        failures.push(`${d.over} of ${pixels} pixels differ from the desktop run by more than ${TECHNIQUE_PIXEL_STEP} (allowed ${100 * TECHNIQUE_PIXELS_ALLOWED}%)`);
    if (d.mean > TECHNIQUE_MEAN_ALLOWED) failures.push(`mean |browser − desktop| ${d.mean.toFixed(4)} (allowed ${TECHNIQUE_MEAN_ALLOWED})`);
    if (uniformError > UNIFORM_TOLERANCE) failures.push(`light_frame.js differs from the exported uniforms by ${uniformError.toExponential(2)} (relative)`);
    if (shadowed === 0) failures.push("the desktop image has no shadowed pixel: the comparison would prove nothing");
    let changed = 0;
    if (bundle.config.technique === "oim") { // oim's sun moves only along the bake's path
        const before = await read();
        await page.evaluate((t) => window.penumbra.setSunTime(t), bundle.sun_time + 0.15);
        const after = await read();
        for (let i = 0; i < after.length; ++i) if (Math.abs(after[i] - before[i]) > 2 * R8_STEP) ++changed;
        if (changed === 0) failures.push("moving the sun along its path changed no pixel");
    } else {
        const before = await read();
        const moved = bundle.light.kind === "sun"
            ? {direction: [bundle.light.direction[0] + 0.3, bundle.light.direction[1], bundle.light.direction[2]]}
            : {center: [bundle.light.center[0] + 0.25 * bundle.light.width, bundle.light.center[1], bundle.light.center[2]]};
        await page.evaluate((kind, m) => window.penumbra.setLight(kind, m), bundle.light.kind, moved);
        const after = await read();
        for (let i = 0; i < after.length; ++i) if (Math.abs(after[i] - before[i]) > 2 * R8_STEP) ++changed;
        if (changed === 0) failures.push("moving the light changed no pixel");
    }
    await page.close();
    failures.push(...problems);
    console.log(`${failures.length ? "FAIL" : "ok  "} ${label} (${info.resultFormat} result, ${shadowed} shadowed, ${((Date.now() - started) / 1000).toFixed(1)} s)\n` +
                `     panel: ${changes} fields changed, each re-emitted; ${rerendered} pixels changed from the page's first configuration\n` +
                `     max |browser − desktop| ${d.worst.toExponential(2)}, mean ${d.mean.toExponential(2)}, ${d.over} of ${pixels} pixels more than ` +
                `${TECHNIQUE_PIXEL_STEP} apart (no oracle for ${bundle.config.technique})\n` +
                `     light_frame.js vs exported uniforms ${uniformError.toExponential(2)} (relative); moved light changed ${changed} pixels`);
    for (const f of failures) console.log(`     ${f}`);
    return {failures: failures.length, renderer: info.renderer};
}

async function checkBundle(browser, port, index, dir, screenshots) {
    const bundle = JSON.parse(fs.readFileSync(path.join(dir, "uniforms.json"), "utf8"));
    const c = bundle.config;
    const label = c.technique !== "occlusion" ? `${bundle.scene} ${c.technique}/${c.light} ${bundle.width}x${bundle.height}`
        : `${bundle.scene} ${c.filter}/${c.packing}/${c.light}/${c.fusion}${c.tangent_clip ? " tangent-clip" : ""} ` +
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
    const reference = readReference(dir);
    const read = async () => {
        const v = Float32Array.from(await page.evaluate(() => Array.from(window.penumbra.readVisibility())));
        if (v.length !== reference.gl.length) throw new Error(`${label}: ${v.length} pixels read, expected ${reference.gl.length}`);
        return v;
    };
    const failures = [];

    // 0. The bundle's configuration, through the panel only.
    const first = await read();
    const firstConfig = await page.evaluate(() => window.penumbra.emission().layoutConfig);
    let changes = 0;
    const fields = [...PANEL_FIELDS, ...TECHNIQUE_FIELDS[c.technique]];
    for (const field of fields) {
        if (valueAt(firstConfig, field) === valueAt(c, field)) continue;
        // a field the first layout leaves out (a section of another technique) shows its default
        if (valueAt(firstConfig, field) === undefined && (await panelValue(page, "left", field)) === valueAt(c, field))
            continue;
        const before = await page.evaluate(() => window.penumbra.emissions());
        await setField(page, "left", field, valueAt(c, field));
        const after = await page.evaluate(() => window.penumbra.emissions());
        if (after <= before) failures.push(`setting ${field} to ${valueAt(c, field)} in the panel did not re-emit`);
        ++changes;
    }
    const reached = await page.evaluate(() => window.penumbra.emission());
    if (!reached.ok) throw new Error(`${label}: the panel's configuration was refused: ${reached.error}`);
    for (const field of fields)
        if (valueAt(reached.layoutConfig, field) !== valueAt(c, field))
            failures.push(`after the panel, ${field} is ${valueAt(reached.layoutConfig, field)}, the bundle's is ${valueAt(c, field)}`);
    if (!(await page.evaluate(() => window.penumbra.running()))) throw new Error(`${label}: does not run: ${await page.evaluate(() => window.penumbra.reason())}`);
    if (changes === 0) failures.push("the page started at the bundle's configuration: the panel was not exercised");
    let rerendered = 0;
    const reachedImage = await read();
    for (let i = 0; i < first.length; ++i) if (Math.abs(reachedImage[i] - first[i]) > 2 * R8_STEP) ++rerendered;
    if (rerendered === 0) failures.push(`${changes} panel changes left the image as it was`);

    const info = await page.evaluate(() => window.penumbra.info());
    const q = info.resultFormat === "R8" || info.resultFormat === "RGBA8" ? R8_STEP : 0;

    // The page's own light frame (light_frame.js) against the desktop runtime's.
    const uniforms = await page.evaluate(() => window.penumbra.uniforms());
    let uniformError = 0;
    for (const [name, value] of Object.entries(uniforms.bundle)) {
        const computed = uniforms.computed[name];
        // oim shades by the bake's sun; its layout's toLight (read by shading_example only) follows config.light
        if (c.technique === "oim" && name === "penumbra_toLight") continue;
        const a = typeof computed === "number" ? [computed] : computed, b = typeof value === "number" ? [value] : value;
        uniformError = Math.max(uniformError, largestDifference(a.map(Math.fround), b));
    }

    let shadowed = 0, worstBound = 0;
    for (let i = 0; i < reference.gl.length; ++i) {
        if (reference.gl[i] < 0.98) ++shadowed;
        if (reference.bound) worstBound = Math.max(worstBound, reference.bound[i]);
    }
    if (c.technique !== "occlusion")
        return finishTechnique({page, bundle, label, reference, read, failures, problems, changes, rerendered, uniformError, shadowed, started, info});

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
    await page.evaluate((kind, m) => window.penumbra.setLight(kind, m), bundle.light.kind, moved);
    const after = await read();
    let changed = 0;
    for (let i = 0; i < after.length; ++i) if (Math.abs(after[i] - before[i]) > 2 * R8_STEP) ++changed;
    // The error view against the bundle's ray-traced truth (--reference): the page's MAE is the
    // one of its own visibility over the pixels where the truth is defined.
    let truthLine = "";
    if (reference.truth) {
        await page.select("#view-mode", "error");
        const status = await page.evaluate(() => window.penumbra.status());
        const shown = status.match(/MAE against the truth \([^)]*\) ([0-9.]+) over (\d+) pixels/);
        const v = await read(), geometry = readFloats(path.join(dir, "positions.f32"));
        let sum = 0, n = 0;
        for (let i = 0; i < v.length; ++i)
            if (geometry[4 * i + 3] > 0.5 && Number.isFinite(reference.truth[i])) { sum += Math.abs(v[i] - reference.truth[i]); ++n; }
        if (!shown || Math.abs(Number(shown[1]) - sum / n) > 1e-4 || Number(shown[2]) !== n)
            failures.push(`error view: the page shows '${shown ? shown[0] : status}', the test computes MAE ${(sum / n).toFixed(4)} over ${n} pixels`);
        // What the view draws: white where the page agrees with the truth, red or blue where it is
        // 0.25 or more off, at each bundle pixel's place on the canvas.
        const canvas = await page.evaluate(() => window.penumbra.readCanvas());
        let checked = 0, wrong = 0;
        for (let y = 0; y < bundle.height; ++y)
            for (let x = 0; x < bundle.width; ++x) {
                const i = y * bundle.width + x;
                if (geometry[4 * i + 3] < 0.5 || !Number.isFinite(reference.truth[i])) continue;
                const d = Math.abs(v[i] - reference.truth[i]);
                if (d > 0.01 && d < 0.25) continue;
                const cx = Math.floor((x + 0.5) * canvas.width / bundle.width), cy = Math.floor((y + 0.5) * canvas.height / bundle.height);
                const [r, g, b] = canvas.rgba.slice(4 * (cy * canvas.width + cx), 4 * (cy * canvas.width + cx) + 3);
                const white = r > 230 && g > 230 && b > 230, saturated = (r > 230 && g < 30 && b < 30) || (b > 230 && r < 30 && g < 30);
                ++checked;
                if (d <= 0.01 ? !white : !saturated) ++wrong;
            }
        if (checked === 0 || wrong > 0.01 * checked) failures.push(`error view: ${wrong} of ${checked} checked pixels drawn in the wrong colour`);
        truthLine = shown ? `\n     error view: ${shown[0]}; ${checked - wrong} of ${checked} checked pixels drawn as their error` : "";
        await page.select("#view-mode", "shaded");
    }
    if (index === 0) failures.push(...await checkPanel(page, label));
    if (screenshots) {
        fs.mkdirSync(screenshots, {recursive: true});
        await page.screenshot({path: path.join(screenshots, `${index}_${c.filter}_${c.packing}${c.tangent_clip ? "_clip" : ""}.png`)});
    }
    await page.close();

    const pixels = reference.gl.length;
    failures.push(...problems);
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
                `     panel: ${changes} fields changed, each re-emitted; ${rerendered} pixels changed from the page's first configuration\n` +
                `     desktop slices: max |browser − desktop| ${injected.worstGl.toExponential(2)}, max |browser − oracle| ${injected.worstOracle.toExponential(2)}, ` +
                `${injected.outsideOracle} pixels outside bound + q\n` +
                `     own slicing:    max |browser − desktop| ${own.worstGl.toExponential(2)}, ${own.outsideGl} of ${pixels} pixels outside 2·bound + q; ` +
                `slicing texels differing ${slices.differing} of ${slices.covered} covered\n` +
                `     light_frame.js vs exported uniforms ${uniformError.toExponential(2)} (relative); moved light changed ${changed} pixels` +
                truthLine);
    for (const f of failures) console.log(`     ${f}`);
    return {failures: failures.length, renderer: info.renderer};
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    if (!fs.existsSync(args.chromium)) {
        console.log(`skip: no chromium at ${args.chromium} (scripts/setup.sh installs Debian's chromium)`);
        process.exit(77);
    }
    if (!fs.existsSync(args.wasm)) {
        console.log(`error: no WebAssembly emitter at ${args.wasm} (cmake --build build --target penumbra-emitter-wasm)`);
        process.exit(1);
    }
    const server = await serve(args.web, args.bundles, {"/web/three/penumbra_emitter.wasm": path.resolve(args.wasm)});
    const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "penumbra-chromium-"));
    const browser = await launchChromium(args.chromium, userDataDir);
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
