// three_bench.mjs — frame time of the add-on's example (web/three/example/) in Debian's chromium
// (headless, WebGL2 on SwiftShader: CPU rasterization, so compare ratios only): Penumbra's add-on
// with a still light (the shadow phase ran once; each frame pays the visibility in the materials)
// and with a light moving every frame (the shadow phase re-runs every frame), against three.js's
// PCFSoftShadowMap (PCFShadowMap in r187) and VSMShadowMap from a SpotLight (three re-renders
// its shadow map every frame), and no shadows. Prints the median frame time of each and its ratio
// to PCFSoftShadowMap's; asserts nothing about the times.
//
//   node targets/web/three_bench.mjs --web web [--chromium PATH] [--size 960x600] [--frames 20]
//                                    [--light rect|sun] [--emission KEY]
import {serve, launchChromium, openPage} from "./harness.mjs";

function parseArguments(argv) {
    const out = {web: null, chromium: "/usr/bin/chromium", size: "960x600", frames: 20, light: "rect", emission: null};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        if (!["--web", "--chromium", "--size", "--frames", "--light", "--emission"].includes(flag)) usage(`unknown argument '${flag}'`);
        if (i + 1 >= argv.length) usage(`${flag}: missing value`);
        out[flag.slice(2)] = argv[++i];
    }
    if (!out.web) usage("--web: missing");
    if (!/^\d+x\d+$/.test(out.size)) usage(`--size: '${out.size}' is not WxH`);
    out.frames = Number(out.frames);
    if (!Number.isInteger(out.frames) || out.frames < 1 || out.frames > 1000) usage("--frames: an integer from 1 to 1000");
    if (!["rect", "sun"].includes(out.light)) usage(`--light: '${out.light}'; allowed: rect, sun`);
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node three_bench.mjs --web DIR [--chromium PATH] [--size WxH] [--frames N] [--light rect|sun] [--emission KEY]`);
    process.exit(2);
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    const {browser, close} = await launchChromium(args.chromium);
    const server = await serve({web: args.web});
    const [w, h] = args.size.split("x").map(Number);
    let status = 0;
    try {
        const {page, problems} = await openPage(browser, `http://127.0.0.1:${server.address().port}/web/three/example/index.html?size=${args.size}&light=${args.light}`,
                                                "example", {width: w, height: h});
        await page.evaluate(() => window.example.ready);
        if (args.emission) await page.evaluate((e) => window.example.set({emission: e}), args.emission);
        const info = await page.evaluate(() => window.example.info());
        const runs = [
            ["Penumbra add-on, light still", {mode: "penumbra", moving: false}],
            ["Penumbra add-on, light moving (shadow phase every frame)", {mode: "penumbra", moving: true}],
            [`three PCFSoftShadowMap (= PCFShadowMap), ${args.light === "sun" ? "DirectionalLight" : "SpotLight"}`, {mode: "pcf", moving: false}],
            [`three VSMShadowMap, ${args.light === "sun" ? "DirectionalLight" : "SpotLight"}`, {mode: "vsm", moving: false}],
            ["no shadows", {mode: "none", moving: false}],
        ];
        const results = [];
        for (const [name, run] of runs) results.push([name, await page.evaluate((r) => window.example.bench(r), {...run, frames: args.frames})]);
        const pcf = results.find(([n]) => n.startsWith("three PCF"))[1].medianMs;
        const c = info.config;
        console.log(`example ${args.size}, ${args.light} light, ${c.slices} slices ${c.resolution}² ${c.filter}, three r${info.three}, ` +
                    `${args.frames} frames each (median), SwiftShader: ratios only`);
        console.log("| run | median frame (ms) | ratio to PCFSoftShadowMap |\n|---|---|---|");
        for (const [name, r] of results) console.log(`| ${name} | ${r.medianMs.toFixed(1)} | ${(r.medianMs / pcf).toFixed(2)} |`);
        for (const p of problems) console.log(`page: ${p}`);
        await page.close();
    } catch (e) {
        console.log(`FAIL ${e.message}`);
        status = 1;
    } finally {
        await close();
        server.close();
    }
    process.exit(status);
}

main();
