// wgsl_matrix.mjs — the `wgsl_matrix` test, the WGSL counterpart of the glslang matrix: runs
// `penumbra-gen --target wgsl` over a configuration matrix into OUT (one folder a configuration) and
// compiles every WGSL module it wrote in chromium's WebGPU (wgsl_compile.mjs: one browser, one page).
//
//   node targets/web/wgsl_matrix.mjs --gen PATH --out DIR [--web DIR] [--wasm MODULE] [--chromium PATH] [--only REGEX]
//
// Each configuration of the matrix (VARIANTS × LIGHTS × ...) must be accepted, list only .wgsl files in
// layout.json's programs (each present, one `fn main` with its stage's attribute) and compile with
// zero errors. Each one of REFUSED must be refused by penumbra-gen as a user error (exit 2, one
// `error: ...` line that names wgsl), so that a crash or an unrelated failure cannot pass as a refusal.
// With --web (the folder of three/penumbra_webgpu_runner.js), each configuration whose modules compile is also built
// by the WebGPU layout runner from its layout.json alone (bind group layouts from the parameters'
// bindings, textures of its webgpu formats and usages, a pipeline for every shadow and screen pass):
// WebGPU's validation then checks layout.json against the WGSL (binding types, inter-stage locations,
// target formats), which compiling each module alone does not. With --wasm
// (build/wasm/penumbra_emitter.wasm), the WebAssembly emitter must write every configuration's files
// byte for byte as penumbra-gen did (from the configuration layout.json records; in node).
// Exit 0 pass, 1 fail, 2 bad arguments, 77 skip (no chromium; no adapter only with PENUMBRA_WEBGPU_OPTIONAL=1).
import fs from "node:fs";
import path from "node:path";
import {spawnSync} from "node:child_process";
import {adapterLine, compileModules, startWebGPU} from "./wgsl_compile.mjs";

// ---- The matrix: the variants tests/technique_variants.json lists (shared with tests/hlsl/hlsl_matrix.py),
// each × light × alpha test, and for the techniques with a normal offset (normal_offset_techniques) × normal offset.
const MATRIX = JSON.parse(fs.readFileSync(new URL("../../tests/technique_variants.json", import.meta.url), "utf8"));
const {variants: VARIANTS, variant_lights: VARIANT_LIGHTS, normal_offset_techniques: NORMAL_OFFSET_TECHNIQUES,
       lights: LIGHTS, normal_offsets: NORMAL_OFFSETS, alpha_test: ALPHA_TEST} = MATRIX;
// What the wgsl target refuses today (the lead ports these next; move a line up into VARIANTS when it lands).
const REFUSED = {
    "oim": "--technique oim",
};
// ----

