// bench.mjs — the WebAssembly emitter's size and emission time, first call and warm, in node and
// in headless Chromium (not a test: it prints numbers). Times include the copies in and out of the
// module and JSON.parse of the result (what emit() returns to a page).
//
//   node wasm/bench.mjs --wasm build/wasm/penumbra_emitter.wasm [--runs N] [--chromium PATH]
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import {fileURLToPath, pathToFileURL} from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const args = {wasm: null, runs: 50, chromium: "/usr/bin/chromium"};
for (let i = 2; i < process.argv.length; i += 2) {
    const key = process.argv[i].replace(/^--/, "");
    if (!(key in args) || i + 1 >= process.argv.length) {
        console.error("usage: node wasm/bench.mjs --wasm MODULE [--runs N] [--chromium PATH]");
        process.exit(2);
    }
    args[key] = key === "runs" ? Number(process.argv[i + 1]) : process.argv[i + 1];
}
if (!args.wasm) {
    console.error("error: --wasm MODULE is required");
    process.exit(2);
}

const CONFIGS = {
    "default (glsl450)": {},
    "essl300 default": {target: "essl300"},
    "128 slices, sat": {slices: 128, filter: "sat", resolution: 256},
    "pcss 32/64": {technique: "pcss", pcss: {blocker_samples: 32, filter_samples: 64}},
    "erosion": {technique: "erosion"},
};

// Runs in node and, as text, in the page: first = the first emit() after loading the module.
async function measure(loadEmitter, source, configs, runs) {
    const t0 = performance.now();
    const emitter = await loadEmitter(source);
    const loadMs = performance.now() - t0;
    const out = {loadMs, rows: []};
    let first = true;
    for (const [name, config] of Object.entries(configs)) {
        const a = performance.now();
        const r = emitter.emit(config);
        const firstMs = performance.now() - a;
        const times = [];
        for (let i = 0; i < runs; ++i) {
            const b = performance.now();
            emitter.emit(config);
            times.push(performance.now() - b);
        }
        times.sort((x, y) => x - y);
        const bytes = Object.values(r.files).reduce((n, t) => n + t.length, 0);
        out.rows.push({name, ok: r.ok, files: Object.keys(r.files).length, bytes, firstMs, coldModule: first,
                       medianMs: times[times.length >> 1], minMs: times[0]});
        first = false;
    }
    return out;
}

function print(where, result) {
    console.log(`${where}: module load (fetch/read + compile + instantiate + _initialize) ${result.loadMs.toFixed(1)} ms`);
    console.log("  configuration          files   bytes    first call   warm median   warm min");
    for (const r of result.rows)
        console.log(`  ${r.name.padEnd(22)} ${String(r.files).padStart(5)} ${String(r.bytes).padStart(7)}   ${r.firstMs.toFixed(2).padStart(8)} ms` +
                    `${r.coldModule ? "*" : " "}  ${r.medianMs.toFixed(2).padStart(8)} ms  ${r.minMs.toFixed(2).padStart(7)} ms` + (r.ok ? "" : "  (refused)"));
    console.log("  * the module's first emission of all (the others: first of that configuration)");
}

const size = fs.statSync(args.wasm).size;
console.log(`penumbra_emitter.wasm: ${size} bytes (${(size / 1024).toFixed(0)} KiB); ${args.runs} warm runs per configuration`);
const {loadEmitter} = await import(pathToFileURL(path.join(here, "../web/three/penumbra_emitter.js")));
print(`node ${process.version}`, await measure(loadEmitter, fs.readFileSync(args.wasm), CONFIGS, args.runs));

if (!fs.existsSync(args.chromium)) {
    console.log(`no chromium at ${args.chromium}: the browser's numbers are left out`);
    process.exit(0);
}
const {serve, launchChromium} = await import(pathToFileURL(path.join(here, "../targets/web/bundle_compare.mjs")));
const server = await serve(path.join(here, "../web"), [], {"/web/three/penumbra_emitter.wasm": path.resolve(args.wasm)});
const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "penumbra-bench-"));
const browser = await launchChromium(args.chromium, userDataDir);
try {
    const page = await browser.newPage();
    await page.goto(`http://127.0.0.1:${server.address().port}/web/scenes/index.json`); // an origin for the module's import
    const result = await page.evaluate(async (measureText, configs, runs) => {
        const {loadEmitter} = await import("/web/three/penumbra_emitter.js");
        const measure = eval(`(${measureText})`);
        return measure(loadEmitter, "/web/three/penumbra_emitter.wasm", configs, runs);
    }, measure.toString(), CONFIGS, args.runs);
    print(`chromium ${await browser.version()}`, result);
} finally {
    await browser.close();
    server.close();
    fs.rmSync(userDataDir, {recursive: true, force: true});
}
