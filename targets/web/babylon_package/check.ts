// check.ts — compiled with tsc --noEmit by the babylon-package test: penumbra-babylon's
// declarations, reached through its "exports", as a TypeScript user sees them, against
// @babylonjs/core's own declarations.
import type {Engine} from "@babylonjs/core/Engines/engine.js";
import type {WebGPUEngine} from "@babylonjs/core/Engines/webgpuEngine.js";
import type {Scene} from "@babylonjs/core/scene.js";
import type {Camera} from "@babylonjs/core/Cameras/camera.js";
import {RectAreaLight} from "@babylonjs/core/Lights/rectAreaLight.js";
import {DirectionalLight} from "@babylonjs/core/Lights/directionalLight.js";
import {PointLight} from "@babylonjs/core/Lights/pointLight.js";
import {Vector3} from "@babylonjs/core/Maths/math.vector.js";
import type {Mesh} from "@babylonjs/core/Meshes/mesh.js";
import {StandardMaterial} from "@babylonjs/core/Materials/standardMaterial.js";
import {PenumbraShadows, PenumbraError, EMISSIONS, cutOf, type PenumbraShadowsOptions} from "penumbra-babylon";
import {loadEmitter, type EmitResult} from "penumbra-babylon/emitter";

export async function attach(engine: Engine, scene: Scene, camera: Camera, box: Mesh, gpu: WebGPUEngine): Promise<number> {
    const rect = new RectAreaLight("rect", Vector3.Zero(), 3, 2, scene);
    const options: PenumbraShadowsOptions = {emission: "rect-mipmap-16x512", intensity: 0.8};
    const shadows: PenumbraShadows = await PenumbraShadows.load(engine, scene, rect, options);
    const sun = await PenumbraShadows.load(engine, scene, new DirectionalLight("sun", new Vector3(0, -1, 0), scene), {angularDiameter: 0.0093, alphaTest: false});
    const cut = cutOf(new StandardMaterial("leaf", scene));
    const cutoff: number = cut ? cut.cutoff : 0;
    const cutting: boolean = shadows.info.alphaTest && shadows.info.cutDraws > 0 && shadows.alphaTest !== false;
    const onWebGPU: PenumbraShadows = await PenumbraShadows.load(gpu, scene, rect, {emission: "rect-nbuffer-16x512"});
    const webgpu: boolean = onWebGPU.webgpu && !shadows.webgpu;
    shadows.addShadowCaster(box).addShadowCaster(box, false);
    shadows.update();
    sun.enabled = false;
    const visibility: Float32Array = await shadows.renderVisibility(camera, 64, 64);
    const files: Readonly<Record<string, URL>> = EMISSIONS["sun-nbuffer-16x512"];
    // @ts-expect-error: a PointLight is neither a RectAreaLight nor a DirectionalLight
    await PenumbraShadows.load(engine, scene, new PointLight("point", Vector3.Zero(), scene));
    // @ts-expect-error: no such emission filter
    await PenumbraShadows.load(engine, scene, rect, {emission: {filter: "box"}});
    const emitted: EmitResult = (await loadEmitter()).emit({slices: 4, target: "essl300"});
    shadows.dispose();
    try { shadows.update(); } catch (e) { if (!(e instanceof PenumbraError)) throw e; }
    return visibility.length + Object.keys(files).length + shadows.info.shadowUpdates + shadows.getShadowCasters().length + (emitted.ok ? 1 : 0) + (webgpu ? 1 : 0) + cutoff + (cutting ? 1 : 0);
}