function configurations() {
    const out = [];
    for (const [variant, flags] of Object.entries(VARIANTS)) {
        const offsets = NORMAL_OFFSET_TECHNIQUES.includes(flags.split(" ")[1]) ? NORMAL_OFFSETS : [null];
        for (const light of VARIANT_LIGHTS[variant] || LIGHTS)
            for (const offset of offsets)
                for (const alpha of ALPHA_TEST)
                    out.push({name: `${variant}-${light}${offset === null ? "" : `-n${offset}`}${alpha ? "-alpha" : ""}`,
                              flags: [...flags.split(" "), "--light", light, ...(offset === null ? [] : ["--shadow-normal-offset", offset]),
                                      ...(alpha ? ["--alpha-test"] : [])]});
    }
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node wgsl_matrix.mjs --gen PENUMBRA_GEN --out DIR [--web DIR] [--wasm MODULE] [--chromium PATH] [--only REGEX]`);
    process.exit(2);
}

function parseArguments(argv) {
    const out = {gen: null, out: null, web: null, wasm: null, chromium: "/usr/bin/chromium", only: null};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        if (!["--gen", "--out", "--web", "--wasm", "--chromium", "--only"].includes(flag)) usage(`unknown argument '${flag}'`);
        if (i + 1 >= argv.length) usage(`${flag}: missing value`);
        out[flag.slice(2)] = argv[++i];
    }
    if (!out.gen) usage("--gen: missing (the penumbra-gen executable)");
    if (!fs.existsSync(out.gen)) usage(`--gen: no file ${out.gen}`);
    if (!out.out) usage("--out: missing (a folder for the emissions)");
    if (out.wasm && !fs.existsSync(out.wasm)) usage(`--wasm: no file ${out.wasm} (cmake --build build --target penumbra-emitter-wasm)`);
    if (out.web && !fs.existsSync(path.join(out.web, "three/penumbra_webgpu_runner.js"))) usage(`--web: no three/penumbra_webgpu_runner.js in ${out.web}`);
    return out;
}

const STAGE_ATTRIBUTE = {vertex: /@vertex\s+fn\s+main\s*\(/, fragment: /@fragment\s+fn\s+main\s*\(/,
                         compute: /@compute\s+@workgroup_size\([^)]*\)\s+fn\s+main\s*\(/};

async function main() {
    const args = parseArguments(process.argv.slice(2));
    const only = args.only ? new RegExp(args.only) : null;
    const started = Date.now();
    const failures = [];
    fs.rmSync(args.out, {recursive: true, force: true});
    fs.mkdirSync(args.out, {recursive: true});
    const gen = (flags, dir) => spawnSync(args.gen, ["--target", "wgsl", ...flags, "--out", dir], {encoding: "utf8"});

    // 1. Emit every configuration; check layout.json's program files.
    const modules = [];
    const emissions = []; // {name, dir, files: [.wgsl names]}
    let emitted = 0;
    for (const c of configurations()) {
        if (only && !only.test(c.name)) continue;
        const dir = path.join(args.out, c.name);
        const r = gen(c.flags, dir);
        if (r.status !== 0) {
            failures.push(`${c.name}: penumbra-gen --target wgsl ${c.flags.join(" ")} exited ${r.status ?? r.signal}: ${(r.stderr || "").trim()}`);
            continue;
        }
        ++emitted;
        const layout = JSON.parse(fs.readFileSync(path.join(dir, "layout.json"), "utf8"));
        if (layout.config?.target !== "wgsl") failures.push(`${c.name}: layout.json config.target is '${layout.config?.target}'`);
        for (const program of layout.programs || [])
            program.files.forEach((file, i) => {
                const stage = (program.stages || [])[i];
                if (!file.endsWith(".wgsl")) return failures.push(`${c.name}: program ${program.name} lists '${file}', not a .wgsl file`);
                if (!fs.existsSync(path.join(dir, file))) return failures.push(`${c.name}: program ${program.name}: ${file} was not written`);
                const text = fs.readFileSync(path.join(dir, file), "utf8");
                if (stage && STAGE_ATTRIBUTE[stage] && !STAGE_ATTRIBUTE[stage].test(text))
                    failures.push(`${c.name}: ${file}: no '@${stage} fn main' (WGSL.md: one entry point named main per stage file)`);
            });
        const files = {"layout.json": fs.readFileSync(path.join(dir, "layout.json"), "utf8")};
        for (const file of fs.readdirSync(dir).sort())
            if (file.endsWith(".wgsl")) {
                files[file] = fs.readFileSync(path.join(dir, file), "utf8");
                modules.push({name: path.join(dir, file), code: files[file]});
            } else if (file !== "layout.json") failures.push(`${c.name}: wrote '${file}', neither WGSL nor layout.json`);
        emissions.push({name: c.name, dir, files});
    }

    // 2. The refusals: a user error naming wgsl, not a crash.
    let refused = 0;
    for (const [name, flags] of Object.entries(REFUSED)) {
        if (only && !only.test(name)) continue;
        const r = gen(flags.split(" "), path.join(args.out, `refused-${name}`));
        const message = (r.stderr || "").trim();
        if (r.status === 0) failures.push(`${name}: expected a refusal for wgsl, but penumbra-gen ${flags} --target wgsl wrote an emission (move it to VARIANTS?)`);
        else if (r.status !== 2 || !/^error: /.test(message) || !/wgsl/i.test(message) || /^error: --target:/.test(message))
            failures.push(`${name}: not a refusal naming wgsl (exit ${r.status ?? r.signal}): ${message}`);
        else {
            ++refused;
            console.log(`refused ${name}: ${message.split("\n")[0]}`);
        }
    }
    if (modules.length === 0) failures.push("no WGSL module was emitted: nothing compiled");

    // 3. The WebAssembly emitter: the same files, byte for byte.
    let identical = 0;
    if (args.wasm) {
        const {loadEmitter} = await import("../../web/three/penumbra_emitter.js");
        const emitter = await loadEmitter(fs.readFileSync(args.wasm));
        for (const e of emissions) {
            const r = emitter.emit(JSON.parse(e.files["layout.json"]).config);
            const written = fs.readdirSync(e.dir).sort();
            if (!r.ok) failures.push(`${e.name}: the WebAssembly emitter refuses it: ${r.error}`);
            else if (JSON.stringify(Object.keys(r.files).sort()) !== JSON.stringify(written))
                failures.push(`${e.name}: the WebAssembly emitter writes ${Object.keys(r.files).sort().join(", ")}; penumbra-gen ${written.join(", ")}`);
            else {
                const different = written.filter((f) => r.files[f] !== fs.readFileSync(path.join(e.dir, f), "utf8"));
                if (different.length) failures.push(`${e.name}: the WebAssembly emitter's ${different.join(", ")} differ from penumbra-gen's`);
                else ++identical;
            }
        }
    }

    // 4. Compile every module in one page.
    let errors = 0, warnings = 0, clean = 0, built = 0;
    if (modules.length) {
        const gpu = await startWebGPU(args.chromium, args.web ? {web: args.web} : {});
        try {
            console.log(adapterLine(gpu.adapter));
            const [broken] = await compileModules(gpu.page, [{name: "self-check", code: "fn f() -> f32 { return undeclared; }\n"}]);
            if (!broken.messages.some((m) => m.type === "error")) failures.push("self-check: chromium reports no error for a broken module");
            const badModules = new Set();
            for (const {name, messages} of await compileModules(gpu.page, modules)) {
                let bad = false;
                for (const m of messages) {
                    if (m.type === "info") continue;
                    if (m.type === "error") { ++errors; bad = true; } else ++warnings;
                    console.log(`${name}:${m.line}:${m.column}: ${m.type}: ${m.message}`);
                }
                if (!bad) ++clean;
                else badModules.add(name);
            }
            // 5. The layout runner builds every configuration whose modules compiled.
            for (const e of args.web ? emissions : []) {
                if (Object.keys(e.files).some((f) => badModules.has(path.join(e.dir, f)))) continue;
                const error = await gpu.page.evaluate(async (files) => {
                    try {
                        const {WebGPULayoutRunner} = await import("/web/three/penumbra_webgpu_runner.js");
                        const runner = await WebGPULayoutRunner.fromEmission(window.penumbraDevice, {files});
                        runner.dispose();
                        return null;
                    } catch (x) {
                        return x.message;
                    }
                }, e.files);
                if (error) failures.push(`${e.name}: the WebGPU layout runner cannot build it from layout.json: ${error}`);
                else ++built;
            }
        } finally {
            await gpu.close();
        }
    }
    if (errors) failures.push(`${errors} WGSL errors in ${modules.length - clean} modules`);
    for (const f of failures) console.log(`FAIL ${f}`);
    console.log(`${failures.length ? "FAIL" : "ok"}: ${emitted} configurations emitted, ${refused} refused for wgsl as expected; ` +
                `${modules.length} WGSL modules compiled, ${clean} clean, ${errors} errors, ${warnings} warnings; ` +
                `${args.web ? `${built} of ${emissions.length} built by the WebGPU layout runner (pipelines and bind groups)` : "layouts not built (no --web)"}; ` +
                `${args.wasm ? `${identical} of ${emissions.length} byte-identical from the WebAssembly emitter` : "WebAssembly emitter not compared (no --wasm)"} ` +
                `in ${((Date.now() - started) / 1000).toFixed(1)} s`);
    process.exit(failures.length ? 1 : 0);
}

main().catch((e) => {
    console.log(`FAIL ${e.stack || e.message}`);
    process.exit(1);
});
