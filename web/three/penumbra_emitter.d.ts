// Types of penumbra_emitter.js (import {loadEmitter} from "penumbra-three/emitter"): the Penumbra
// emitter compiled to WebAssembly, with `penumbra-gen --config`'s schema in and its files out.

/** A problem with the configuration, as penumbra-gen reports it. */
export interface Diagnostic {
    severity: "error";
    /** The configuration key it concerns ("config" for the whole of it). */
    field: string;
    message: string;
}

/** What emit() returns: `penumbra-gen --out`'s files (layout.json among them) or the reasons why not. */
export interface EmitResult {
    ok: boolean;
    /** File name → text, layout.json included; empty when not ok. */
    files: Record<string, string>;
    /** layout.json parsed; null when not ok. */
    layout: Record<string, any> | null;
    /** The line penumbra-gen prints ("error: …"); "" when ok. */
    error: string;
    diagnostics: Diagnostic[];
    /** Milliseconds the emission took, copies in and out included. */
    ms: number;
}

export class Emitter {
    private constructor();
    /** fetch + compile + instantiate, milliseconds. */
    readonly compileMs: number;
    readonly exports: WebAssembly.Exports;
    /** config: an object or JSON text in the `penumbra-gen --config` schema; options.source names it in messages. */
    emit(config: Record<string, unknown> | string, options?: {source?: string}): EmitResult;
}

/** source: the module's URL (default: penumbra_emitter.wasm beside penumbra_emitter.js), its bytes, or a compiled module. */
export function loadEmitter(source?: string | URL | ArrayBuffer | ArrayBufferView | WebAssembly.Module | null): Promise<Emitter>;
