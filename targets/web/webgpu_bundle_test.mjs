// webgpu_bundle_test.mjs — the `webgpu_bundles` test: the WebGPU layout runner (web/three/penumbra_webgpu_runner.js)
// in Debian's chromium (headless, WebGPU through SwiftShader) over bundles exported with
// `penumbra-export-bundle --target wgsl` (the desktop GL runtime ran glsl450; emission/ holds the
// wgsl emission of the same configuration). For each bundle the page builds the layout's textures,
// pipelines and bind groups from emission/layout.json alone, uploads the bundle's uniforms, draws
// mesh.f32 in the shadow phase, fills the caller G-buffers (positions.f32, normals.f32), runs the
// screen phase at the bundle's size and reads the result back; it must match visibility_gl.f32 as
// the WebGL2 bundles of these techniques do (TECHNIQUE_* in bundle_compare.mjs: the shadow-map-based
// techniques have no oracle bound; SwiftShader and llvmpipe rasterize the depth pass differently), and
// away from silhouettes at most one pixel a bundle may be more than TECHNIQUE_PIXEL_STEP apart.
// Occlusion textures also against the CPU oracle, which read the desktop's slices: with WebGPU's own
// slices outside its bound only at silhouettes (SwiftShader and llvmpipe rasterize caster edges
// differently), and with the desktop's slices uploaded in place of the slicing pass, 0 pixels outside.
// First, on a small layout written in the test, the runner conventions occlusion textures will use
// (copy passes into array layers, renders into 3D slices, int_uniforms per pass).
//
//   node targets/web/webgpu_bundle_test.mjs --web web [--wasm EMITTER.wasm] [--chromium PATH] [--images DIR]
//        BUNDLE_DIR... [--playground BUNDLE_DIR]...
//
// With --wasm (build/wasm/penumbra_emitter.wasm), the playground too (web/index.html): opened on each
// bundle given with --playground (a few: each costs a page load and 512² frames) with ?backend=webgpu, its panel set to the bundle's configuration, at the bundle's camera and
// uniforms it must show WebGPU's image within the same tolerances of the desktop run; switched to
// WebGL2 by its renderer switch it must run WebGL2 and show nearly the same image (both SwiftShader).
//
// Exit 0 pass, 1 fail, 2 bad arguments, 77 skip (no chromium; no WebGPU adapter only with
// PENUMBRA_WEBGPU_OPTIONAL=1).
import fs from "node:fs";
import path from "node:path";
import {compare, difference, readReference, OWN_PIXELS_ALLOWED, TECHNIQUE_MEAN_ALLOWED, TECHNIQUE_PIXEL_STEP,
        TECHNIQUE_PIXELS_ALLOWED} from "./bundle_compare.mjs";
import {readFloats, writeGreyPng} from "./harness.mjs";
import {adapterLine, startWebGPU} from "./wgsl_compile.mjs";

// A silhouette: a 4-neighbour on the background or more than SILHOUETTE_STEP world units away (the
// G-buffer positions.f32, RGBA a pixel).
const SILHOUETTE_STEP = 0.25;
const INTERIOR_PIXELS_ALLOWED = 1;
// The pixels at a silhouette: a 4-neighbour on the background or more than SILHOUETTE_STEP world units away.
function silhouetteSet(positions, width, height) {
    const at = (j) => [positions[4 * j], positions[4 * j + 1], positions[4 * j + 2], positions[4 * j + 3]];
    const edges = new Set();
    for (let y = 0; y < height; ++y)
        for (let x = 0; x < width; ++x) {
            const p = at(y * width + x);
            const edge = [[1, 0], [-1, 0], [0, 1], [0, -1]].some(([dx, dy]) => {
                const nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= width || ny >= height) return false;
                const q = at(ny * width + nx);
                return (q[3] < 0.5) !== (p[3] < 0.5) || Math.hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]) > SILHOUETTE_STEP;
            });
            if (edge) edges.add(y * width + x);
        }
    return edges;
}

