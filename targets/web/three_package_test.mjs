// three_package_test.mjs — the `three-package` test: the three.js add-on as a user installs it.
//   1. web/three/emissions.js lists every shipped emission file (three_emissions_table.mjs).
//   2. `npm pack` of web/three (prepack.mjs puts the WebAssembly emitter in): the tarball holds the
//      modules, their declarations, penumbra_emitter.wasm and the emissions, and nothing of the
//      example or the tests.
//   3. A fresh project (WORK/app) installs the tarball with npm, offline (three and @types/three
//      linked from this folder's node_modules, which scripts/setup.sh installs from npm), and
//      `tsc --noEmit` checks three_package/check.ts against @types/three r187 and r180.
//   4. Vite (pinned in package.json here) builds three_package/index.html + main.js twice, with
//      three r187 and r180; each dist/ is served on 127.0.0.1 and opened in Debian's chromium:
//      a ground under two shadowed lights, one add-on each on the same material (two
//      RectAreaLights; a RectAreaLight and a sun): with one light on, (lit with the add-ons) /
//      (lit without) is that light's visibility (so the other add-on leaves its term alone);
//      both lights on is the sum of the two; each light casts a shadow of its own, somewhere the
//      other does not; after dispose(), update() throws and the other add-on still shadows; a
//      configuration emitted in the page by the package's WebAssembly emitter shadows too.
//      The same page from Vite's dev server (three r187; the package excluded from pre-bundling, as
//      web/three/README.md says) for the two RectAreaLights. Each build's page again with
//      ?renderer=webgpu: the same checks on WebGPURenderer (WebGPU through SwiftShader), the
//      add-on's wgsl path as Vite bundles it (the dynamically imported penumbra_shadows_webgpu.js,
//      three/webgpu, the wgsl emitted in the page).
//   5. The example (web/three/example/, served from the repository) switches from the
//      RectAreaLight to the sun and back, its shadows there after each switch; then to its
//      "room (glTF)" scene (web/rooms/room.gltf through the package's EXT_lights_area plugin), shadowed
//      by the add-on on the file's RectAreaLight.
//
//   node targets/web/three_package_test.mjs --three web/three --work DIR [--wasm FILE] [--chromium PATH] [--images DIR]
//
// Exit 0 pass, 1 fail, 77 skip (no chromium), 2 bad arguments.
import {execFile, execFileSync, spawn} from "node:child_process";
import fs from "node:fs";
import path from "node:path";
import {fileURLToPath} from "node:url";
import {serve, launchChromium, openPage, writeGreyPng, WEBGPU_ARGS} from "./harness.mjs";
import {emissionsTable} from "./three_emissions_table.mjs";

const here = path.dirname(fileURLToPath(import.meta.url));
const modules = path.join(here, "node_modules");
const RATIO_TOLERANCE = 0.01;   // (lit with) / (lit without) against the visibility, both float
const PIXELS_ALLOWED = 0.01;
const SHADOW_PIXELS = 0.03;     // each light's own shadow (visibility < 0.5 where the other's > 0.9)
const WEBGPU_SHADOW_PIXELS = 0.025; // the same on WebGPU, whose 32²/64² emissions (16 sampled textures) shadow softer

