// bundle_test.mjs — the `bundler-<bundler>` tests: the packed add-ons (npm pack tarballs) as a new
// user's project bundles them, with one of Vite, esbuild, webpack 5 or Rollup, then the built
// pages run in Debian's chromium (headless, WebGL2 through SwiftShader).
//   1. A fresh project (WORK/app) installs the tarballs with npm, offline, beside three (and
//      @babylonjs/core) linked from this folder's node_modules (scripts/setup.sh installs them).
//   2. The bundler builds one page per package (bundle_pages/<package>.js: a ground, a box casting,
//      one shadowed light) with no configuration beyond what its documentation gives for assets:
//      Vite and webpack 5 copy the `new URL("./…", import.meta.url)` assets (the emissions, the
//      WebAssembly emitter) themselves; esbuild and Rollup leave those URLs to the page, so the
//      package's emissions/ and penumbra_emitter.wasm are copied beside the bundle (web/three/README.md).
//      No `node:` import may reach a browser bundle (the emitter's node half sits behind the
//      "node" condition of package.json's exports).
//   3. In chromium each page renders lit without the add-on and lit with it: (lit with) / (lit
//      without) is the add-on's visibility at the lit pixels, the box's shadow covers a share of the
//      ground and the rest is lit; update() after dispose() throws the add-on's error. The Babylon
//      page has two lights (a RectAreaLight and a sun), one add-on each on one material: each scales
//      its own light's term only, both on is the sum of each alone, and the first light's image is
//      unchanged after the second add-on's dispose(); on a StandardMaterial and on a PBRMaterial.
//      The React Three Fiber page (Vite): web/three/r3f's <PenumbraShadows> component shadows the
//      canvas, useFrame updates it, and unmounting disposes it.
// The bundle's size (its JavaScript, unminified, and gzipped; the assets apart) is printed.
//
//   node targets/web/bundle_test.mjs --bundler vite|esbuild|webpack|rollup --work DIR --tarball three=FILE
//        [--tarball babylon=FILE] [--tarball r3f=FILE (Vite only; penumbra-three's)] [--chromium PATH]
//
// Exit 0 pass, 1 fail, 77 skip (no chromium), 2 bad arguments.
import fs from "node:fs";
import path from "node:path";
import zlib from "node:zlib";
import {fileURLToPath} from "node:url";
import {serve, launchChromium, openPage, run} from "./harness.mjs";
import {ltcTables, serveLtc} from "./ltc_tables.mjs";

const here = path.dirname(fileURLToPath(import.meta.url));
const modules = path.join(here, "node_modules");
const BUNDLERS = ["vite", "esbuild", "webpack", "rollup"];
// the npm package of each page, the peer dependencies its project links from node_modules here, and
// the package's folder of emissions/ and penumbra_emitter.wasm
const PACKAGES = {
    three: {name: "penumbra-three", peers: ["three"], assets: "."},
    babylon: {name: "penumbra-babylon", peers: ["@babylonjs/core"], assets: "shared"},
    // React Three Fiber (Vite only): the example's hook copied into the project, as a user does
    r3f: {name: "penumbra-three", peers: ["three", "react", "react-dom", "@react-three/fiber"], assets: ".", entry: "r3f.jsx",
          copied: ["../../web/three/r3f/usePenumbraShadows.js"]},
};
const RATIO_TOLERANCE = 0.01; // (lit with) / (lit without) against the visibility, both float
const PIXELS_ALLOWED = 0.01;  // share of lit pixels allowed outside it
const SHADOW_PIXELS = 0.03;   // share of the image in the box's shadow (visibility < 0.5), at least
const LIT_PIXELS = 0.3;       // share of the image fully lit (visibility > 0.9), at least

