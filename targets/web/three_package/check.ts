// check.ts — compiled with tsc --noEmit against @types/three (r180 and r187) by the npm package
// test: the package's declarations, reached through its "exports", as a TypeScript user sees them.
import * as THREE from "three";
import type {WebGPURenderer} from "three/webgpu";
import {PenumbraShadows, PenumbraError, EMISSIONS, type PenumbraShadowsOptions, type PenumbraShadowsWebGPU} from "penumbra-three";
import {loadEmitter, type EmitResult} from "penumbra-three/emitter";
import {GLTFLoader} from "three/addons/loaders/GLTFLoader.js";
import {GLTFLightsAreaExtension, EXT_LIGHTS_AREA} from "penumbra-three";

export async function attach(renderer: THREE.WebGLRenderer, scene: THREE.Scene, camera: THREE.Camera): Promise<number> {
    const rect = new THREE.RectAreaLight(0xffffff, 5, 3, 2);
    const options: PenumbraShadowsOptions = {emission: "rect-mipmap-16x512", intensity: 0.8};
    const shadows: PenumbraShadows = await PenumbraShadows.load(renderer, scene, rect, options);
    const sun = await PenumbraShadows.load(renderer, scene, new THREE.DirectionalLight(), {angularDiameter: 0.0093});
    shadows.update();
    sun.enabled = false;
    await shadows.setEmission({slices: 8, resolution: 256, filter: "mipmap"});
    const visibility: Float32Array = shadows.renderVisibility(camera, 64, 64);
    const files: Readonly<Record<string, URL>> = EMISSIONS["sun-nbuffer-16x512"];
    // @ts-expect-error: a PointLight is neither a RectAreaLight nor a DirectionalLight
    await PenumbraShadows.load(renderer, scene, new THREE.PointLight());
    // @ts-expect-error: no such emission filter
    await shadows.setEmission({filter: "box"});
    const emitted: EmitResult = (await loadEmitter()).emit({slices: 4, target: "essl300"});
    shadows.dispose();
    try { shadows.update(); } catch (e) { if (!(e instanceof PenumbraError)) throw e; }
    return visibility.length + Object.keys(files).length + shadows.info.shadowUpdates + (emitted.ok ? 1 : 0);
}

// On a WebGPURenderer the same load() gives the WebGPU add-on (renderVisibility is asynchronous).
export async function attachWebGPU(renderer: WebGPURenderer, scene: THREE.Scene, camera: THREE.Camera): Promise<number> {
    const shadows: PenumbraShadowsWebGPU = await PenumbraShadows.load(renderer, scene, new THREE.RectAreaLight(0xffffff, 5, 3, 2));
    shadows.update();
    const visibility: Float32Array = await shadows.renderVisibility(camera, 64, 64);
    shadows.dispose();
    return visibility.length + (shadows.info.error === null ? 0 : 1);
}

// glTF area lights (EXT_lights_area) through the package's GLTFLoader plugin, each shadowed.
export async function attachGLTF(renderer: THREE.WebGLRenderer, scene: THREE.Scene, url: string): Promise<number> {
    const loader = new GLTFLoader().register((parser) => new GLTFLightsAreaExtension(parser));
    const gltf = await loader.loadAsync(url);
    scene.add(gltf.scene);
    const lights: THREE.RectAreaLight[] = [];
    gltf.scene.traverse((o) => { if (o instanceof THREE.RectAreaLight) lights.push(o); });
    const all: PenumbraShadows[] = await Promise.all(lights.map((light) => PenumbraShadows.load(renderer, scene, light)));
    const name: "EXT_lights_area" = EXT_LIGHTS_AREA;
    return all.length + name.length;
}
