// wgsl_compile.mjs — compiles WGSL modules in Debian's chromium (headless, WebGPU through
// SwiftShader): Chromium's Tint is the WGSL validator (Debian and npm have none). One browser, one
// page, every module: device.createShaderModule + getCompilationInfo().
//
//   node targets/web/wgsl_compile.mjs [--chromium PATH] [--quiet] FILE.wgsl|DIR...
//
// Directories are searched recursively for *.wgsl. Each diagnostic is printed as
// `FILE:LINE:COL: error|warning: message`, then one summary line. Before the files, a module with a
// deliberate error must be reported as an error and a valid one as clean, so that the harness
// cannot pass vacuously (an adapter that reports nothing).
// Exit 0 every module clean (warnings allowed), 1 any error (or the self-check failed), 2 bad
// arguments, 77 (ctest's skip) without chromium, or — only with PENUMBRA_WEBGPU_OPTIONAL=1 — when
// chromium has no WebGPU adapter; without that variable a missing adapter is a failure (CI's
// chromium has WebGPU through SwiftShader, so the test must not skip there silently).
import fs from "node:fs";
import path from "node:path";
import {pathToFileURL} from "node:url";
import {launchChromium, serve, WEBGPU_ARGS} from "./harness.mjs";

const HERE = path.dirname(new URL(import.meta.url).pathname);

// The self-check's modules: one Tint must reject (an undeclared identifier on line 3) and one it must accept.
const BROKEN = "@fragment\nfn main() -> @location(0) vec4f {\n    return vec4f(penumbra_undeclared, 0.0, 0.0, 1.0);\n}\n";
const VALID = "@fragment\nfn main() -> @location(0) vec4f {\n    return vec4f(1.0, 0.0, 0.0, 1.0);\n}\n";

// Chromium with WebGPU on an empty page from 127.0.0.1 and a device in window.penumbraDevice.
// {browser, page, port, adapter: {vendor, architecture, device, description, isFallbackAdapter}, close}.
// Exits 77 without chromium; without an adapter exits 1 (77 with PENUMBRA_WEBGPU_OPTIONAL=1).
// `roots`, `files`: more folders and files to serve (as harness.mjs serve()).
export async function startWebGPU(chromium, roots = {}, files = {}) {
    const server = await serve(roots, {"/": path.join(HERE, "webgpu_page.html"), ...files});
    const {browser, close} = await launchChromium(chromium, WEBGPU_ARGS);
    const port = server.address().port;
    const done = async () => {
        await close();
        server.close();
    };
    try {
        const page = await browser.newPage();
        await page.goto(`http://127.0.0.1:${port}/`);
        const adapter = await page.evaluate(async () => {
            if (!navigator.gpu) return {error: "navigator.gpu is undefined (not a secure context, or WebGPU disabled)"};
            const a = await navigator.gpu.requestAdapter();
            if (!a) return {error: "navigator.gpu.requestAdapter() returned null"};
            window.penumbraDevice = await a.requestDevice();
            const info = a.info || {};
            return {vendor: info.vendor, architecture: info.architecture, device: info.device, description: info.description,
                    isFallbackAdapter: info.isFallbackAdapter ?? a.isFallbackAdapter};
        });
        if (adapter.error) {
            await done();
            const optional = process.env.PENUMBRA_WEBGPU_OPTIONAL === "1";
            console.log(`${optional ? "skip" : "error"}: chromium at ${chromium} has no WebGPU adapter: ${adapter.error}` +
                        (optional ? " (PENUMBRA_WEBGPU_OPTIONAL=1)" : " (set PENUMBRA_WEBGPU_OPTIONAL=1 to skip instead of failing)"));
            process.exit(optional ? 77 : 1);
        }
        return {browser, page, port, adapter, close: done};
    } catch (e) {
        await done();
        throw e;
    }
}

// One line naming the adapter (what ran).
export function adapterLine(adapter) {
    return `WebGPU adapter: vendor '${adapter.vendor}', architecture '${adapter.architecture}'` +
           (adapter.description ? `, '${adapter.description}'` : "") + (adapter.isFallbackAdapter ? " (fallback adapter)" : "");
}

