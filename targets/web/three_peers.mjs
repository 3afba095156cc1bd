// three_peers.mjs — three.js's own shadows as peers: on a built-in scene rebuilt in three.js
// (web/three/test/), three's PCFSoftShadowMap (in r187 an alias of PCFShadowMap: 5 Vogel-disk
// taps over shadow.radius texels) and VSMShadowMap from a SpotLight placed where the rectangle
// is (a DirectionalLight along the sun), Penumbra's add-on and the desktop runtime, all against
// the bundle's Embree ground truth (penumbra-export-bundle --reference N): MAE and p95 over the
// penumbra pixels (truth or estimate < 0.98) and MAE over all geometry pixels, on the fair
// reference (`oriented`: the part of the light above each receiver's tangent plane; NaN pixels
// left out, as playground/src/reference/metrics.cpp does).
//
//   node targets/web/three_peers.mjs --web web [--quick] [--chromium PATH] [--json FILE] [--markdown FILE] BUNDLE_DIR...
//
// three's shadows are shown twice: at three's defaults (radius 1, bias 0) with a 1024² map, and
// at the best setting of a sweep (radius, bias, map size) by fair penumbra MAE — the most a user
// tuning them by eye could get, and more: the sweep picks by the truth itself (--quick: a sweep
// of two settings, for the test suite). Asserts: the add-on's fair penumbra MAE is the desktop
// runtime's within 0.01 (same emission), and each peer casts a shadow (some pixel below 0.5).
// Exit 0 pass, 1 fail, 77 skip (no chromium), 2 bad arguments.
import fs from "node:fs";
import path from "node:path";
import {serve, launchChromium, openPage, readFloats, errorStats} from "./harness.mjs";

const ADDON_TOLERANCE = 0.01;
const SWEEP = {
    PCFSoftShadowMap: {radius: [1, 2, 4, 8, 16, 32, 64, 128], bias: [0, -0.0005, -0.002, -0.005, -0.01, -0.02], mapSize: [1024, 2048]},
    VSMShadowMap: {radius: [1, 4, 8, 16, 32, 64, 128], bias: [0, -0.0005, -0.002, -0.005, -0.01, -0.02], mapSize: [1024, 2048]},
};
const QUICK = {
    PCFSoftShadowMap: {radius: [1, 8], bias: [-0.0005], mapSize: [1024]},
    VSMShadowMap: {radius: [4, 16], bias: [0], mapSize: [1024]},
};
const DEFAULTS = {radius: 1, bias: 0, normalBias: 0, mapSize: 1024};