function parseArguments(argv) {
    const out = {three: null, work: null, wasm: null, chromium: "/usr/bin/chromium", images: null};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        const key = flag.slice(2);
        if (!["--three", "--work", "--wasm", "--chromium", "--images"].includes(flag))
            usage(`unknown argument '${flag}'; allowed: --three, --work, --wasm, --chromium, --images`);
        if (i + 1 >= argv.length) usage(`${flag}: missing value`);
        out[key] = argv[++i];
    }
    if (!out.three || !out.work) usage("--three and --work are required");
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node three_package_test.mjs --three web/three --work DIR [--wasm FILE] [--chromium PATH] [--images DIR]`);
    process.exit(2);
}

function run(command, args, options = {}) {
    const started = Date.now();
    try {
        const stdout = execFileSync(command, args, {encoding: "utf8", stdio: ["ignore", "pipe", "pipe"], ...options});
        return {stdout, seconds: (Date.now() - started) / 1000};
    } catch (e) {
        throw new Error(`${[command, ...args].join(" ")} failed (exit ${e.status}):\n${e.stdout || ""}${e.stderr || ""}`);
    }
}

// The same, without blocking: the type checks and the builds run side by side.
function runAsync(command, args, options = {}) {
    const started = Date.now();
    return new Promise((resolve, reject) => execFile(command, args, {encoding: "utf8", maxBuffer: 1 << 26, ...options}, (e, stdout, stderr) => {
        if (e) reject(new Error(`${[command, ...args].join(" ")} failed (exit ${e.code}):\n${stdout || ""}${stderr || ""}`));
        else resolve({stdout, seconds: (Date.now() - started) / 1000});
    }));
}

// 2. npm pack: the tarball and its file list
function pack(three, work, wasm) {
    const env = {...process.env};
    if (wasm) env.PENUMBRA_EMITTER_WASM = path.resolve(wasm);
    const {stdout, seconds} = run("npm", ["pack", "--json", "--pack-destination", work, "--loglevel=error"], {cwd: three, env});
    const [info] = JSON.parse(stdout.slice(stdout.indexOf("[")));
    const files = info.files.map((f) => f.path);
    const failures = [];
    for (const need of ["package.json", "penumbra_shadows.js", "penumbra_shadows.d.ts", "penumbra_runner.js", "light_frame.js",
                        "penumbra_emitter.js", "penumbra_emitter.d.ts", "penumbra_emitter.wasm", "emissions.js", "LICENSE",
                        "emissions/rect-nbuffer-16x512/layout.json", "emissions/sun-mipmap-16x512/penumbra_visibility.glsl",
                        "penumbra_scene.js", "penumbra_emission.js", "penumbra_emitter_node.js", "penumbra_shadows_webgpu.js", "penumbra_webgpu_runner.js",
                        "gltf_lights_area.js", "gltf_lights_area.d.ts",
                        "emissions/rect-nbuffer-16x512-wgsl/penumbra_visibility.wgsl"])
        if (!files.includes(need)) failures.push(`the tarball lacks ${need}`);
    for (const f of files) if (/^(example|test|node_modules)\/|\.tgz$|prepack\.mjs$|regenerate\.sh$/.test(f)) failures.push(`the tarball holds ${f}`);
    console.log(`${failures.length ? "FAIL" : "ok  "} npm pack: ${info.filename}, ${files.length} files, ${(info.size / 1024).toFixed(0)} KiB ` +
                `(${(info.unpackedSize / 1024).toFixed(0)} KiB unpacked; penumbra_emitter.wasm ${(info.files.find((f) => f.path === "penumbra_emitter.wasm")?.size / 1024).toFixed(0)} KiB) in ${seconds.toFixed(1)} s`);
    return {tarball: path.join(work, info.filename), failures};
}

// 3. a fresh project with the tarball installed
function project(work, tarball) {
    const app = path.join(work, "app");
    fs.rmSync(app, {recursive: true, force: true});
    fs.mkdirSync(app, {recursive: true});
    for (const f of ["index.html", "main.js", "check.ts"]) fs.copyFileSync(path.join(here, "three_package", f), path.join(app, f));
    fs.writeFileSync(path.join(app, "package.json"), JSON.stringify({
        name: "penumbra-three-user", private: true, type: "module",
        dependencies: {"penumbra-three": `file:${path.relative(app, tarball)}`, three: `file:${path.join(modules, "three")}`},
        devDependencies: {"@types/three": `file:${path.join(modules, "@types/three")}`},
    }, null, 2));
    const installed = run("npm", ["install", "--offline", "--no-audit", "--no-fund", "--loglevel=error"], {cwd: app});
    // vite.config.js: three from THREE_DIR (r187 or r180), relative URLs (dist/ is served under a prefix)
    fs.writeFileSync(path.join(app, "vite.config.js"), `const three = process.env.THREE_DIR;
