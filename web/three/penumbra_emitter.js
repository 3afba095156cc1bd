// penumbra_emitter.js — the Penumbra emitter in the browser (or node): penumbra_emitter.wasm, the
// C++ emitter and penumbra-gen's configuration parser compiled to WebAssembly (wasm/), behind the
// same schema as `penumbra-gen --config` and the same files as `penumbra-gen --out`.
//
//   import {loadEmitter} from "penumbra-three/emitter";  // or "./penumbra_emitter.js" (web/three/)
//   const emitter = await loadEmitter();              // or loadEmitter(url | bytes | WebAssembly.Module)
//   const r = emitter.emit({slices: 8, filter: "mipmap", target: "essl300"}); // or JSON text
//   r.ok, r.files {"<name>": text, ..., "layout.json": text}, r.layout (parsed), r.diagnostics
//   [{severity, field, message}], r.error ("error: …", the line penumbra-gen prints; "" when ok)
//   emitter.fields()  // the table of configuration fields: [{key, flag, kind, min, max, help, techniques, names, default, …}]
//
// The module imports nothing (wasm/wasi_stubs.cpp defines the three WASI calls libc's stdio would
// import): no WASI runtime and no import object, in a browser or in node. Nothing here is for node
// alone (esbuild and webpack 5 fail on such imports in a browser bundle): node reads file: URLs
// through penumbra_emitter_node.js, which package.json's "node" condition of "./emitter" selects.

const encoder = new TextEncoder();
const decoder = new TextDecoder();

async function moduleFrom(source) {
    if (source instanceof WebAssembly.Module) return source;
    if (source instanceof ArrayBuffer || ArrayBuffer.isView(source)) return WebAssembly.compile(source);
    // The default as a literal `new URL("./…", import.meta.url)`: bundlers (Vite, webpack) copy
    // the module into the build only when they see that form.
    // (a caller's URL against a copy of import.meta.url: webpack warns "Critical dependency" on
    // `new URL(expression, import.meta.url)`, a form it would bundle only with a literal)
    const moduleUrl = import.meta.url;
    const url = source == null ? new URL("./penumbra_emitter.wasm", import.meta.url) : new URL(source, moduleUrl);
    if (url.protocol === "file:") // node's fetch() reads no file
        throw new Error(`${url}: a file: URL; in node import "penumbra-three/emitter" (its "node" export reads files) or pass the module's bytes`);
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status} (build the emitter: cmake --build build --target penumbra-emitter-wasm)`);
    return WebAssembly.compile(await response.arrayBuffer());
}

export class Emitter {
    constructor(instance, compileMs) {
        this.exports = instance.exports;
        this.compileMs = compileMs; // fetch + compile + instantiate, ms
    }

    // config: an object or JSON text in the `penumbra-gen --config` schema. options.source names
    // the configuration in messages (penumbra-gen names the file: "error: FILE: key …").
    emit(config, {source = "config"} = {}) {
        const text = typeof config === "string" ? config : JSON.stringify(config);
        const started = performance.now();
        const configBytes = encoder.encode(text), sourceBytes = encoder.encode(source);
        const e = this.exports;
        const input = e.penumbra_input(configBytes.length + sourceBytes.length) >>> 0;
        const memory = new Uint8Array(e.memory.buffer, input, configBytes.length + sourceBytes.length);
        memory.set(configBytes);
        memory.set(sourceBytes, configBytes.length);
        try {
            e.penumbra_emit(configBytes.length, sourceBytes.length);
        } catch (trap) { // an abort in the C++ code (a bug: what would have been an exception); load a new emitter after it
            const error = `error: internal: the emitter trapped (${trap.message}); please report the configuration`;
            return {ok: false, files: {}, layout: null, error, diagnostics: [{severity: "error", field: "config", message: error}],
                    ms: performance.now() - started};
        }
        const output = new Uint8Array(e.memory.buffer, e.penumbra_output() >>> 0, e.penumbra_output_size() >>> 0);
        const result = JSON.parse(decoder.decode(output));
        result.layout = result.ok ? JSON.parse(result.files["layout.json"]) : null;
        result.ms = performance.now() - started; // emission, with the copies in and out
        return result;
    }

    // The table of configuration fields (penumbra/config_fields.hpp, wasm/README.md): one object per
    // field, {key, flag, metavar, kind: "integer" | "real" | "boolean" | "choice", min, max,
    // min_exclusive, allowed, help, techniques: [] (every technique) or names, names, default, optional}.
    fields() {
        if (!this.fieldTable) {
            const e = this.exports;
            const at = e.penumbra_fields() >>> 0, size = e.penumbra_fields_size() >>> 0; // first: they may grow the memory
            const text = new Uint8Array(e.memory.buffer, at, size);
            this.fieldTable = JSON.parse(decoder.decode(text));
        }
        return this.fieldTable;
    }
}

// Loads the module: `source` is its URL (default: penumbra_emitter.wasm beside this file), its
// bytes, or a compiled WebAssembly.Module.
export async function loadEmitter(source) {
    const started = performance.now();
    return instantiate(await moduleFrom(source), started);
}

// (penumbra_emitter_node.js compiles from the file's bytes, then comes here)
export async function instantiate(module, started = performance.now()) {
    const instance = await WebAssembly.instantiate(module, {});
    instance.exports._initialize(); // reactor: the static constructors, once
    return new Emitter(instance, performance.now() - started);
}
