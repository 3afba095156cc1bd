// three_screenshots.mjs — screenshots of the add-on's example (web/three/example/) in Debian's
// chromium (headless, SwiftShader), for the README and reviews:
//
//   node targets/web/three_screenshots.mjs --web web --out DIR [--chromium PATH] [--size 960x600]
//                                          [--wasm build/wasm/penumbra_emitter.wasm] [--renderer webgl|webgpu]
//
// Writes DIR/example_*.png: the RectAreaLight at the example's settings and enlarged, the same
// scene with three's PCFSoftShadowMap and VSMShadowMap from a SpotLight, the sun, and the room (a
// closed room lit by a ceiling panel, the camera inside); with --wasm
// also example_emitted.png: a configuration emitted in the page (8 slices, 256², mip-mapped texture array).
import fs from "node:fs";
import path from "node:path";
import {serve, launchChromium, openPage, WEBGPU_ARGS} from "./harness.mjs";

const SHOTS = [
    ["example_rect", {}],
    ["example_rect_large", {width: 6, height: 4}],
    ["example_three_pcf", {mode: "pcf", width: 3, height: 2}],
    ["example_three_vsm", {mode: "vsm"}],
    ["example_sun", {mode: "penumbra", light: "sun"}],
    ["example_room", {light: "rect", scene: "room"}],
];

function parseArguments(argv) {
    // --renderer webgpu: the example on WebGPURenderer (?renderer=webgpu), files example_*_webgpu.png
    const out = {web: null, out: null, chromium: "/usr/bin/chromium", size: "960x600", wasm: null, renderer: "webgl"};
    for (let i = 0; i < argv.length; i += 2) {
        const flag = argv[i];
        if (!["--web", "--out", "--chromium", "--size", "--wasm", "--renderer"].includes(flag) || i + 1 >= argv.length) {
            console.error(`error: bad argument '${flag}'\nusage: node three_screenshots.mjs --web DIR --out DIR [--chromium PATH] [--size WxH] [--wasm FILE]`);
            process.exit(2);
        }
        out[flag.slice(2)] = argv[i + 1];
    }
    if (!out.web || !out.out || !/^\d+x\d+$/.test(out.size) || !["webgl", "webgpu"].includes(out.renderer)) {
        console.error("error: --web and --out are required, --size is WxH, --renderer webgl or webgpu");
        process.exit(2);
    }
    return out;
}

const args = parseArguments(process.argv.slice(2));
// WebGPU: the frame through the example's render target (capture(); a presented WebGPU canvas loses
// its device in headless chromium on SwiftShader), without the panel; WebGL2: the page as shown.
async function shoot(page, file) {
    if (args.renderer !== "webgpu") return page.screenshot({path: file});
    const url = await page.evaluate(() => window.example.capture());
    fs.writeFileSync(file, Buffer.from(url.slice(url.indexOf(",") + 1), "base64"));
}
const [width, height] = args.size.split("x").map(Number);
const {browser, close} = await launchChromium(args.chromium, args.renderer === "webgpu" ? WEBGPU_ARGS : []);
const suffix = args.renderer === "webgpu" ? "_webgpu" : "";
const roots = {web: args.web};
if (args.wasm) roots.wasm = path.dirname(path.resolve(args.wasm));
const server = await serve(roots);
let status = 0;
try {
    fs.mkdirSync(args.out, {recursive: true});
    const {page, problems} = await openPage(browser, `http://127.0.0.1:${server.address().port}/web/three/example/index.html?size=${args.size}&renderer=${args.renderer}${args.renderer === "webgpu" ? "&offscreen=1" : ""}${args.wasm ? `&wasm=/wasm/${path.basename(args.wasm)}` : ""}`,
                                            "example", {width, height});
    await page.evaluate(() => window.example.ready);
    for (const [name, changes] of SHOTS) {
        await page.evaluate((c) => window.example.set(c), changes);
        const file = path.join(args.out, `${name}${suffix}.png`);
        await shoot(page, file);
        console.log(`wrote ${file}`);
    }
    if (args.wasm) {
        await page.evaluate(() => window.example.set({mode: "penumbra", light: "rect", scene: "shapes", width: 3, height: 2}));
        const config = await page.evaluate((webgpu) => window.example.emit({slices: 8, resolution: 256, filter: webgpu ? "nbuffer" : "mipmap",
                                                                             packing: webgpu ? "atlas" : "array"}), args.renderer === "webgpu");
        const file = path.join(args.out, `example_emitted${suffix}.png`);
        await shoot(page, file);
        console.log(`wrote ${file} (${config.slices} slices, ${config.resolution}², ${config.filter}, emitted in the page)`);
    }
    for (const p of problems) console.log(`page: ${p}`);
    if (problems.length) status = 1;
} catch (e) {
    console.log(`FAIL ${e.message}`);
    status = 1;
} finally {
    await close();
    server.close();
}
process.exit(status);
