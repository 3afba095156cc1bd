// Types of penumbra_babylon.js (import {PenumbraShadows} from "penumbra-babylon"), checked with tsc
// against @babylonjs/core's own declarations (targets/web/babylon_package_test.mjs).
import type {AbstractEngine} from "@babylonjs/core/Engines/abstractEngine.js";
import type {Scene} from "@babylonjs/core/scene.js";
import type {Camera} from "@babylonjs/core/Cameras/camera.js";
import type {RectAreaLight} from "@babylonjs/core/Lights/rectAreaLight.js";
import type {DirectionalLight} from "@babylonjs/core/Lights/directionalLight.js";
import type {AbstractMesh} from "@babylonjs/core/Meshes/abstractMesh.js";
import type {Material} from "@babylonjs/core/Materials/material.js";
import type {BaseTexture} from "@babylonjs/core/Materials/Textures/baseTexture.js";
import type {Emitter} from "./shared/penumbra_emitter.js";

export {EMISSIONS, PenumbraError, type Emission, type EmissionConfig, type EmissionFiles, type EmissionName} from "./shared/penumbra_emission.js";
import type {Emission} from "./shared/penumbra_emission.js";

export interface PenumbraShadowsOptions {
    /**
     * Default "rect-nbuffer-16x512" (RectAreaLight) or "sun-nbuffer-16x512" (DirectionalLight). A shipped
     * emission's name picks its essl300 files on Engine (WebGL2) and its wgsl files on WebGPUEngine; a folder
     * or an emission in memory must be of the engine's target (essl300 or wgsl); a configuration is emitted for it.
     */
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
     * Cut-out casters (the alpha test; which materials cut: cutOf). undefined (the default) follows the
     * scene: on when an enabled mesh of the scene has a material that cuts at load(); true / false force
     * it. On, load() takes an emission with the alpha test ("<name>-cut" of a shipped name, or a
     * configuration with alpha_test: true).
     */
    alphaTest?: boolean;
}

export interface PenumbraShadowsInfo {
    /** WebGPUEngine: WebGPU's validation message of the last shadow phase that failed, else null. */
    error?: string | null;
    shadowUpdates: number;
    lastShadowMs: number;
    casters: number;
    receivers: number;
    /** true when every corner of the scene's bounds lies in front of the light and inside its slicing pyramid; false in a room (geometry behind the light's plane, which casts nothing, or receivers beside the light, shadowed only by what lies inside the pyramid). Informational: nothing to fix. */
    contained: boolean;
    /** true when the casters' cut-outs are drawn: the emission has the alpha test and the alphaTest option is not false. */
    alphaTest: boolean;
    /** How many caster draws (sub-meshes of the casters' vertex data) the last shadow phase cut. */
    cutDraws: number;
}

/**
 * Whether a caster's material cuts, as Babylon draws it, and where: its alpha-test texture
 * (StandardMaterial's diffuseTexture, PBRMaterial's albedoTexture) with hasAlpha, and transparencyMode
 * ALPHATEST / ALPHATESTANDBLEND (cutoff alphaCutOff; StandardMaterial also needs
 * useAlphaFromDiffuseTexture), ALPHABLEND with useAlphaFrom…Texture (cast as a cut-out at 0.5), or
 * none (Babylon's choice: blended at 0.5 with useAlphaFrom…Texture, else tested at alphaCutOff); the
 * cutoff divided by the material's alpha. null: solid.
 */
export function cutOf(material: Material | null | undefined): {texture: BaseTexture, cutoff: number} | null;

export class PenumbraShadows {
    /**
     * Loads the emission and attaches an add-on to `light` on a WebGL2 `Engine` or an initialized
     * `WebGPUEngine` (after `await engine.initAsync()`): one add-on per shadowed light.
     */
    static load(engine: AbstractEngine, scene: Scene, light: RectAreaLight | DirectionalLight,
                options?: PenumbraShadowsOptions): Promise<PenumbraShadows>;
    private constructor();

    readonly engine: AbstractEngine;
    /** true on WebGPUEngine (the wgsl emission, WGSL in the materials), false on Engine (WebGL2). */
    readonly webgpu: boolean;
    readonly scene: Scene;
    readonly light: RectAreaLight | DirectionalLight;
    readonly kind: "rect" | "sun";
    /** The emission's configuration (layout.json's "config"). */
    readonly config: Record<string, any>;
    readonly info: PenumbraShadowsInfo;
    readonly disposed: boolean;
    /** false: the light's term is left unscaled (no shadow), without recompiling. */
    enabled: boolean;
    intensity: number;
    angularDiameter: number;
    autoUpdate: boolean;
    /** Set to re-run the shadow phase at the next update() (with autoUpdate false). */
    needsUpdate: boolean;
    /** The alphaTest option as given (undefined: the scene's materials decided at load()). */
    readonly alphaTest: boolean | undefined;

    /** Casters, as ShadowGenerator's: the mesh and (by default) its descendants. */
    addShadowCaster(mesh: AbstractMesh, includeDescendants?: boolean): this;
    removeShadowCaster(mesh: AbstractMesh, includeDescendants?: boolean): this;
    getShadowCasters(): AbstractMesh[];
    /**
     * Once per frame before scene.render(): hooks the materials (StandardMaterial, PBRMaterial) of
     * meshes with receiveShadows, re-runs the shadow phase when something moved; throws a
     * PenumbraError after dispose().
     */
    update(): void;
    /** The visibility (0 shadowed … 1 lit) as `camera` sees the receivers, bottom row first; 1 where none is. */
    renderVisibility(camera: Camera, width: number, height: number): Promise<Float32Array>;
    /** Frees the add-on's GPU resources; its material plugins inject nothing any more. */
    dispose(): void;
}

/** The package's WebAssembly emitter, loaded once (for configuration objects). */
export function loadEmitter(wasm?: string | URL | null): Promise<Emitter>;