// Compiles [{name, code}] in the page's device: [{name, messages: [{type, line, column, message}]}].
// Each module in its own validation error scope, so an invalid one does not reach the console as an
// uncaptured error.
export async function compileModules(page, modules) {
    return page.evaluate(async (list) => {
        const device = window.penumbraDevice;
        const out = [];
        for (const {name, code} of list) {
            device.pushErrorScope("validation");
            const module = device.createShaderModule({label: name, code});
            const info = await module.getCompilationInfo();
            const scope = await device.popErrorScope();
            const messages = info.messages.map((m) => ({type: m.type, line: m.lineNum, column: m.linePos, message: m.message}));
            // a validation error without a compilation message (should not happen) still counts
            if (scope && !messages.some((m) => m.type === "error")) messages.push({type: "error", line: 0, column: 0, message: scope.message});
            out.push({name, messages});
        }
        return out;
    }, modules);
}

// Every *.wgsl under each argument (a file is taken as given), sorted per directory.
function collect(inputs) {
    const files = [];
    const walk = (dir) => {
        for (const entry of fs.readdirSync(dir, {withFileTypes: true}).sort((a, b) => a.name.localeCompare(b.name))) {
            const p = path.join(dir, entry.name);
            if (entry.isDirectory()) walk(p);
            else if (entry.isFile() && entry.name.endsWith(".wgsl")) files.push(p);
        }
    };
    for (const input of inputs) {
        if (!fs.existsSync(input)) usage(`${input}: no such file or directory`);
        if (fs.statSync(input).isDirectory()) walk(input);
        else files.push(input);
    }
    return files;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node wgsl_compile.mjs [--chromium PATH] [--quiet] FILE.wgsl|DIR...`);
    process.exit(2);
}

async function main() {
    const args = {chromium: "/usr/bin/chromium", quiet: false, inputs: []};
    const argv = process.argv.slice(2);
    for (let i = 0; i < argv.length; ++i) {
        if (argv[i] === "--chromium") {
            if (i + 1 >= argv.length) usage("--chromium: missing value");
            args.chromium = argv[++i];
        } else if (argv[i] === "--quiet") {
            args.quiet = true;
        } else if (argv[i].startsWith("--")) {
            usage(`unknown flag '${argv[i]}'; allowed: --chromium PATH, --quiet`);
        } else {
            args.inputs.push(argv[i]);
        }
    }
    if (args.inputs.length === 0) usage("no WGSL files or directories given");
    const files = collect(args.inputs);
    if (files.length === 0) usage(`no .wgsl files in ${args.inputs.join(", ")}`);
    const modules = files.map((f) => ({name: f, code: fs.readFileSync(f, "utf8")}));

    const started = Date.now();
    const gpu = await startWebGPU(args.chromium);
    let failed = false;
    try {
        if (!args.quiet) console.log(adapterLine(gpu.adapter));
        // The self-check: the broken module must fail (on line 3), the valid one must not.
        const [broken, valid] = await compileModules(gpu.page, [{name: "self-check-broken", code: BROKEN},
                                                                {name: "self-check-valid", code: VALID}]);
        const brokenErrors = broken.messages.filter((m) => m.type === "error");
        if (brokenErrors.length === 0 || brokenErrors[0].line !== 3) {
            console.log(`error: self-check: chromium reported ${JSON.stringify(broken.messages)} for a module with an undeclared ` +
                        "identifier on line 3; a harness that sees no error there proves nothing");
            process.exitCode = 1;
            return;
        }
        if (valid.messages.some((m) => m.type === "error")) {
            console.log(`error: self-check: chromium rejected a valid module: ${JSON.stringify(valid.messages)}`);
            process.exitCode = 1;
            return;
        }
        const results = await compileModules(gpu.page, modules);
        let errors = 0, warnings = 0, failedModules = 0;
        for (const {name, messages} of results) {
            let bad = false;
            for (const m of messages) {
                if (m.type === "info") continue;
                if (m.type === "error") { ++errors; bad = true; } else ++warnings;
                console.log(`${name}:${m.line}:${m.column}: ${m.type}: ${m.message}`);
            }
            if (bad) ++failedModules;
        }
        failed = errors > 0;
        console.log(`${failed ? "FAIL" : "ok"}: ${results.length} WGSL modules compiled, ${results.length - failedModules} clean, ` +
                    `${errors} errors, ${warnings} warnings (self-check: the broken module's error reported at line 3) ` +
                    `in ${((Date.now() - started) / 1000).toFixed(1)} s`);
        process.exitCode = failed ? 1 : 0;
    } finally {
        await gpu.close();
    }
}

if (import.meta.url === pathToFileURL(process.argv[1]).href) main().catch((e) => {
    console.log(`error: ${e.message}`);
    process.exit(1);
});
