// Types of penumbra_shadows.js (import {PenumbraShadows} from "penumbra-three"), checked with tsc
// against @types/three r180 and r187 (targets/web/three_package_test.mjs).
import type {Camera, DirectionalLight, RectAreaLight, Scene, WebGLRenderer} from "three";
import type {WebGPURenderer} from "three/webgpu";
import type {Emitter} from "./penumbra_emitter.js";

export {EMISSIONS, PenumbraError, type Emission, type EmissionConfig, type EmissionFiles, type EmissionName} from "./penumbra_emission.js";
import type {Emission} from "./penumbra_emission.js";
export {EXT_LIGHTS_AREA, GLTFLightsAreaExtension} from "./gltf_lights_area.js";

export interface PenumbraShadowsOptions {
    /** Default "rect-nbuffer-16x512" (RectAreaLight) or "sun-nbuffer-16x512" (DirectionalLight). */
    emission?: Emission;
    /**
     * A shadow quality tier (penumbra-gen --profile): "balanced" (the default), "large" (lights x4 and up:
     * the irradiance window's quadrants, 1.3 to 1.8 times the frame) or "fast" (a frame budget below PCSS's:
     * 8 slices of 128, chained fusion, the light weighed by area); all but "balanced" emitted by
     * penumbra_emitter.wasm. With a configuration object as `emission`, its fields win over the profile's.
     */
    profile?: "balanced" | "large" | "fast";
    /** Sun only: the angular diameter in radians (default 0.0093, 0.53°). */
    angularDiameter?: number;
    /** Re-run the shadow phase when the light, a caster or a receiver changed (default true). */
    autoUpdate?: boolean;
    /** 0 no shadow … 1 Penumbra's visibility (default 1). */
    intensity?: number;
    /** For a configuration object: the URL of penumbra_emitter.wasm (default: the package's). */
    wasm?: string | URL | null;
    /**
     * Cut-out casters (the alpha test): a caster material cuts when it has a `map` and `alphaTest > 0`
     * (cutoff alphaTest) or `transparent` (cutoff 0.5), the cutoff divided by `opacity`. undefined (the
     * default) follows the scene: on when a caster cuts at load(); true / false force it. On, load()
     * and setEmission() take an emission with the alpha test ("<name>-cut" of a shipped name, or a
     * configuration with alpha_test: true).
     */
    alphaTest?: boolean;
}

export interface PenumbraShadowsInfo {
    shadowUpdates: number;
    lastShadowMs: number;
    casters: number;
    receivers: number;
    /** true when every corner of the scene's bounds lies in front of the light and inside its slicing pyramid; false in a room (geometry behind the light's plane, which casts nothing, or receivers beside the light, shadowed only by what lies inside the pyramid). Informational: nothing to fix. */
    contained: boolean;
    /** true when the casters' cut-outs are drawn: the emission has the alpha test and the alphaTest option is not false. */
    alphaTest: boolean;
    /** How many caster draws the last shadow phase cut (draws of a cutting material with the alpha test on). */
    cutDraws: number;
}

export class PenumbraShadows {
    /** Loads the emission and attaches an add-on to `light`: one add-on per shadowed light. */
    static load(renderer: WebGLRenderer, scene: Scene, light: RectAreaLight | DirectionalLight,
                options?: PenumbraShadowsOptions): Promise<PenumbraShadows>;
    /**
     * On a WebGPURenderer (three/webgpu; it must run its WebGPU backend, not the WebGL2 fallback):
     * the wgsl emission on the renderer's GPUDevice, the visibility in the node materials (TSL).
     */
    static load(renderer: WebGPURenderer, scene: Scene, light: RectAreaLight | DirectionalLight,
                options?: PenumbraShadowsOptions): Promise<PenumbraShadowsWebGPU>;
    private constructor();

    readonly renderer: WebGLRenderer;
    readonly scene: Scene;
    readonly light: RectAreaLight | DirectionalLight;
    readonly kind: "rect" | "sun";
    /** false: the light is unshadowed (nothing recompiles). */
    enabled: boolean;
    intensity: number;
    angularDiameter: number;
    autoUpdate: boolean;
    needsUpdate: boolean;
    /** The alphaTest option as given (undefined: the scene's casters decided at load()). */
    readonly alphaTest: boolean | undefined;
    /** true after dispose(). */
    readonly disposed: boolean;
    /** The emission's configuration (layout.json's "config"). */
    readonly config: Record<string, any>;
    readonly info: PenumbraShadowsInfo;

    /** Once per frame before renderer.render(); throws a PenumbraError after dispose(). */
    update(): void;
    /** Another emission (with the alpha test as load() picks it); the materials recompile. */
    setEmission(emission: Emission): Promise<void>;
    setSize(width: number, height: number): void;
    /** The visibility the receivers get (0 shadowed … 1 lit), width × height, bottom row first. */
    renderVisibility(camera: Camera, width: number, height: number): Float32Array;
    /** Frees the add-on's GPU resources and takes it out of the materials; a second call does nothing. */
    dispose(): void;
}

/** The WebAssembly emitter, loaded once (wasm: its URL; default the package's penumbra_emitter.wasm). */
export function loadEmitter(wasm?: string | URL | null): Promise<Emitter>;

/**
 * The add-on on a WebGPURenderer (what PenumbraShadows.load returns there): as PenumbraShadows, but
 * renderVisibility is asynchronous (WebGPU reads back asynchronously) and info.error holds WebGPU's
 * message when a shadow phase failed validation.
 */
export interface PenumbraShadowsWebGPU extends Omit<PenumbraShadows, "renderer" | "info" | "renderVisibility"> {
    readonly renderer: WebGPURenderer;
    readonly info: PenumbraShadowsInfo & {error: string | null};
    /** The visibility the receivers get (0 shadowed … 1 lit), width × height, bottom row first. */
    renderVisibility(camera: Camera, width: number, height: number): Promise<Float32Array>;
}