function parseArguments(argv) {
    const out = {bundler: null, work: null, chromium: "/usr/bin/chromium", tarballs: {}};
    for (let i = 0; i < argv.length; i += 2) {
        const flag = argv[i], value = argv[i + 1];
        if (!["--bundler", "--work", "--chromium", "--tarball"].includes(flag))
            usage(`unknown argument '${flag}'; allowed: --bundler, --work, --tarball, --chromium`);
        if (value === undefined) usage(`${flag}: missing value`);
        if (flag === "--tarball") {
            const [page, file] = value.split(/=(.*)/s);
            if (!PACKAGES[page] || !file) usage(`--tarball ${value}: wanted PAGE=FILE with PAGE one of ${Object.keys(PACKAGES).join(", ")}`);
            out.tarballs[page] = path.resolve(file);
        } else {
            out[flag.slice(2)] = value;
        }
    }
    if (out.tarballs.r3f && out.bundler !== "vite") usage("--tarball r3f=FILE: the React Three Fiber page is built with Vite only");
    if (!BUNDLERS.includes(out.bundler)) usage(`--bundler '${out.bundler}': allowed ${BUNDLERS.join(", ")}`);
    if (!out.work || !Object.keys(out.tarballs).length) usage("--work and at least one --tarball are required");
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node bundle_test.mjs --bundler vite|esbuild|webpack|rollup --work DIR --tarball three=FILE [--tarball babylon=FILE] [--chromium PATH]`);
    process.exit(2);
}

// 1. the fresh project
function project(work, tarballs) {
    const app = path.join(work, "app");
    fs.rmSync(app, {recursive: true, force: true});
    fs.mkdirSync(app, {recursive: true});
    const dependencies = {};
    for (const [page, tarball] of Object.entries(tarballs)) {
        for (const f of [PACKAGES[page].entry ?? `${page}.js`, `${page}.html`]) fs.copyFileSync(path.join(here, "bundle_pages", f), path.join(app, f));
        for (const f of PACKAGES[page].copied ?? []) fs.copyFileSync(path.join(here, f), path.join(app, path.basename(f)));
        dependencies[PACKAGES[page].name] = `file:${tarball}`;
        for (const peer of PACKAGES[page].peers) {
            if (!fs.existsSync(path.join(modules, peer, "package.json")))
                throw new Error(`${path.join(modules, peer)} is missing: scripts/setup.sh runs npm ci in targets/web`);
            dependencies[peer] = `file:${path.join(modules, peer)}`;
        }
    }
    fs.writeFileSync(path.join(app, "package.json"), JSON.stringify({name: "penumbra-bundle-user", private: true, type: "module", dependencies}, null, 2));
    const started = Date.now();
    // (--legacy-peer-deps: npm 11's arborist fails to place a peer dependency met by a linked scoped
    // package, @babylonjs/core here: "Cannot read properties of null (reading 'matches')")
    run("npm", ["install", "--offline", "--no-audit", "--no-fund", "--loglevel=error", "--legacy-peer-deps"], {cwd: app});
    return {app, seconds: (Date.now() - started) / 1000};
}

// 2. the bundlers, each as its documentation shows; they write dist/<page>.js (and chunks)
const build = {
    async vite(app, pages, dist) {
        fs.writeFileSync(path.join(app, "vite.config.js"), `export default {
    base: "./",
    logLevel: "warn",
    esbuild: {jsx: "automatic"}, // (JSX without @vitejs/plugin-react: React's automatic runtime)
    build: {outDir: ${JSON.stringify(dist)}, emptyOutDir: true, minify: false,
            rollupOptions: {input: ${JSON.stringify(Object.fromEntries(pages.map((p) => [p, `${p}.html`])))}}},
};
`);
        return run(process.execPath, [path.join(modules, "vite/bin/vite.js"), "build"], {cwd: app});
    },
    async esbuild(app, pages, dist) {
        const {build} = await import("esbuild");
        const result = await build({entryPoints: pages.map((p) => path.join(app, `${p}.js`)), bundle: true, format: "esm",
                                    splitting: true, outdir: dist, absWorkingDir: app, logLevel: "silent"});
        return result.warnings.map((w) => w.text).join("\n");
    },
    async webpack(app, pages, dist) {
        const {default: webpack} = await import("webpack");
        const config = {mode: "production", target: "web", context: app,
                        entry: Object.fromEntries(pages.map((p) => [p, `./${p}.js`])),
                        output: {path: dist, filename: "[name].js", clean: true},
                        optimization: {minimize: false}, performance: {hints: false}};
        const stats = await new Promise((resolve, reject) => webpack(config, (e, s) => (e ? reject(e) : resolve(s))));
        const text = stats.toString({all: false, errors: true, warnings: true});
        if (stats.hasErrors()) throw new Error(`webpack: ${text}`);
        return text;
    },
    async rollup(app, pages, dist) {
        const {rollup} = await import("rollup");
        const {nodeResolve} = await import("@rollup/plugin-node-resolve");
        const warnings = [];
        const bundle = await rollup({input: Object.fromEntries(pages.map((p) => [p, path.join(app, `${p}.js`)])),
                                     plugins: [nodeResolve({browser: true})], onwarn: (w) => warnings.push(w.message)});
        await bundle.write({dir: dist, format: "es"});
        await bundle.close();
        return warnings.join("\n");
    },
};

// esbuild and Rollup leave `new URL("./…", import.meta.url)` alone: the package's assets go beside the bundle
function copyAssets(app, pages, dist) {
    for (const page of pages) {
        const installed = path.join(app, "node_modules", PACKAGES[page].name, PACKAGES[page].assets);
        fs.cpSync(path.join(installed, "emissions"), path.join(dist, "emissions"), {recursive: true});
        fs.copyFileSync(path.join(installed, "penumbra_emitter.wasm"), path.join(dist, "penumbra_emitter.wasm"));
    }
}

function sizes(dist) {
    let js = 0, gzip = 0, assets = 0, files = 0;
    const walk = (dir) => {
        for (const entry of fs.readdirSync(dir, {withFileTypes: true})) {
            const file = path.join(dir, entry.name);
            if (entry.isDirectory()) { walk(file); continue; }
            ++files;
            const bytes = fs.readFileSync(file);
            if (/\.m?js$/.test(entry.name)) {
                js += bytes.length;
                gzip += zlib.gzipSync(bytes).length;
                if (/(\bfrom\s*|\bimport\s*\(\s*|\brequire\s*\(\s*)["'`]node:/.test(bytes.toString("utf8"))) nodeImports.push(path.relative(dist, file));
            } else if (!/\.html$/.test(entry.name)) {
                assets += bytes.length;
            }
        }
    };
    const nodeImports = [];
    walk(dist);
    return {js, gzip, assets, files, nodeImports};
}

