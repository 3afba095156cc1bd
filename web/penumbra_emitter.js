// penumbra_emitter.js — the Penumbra emitter in the browser (or node): penumbra_emitter.wasm, the
// C++ emitter and penumbra-gen's configuration parser compiled to WebAssembly (wasm/), behind the
// same schema as `penumbra-gen --config` and the same files as `penumbra-gen --out`.
//
//   import {loadEmitter} from "./penumbra_emitter.js";
//   const emitter = await loadEmitter();              // or loadEmitter(url | bytes | WebAssembly.Module)
//   const r = emitter.emit({slices: 8, filter: "sat", target: "essl300"});   // or JSON text
//   r.ok, r.files {"<name>": text, ..., "layout.json": text}, r.layout (parsed), r.diagnostics
//   [{severity, field, message}], r.error ("error: …", the line penumbra-gen prints; "" when ok)
//
// The module imports three WASI calls (fd_write, fd_seek, fd_close: libc's stdio, reached only
// when the C++ code aborts); the few lines of `wasiShim` below provide them, so no WASI runtime
// is needed, in a browser or in node.

const encoder = new TextEncoder();
const decoder = new TextDecoder();

// fd_write to the console (abort messages); no file is ever opened, so seek and close fail or
// succeed trivially. WASI errno 8 = EBADF, 70 = ESPIPE.
function wasiShim(memory, log) {
    return {
        fd_write(fd, iovs, count, written) {
            const view = new DataView(memory().buffer);
            let text = "", total = 0;
            for (let i = 0; i < count; ++i) {
                const pointer = view.getUint32(iovs + 8 * i, true), length = view.getUint32(iovs + 8 * i + 4, true);
                text += decoder.decode(new Uint8Array(memory().buffer, pointer, length));
                total += length;
            }
            view.setUint32(written, total, true);
            if (fd === 1 || fd === 2) log(text);
            return fd === 1 || fd === 2 ? 0 : 8;
        },
        fd_seek: () => 70,
        fd_close: () => 0,
    };
}

async function moduleFrom(source) {
    if (source instanceof WebAssembly.Module) return source;
    if (source instanceof ArrayBuffer || ArrayBuffer.isView(source)) return WebAssembly.compile(source);
    const url = new URL(source ?? "./penumbra_emitter.wasm", import.meta.url);
    if (url.protocol === "file:") { // node: fetch() does not read files
        const {readFile} = await import("node:fs/promises");
        return WebAssembly.compile(await readFile(url));
    }
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
        e.penumbra_emit(configBytes.length, sourceBytes.length);
        const output = new Uint8Array(e.memory.buffer, e.penumbra_output() >>> 0, e.penumbra_output_size() >>> 0);
        const result = JSON.parse(decoder.decode(output));
        result.layout = result.ok ? JSON.parse(result.files["layout.json"]) : null;
        result.ms = performance.now() - started; // emission, with the copies in and out
        return result;
    }
}

// Loads the module: `source` is its URL (default: penumbra_emitter.wasm beside this file), its
// bytes, or a compiled WebAssembly.Module. options.log receives what the module writes to
// stdout/stderr (default console.error).
export async function loadEmitter(source, {log = (text) => console.error(text)} = {}) {
    const started = performance.now();
    const module = await moduleFrom(source);
    let memory = null;
    const instance = await WebAssembly.instantiate(module, {wasi_snapshot_preview1: wasiShim(() => memory, log)});
    memory = instance.exports.memory;
    instance.exports._initialize(); // reactor: the static constructors, once
    return new Emitter(instance, performance.now() - started);
}