// Of the pixels more than TECHNIQUE_PIXEL_STEP apart, those at a silhouette.
function silhouettePixels(positions, width, height, a, b) {
    const edges = silhouetteSet(positions, width, height);
    let count = 0;
    for (const i of edges) if (Math.abs(a[i] - b[i]) > TECHNIQUE_PIXEL_STEP) ++count;
    return count;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node webgpu_bundle_test.mjs --web DIR [--wasm MODULE] [--chromium PATH] [--images DIR] ` +
                  "BUNDLE_DIR... [--playground BUNDLE_DIR]...");
    process.exit(2);
}

function parseArguments(argv) {
    const out = {web: null, wasm: null, chromium: "/usr/bin/chromium", images: null, bundles: [], playground: new Set()};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        if (flag === "--playground") {
            if (i + 1 >= argv.length) usage(`${flag}: missing value`);
            out.bundles.push(argv[++i]);
            out.playground.add(argv[i]);
        } else if (flag === "--web" || flag === "--wasm" || flag === "--chromium" || flag === "--images") {
            if (i + 1 >= argv.length) usage(`${flag}: missing value`);
            out[flag.slice(2)] = argv[++i];
        } else if (flag.startsWith("--")) {
            usage(`unknown flag '${flag}'`);
        } else {
            out.bundles.push(flag);
        }
    }
    if (!out.web) usage("--web: missing (the web/ folder with three/penumbra_webgpu_runner.js)");
    if (!fs.existsSync(path.join(out.web, "three/penumbra_webgpu_runner.js"))) usage(`--web: no three/penumbra_webgpu_runner.js in ${out.web}`);
    if (out.bundles.length === 0) usage("no bundle directories");
    if (out.wasm && !fs.existsSync(out.wasm)) usage(`--wasm: no file ${out.wasm} (cmake --build build --target penumbra-emitter-wasm)`);
    for (const b of out.bundles) if (!fs.existsSync(path.join(b, "uniforms.json"))) usage(`${b}: not a bundle (no uniforms.json)`);
    return out;
}

// In the page: the runner's conventions that today's emissions do not use yet (occlusion textures will):
// a copy pass into a layer of an array texture, a render pass into a slice of a 3D texture, one
// program run by two passes with different int_uniforms (each pass its own uniform buffer). A
// layout written here: "fill" writes penumbra_value × penumbra_scale; the result reads
// 10 × array layer 0 + array layer 1 + 3D slice 1 + 100 × 3D slice 0, which is 0.25 + 0.5 = 0.75
// only when every pass went to the layer and slice the layout names.
async function conventionsInPage() {
    const {WebGPULayoutRunner} = await import("/web/three/penumbra_webgpu_runner.js");
    const usage = (...u) => ({webgpu: {format: "rgba32float", usage: ["TEXTURE_BINDING", ...u]}});
    const texture = (name, target, depth, size, extra) => ({name, target, width: 4, height: 4, depth, mip_levels: 1, min_filter: "NEAREST",
                                                           mag_filter: "NEAREST", wrap: "CLAMP_TO_EDGE", size, source: "passes", ...extra});
    const state = {blend: false, blend_equation: "ADD", blend_src: "ONE", blend_dst: "ZERO", depth_test: false, depth_func: "LESS",
                   depth_write: false, color_mask: [true, true, true, true], cull: "NONE", clear_color: null, clear_depth: null,
                   polygon_offset_factor: 0, polygon_offset_units: 0, logic_op: "NONE"};
    const pass = (name, program, outputs, extra = {}) => ({name, phase: "screen", action: "fullscreen", program, inputs: [], outputs,
                                                           int_uniforms: {}, viewport: [4, 4], state, ...extra});
    const layout = {
        layout_version: 3, config: {target: "wgsl"}, result: "result",
        textures: [texture("source", "2D", 1, "fixed", usage("RENDER_ATTACHMENT", "COPY_SRC")),
                   texture("layers", "2D_ARRAY", 2, "fixed", usage("COPY_DST")),
                   texture("volume", "3D", 2, "fixed", usage("RENDER_ATTACHMENT")),
                   texture("result", "2D", 1, "output", {webgpu: {format: "r32float", usage: ["RENDER_ATTACHMENT", "COPY_SRC"]}})],
        programs: [
            {name: "fill", files: ["fullscreen.vert.wgsl", "fill.frag.wgsl"], stages: ["vertex", "fragment"], vertex_inputs: [], parameters: [
                {name: "penumbra_value", type: "float", source: "light", block: "Fill", block_binding: 0, offset: 0, group: 0},
                {name: "penumbra_scale", type: "int", source: "pass", block: "Fill", block_binding: 0, offset: 4, group: 0}]},
            {name: "read", files: ["fullscreen.vert.wgsl", "read.frag.wgsl"], stages: ["vertex", "fragment"], vertex_inputs: [], parameters: [
                {name: "layers", type: "sampler2DArray", binding: 0, sampler_binding: -1, texture: "layers", texture_type: "texture_2d_array<f32>",
                 sample_type: "unfilterable-float", group: 0},
                {name: "volume", type: "sampler3D", binding: 1, sampler_binding: -1, texture: "volume", texture_type: "texture_3d<f32>",
                 sample_type: "unfilterable-float", group: 0}]}],
        passes: [pass("fill_source", "fill", [{texture: "source", kind: "color", level: 0, layer: -1}], {int_uniforms: {penumbra_scale: 1}}),
                 {...pass("copy_layer", "", [{texture: "layers", kind: "color", level: 0, layer: 1}]), action: "copy",
                  inputs: [{sampler: "", texture: "source", binding: -1, level: 0}],
                  copy: {source_level: 0, source_layer: -1, target_level: 0, target_layer: 1, width: 4, height: 4}},
                 pass("fill_slice", "fill", [{texture: "volume", kind: "color", level: 0, layer: 1}], {int_uniforms: {penumbra_scale: 2}}),
                 pass("read", "read", [{texture: "result", kind: "color", level: 0, layer: -1}], {viewport: [0, 0]})],
    };
    const files = {
        "fullscreen.vert.wgsl": "@vertex fn main(@builtin(vertex_index) i: u32) -> @builtin(position) vec4f {\n" +
            "    let c = vec2f(f32((i << 1u) & 2u), f32(i & 2u));\n    return vec4f(c * 2.0 - 1.0, 0.0, 1.0);\n}\n",
        "fill.frag.wgsl": "struct Fill { penumbra_value: f32, penumbra_scale: i32 }\n@group(0) @binding(0) var<uniform> fill: Fill;\n" +
            "@fragment fn main() -> @location(0) vec4f { return vec4f(fill.penumbra_value * f32(fill.penumbra_scale)); }\n",
        "read.frag.wgsl": "@group(0) @binding(0) var layers: texture_2d_array<f32>;\n@group(0) @binding(1) var volume: texture_3d<f32>;\n" +
            "@fragment fn main(@builtin(position) p: vec4f) -> @location(0) vec4f {\n    let c = vec2i(p.xy);\n" +
            "    return vec4f(10.0 * textureLoad(layers, c, 0, 0).x + textureLoad(layers, c, 1, 0).x + textureLoad(volume, vec3i(c, 1), 0).x" +
            " + 100.0 * textureLoad(volume, vec3i(c, 0), 0).x);\n}\n",
    };
    try {
        const runner = await WebGPULayoutRunner.fromEmission(window.penumbraDevice, {files, layout});
        runner.setUniforms({penumbra_value: 0.25});
        await runner.runPhase("screen", null, {width: 4, height: 4});
        const values = Array.from(await runner.readResult());
        runner.dispose();
        return {values};
    } catch (e) {
        return {error: e.message};
    }
}

// In the page: the runner over bundle /bundle/<index>/, with the device of startWebGPU. With
// `injectSlices`, the desktop run's slicing output (slices.f32, slice k of R² floats at k·R², rows
// bottom first) takes the place of the slicing pass, as browser_test.mjs does for WebGL2.
async function runInPage(index, injectSlices = false) {
    const {WebGPULayoutRunner} = await import("/web/three/penumbra_webgpu_runner.js");
    const base = `/bundle/${index}/`;
    const get = async (name, kind) => {
        const response = await fetch(base + name);
        if (!response.ok) throw new Error(`${base}${name}: HTTP ${response.status}`);
        return kind === "json" ? response.json() : new Float32Array(await response.arrayBuffer());
    };
    try {
        const bundle = await get("uniforms.json", "json");
        const started = performance.now();
        const writable = [], replace = {};
        if (injectSlices) {
            const layout = await get("emission/layout.json", "json");
            const slicing = layout.passes.find((p) => p.name === "slicing");
            if (!slicing) throw new Error("injectSlices: the layout has no slicing pass");
            writable.push(...new Set(slicing.outputs.map((o) => o.texture)));
            const slices = await get("slices.f32");
            const {slices: S, resolution: R} = layout.config;
            if (slices.length !== S * R * R) throw new Error(`slices.f32: ${slices.length} floats, expected ${S}·${R}² = ${S * R * R}`);
            // slice k is channel k % 4 of the slicing output layout.json's slice_map names (several slicing
            // passes on WebGPU beyond four targets: each fills its own outputs)
            replace.slicing = (pass) => pass.outputs.forEach((out) => {
                const rgba = new Float32Array(4 * R * R);
                for (const m of layout.slice_map.filter((e) => e.texture === out.texture && e.layer === out.layer))
                    for (let i = 0; i < R * R; ++i) rgba[4 * i + (m.slice % 4)] = slices[m.slice * R * R + i];
                runner.uploadTexture(out.texture, out.level, out.layer, rgba);
            });
            // adaptive placement: the desktop's boundaries too (the oracle's), as float bits
            const placement = layout.passes.find((p) => p.name === "slice_boundaries");
            if (placement) {
                const depths = await get("boundaries.f32");
                const target = placement.outputs[0].texture;
                writable.push(target);
                const bits = new Uint32Array(depths.buffer, depths.byteOffset, depths.length);
                replace.slice_boundaries = () => {
                    const rgba = new Array(4 * depths.length).fill(0);
                    bits.forEach((b, k) => (rgba[4 * k] = b));
                    runner.uploadTexture(target, 0, -1, rgba);
                };
            }
        }
        const runner = await WebGPULayoutRunner.load(window.penumbraDevice, `${base}emission/`, {writable});
        const created = performance.now();
        runner.setUniforms(bundle.uniforms);
        const shadowPasses = await runner.runPhase("shadow", runner.sceneDrawer(await get("mesh.f32")), null, replace);
        const size = {width: bundle.width, height: bundle.height};
        runner.allocateOutputSized(size.width, size.height);
        const filled = [];
        for (const t of runner.layout.textures) {
            if (t.source !== "caller") continue;
            const file = bundle.caller_textures?.[t.name];
            if (!file) throw new Error(`layout texture ${t.name} is filled by the caller, but uniforms.json caller_textures has no file for it`);
            runner.fillTexture(t.name, size.width, size.height, await get(file));
            filled.push(t.name);
        }
        const screenPasses = await runner.runPhase("screen", null, size);
        const visibility = await runner.readResult();
        const finished = performance.now();
        const result = {visibility: Array.from(visibility), shadowPasses, screenPasses, filled, target: runner.layout.config.target,
                        result: runner.layout.result, resultFormat: runner.description(runner.layout.result).webgpu.format,
                        programs: runner.layout.programs.map((p) => p.name), createMs: created - started, runMs: finished - created};
        runner.dispose();
        return result;
    } catch (e) {
        return {error: e.message};
    }
}

const valueAt = (object, key) => key.split(".").reduce((o, k) => (o === undefined ? undefined : o[k]), object);

// The playground on bundle `index` with ?backend=webgpu: its panel set to the bundle's configuration
// (every shown field that differs, as a user would), then WebGPU's image and WebGL2's after the switch.
async function checkPlayground(browser, port, index, dir, label, images) {
    const bundle = JSON.parse(fs.readFileSync(path.join(dir, "uniforms.json"), "utf8"));
    const failures = [];
    const page = await browser.newPage();
    const problems = [];
    page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
    page.on("console", (m) => m.type() === "error" && problems.push(`console: ${m.text()}`));
    await page.goto(`http://127.0.0.1:${port}/web/index.html?bundle=/bundle/${index}/&backend=webgpu`);
    await page.waitForFunction(() => window.penumbra !== undefined, {timeout: 60000});
    const error = await page.evaluate(() => window.penumbra.error);
    if (error) throw new Error(`${label}: the playground failed: ${error}`);
    if ((await page.evaluate(() => window.penumbra.backend())) !== "webgpu")
        failures.push(`?backend=webgpu: the page runs ${await page.evaluate(() => window.penumbra.backend())}: ${await page.evaluate(() => window.penumbra.status())}`);
    // The panel: technique first, then every shown field whose value differs from the bundle's (the
    // page runs wgsl whatever the panel's target says, so that field stays).
    let changes = 0;
    for (let round = 0; round < 3; ++round) {
        const fields = await page.$$eval("#left [data-key]", (es) => es.filter((e) => !e.closest("[hidden]"))
            .map((e) => ({key: e.dataset.key, kind: e.tagName === "SELECT" ? "select" : e.type,
                          value: e.tagName === "SELECT" ? e.value : e.type === "checkbox" ? e.checked : Number(e.value)})));
        fields.sort((a, b) => (b.key === "technique") - (a.key === "technique"));
        const field = fields.find((f) => f.key !== "target" && valueAt(bundle.config, f.key) !== undefined && f.value !== valueAt(bundle.config, f.key));
        if (!field) break;
        const selector = `#left [data-key="${field.key}"]`, wanted = valueAt(bundle.config, field.key);
        if (field.kind === "select") await page.select(selector, String(wanted));
        else if (field.kind === "checkbox") await page.click(selector);
        else {
            await page.click(selector, {clickCount: 3});
            await page.keyboard.press("Backspace");
            await page.type(selector, String(wanted));
            await page.keyboard.press("Tab");
        }
        ++changes;
        round = -1; // until no shown field differs
    }
    // The orbit camera (the page's own WebGL2 G-buffer, read back into WebGPU's caller textures) at the canvas size.
    await page.evaluate(async () => {
        window.penumbra.setCamera("orbit");
        await window.penumbra.settled();
    });
    const orbit = await page.evaluate(() => {
        try { const v = window.penumbra.readVisibility(); return {count: v.length, shadowed: v.filter((x) => x < 0.5).length}; }
        catch (e) { return {error: e.message}; }
    });
    const shot = async (name) => images && (await page.$("#view")).screenshot({path: path.join(images, `${index}_${bundle.config.technique}_${bundle.config.light}_${name}.png`)});
    await shot("playground_webgpu_orbit");
    if (orbit.error || !(orbit.shadowed > 0)) failures.push(`orbit camera on WebGPU: ${orbit.error || `${orbit.shadowed} of ${orbit.count} pixels shadowed`}`);
    await page.evaluate(async () => {
        window.penumbra.setCamera("bundle");
        window.penumbra.useBundleUniforms(true);
        await window.penumbra.settled();
    });
    const read = async () => {
        const v = await page.evaluate(() => { try { return Array.from(window.penumbra.readVisibility()); } catch (e) { return e.message; } });
        if (typeof v === "string") throw new Error(`${label}: playground: ${v} (${await page.evaluate(() => window.penumbra.reason())})`);
        return Float32Array.from(v);
    };
    const reference = readReference(dir);
    const webgpu = await read();
    const info = await page.evaluate(() => window.penumbra.info());
    const d = difference(webgpu, reference.gl);
    if (info.backend !== "webgpu" || !info.adapter) failures.push(`the page says backend ${info.backend}, adapter ${JSON.stringify(info.adapter)}`);
    if (d.over > TECHNIQUE_PIXELS_ALLOWED * webgpu.length || d.mean > TECHNIQUE_MEAN_ALLOWED)
        failures.push(`playground on WebGPU: ${d.over} pixels more than ${TECHNIQUE_PIXEL_STEP} from the desktop run, mean ${d.mean.toFixed(4)}`);
    // The switch: WebGL2 runs the essl300 emission of the same configuration.
    const switched = await page.evaluate(async () => {
        const ok = await window.penumbra.setBackend("webgl2");
        window.penumbra.setCamera("orbit");
        return ok;
    });
    await shot("playground_webgl2_orbit");
    await page.evaluate(() => window.penumbra.setCamera("bundle"));
    const webgl = await read();
    const afterInfo = await page.evaluate(() => window.penumbra.info());
    const between = difference(webgl, webgpu);
    if (!switched || afterInfo.backend !== "webgl2") failures.push(`the renderer switch to WebGL2 did not take (${afterInfo.backend})`);
    if (between.over > TECHNIQUE_PIXELS_ALLOWED * webgpu.length || between.mean > TECHNIQUE_MEAN_ALLOWED)
        failures.push(`WebGL2 and WebGPU in the playground: ${between.over} pixels more than ${TECHNIQUE_PIXEL_STEP} apart, mean ${between.mean.toFixed(4)}`);
    await page.close();
    failures.push(...problems);
    console.log(`${failures.length ? "FAIL" : "ok  "} ${label} in the playground: ${changes} panel fields set; orbit camera ${orbit.shadowed} of ${orbit.count} ` +
                `pixels shadowed; at the bundle's camera WebGPU (${info.adapter?.architecture}) ` +
                `vs desktop max ${d.worst.toExponential(2)}, ${d.over} pixels > ${TECHNIQUE_PIXEL_STEP}; switched to WebGL2 (${afterInfo.renderer}): ` +
                `vs WebGPU max ${between.worst.toExponential(2)}, ${between.over} pixels > ${TECHNIQUE_PIXEL_STEP}`);
    for (const f of failures) console.log(`     ${f}`);
    return failures.length;
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    const roots = {web: args.web};
    args.bundles.forEach((dir, i) => (roots[`bundle/${i}`] = dir));
    const started = Date.now();
    const files = args.wasm ? {"/web/three/penumbra_emitter.wasm": path.resolve(args.wasm)} : {};
    const gpu = await startWebGPU(args.chromium, roots, files);
    let failed = 0;
    try {
        const problems = [];
        gpu.page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
        gpu.page.on("console", (m) => m.type() === "error" && problems.push(`console: ${m.text()}`));
        console.log(`chromium ${await gpu.browser.version()}; ${adapterLine(gpu.adapter)}`);
        // What ran must be a real WebGPU adapter (not WebGL2, which has no such object): it names its vendor.
        if (!gpu.adapter.vendor && !gpu.adapter.architecture) {
            console.log("FAIL the WebGPU adapter names no vendor or architecture: cannot say what ran");
            failed++;
        }
        const conventions = await gpu.page.evaluate(conventionsInPage);
        const wrong = conventions.error ? conventions.error : conventions.values.filter((v) => v !== 0.75).length
            ? `result ${[...new Set(conventions.values)].join(", ")}, expected 0.75 everywhere` : "";
        console.log(`${wrong ? "FAIL" : "ok  "} runner conventions: a copy into an array layer, a render into a 3D slice, int_uniforms per pass` +
                    (wrong ? `: ${wrong}` : ""));
        if (wrong) failed++;
        for (let i = 0; i < args.bundles.length; ++i) {
            const dir = args.bundles[i];
            const bundle = JSON.parse(fs.readFileSync(path.join(dir, "uniforms.json"), "utf8"));
            const c = bundle.config;
            const label = `${bundle.scene} ${c.technique}/${c.light} ${bundle.width}x${bundle.height}`;
            const failures = [];
            const r = await gpu.page.evaluate(runInPage, i);
            if (r.error) {
                console.log(`FAIL ${label}: ${r.error.split("\n").join("\n     ")}`);
                failed++;
                continue;
            }
            const reference = readReference(dir);
            const visibility = Float32Array.from(r.visibility);
            if (visibility.length !== reference.gl.length) failures.push(`${visibility.length} pixels read, expected ${reference.gl.length}`);
            if (r.target !== "wgsl") failures.push(`emission target '${r.target}', expected wgsl`);
            if (r.shadowPasses === 0 || r.screenPasses === 0) failures.push(`ran ${r.shadowPasses} shadow and ${r.screenPasses} screen passes`);
            const d = difference(visibility, reference.gl);
            const pixels = reference.gl.length;
            const edges = silhouettePixels(readFloats(path.join(dir, "positions.f32")), bundle.width, bundle.height, visibility, reference.gl);
            let shadowed = 0, shadowedHere = 0;
            for (let k = 0; k < pixels; ++k) {
                if (reference.gl[k] < 0.98) ++shadowed;
                if (visibility[k] < 0.98) ++shadowedHere;
            }
            if (shadowed === 0) failures.push("the desktop image has no shadowed pixel: the comparison would prove nothing");
            if (d.over > TECHNIQUE_PIXELS_ALLOWED * pixels)
                failures.push(`${d.over} of ${pixels} pixels differ from the desktop run by more than ${TECHNIQUE_PIXEL_STEP} (allowed ${100 * TECHNIQUE_PIXELS_ALLOWED}%)`);
            // Rasterization differences move shadow-map texels at casters' edges only: away from silhouettes at most
            // INTERIOR_PIXELS_ALLOWED pixels may be more than TECHNIQUE_PIXEL_STEP apart (measured: 0 in every bundle).
            if (d.over - edges > INTERIOR_PIXELS_ALLOWED)
                failures.push(`${d.over - edges} pixels away from silhouettes differ from the desktop run by more than ${TECHNIQUE_PIXEL_STEP} (allowed ${INTERIOR_PIXELS_ALLOWED})`);
            if (d.mean > TECHNIQUE_MEAN_ALLOWED) failures.push(`mean |WebGPU − desktop| ${d.mean.toFixed(4)} (allowed ${TECHNIQUE_MEAN_ALLOWED})`);
            // occlusion textures: the model, as the CPU oracle computes it from the desktop's slices, within its bound
            let oracleLine = "";
            if (reference.oracle && reference.bound) {
                const o = compare(visibility, reference, 0);
                const outside = [];
                for (let k = 0; k < pixels; ++k)
                    if (Math.abs(visibility[k] - reference.oracle[k]) > reference.bound[k] + 1e-6) outside.push(k);
                const silhouette = silhouetteSet(readFloats(path.join(dir, "positions.f32")), bundle.width, bundle.height);
                const inside = outside.filter((k) => !silhouette.has(k)).length;
                oracleLine = `\n     oracle: max |WebGPU − oracle| ${o.worstOracle.toExponential(2)}, ${o.outsideOracle} of ${pixels} pixels outside the bound ` +
                             `(${inside} away from silhouettes)`;
                // WebGPU slices the scene itself, and SwiftShader rasterizes casters' edges unlike the desktop's llvmpipe,
                // whose slices the oracle read: as for the WebGL2 runner's own slices (browser_test.mjs), a share of the
                // pixels may leave the bound, all of them at silhouettes (measured: 10 and 2 of 4096)
                if (o.outsideOracle > OWN_PIXELS_ALLOWED * pixels || inside > 0)
                    failures.push(`${o.outsideOracle} pixels outside the oracle's bound, ${inside} of them away from silhouettes ` +
                                  `(allowed ${100 * OWN_PIXELS_ALLOWED}%, at silhouettes only)`);
                // With the desktop's slices in place of WebGPU's own, everything after slicing is the model the oracle
                // computes: every pixel within the bound (the result is r32float: no quantization step to add).
                const injected = await gpu.page.evaluate(runInPage, i, true);
                if (injected.error) {
                    failures.push(`with the desktop slices: ${injected.error}`);
                } else {
                    const withSlices = compare(Float32Array.from(injected.visibility), reference, 0);
                    oracleLine += `\n     with the desktop slices: max |WebGPU − oracle| ${withSlices.worstOracle.toExponential(2)}, ` +
                                  `${withSlices.outsideOracle} of ${pixels} pixels outside the bound`;
                    if (withSlices.outsideOracle > 0)
                        failures.push(`with the desktop slices, ${withSlices.outsideOracle} pixels outside the oracle's bound (allowed 0)`);
                }
            }
            failures.push(...problems.splice(0));
            if (args.images) {
                fs.mkdirSync(args.images, {recursive: true});
                const name = `${i}_${c.technique}_${c.light}`;
                await writeGreyPng(path.join(args.images, `${name}_webgpu.png`), bundle.width, bundle.height, visibility);
                await writeGreyPng(path.join(args.images, `${name}_gl.png`), bundle.width, bundle.height, reference.gl);
            }
            console.log(`${failures.length ? "FAIL" : "ok  "} ${label}: WebGPU ran ${r.shadowPasses} shadow + ${r.screenPasses} screen passes ` +
                        `(programs ${r.programs.join(", ")}; caller textures ${r.filled.join(", ")}; result ${r.result} ${r.resultFormat}; ` +
                        `created in ${r.createMs.toFixed(0)} ms, ran and read back in ${r.runMs.toFixed(0)} ms)\n` +
                        `     max |WebGPU − desktop| ${d.worst.toExponential(2)}, mean ${d.mean.toExponential(2)}, ${d.over} of ${pixels} pixels more than ` +
                        `${TECHNIQUE_PIXEL_STEP} apart (${edges} of them at silhouettes); shadowed (< 0.98) desktop ${shadowed}, WebGPU ${shadowedHere}` +
                        oracleLine);
            for (const f of failures) console.log(`     ${f}`);
            if (failures.length) failed++;
            if (args.wasm && args.playground.has(dir)) failed += (await checkPlayground(gpu.browser, gpu.port, i, dir, label, args.images)) ? 1 : 0;
        }
    } finally {
        await gpu.close();
    }
    console.log(`${failed ? "FAIL" : "ok"}: ${args.bundles.length} bundles, ${failed} failed, ${((Date.now() - started) / 1000).toFixed(1)} s`);
    process.exit(failed ? 1 : 0);
}

main().catch((e) => {
    console.log(`FAIL ${e.stack || e.message}`);
    process.exit(1);
});
