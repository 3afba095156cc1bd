// prepack.mjs — run by `npm pack` / `npm publish` here (package.json's "prepack"): puts beside the
// modules what the package ships but the repository does not track: the shipped emissions
// (emissions/regenerate.sh with penumbra-gen: build/generator/penumbra-gen, or PENUMBRA_GEN=FILE; the
// build writes them too), the WebAssembly emitter (penumbra_emitter.wasm, built by
// `cmake --build build --target penumbra-emitter-wasm`; another build with PENUMBRA_EMITTER_WASM=FILE)
// and the repository's LICENSE.
import {execFileSync} from "node:child_process";
import fs from "node:fs";
import path from "node:path";
import {fileURLToPath} from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const root = path.join(here, "../..");
const gen = process.env.PENUMBRA_GEN || path.join(root, "build/generator/penumbra-gen");
if (fs.existsSync(gen)) {
    execFileSync("sh", [path.join(here, "emissions/regenerate.sh"), gen], {stdio: "inherit"});
} else if (!fs.readdirSync(path.join(here, "emissions")).some((name) => name.endsWith("-wgsl"))) {
    console.error(`error: ${gen} is missing and emissions/ holds no emission: build penumbra-gen ` +
                  "(cmake --build build --target penumbra-gen) or name it with PENUMBRA_GEN=FILE; the package ships its emissions");
    process.exit(1);
}
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
