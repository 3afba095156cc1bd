// Types of penumbra_emission.js: what the add-ons (penumbra-three, penumbra-babylon) share about
// emissions, whatever the engine.

/**
 * The emissions shipped in the package (penumbra-gen output): essl300 for WebGLRenderer; on
 * WebGPURenderer the same name loads its "<name>-wgsl" twin (the "-mipmap-" ones have none: WGSL
 * has no mipmap filter).
 */
export type EmissionName =
    | "rect-nbuffer-16x512" | "rect-mipmap-16x512" | "rect-nbuffer-16x256" | "rect-nbuffer-8x256"
    | "sun-nbuffer-16x512" | "sun-mipmap-16x512"
    /** with the alpha test (penumbra-gen --alpha-test): cut-out casters; load() picks them when casters cut */
    | "rect-nbuffer-16x512-cut" | "sun-nbuffer-16x512-cut";

/** Shipped emission → its files (name → URL, each a literal `new URL(…, import.meta.url)` bundlers copy). */
export const EMISSIONS: Readonly<Record<EmissionName | `${EmissionName}-wgsl`, Readonly<Record<string, URL>>>>;

/** An emission in memory: what the WebAssembly emitter's emit() returns (files by name, layout.json parsed). */
export interface EmissionFiles {
    layout: Record<string, any> | null;
    files: Record<string, string>;
}

/** A configuration in `penumbra-gen --config`'s schema, emitted in the page by the WebAssembly emitter. */
export interface EmissionConfig {
    slices?: number;
    resolution?: number;
    filter?: "mipmap" | "nbuffer" | "gaussian" | "sat";
    fusion?: "probabilistic" | "additive" | "maximum" | "average" | "chained" | "correlated" | "extent" | "clustered";
    packing?: "atlas" | "array" | "volume";
    tangent_clip?: boolean;
    /** cut-out casters (penumbra-gen --alpha-test); the three add-on sets it when its casters cut */
    alpha_test?: boolean;
    [key: string]: unknown;
}

/**
 * A shipped emission's name, a folder URL ending in "/" holding `penumbra-gen --target essl300`
 * output, an emission in memory, or a configuration to emit.
 */
export type Emission = EmissionName | string | EmissionFiles | EmissionConfig;

/** Thrown with a message naming what is wrong ("PenumbraShadows: …"). */
export class PenumbraError extends Error {}
