// babylon.js — the Babylon.js page of the bundler tests (bundle_test.mjs): an entry that imports
// "penumbra-babylon" and "@babylonjs/core" (deep imports, as Babylon's docs advise for tree
// shaking) as a user's project does. A ground (a StandardMaterial or a PBRMaterial) lit by a RectAreaLight and a sun
// (DirectionalLight), one add-on each on the same material, and a box casting (on a layer the
// camera does not render, so that every pixel is ground). window.bundleCheck.run(material) returns the
// images the test compares: each light alone without and with its shadow, both on, each add-on's
// visibility, and the first light after the second add-on's dispose(). run(material, "webgpu"): on a
// WebGPUEngine (babylon_package_test.mjs runs it so, unbundled; the bundler tests run WebGL2).
import {Engine} from "@babylonjs/core/Engines/engine.js";
import {Scene} from "@babylonjs/core/scene.js";
import {FreeCamera} from "@babylonjs/core/Cameras/freeCamera.js";
import {RectAreaLight} from "@babylonjs/core/Lights/rectAreaLight.js";
import {DirectionalLight} from "@babylonjs/core/Lights/directionalLight.js";
import {TransformNode} from "@babylonjs/core/Meshes/transformNode.js";
import {CreateGround} from "@babylonjs/core/Meshes/Builders/groundBuilder.js";
import {CreateBox} from "@babylonjs/core/Meshes/Builders/boxBuilder.js";
import {StandardMaterial} from "@babylonjs/core/Materials/standardMaterial.js";
import {PBRMaterial} from "@babylonjs/core/Materials/PBR/pbrMaterial.js";
import {RenderTargetTexture} from "@babylonjs/core/Materials/Textures/renderTargetTexture.js";
import {Color3, Color4} from "@babylonjs/core/Maths/math.color.js";
import {Vector3} from "@babylonjs/core/Maths/math.vector.js";
import {PenumbraShadows, PenumbraError} from "penumbra-babylon";

const W = 96, H = 96;
const frame = () => new Promise((resolve) => requestAnimationFrame(resolve));

// kind: "standard" or "pbr" (StandardMaterial or PBRMaterial on the ground); engineKind: "webgl2" or "webgpu"
async function run(kind, engineKind = "webgl2") {
    const canvas = document.createElement("canvas");
    canvas.width = W;
    canvas.height = H;
    document.body.appendChild(canvas);
    let engine;
    if (engineKind === "webgpu") { // (imported here: the bundler tests' pages stay WebGL2's)
        const {WebGPUEngine} = await import("@babylonjs/core/Engines/webgpuEngine.js");
        engine = new WebGPUEngine(canvas, {antialias: false});
        await engine.initAsync();
    } else {
        engine = new Engine(canvas, false, {preserveDrawingBuffer: true});
    }
    const scene = new Scene(engine);
    scene.clearColor = new Color4(0, 0, 0, 1);
    const camera = new FreeCamera("camera", new Vector3(0, 7, 5), scene);
    camera.setTarget(Vector3.Zero());
    camera.layerMask = 0x0fffffff;
    const ground = CreateGround("ground", {width: 10, height: 10}, scene);
    let material;
    if (kind === "pbr") {
        // (image processing left to a post process, of which there is none: the output stays linear)
        scene.imageProcessingConfiguration.applyByPostProcess = true;
        material = new PBRMaterial("ground", scene);
        material.albedoColor = new Color3(1, 1, 1);
        material.metallic = 0;
        material.roughness = 0.8;
    } else {
        material = new StandardMaterial("ground", scene);
        material.diffuseColor = new Color3(1, 1, 1);
        material.specularColor = new Color3(0, 0, 0);
    }
    ground.material = material;
    ground.receiveShadows = true;
    const box = CreateBox("box", {width: 1.2, height: 2, depth: 1.2}, scene);
    box.position.y = 1;
    box.layerMask = 0x10000000; // cast, unseen
    // the rectangle faces local -z: a parent turned so that -z is down
    const holder = new TransformNode("rectHolder", scene);
    holder.position = new Vector3(-1.5, 4, 0);
    holder.rotation.x = -Math.PI / 2;
    const rect = new RectAreaLight("rect", Vector3.Zero(), 1.2, 1.2, scene);
    rect.parent = holder;
    rect.intensity = 15;
    const sun = new DirectionalLight("sun", new Vector3(0.8, -1, 0.2), scene);
    sun.intensity = 0.5;
    const a = await PenumbraShadows.load(engine, scene, rect);
    a.addShadowCaster(box);
    // (the second add-on with the one-texture emission: two default ones sample 20 textures, over WebGL2's 16 units)
    const b = await PenumbraShadows.load(engine, scene, sun, {emission: "sun-mipmap-16x512", angularDiameter: 0.05});
    b.addShadowCaster(box);
    const target = new RenderTargetTexture("image", {width: W, height: H}, scene, {generateMipMaps: false, type: 1 /* float */});
    target.activeCamera = camera;
    target.renderList = [ground];
    target.clearColor = new Color4(0, 0, 0, 1);
    const intensities = [rect.intensity, sun.intensity];
    const image = async (lights, shadowed) => {
        rect.intensity = lights[0] ? intensities[0] : 0;
        sun.intensity = lights[1] ? intensities[1] : 0;
        for (const s of [a, b]) {
            if (s.disposed) continue;
            s.enabled = shadowed;
            s.update();
        }
        for (let i = 0; !target.isReadyForRendering() || !scene.isReady(); ++i) {
            if (i > 600) throw new Error("the scene's materials never got ready");
            await frame();
        }
        scene.render(); // (the frame updates the lights' uniforms, which Babylon 9.0 does not do for a target alone)
        target.render();
        const rgba = await target.readPixels();
        return Array.from({length: W * H}, (_, i) => (rgba[4 * i] + rgba[4 * i + 1] + rgba[4 * i + 2]) / 3);
    };
    const out = {width: W, height: H, library: `@babylonjs/core ${Engine.Version} ${engine.name}, ${material.getClassName()}`, lights: ["RectAreaLight", "DirectionalLight (sun)"]};
    out.unshadowed = [await image([1, 0], false), await image([0, 1], false)];
    out.shadowed = [await image([1, 0], true), await image([0, 1], true)];
    out.both = await image([1, 1], true);
    out.visibility = [Array.from(await a.renderVisibility(camera, W, H)), Array.from(await b.renderVisibility(camera, W, H))];
    b.dispose();
    try {
        b.update();
        out.afterDispose = "no error";
    } catch (e) {
        out.afterDispose = e instanceof PenumbraError ? e.message : `not a PenumbraError: ${e}`;
    }
    b.dispose(); // a second time: nothing
    out.firstAfterDispose = await image([1, 0], true);
    out.info = [a.info, b.info];
    a.dispose();
    engine.dispose();
    canvas.remove();
    return out;
}

window.bundleCheck = {run: (kind, engineKind) => run(kind, engineKind).catch((e) => ({error: `${e.message}\n${e.stack}`})), materials: ["standard", "pbr"]};