// 3. one page's images: per light (lit with the add-on) / (lit without) is the add-on's visibility, its
// shadow is there and the rest lit; with several lights, both on is the sum of each alone and the
// first is unchanged after the second add-on's dispose()
export function check(r) {
    if (r.kind === "r3f") return checkR3F(r);
    const failures = [], stats = [];
    const n = r.width * r.height;
    r.unshadowed.forEach((u, k) => {
        const s = r.shadowed[k], v = r.visibility[k];
        const peak = Math.max(...u);
        let lit = 0, outside = 0, worst = 0;
        for (let i = 0; i < n; ++i) {
            if (!(u[i] > 1e-3 * peak)) continue;
            ++lit;
            const d = Math.abs(s[i] / u[i] - v[i]);
            worst = Math.max(worst, d);
            if (!(d <= RATIO_TOLERANCE)) ++outside;
        }
        const shadow = v.filter((x) => x < 0.5).length, full = v.filter((x) => x > 0.9).length;
        const light = `${r.lights[k]}`;
        if (lit < 0.5 * n) failures.push(`the ${light} lights only ${lit} of ${n} pixels`);
        if (outside > PIXELS_ALLOWED * lit)
            failures.push(`${light}: (lit with the add-on) / (lit without) is not its visibility at ${outside} of ${lit} lit pixels (max |Δ| ${worst.toFixed(3)})`);
        if (shadow < SHADOW_PIXELS * n) failures.push(`${light}: the box's shadow covers ${shadow} pixels (visibility < 0.5); wanted ≥ ${SHADOW_PIXELS * n}`);
        if (full < LIT_PIXELS * n) failures.push(`${light}: only ${full} pixels are lit (visibility > 0.9); wanted ≥ ${LIT_PIXELS * n}`);
        stats.push(`${light}: shadow on ${shadow} of ${n} pixels, lit ${full}, ratio vs visibility max |Δ| ${worst.toFixed(4)} (${outside} of ${lit} over ${RATIO_TOLERANCE})`);
    });
    if (r.both) {
        let worst = 0, peak = 0;
        for (let i = 0; i < n; ++i) {
            worst = Math.max(worst, Math.abs(r.both[i] - r.shadowed[0][i] - r.shadowed[1][i]));
            peak = Math.max(peak, r.both[i]);
        }
        if (!(worst <= 1e-3 * peak)) failures.push(`both lights on is not the sum of each alone (max |Δ| ${worst} of ${peak})`);
        stats.push(`both on vs the sum max |Δ| ${worst.toExponential(1)}`);
    }
    if (r.firstAfterDispose) {
        let worst = 0;
        for (let i = 0; i < n; ++i) worst = Math.max(worst, Math.abs(r.firstAfterDispose[i] - r.shadowed[0][i]));
        if (!(worst <= 1e-4 * Math.max(...r.shadowed[0]))) failures.push(`after the second add-on's dispose() the first light's image changed by ${worst}`);
    }
    if (!/update\(\) after dispose\(\)/.test(r.afterDispose)) failures.push(`update() after dispose(): ${r.afterDispose}`);
    return {failures, summary: `${r.library}: ${stats.join("; ")}`};
}

