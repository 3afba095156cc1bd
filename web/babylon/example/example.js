// example.js — the add-on's example: a Babylon.js scene (a ground, a few shapes, instances and thin
// instances of posts) lit by a RectAreaLight or a sun (DirectionalLight) with Penumbra's soft
// shadows, an ArcRotateCamera, and buttons to switch the light, the shadows off and on, and the
// engine (Engine, WebGL2, or WebGPUEngine: the page reloads with ?engine=webgl2|webgpu).
// URL parameter ?size=WxH: a fixed canvas size (screenshots).
// window.example (automation): ready, set({light, mode}), render(), info(), scene.
import {Engine} from "@babylonjs/core/Engines/engine.js";
import {WebGPUEngine} from "@babylonjs/core/Engines/webgpuEngine.js";
import {Scene} from "@babylonjs/core/scene.js";
import {ArcRotateCamera} from "@babylonjs/core/Cameras/arcRotateCamera.js";
import "@babylonjs/core/Cameras/Inputs/arcRotateCameraPointersInput.js";
import {RectAreaLight} from "@babylonjs/core/Lights/rectAreaLight.js";
import {DirectionalLight} from "@babylonjs/core/Lights/directionalLight.js";
import {HemisphericLight} from "@babylonjs/core/Lights/hemisphericLight.js";
import {TransformNode} from "@babylonjs/core/Meshes/transformNode.js";
import {CreateGround} from "@babylonjs/core/Meshes/Builders/groundBuilder.js";
import {CreateBox} from "@babylonjs/core/Meshes/Builders/boxBuilder.js";
import {CreateSphere} from "@babylonjs/core/Meshes/Builders/sphereBuilder.js";
import {CreateTorusKnot} from "@babylonjs/core/Meshes/Builders/torusKnotBuilder.js";
import {CreateCylinder} from "@babylonjs/core/Meshes/Builders/cylinderBuilder.js";
import "@babylonjs/core/Meshes/thinInstanceMesh.js";
import "@babylonjs/core/Meshes/instancedMesh.js";
import {StandardMaterial} from "@babylonjs/core/Materials/standardMaterial.js";
import {PBRMaterial} from "@babylonjs/core/Materials/PBR/pbrMaterial.js";
import {Color3, Color4} from "@babylonjs/core/Maths/math.color.js";
import {Matrix, Vector3} from "@babylonjs/core/Maths/math.vector.js";
import {PenumbraShadows} from "../penumbra_babylon.js"; // "penumbra-babylon" from npm

const params = new URLSearchParams(location.search);
const fixedSize = params.get("size") ? params.get("size").split("x").map(Number) : null;
const canvas = document.getElementById("view");
if (fixedSize) {
    canvas.style.width = `${fixedSize[0]}px`;
    canvas.style.height = `${fixedSize[1]}px`;
}
// the engine: WebGPUEngine where asked for and the browser has WebGPU, else Engine (WebGL2)
const engineKind = params.get("engine") === "webgpu" ? "webgpu" : "webgl2";
const status = document.getElementById("status");
let engine;
if (engineKind === "webgpu" && navigator.gpu) {
    engine = new WebGPUEngine(canvas, {antialias: true});
    await engine.initAsync();
} else {
    if (engineKind === "webgpu") status.textContent = "no WebGPU in this browser: WebGL2 ";
    engine = new Engine(canvas, true, {preserveDrawingBuffer: true});
}
for (const button of document.querySelectorAll("[data-engine]")) {
    button.disabled = button.dataset.engine === (engine.isWebGPU ? "webgpu" : "webgl2");
    button.onclick = () => {
        params.set("engine", button.dataset.engine);
        location.search = params.toString();
    };
}
const scene = new Scene(engine);
scene.clearColor = new Color4(0.12, 0.14, 0.16, 1);
const camera = new ArcRotateCamera("camera", -Math.PI / 3, 1.0, 16, new Vector3(0, 1, 0), scene);
camera.attachControl(canvas, true);
new HemisphericLight("sky", new Vector3(0, 1, 0), scene).intensity = 0.08;

