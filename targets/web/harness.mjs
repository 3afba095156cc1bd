// harness.mjs — what the three.js add-on's browser tests share (three_test.mjs, three_peers.mjs,
// three_bench.mjs): a localhost static server over named folders, Debian's chromium through
// puppeteer-core (headless, WebGL2 on SwiftShader), and raw float32 files.
import {execFileSync} from "node:child_process";
import fs from "node:fs";
import http from "node:http";
import os from "node:os";
import path from "node:path";

const CONTENT_TYPES = {".html": "text/html", ".js": "text/javascript", ".mjs": "text/javascript", ".json": "application/json",
                       ".wasm": "application/wasm"};

// A command's standard output; its exit status, output and errors in the exception when it fails
// (the package and bundler tests: npm, tsc, the bundlers).
export function run(command, args, options = {}) {
    try {
        return execFileSync(command, args, {encoding: "utf8", stdio: ["ignore", "pipe", "pipe"], ...options});
    } catch (e) {
        throw new Error(`${[command, ...args].join(" ")} failed (exit ${e.status}):\n${e.stdout || ""}${e.stderr || ""}`);
    }
}

// Headless chromium's flags for WebGL2 on SwiftShader in a container (every browser test).
export const CHROMIUM_ARGS = ["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
                              "--disable-background-networking", "--disable-component-update", "--disable-sync",
                              "--no-first-run", "--disable-quic", "--disable-extensions",
                              "--disable-dev-shm-usage"]; // containers often have a tiny /dev/shm
// Added for WebGPU on SwiftShader (navigator.gpu exists only on a page served from 127.0.0.1, not about:blank).
export const WEBGPU_ARGS = ["--enable-unsafe-webgpu", "--use-webgpu-adapter=swiftshader"];

// Serves /<prefix>/... from roots[prefix] (longest prefix first) and each URL path of `files` from
// its file, on 127.0.0.1 only.
export function serve(roots, files = {}) {
    const entries = Object.entries(roots).map(([prefix, dir]) => [prefix, path.resolve(dir)])
        .sort((a, b) => b[0].length - a[0].length);
    const send = (response, file) => {
        response.writeHead(200, {"Content-Type": CONTENT_TYPES[path.extname(file)] || "application/octet-stream",
                                 "Cache-Control": "no-store"});
        fs.createReadStream(file).pipe(response);
    };
    const server = http.createServer((request, response) => {
        const url = decodeURIComponent(new URL(request.url, "http://localhost").pathname);
        if (files[url]) return send(response, files[url]);
        for (const [prefix, root] of entries) {
            if (!url.startsWith(`/${prefix}/`)) continue;
            const file = path.join(root, url.slice(prefix.length + 2));
            if (!file.startsWith(root) || !fs.existsSync(file) || !fs.statSync(file).isFile()) break;
            send(response, file);
            return;
        }
        response.writeHead(404);
        response.end();
    });
    return new Promise((resolve) => server.listen(0, "127.0.0.1", () => resolve(server)));
}

// Exit 77 (ctest's skip) without chromium; exit 1 without puppeteer-core. `extraArgs`: e.g. WEBGPU_ARGS.
export async function launchChromium(executablePath, extraArgs = []) {
    if (!fs.existsSync(executablePath)) {
        console.log(`skip: no chromium at ${executablePath} (scripts/setup.sh installs Debian's chromium)`);
        process.exit(77);
    }
    let puppeteer;
    try {
        ({default: puppeteer} = await import("puppeteer-core"));
    } catch (e) {
        console.log(`error: puppeteer-core is not installed next to this script (scripts/setup.sh runs npm ci in targets/web): ${e.message}`);
        process.exit(1);
    }
    const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), "penumbra-chromium-"));
    const browser = await puppeteer.launch({
        executablePath,
        headless: true,
        userDataDir,
        protocolTimeout: 600000,
        args: [...CHROMIUM_ARGS, ...extraArgs],
    });
    const close = async () => {
        await browser.close();
        fs.rmSync(userDataDir, {recursive: true, force: true});
    };
    return {browser, close};
}

// Opens `url`, waits for window[name] and fails with the page's own error when it set one.
// `prepare(page)`, when given, runs before the page loads (request interception, say).
export async function openPage(browser, url, name, viewport = {width: 800, height: 600}, prepare = null) {
    const page = await browser.newPage();
    if (prepare) await prepare(page);
    await page.setViewport(viewport);
    const problems = [];
    page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
    // (the example probes for the optional WebAssembly emitter: its 404 is no problem)
    page.on("console", (m) => m.type() === "error" && !/penumbra_emitter/.test(m.location()?.url || "") &&
                              problems.push(`console: ${m.text()}`));
    await page.goto(url);
    await page.waitForFunction((n) => window[n] !== undefined, {timeout: 120000}, name);
    const error = await page.evaluate((n) => window[n].error, name);
    if (error) throw new Error(`${url}: the page failed: ${error}`);
    return {page, problems};
}

export function readFloats(file) {
    const bytes = fs.readFileSync(file);
    return new Float32Array(bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.length));
}

// MAE / p95 over the geometry pixels whose reference is not NaN; "penumbra": where the reference
// or the estimate is below 0.98 (playground/src/reference/metrics.cpp).
export function errorStats(estimate, reference, geometry) {
    const all = [], penumbra = [];
    for (let i = 0; i < estimate.length; ++i) {
        if (!geometry[i] || Number.isNaN(reference[i])) continue;
        const e = Math.abs(estimate[i] - reference[i]);
        all.push(e);
        if (reference[i] < 0.98 || estimate[i] < 0.98) penumbra.push(e);
    }
    const stats = (v) => {
        if (v.length === 0) return {mae: NaN, p95: NaN, count: 0};
        const mae = v.reduce((s, x) => s + x, 0) / v.length;
        const sorted = Float64Array.from(v).sort();
        const k = Math.min(v.length - 1, Math.ceil(0.95 * v.length) - 1);
        return {mae, p95: sorted[k], count: v.length};
    };
    return {all: stats(all), penumbra: stats(penumbra)};
}

// A grey PNG of `values` (0..1, width × height, bottom row first), for looking at images.
export async function writeGreyPng(file, width, height, values) {
    const zlib = await import("node:zlib");
    const rows = Buffer.alloc((width + 1) * height);
    for (let y = 0; y < height; ++y)
        for (let x = 0; x < width; ++x) {
            const v = values[(height - 1 - y) * width + x];
            rows[y * (width + 1) + 1 + x] = Number.isFinite(v) ? Math.round(255 * Math.min(Math.max(v, 0), 1)) : 0;
        }
    const chunk = (type, data) => {
        const length = Buffer.alloc(4), crc = Buffer.alloc(4), body = Buffer.concat([Buffer.from(type), data]);
        length.writeUInt32BE(data.length);
        crc.writeUInt32BE(zlib.crc32(body) >>> 0);
        return Buffer.concat([length, body, crc]);
    };
    const header = Buffer.alloc(13);
    header.writeUInt32BE(width, 0);
    header.writeUInt32BE(height, 4);
    header[8] = 8; // bit depth
    header[9] = 0; // grey
    fs.writeFileSync(file, Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk("IHDR", header),
                                          chunk("IDAT", zlib.deflateSync(rows)), chunk("IEND", Buffer.alloc(0))]));
}
