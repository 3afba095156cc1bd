// prepack.mjs — run by `npm pack` / `npm publish` here (package.json's "prepack"): puts beside the
// modules what the package ships but the repository does not track: the WebAssembly emitter
// (penumbra_emitter.wasm, built by `cmake --build build --target penumbra-emitter-wasm`; another
// build with PENUMBRA_EMITTER_WASM=FILE) and the repository's LICENSE.
import fs from "node:fs";
import path from "node:path";
import {fileURLToPath} from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.join(here, "../..");
const wasm = process.env.PENUMBRA_EMITTER_WASM || path.join(root, "build/wasm/penumbra_emitter.wasm");
if (!fs.existsSync(wasm)) {
    console.error(`error: ${wasm} is missing: build it (cmake --build build --target penumbra-emitter-wasm) ` +
                  "or name it with PENUMBRA_EMITTER_WASM=FILE; the package ships the WebAssembly emitter");
    process.exit(1);
}
// Each file whole or not at all (a copy beside it, then a rename): a page or test reading the
// package folder while this runs never sees half a file.
function copyWhole(from, to) {
    fs.copyFileSync(from, `${to}.partial`);
    fs.renameSync(`${to}.partial`, to);
}
copyWhole(wasm, path.join(here, "penumbra_emitter.wasm"));
copyWhole(path.join(root, "LICENSE"), path.join(here, "LICENSE"));