// The scene: a ground (PBR) and shapes (Standard and PBR); all cast, the ground and the shapes receive.
const ground = CreateGround("ground", {width: 24, height: 24}, scene);
const groundMaterial = new PBRMaterial("ground", scene);
groundMaterial.albedoColor = new Color3(0.72, 0.72, 0.72);
groundMaterial.metallic = 0;
groundMaterial.roughness = 0.9;
ground.material = groundMaterial;
ground.receiveShadows = true;
const shapes = [];
const standard = (name, color) => {
    const m = new StandardMaterial(name, scene);
    m.diffuseColor = color;
    m.specularColor = new Color3(0.2, 0.2, 0.2);
    return m;
};
const box = CreateBox("box", {size: 1.6}, scene);
box.position.set(-2, 0.8, 0.5);
box.material = standard("box", new Color3(0.8, 0.45, 0.3));
const sphere = CreateSphere("sphere", {diameter: 1.8, segments: 24}, scene);
sphere.position.set(1.8, 0.9, -1);
sphere.material = standard("sphere", new Color3(0.3, 0.55, 0.8));
const knot = CreateTorusKnot("knot", {radius: 0.8, tube: 0.25, radialSegments: 96}, scene);
knot.position.set(0.2, 2.2, 1.8);
knot.material = standard("knot", new Color3(0.85, 0.8, 0.4));
shapes.push(box, sphere, knot);
// posts: an InstancedMesh row and a thin-instanced row
const post = CreateCylinder("post", {height: 2.4, diameter: 0.3}, scene);
post.material = standard("post", new Color3(0.6, 0.6, 0.62));
post.position.set(-4, 1.2, -3);
for (let i = 1; i < 5; ++i) post.createInstance(`post${i}`).position.set(-4 + 2 * i, 1.2, -3);
const thin = CreateCylinder("thinPost", {height: 1.2, diameter: 0.3}, scene);
thin.material = post.material;
thin.thinInstanceAdd([0, 1, 2, 3, 4].map((i) => Matrix.Translation(-4 + 2 * i, 0.6, 3.5)));
shapes.push(post, thin);
for (const m of shapes) m.receiveShadows = true;

// The lights: the rectangle faces its local -z, turned down by its parent
const holder = new TransformNode("rectHolder", scene);
holder.position = new Vector3(-1, 6, 1);
holder.rotation.x = -Math.PI / 2;
const rect = new RectAreaLight("rect", Vector3.Zero(), 3, 2, scene);
rect.parent = holder;
rect.intensity = 40;
const sun = new DirectionalLight("sun", new Vector3(0.5, -1, 0.35), scene);
sun.intensity = 1.6;

const state = {light: params.get("light") === "sun" ? "sun" : "rect", mode: "penumbra"};
let shadows = null;

let attaching = 0;
async function attach() {
    // (the render loop goes on while the new add-on loads: it must not update the disposed one;
    // a switch during the load supersedes it)
    const mine = ++attaching;
    const old = shadows;
    shadows = null;
    if (old) old.dispose();
    const light = state.light === "sun" ? sun : rect;
    rect.setEnabled(light === rect);
    sun.setEnabled(light === sun);
    const loaded = await PenumbraShadows.load(engine, scene, light, light === sun ? {angularDiameter: 0.04} : {});
    if (mine !== attaching) return loaded.dispose();
    for (const m of [...shapes, ...post.instances]) loaded.addShadowCaster(m);
    loaded.enabled = state.mode === "penumbra";
    shadows = loaded;
}

async function set(changes) {
    const light = changes.light && changes.light !== state.light;
    Object.assign(state, changes);
    if (light) await attach();
    if (shadows) shadows.enabled = state.mode === "penumbra";
}

function render() {
    if (!shadows) return scene.render();
    shadows.update();
    scene.render();
    status.textContent = `${engine.isWebGPU ? "WebGPU" : "WebGL2"}, ${state.light}: ${shadows.info.casters} casters, ${shadows.info.receivers} receivers, last shadow update ${shadows.info.lastShadowMs.toFixed(1)} ms`;
}

for (const button of document.querySelectorAll("[data-light]")) button.onclick = () => set({light: button.dataset.light});
for (const button of document.querySelectorAll("[data-mode]")) button.onclick = () => set({mode: button.dataset.mode});
window.addEventListener("resize", () => engine.resize());

const ready = attach().then(async () => {
    await scene.whenReadyAsync();
    engine.runRenderLoop(render);
});
window.example = {ready, set, render, scene, info: () => ({engine: engine.isWebGPU ? "webgpu" : "webgl2", light: state.light, mode: state.mode, shadows: shadows.info})};
