// copy_shared.mjs — puts into shared/ the modules penumbra-babylon shares with penumbra-three, from
// their one place, web/three/ (the layout runners, WebGL2's and WebGPU's, the light frame, the emission's files and the
// snippet's parameters, the WebAssembly emitter, the shipped emissions): npm runs it as "prepare"
// (npm ci / npm install here) and, with --pack, as "prepack" (npm pack / npm publish), which also
// puts in the emitter's .wasm (built by `cmake --build build --target penumbra-emitter-wasm`; another
// build with PENUMBRA_EMITTER_WASM=FILE) and the repository's LICENSE. shared/ is not tracked.
import fs from "node:fs";
import path from "node:path";
import {fileURLToPath} from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.join(here, "../..");
const three = path.join(root, "web/three");
export const SHARED = ["penumbra_runner.js", "penumbra_webgpu_runner.js", "light_frame.js", "penumbra_emission.js", "penumbra_emission.d.ts", "penumbra_emitter.js",
                       "penumbra_emitter_node.js", "penumbra_emitter.d.ts", "emissions.js", "emissions"];
const pack = process.argv.includes("--pack");

// Each file whole or not at all (a copy beside it, then a rename): a page or test reading the
// package folder while this runs never sees half a file.
function copyWhole(from, to) {
    fs.mkdirSync(path.dirname(to), {recursive: true});
    fs.copyFileSync(from, `${to}.partial`);
    fs.renameSync(`${to}.partial`, to);
}
function copy(from, to) {
    if (fs.statSync(from).isDirectory()) {
        for (const name of fs.readdirSync(from)) if (name !== "regenerate.sh") copy(path.join(from, name), path.join(to, name));
    } else {
        copyWhole(from, to);
    }
}
// The emissions are penumbra-gen's output, written by the build (or web/three's prepack), not tracked:
// npm ci's "prepare" runs before the first build and copies what there is; packing needs them.
if (pack && !fs.readdirSync(path.join(three, "emissions")).some((name) => name.endsWith("-wgsl"))) {
    console.error(`error: ${path.join(three, "emissions")} holds no emission: build first (cmake --build build ` +
                  "writes them) or run npm pack in web/three; the package ships the emissions");
    process.exit(1);
}
for (const name of SHARED) copy(path.join(three, name), path.join(here, "shared", name));
const wasm = process.env.PENUMBRA_EMITTER_WASM || [path.join(three, "penumbra_emitter.wasm"), path.join(root, "build/wasm/penumbra_emitter.wasm")].find((f) => fs.existsSync(f));
if (wasm && fs.existsSync(wasm)) {
    copyWhole(wasm, path.join(here, "shared", "penumbra_emitter.wasm"));
} else if (pack) {
    console.error(`error: ${wasm || path.join(root, "build/wasm/penumbra_emitter.wasm")} is missing: build it (cmake --build build --target penumbra-emitter-wasm) ` +
                  "or name it with PENUMBRA_EMITTER_WASM=FILE; the package ships the WebAssembly emitter");
    process.exit(1);
}
if (pack) copyWhole(path.join(root, "LICENSE"), path.join(here, "LICENSE"));