// The R3F page: the component's shadow is on the canvas (pixels differing from the frame after it
// unmounted), useFrame updated the add-on, and unmounting disposed it.
function checkR3F(r) {
    const failures = [];
    let differing = 0;
    for (let i = 0; i < r.on.length; i += 4)
        if (Math.abs(r.on[i] - r.off[i]) + Math.abs(r.on[i + 1] - r.off[i + 1]) + Math.abs(r.on[i + 2] - r.off[i + 2]) > 12) ++differing;
    const n = r.width * r.height;
    if (differing < SHADOW_PIXELS * n) failures.push(`with <PenumbraShadows> mounted the canvas differs from the frame after unmounting at ${differing} of ${n} pixels only`);
    if (!(r.updates >= 1)) failures.push("useFrame never ran the add-on's update()");
    if (!r.disposed) failures.push("unmounting <PenumbraShadows> did not dispose the add-on");
    return {failures, summary: `${r.library}: the mounted component's shadow on ${differing} of ${n} pixels, ${r.updates} shadow update(s), disposed on unmount: ${r.disposed}`};
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    if (!fs.existsSync(args.chromium)) {
        console.log(`skip: no chromium at ${args.chromium} (scripts/setup.sh installs Debian's chromium)`);
        process.exit(77);
    }
    for (const tarball of Object.values(args.tarballs))
        if (!fs.existsSync(tarball)) usage(`${tarball}: no such tarball (the pack-web-packages test writes it)`);
    const work = path.resolve(args.work);
    fs.mkdirSync(work, {recursive: true});
    const pages = Object.keys(args.tarballs);
    const failures = [];
    const {app, seconds: installSeconds} = project(work, args.tarballs);
    console.log(`ok   npm install --offline of ${pages.map((p) => PACKAGES[p].name).join(", ")} into a fresh project (${installSeconds.toFixed(1)} s)`);
    // each page its own build (dist-<page>/), so that each package's bundle size is its own
    const dists = {};
    for (const page of pages) {
        const dist = dists[page] = path.join(work, `dist-${page}`);
        fs.rmSync(dist, {recursive: true, force: true});
        const started = Date.now();
        const warnings = (await build[args.bundler](app, [page], dist)).trim();
        if (args.bundler === "esbuild" || args.bundler === "rollup") copyAssets(app, [page], dist);
        if (args.bundler !== "vite") fs.copyFileSync(path.join(app, `${page}.html`), path.join(dist, `${page}.html`));
        const size = sizes(dist);
        if (size.nodeImports.length) failures.push(`a node: import in the browser bundle: ${size.nodeImports.join(", ")}`);
        console.log(`${size.nodeImports.length ? "FAIL" : "ok  "} ${args.bundler} build of the ${page} page (${PACKAGES[page].name}) in ${((Date.now() - started) / 1000).toFixed(1)} s: ` +
                    `${(size.js / 1024).toFixed(0)} KiB of JavaScript unminified (${(size.gzip / 1024).toFixed(0)} KiB gzipped, lazy chunks included), ` +
                    `${(size.assets / 1024).toFixed(0)} KiB of assets, ${size.files} files` + (warnings ? `\n     ${warnings.split("\n").join("\n     ")}` : ""));
    }

    const {browser, close} = await launchChromium(args.chromium);
    const server = await serve(dists);
    try {
        for (const page of pages) {
            const ltc = page === "babylon" ? await ltcTables() : null;
            const {page: tab, problems} = await openPage(browser, `http://127.0.0.1:${server.address().port}/${page}/${page}.html`, "bundleCheck",
                                                         undefined, ltc ? (p) => serveLtc(p, ltc) : null);
            for (const material of await tab.evaluate(() => window.bundleCheck.materials)) {
                const r = await tab.evaluate((m) => window.bundleCheck.run(m), material);
                if (r.error) throw new Error(`${page}.html: ${r.error}`);
                const {failures: pageFailures, summary} = check(r);
                failures.push(...pageFailures.map((f) => `${page}.html (${material}): ${f}`));
                console.log(`${pageFailures.length ? "FAIL" : "ok  "} ${args.bundler}, the ${page} page (${PACKAGES[page].name}) in chromium: ${summary}`);
            }
            failures.push(...problems.map((f) => `${page}.html: ${f}`));
            await tab.close();
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

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) main();