function parseArguments(argv) {
    const out = {web: null, chromium: "/usr/bin/chromium", json: null, markdown: null, quick: false, bundles: []};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        if (flag === "--quick") out.quick = true;
        else if (["--web", "--chromium", "--json", "--markdown"].includes(flag)) {
            if (i + 1 >= argv.length) usage(`${flag}: missing value`);
            out[flag.slice(2)] = argv[++i];
        } else if (flag.startsWith("--")) usage(`unknown flag '${flag}'; allowed: --web, --chromium, --json, --markdown, --quick`);
        else out.bundles.push(flag);
    }
    if (!out.web) usage("--web: missing");
    if (out.bundles.length === 0) usage("no bundle directories");
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node three_peers.mjs --web DIR [--quick] [--chromium PATH] [--json FILE] [--markdown FILE] BUNDLE_DIR...`);
    process.exit(2);
}

const fmt = (x) => (Number.isFinite(x) ? x.toFixed(4) : "—");

async function measureBundle(browser, port, index, dir, sweeps) {
    const bundle = JSON.parse(fs.readFileSync(path.join(dir, "uniforms.json"), "utf8"));
    if (!bundle.truth) throw new Error(`${dir}: no ground truth (export it with --reference)`);
    const c = bundle.config;
    const lightText = c.light === "sun" ? `sun ${bundle.light.angular_diameter_degrees.toFixed(2)}°` : `rect ${bundle.light.width}×${bundle.light.height}`;
    const label = `${bundle.scene}, ${lightText}, ${bundle.width}x${bundle.height}, truth ${bundle.truth.samples}² rays`;
    const positions = readFloats(path.join(dir, "positions.f32"));
    const geometry = new Uint8Array(positions.length / 4).map((_, i) => (positions[4 * i + 3] !== 0 ? 1 : 0));
    if (bundle.truth.kind !== "oriented") throw new Error(`${dir}: truth of kind '${bundle.truth.kind}'; this measures against 'oriented'`);
    const fair = readFloats(path.join(dir, bundle.truth.file));
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${port}/web/three/test/index.html?bundle=/bundle/${index}/`, "penumbraThree");
    const info = await page.evaluate(() => window.penumbraThree.info());
    const rows = [];
    const measure = (name, setting, estimate) => {
        let darkest = 1;
        for (let i = 0; i < estimate.length; ++i) if (geometry[i]) darkest = Math.min(darkest, estimate[i]);
        const row = {name, setting, fair: errorStats(estimate, fair, geometry), darkest};
        rows.push(row);
        return row;
    };
    const config = `${c.slices} slices, ${c.resolution}², ${c.filter}`;
    const desktop = measure("Penumbra, desktop GL runtime", config, readFloats(path.join(dir, "visibility_gl.f32")));
    const addon = measure("Penumbra three.js add-on", config, Float32Array.from(await page.evaluate(() => window.penumbraThree.visibility())));
    for (const [type, sweep] of Object.entries(sweeps)) {
        const shown = type === "PCFSoftShadowMap" ? "three PCFSoftShadowMap (= PCFShadowMap in r187)" : "three VSMShadowMap";
        const run = async (s) => Float32Array.from(await page.evaluate((t, settings) => window.penumbraThree.peer(t, settings), type, s));
        const settingText = (s) => `map ${s.mapSize}², radius ${s.radius}, bias ${s.bias}`;
        measure(`${shown}, defaults`, settingText(DEFAULTS), await run(DEFAULTS));
        let best = null;
        for (const mapSize of sweep.mapSize)
            for (const radius of sweep.radius)
                for (const bias of sweep.bias) {
                    const s = {...DEFAULTS, mapSize, radius, bias};
                    const estimate = await run(s);
                    const stats = errorStats(estimate, fair, geometry);
                    if (!best || stats.penumbra.mae < best.mae) best = {mae: stats.penumbra.mae, s, estimate};
                }
        measure(`${shown}, best of ${sweep.mapSize.length * sweep.radius.length * sweep.bias.length}`, settingText(best.s), best.estimate);
    }
    await page.close();
    const failures = [...problems];
    if (Math.abs(addon.fair.penumbra.mae - desktop.fair.penumbra.mae) > ADDON_TOLERANCE)
        failures.push(`the add-on's fair penumbra MAE ${fmt(addon.fair.penumbra.mae)} is not the desktop's ${fmt(desktop.fair.penumbra.mae)} within ${ADDON_TOLERANCE}`);
    for (const row of rows) if (row.darkest > 0.5) failures.push(`${row.name} (${row.setting}) casts no shadow (darkest pixel ${row.darkest.toFixed(3)})`);
    return {label, scene: bundle.scene, light: bundle.light, width: bundle.width, height: bundle.height,
            samples: bundle.truth.samples, renderer: info.renderer, three: info.three, rows, failures};
}

function markdown(results) {
    const lines = [];
    for (const r of results) {
        lines.push(`**${r.label}** (three r${r.three}, chromium ${r.renderer}):`, "",
                   "| technique | setting | fair penumbra MAE | fair penumbra p95 | fair all MAE | penumbra px |",
                   "|---|---|---|---|---|---|");
        for (const row of r.rows)
            lines.push(`| ${row.name} | ${row.setting} | ${fmt(row.fair.penumbra.mae)} | ${fmt(row.fair.penumbra.p95)} | ${fmt(row.fair.all.mae)} | ` +
                       `${row.fair.penumbra.count} |`);
        lines.push("");
    }
    return lines.join("\n");
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    const {browser, close} = await launchChromium(args.chromium);
    const roots = {web: args.web};
    args.bundles.forEach((dir, i) => (roots[`bundle/${i}`] = dir));
    const server = await serve(roots);
    const results = [];
    let failures = 0;
    try {
        for (let i = 0; i < args.bundles.length; ++i) {
            const started = Date.now();
            const r = await measureBundle(browser, server.address().port, i, args.bundles[i], args.quick ? QUICK : SWEEP);
            results.push(r);
            failures += r.failures.length;
            console.log(`${r.failures.length ? "FAIL" : "ok  "} ${r.label} (${((Date.now() - started) / 1000).toFixed(1)} s)`);
            for (const f of r.failures) console.log(`     ${f}`);
        }
    } catch (e) {
        console.log(`FAIL ${e.message}`);
        failures += 1;
    } finally {
        await close();
        server.close();
    }
    const text = markdown(results);
    console.log(text);
    if (args.json) fs.writeFileSync(args.json, JSON.stringify(results, null, 2) + "\n");
    if (args.markdown) fs.writeFileSync(args.markdown, text + "\n");
    process.exit(failures ? 1 : 0);
}

main();
