// penumbra_emitter_node.js — penumbra_emitter.js for node: the same Emitter, with file: URLs (the
// default, penumbra_emitter.wasm beside this file, among them) read from the disk, which node's
// fetch() does not do. package.json's "node" condition of "./emitter" selects this module, so the
// `node:` import below never reaches a browser bundle.
import {readFile} from "node:fs/promises";
import {Emitter, instantiate, loadEmitter as loadInBrowser} from "./penumbra_emitter.js";

export {Emitter};

// Loads the module: `source` is its URL or path (default: penumbra_emitter.wasm beside this file),
// its bytes, or a compiled WebAssembly.Module.
export async function loadEmitter(source) {
    const started = performance.now();
    const url = source == null ? new URL("./penumbra_emitter.wasm", import.meta.url)
        : typeof source === "string" || source instanceof URL ? new URL(source, import.meta.url) : null;
    if (!url || url.protocol !== "file:") return loadInBrowser(source);
    return instantiate(await WebAssembly.compile(await readFile(url)), started);
}