export default {
    base: "./",
    logLevel: "warn",
    optimizeDeps: {exclude: ["penumbra-three"]}, // the dev server's pre-bundling would lose the new URL(…) assets (README)
    build: {outDir: process.env.OUT_DIR, emptyOutDir: true, minify: false}, // (minifying three takes longer than the rest)
    resolve: {alias: three ? [{find: /^three$/, replacement: three + "/build/three.module.js"},
                              {find: /^three\\/webgpu$/, replacement: three + "/build/three.webgpu.js"},
                              {find: /^three\\/tsl$/, replacement: three + "/build/three.tsl.js"},
                              {find: /^three\\/addons\\//, replacement: three + "/examples/jsm/"}] : []},
};
`);
    // the exports resolve in node too: "." and "./emitter", whose default module file is in the tarball
    const probe = `const {PenumbraShadows, EMISSIONS} = await import("penumbra-three");
const {loadEmitter} = await import("penumbra-three/emitter");
const r = (await loadEmitter()).emit({slices: 4, target: "essl300"});
console.log(typeof PenumbraShadows.load, Object.keys(EMISSIONS).length, r.ok, Object.keys(r.files).length);`;
    const {stdout} = run(process.execPath, ["--input-type=module", "-e", probe], {cwd: app});
    const [load, emissions, ok] = stdout.trim().split(" ");
    const failures = [];
    // (every folder of web/three/emissions: essl300 ones and their "-wgsl" twins)
    const shipped = fs.readdirSync(path.join(here, "../../web/three/emissions"), {withFileTypes: true}).filter((d) => d.isDirectory()).length;
    if (load !== "function" || emissions !== String(shipped) || ok !== "true")
        failures.push(`in node, import("penumbra-three") and import("penumbra-three/emitter") gave: ${stdout.trim()}`);
    console.log(`${failures.length ? "FAIL" : "ok  "} npm install --offline of the tarball into a fresh project (${installed.seconds.toFixed(1)} s); ` +
                `in node its exports resolve and the emitter emits (${stdout.trim().split(" ")[3]} files)`);
    return {app, failures};
}

// tsc --noEmit over check.ts against @types/three r187 and r180
async function typecheck(app) {
    const tsconfig = (types) => ({
        compilerOptions: {strict: true, noEmit: true, target: "es2022", module: "esnext", moduleResolution: "bundler",
                          lib: ["es2022", "dom"], skipLibCheck: true, types: [],
                          ...(types ? {paths: {three: [path.join(types, "index.d.ts")]}} : {})},
        files: ["check.ts"],
    });
    const failures = [];
    const tsc = path.join(modules, "typescript/bin/tsc");
    const checks = await Promise.all([["r187", null], ["r180", path.join(modules, "@types/three-r180")]].map(async ([name, types]) => {
        fs.writeFileSync(path.join(app, `tsconfig.${name}.json`), JSON.stringify(tsconfig(types), null, 2));
        try {
            const {seconds} = await runAsync(process.execPath, [tsc, "-p", `tsconfig.${name}.json`], {cwd: app});
            return `@types/three ${name} ok (${seconds.toFixed(1)} s)`;
        } catch (e) {
            failures.push(`tsc against @types/three ${name}: ${e.message}`);
            return `@types/three ${name} FAILED`;
        }
    }));
    console.log(`${failures.length ? "FAIL" : "ok  "} tsc --noEmit check.ts: ${checks.join(", ")}`);
    return failures;
}

async function build(app, name, threeDir) {
    const out = path.join(app, `dist-${name}`);
    const {stdout, seconds} = await runAsync(process.execPath, [path.join(modules, "vite/bin/vite.js"), "build"],
                                             {cwd: app, env: {...process.env, THREE_DIR: threeDir, OUT_DIR: out}});
    const files = fs.readdirSync(path.join(out, "assets"));
    const failures = [];
    // the add-on's assets were copied (or inlined): layout.json and the wasm at least
    if (!files.some((f) => /^layout.*\.json$/.test(f))) failures.push(`dist-${name}/assets has no layout*.json: the emissions were not copied`);
    if (!files.some((f) => /^penumbra_emitter.*\.wasm$/.test(f))) failures.push(`dist-${name}/assets has no penumbra_emitter*.wasm`);
    const bytes = files.reduce((n, f) => n + fs.statSync(path.join(out, "assets", f)).size, 0);
    console.log(`${failures.length ? "FAIL" : "ok  "} vite build with three ${name}: ${files.length} assets, ${(bytes / 1024).toFixed(0)} KiB, ${seconds.toFixed(1)} s` +
                (stdout.trim() ? `\n     ${stdout.trim().split("\n").join("\n     ")}` : ""));
    return {out, failures};
}

// Vite's dev server on the fresh project; resolves to {url, stop}.
function devServer(app) {
    const child = spawn(process.execPath, [path.join(modules, "vite/bin/vite.js"), "--host", "127.0.0.1", "--logLevel", "info"],
                        {cwd: app, env: {...process.env, THREE_DIR: ""}, stdio: ["ignore", "pipe", "pipe"]});
    let output = "";
    return new Promise((resolve, reject) => {
        const timer = setTimeout(() => { child.kill(); reject(new Error(`vite dev server: no URL after 60 s:\n${output}`)); }, 60000);
        const read = (chunk) => {
            output += chunk;
            const m = /(http:\/\/127\.0\.0\.1:\d+\/)/.exec(output.replace(/\x1b\[[0-9;]*m/g, ""));
            if (m) {
                clearTimeout(timer);
                resolve({url: m[1], stop: () => child.kill()});
            }
        };
        child.stdout.on("data", read);
        child.stderr.on("data", read);
        child.on("exit", (code) => { clearTimeout(timer); reject(new Error(`vite dev server exited (${code}):\n${output}`)); });
    });
}

// 4. the two-light checks on one page's results
function checkPair(r, label) {
    const failures = [];
    const n = r.width * r.height;
    const stats = [];
    for (const k of [0, 1]) {
        const u = r.unshadowed[k], s = r.shadowed[k], v = r.visibility[k];
        const peak = Math.max(...u);
        let lit = 0, outside = 0, worst = 0;
        for (let i = 0; i < n; ++i) {
            if (!(u[i] > 1e-3 * peak)) continue;
            ++lit;
            const d = Math.abs(s[i] / u[i] - v[i]);
            worst = Math.max(worst, d);
            if (!(d <= RATIO_TOLERANCE)) ++outside;
        }
        if (lit < 0.5 * n) failures.push(`light ${k + 1} lights only ${lit} of ${n} pixels`);
        if (outside > PIXELS_ALLOWED * lit) failures.push(`with light ${k + 1} alone, (lit with the add-ons) / (lit without) is not its add-on's visibility at ${outside} of ${lit} pixels (max |Δ| ${worst.toFixed(3)}): the other add-on scales its term, or this one does not`);
        const own = r.visibility[k].filter((x, i) => x < 0.5 && r.visibility[1 - k][i] > 0.9).length;
        // (WebGPU: the 32² and 64² emissions that fit its 16 sampled textures cast softer, smaller
        // shadows; measured 262 pixels for the sun)
        const wanted = (r.webgpu ? WEBGPU_SHADOW_PIXELS : SHADOW_PIXELS) * n;
        if (own < wanted) failures.push(`light ${k + 1} casts its own shadow on ${own} pixels only (visibility < 0.5 where the other light's > 0.9; wanted ≥ ${wanted})`);
        stats.push(`light ${k + 1} (${r.configs[k]}): its own shadow on ${own} pixels, ratio vs visibility max |Δ| ${worst.toFixed(4)} (${outside} of ${lit} lit pixels over ${RATIO_TOLERANCE})`);
    }
    let sumWorst = 0, peak = 0;
    for (let i = 0; i < n; ++i) {
        sumWorst = Math.max(sumWorst, Math.abs(r.both[i] - r.shadowed[0][i] - r.shadowed[1][i]));
        peak = Math.max(peak, r.both[i]);
    }
    if (!(sumWorst <= 1e-3 * peak)) failures.push(`both lights on is not the sum of each alone (max |Δ| ${sumWorst} of ${peak})`);
    if (!/update\(\) after dispose\(\)/.test(r.updateAfterDispose)) failures.push(`update() after dispose(): ${r.updateAfterDispose}`);
    let after = 0;
    for (let i = 0; i < n; ++i) after = Math.max(after, Math.abs(r.afterDispose[i] - r.shadowed[0][i]));
    if (!(after <= 1e-4 * Math.max(...r.shadowed[0]))) failures.push(`after the second add-on's dispose() the first light's image changed by ${after}`);
    if (!r.restored) failures.push("after both dispose() calls the material's hooks are not its own");
    let emitted = "";
    if (r.emitted) {
        emitted = `; emitted in the page (WebAssembly): ${r.emitted.config}, ${r.emitted.shadowed} pixels in shadow`;
        const wanted = r.webgpu ? "rect nbuffer 8x64" : "rect mipmap 8x256";
        if (r.emitted.config !== wanted || r.emitted.shadowed < SHADOW_PIXELS * n)
            failures.push(`the configuration emitted by the package's WebAssembly emitter gave ${r.emitted.config} with ${r.emitted.shadowed} pixels in shadow`);
    }
    console.log(`${failures.length ? "FAIL" : "ok  "} ${label} ${r.pair}: ${stats.join("; ")}; both on vs sum max |Δ| ${sumWorst.toExponential(1)}; ` +
                `update() after dispose(): "${r.updateAfterDispose}"${emitted}`);
    return failures;
}

// 5. the example's light switch: penumbra mode differs from "no shadows" after each switch
async function checkExample(browser, port) {
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/web/three/example/index.html`, "example", {width: 160, height: 120});
    await page.evaluate(() => window.example.ready);
    const failures = [];
    const steps = [];
    const shot = (mode) => page.evaluate(async (m) => {
        await window.example.set({mode: m});
        window.example.render();
        const canvas = document.querySelector("canvas");
        const c = document.createElement("canvas");
        c.width = canvas.width;
        c.height = canvas.height;
        const ctx = c.getContext("2d");
        ctx.drawImage(canvas, 0, 0);
        return Array.from(ctx.getImageData(0, 0, c.width, c.height).data);
    }, mode);
    for (const light of ["rect", "sun", "rect"]) {
        await page.evaluate((l) => window.example.set({light: l}), light);
        await new Promise((resolve) => setTimeout(resolve, 300)); // animation frames with the new add-on
        const on = await shot("penumbra"), off = await shot("none");
        let differing = 0;
        for (let i = 0; i < on.length; i += 4) if (Math.abs(on[i] - off[i]) + Math.abs(on[i + 1] - off[i + 1]) + Math.abs(on[i + 2] - off[i + 2]) > 12) ++differing;
        const info = await page.evaluate(() => window.example.info());
        steps.push(`${light}: ${differing} pixels shadowed, ${info.shadows.receivers} receivers`);
        if (differing < 0.01 * on.length / 4) failures.push(`after switching to the ${light} light, Penumbra's mode differs from "no shadows" at ${differing} pixels only`);
    }
    // the "room (glTF)" scene: web/rooms/room.gltf through GLTFLoader and the package's EXT_lights_area
    // plugin, the add-on on the RectAreaLight the file brings
    await page.evaluate(() => window.example.set({scene: "gltf", light: "rect"}));
    await new Promise((resolve) => setTimeout(resolve, 300));
    const on = await shot("penumbra"), off = await shot("none");
    let differing = 0;
    for (let i = 0; i < on.length; i += 4) if (Math.abs(on[i] - off[i]) + Math.abs(on[i + 1] - off[i + 1]) + Math.abs(on[i + 2] - off[i + 2]) > 12) ++differing;
    const info = await page.evaluate(() => window.example.info());
    steps.push(`room (glTF): ${differing} pixels shadowed, ${info.shadows.receivers} receivers, the add-on on ${info.light}`);
    if (differing < 0.01 * on.length / 4 || !/^RectAreaLight ceiling_panel/.test(info.light))
        failures.push(`the example's room (glTF): ${differing} pixels shadowed, the add-on on ${info.light} (the glTF's RectAreaLight "ceiling panel" expected)`);
    failures.push(...problems);
    await page.close();
    console.log(`${failures.length ? "FAIL" : "ok  "} the example's light switch (rect → sun → rect) and its glTF room: ${steps.join("; ")}`);
    return failures;
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    if (!fs.existsSync(args.chromium)) {
        console.log(`skip: no chromium at ${args.chromium} (scripts/setup.sh installs Debian's chromium)`);
        process.exit(77);
    }
    for (const need of ["vite/bin/vite.js", "typescript/bin/tsc", "three/package.json", "three-r180/package.json", "@types/three-r180/package.json"])
        if (!fs.existsSync(path.join(modules, need))) {
            console.log(`error: ${path.join(modules, need)} is missing: scripts/setup.sh runs npm ci in targets/web`);
            process.exit(1);
        }
    const three = path.resolve(args.three), work = path.resolve(args.work);
    fs.mkdirSync(work, {recursive: true});
    let failures = [];
    const table = fs.readFileSync(path.join(three, "emissions.js"), "utf8") === emissionsTable(path.join(three, "emissions"));
    if (!table) failures.push("web/three/emissions.js does not list the files of web/three/emissions/: run node targets/web/three_emissions_table.mjs --write");
    console.log(`${table ? "ok  " : "FAIL"} web/three/emissions.js lists the files of web/three/emissions/`);
    const packed = pack(three, work, args.wasm);
    failures.push(...packed.failures);
    const {app, failures: installFailures} = project(work, packed.tarball);
    failures.push(...installFailures);
    const [tscFailures, ...builds] = await Promise.all([
        typecheck(app),
        ...[["r187", path.join(modules, "three")], ["r180", path.join(modules, "three-r180")]].map(async ([name, dir]) => ({name, ...(await build(app, name, dir))})),
    ]);
    failures.push(...tscFailures);
    for (const b of builds) failures.push(...b.failures);

    const {browser, close} = await launchChromium(args.chromium, WEBGPU_ARGS);
    const roots = {web: path.join(three, "..")};
    for (const b of builds) roots[b.name] = b.out;
    const server = await serve(roots);
    const port = server.address().port;
    try {
        for (const [b, renderer] of builds.flatMap((b) => [[b, "webgl"], [b, "webgpu"]])) {
            const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/${b.name}/index.html?renderer=${renderer}`, "penumbraPackage");
            const name = await page.evaluate(() => window.penumbraPackage.renderer);
            if (renderer === "webgpu" && name !== "WebGPU") failures.push(`?renderer=webgpu runs ${name}`);
            for (const pair of ["rect+rect", "rect+sun"]) {
                const r = await page.evaluate((p) => window.penumbraPackage.run(p), pair);
                r.webgpu = renderer === "webgpu";
                if (r.three !== b.name.slice(1)) failures.push(`the ${b.name} build runs three r${r.three}`);
                failures.push(...checkPair(r, `three r${r.three} ${renderer === "webgpu" ? "WebGPURenderer" : "WebGLRenderer"} (Vite build of the tarball)`));
                if (args.images && b.name === "r187" && renderer === "webgl") {
                    fs.mkdirSync(args.images, {recursive: true});
                    const tag = pair.replace("+", "_");
                    const peak = Math.max(...r.both);
                    await writeGreyPng(path.join(args.images, `${tag}_both.png`), r.width, r.height, r.both.map((x) => x / peak));
                    await writeGreyPng(path.join(args.images, `${tag}_visibility1.png`), r.width, r.height, r.visibility[0]);
                    await writeGreyPng(path.join(args.images, `${tag}_visibility2.png`), r.width, r.height, r.visibility[1]);
                }
            }
            failures.push(...problems);
            await page.close();
        }
        const dev = await devServer(app);
        try {
            const {page, problems} = await openPage(browser, `${dev.url}index.html`, "penumbraPackage");
            failures.push(...checkPair(await page.evaluate(() => window.penumbraPackage.run("rect+rect")), "Vite dev server"));
            failures.push(...problems);
            await page.close();
        } finally {
            dev.stop();
        }
        failures.push(...(await checkExample(browser, port)));
    } catch (e) {
        failures.push(e.message);
    } finally {
        await close();
        server.close();
    }
    for (const f of failures) console.log(`FAIL ${f}`);
    process.exit(failures.length ? 1 : 0);
}

main();
