// example.js — the add-on's example: a Babylon.js scene (a ground, a few shapes, instances and thin
// instances of posts; or a closed room lit by a ceiling panel) lit by a RectAreaLight or a sun
// (DirectionalLight) with Penumbra's soft shadows, an ArcRotateCamera, and buttons to switch the
// scene, the light, the shadows off and on, and the engine (Engine, WebGL2, or WebGPUEngine: the page
// reloads with ?engine=webgl2|webgpu).
// URL parameters ?size=WxH: a fixed canvas size (screenshots); ?scene=shapes|room.
// window.example (automation): ready, set({scene, light, mode}), render(), info(), scene.
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
import {Mesh} from "@babylonjs/core/Meshes/mesh.js";
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
const outdoor = [ground, ...shapes, ...post.instances];

// The room: a closed 6 × 3 × 5 box seen from inside (floor, walls, ceiling), a table with a box on it,
// a chair, a bookshelf and a crate, lit by a 1.2 × 0.6 panel 2 cm under the ceiling. The ceiling, behind
// the light's plane, casts nothing; the walls beside the panel lie outside the slicing pyramid
// (info.contained is false: docs/model.md §1.2b). Everything casts and receives.
const room = [];
const shell = CreateBox("room", {width: 6, height: 3, depth: 5, sideOrientation: Mesh.BACKSIDE}, scene);
shell.position.y = 1.5;
shell.material = standard("walls", new Color3(0.85, 0.83, 0.8));
shell.material.specularColor = Color3.Black();
room.push(shell);
const block = ([w, h, d], [x, y, z], material) => { // a box standing on (x, y, z)
    const mesh = CreateBox("block", {width: w, height: h, depth: d}, scene);
    mesh.position.set(x, y + h / 2, z);
    mesh.material = material;
    room.push(mesh);
};
const legs = (w, d, h, [x, z], material) => { // four legs under a w × d top
    for (const [dx, dz] of [[-1, -1], [1, -1], [-1, 1], [1, 1]]) block([0.05, h, 0.05], [x + dx * (w / 2 - 0.05), 0, z + dz * (d / 2 - 0.05)], material);
};
const wood = standard("wood", new Color3(0.6, 0.42, 0.26)), red = standard("red", new Color3(0.8, 0.38, 0.23));
block([1.6, 0.05, 0.8], [-0.7, 0.72, -1.9], wood); // the table
legs(1.6, 0.8, 0.72, [-0.7, -1.9], wood);
block([0.35, 0.25, 0.25], [-1.1, 0.77, -2.0], standard("blue", new Color3(0.23, 0.47, 0.8))); // a box on it
block([0.45, 0.05, 0.45], [-0.5, 0.43, -1.2], red); // a chair: seat, back, legs
block([0.45, 0.5, 0.05], [-0.5, 0.48, -0.99], red);
legs(0.45, 0.45, 0.43, [-0.5, -1.2], red);
block([1.1, 2.0, 0.35], [1.6, 0, -2.3], standard("shelf", new Color3(0.44, 0.5, 0.38))); // a bookshelf, a crate
block([0.5, 0.45, 0.6], [2.4, 0, -1.3], standard("crate", new Color3(0.69, 0.56, 0.38)));
for (const m of room) m.receiveShadows = true;

// The lights: the rectangle faces its local -z, turned down by its parent
const holder = new TransformNode("rectHolder", scene);
holder.position = new Vector3(-1, 6, 1);
holder.rotation.x = -Math.PI / 2;
const rect = new RectAreaLight("rect", Vector3.Zero(), 3, 2, scene);
rect.parent = holder;
rect.intensity = 40;
const sun = new DirectionalLight("sun", new Vector3(0.5, -1, 0.35), scene);
sun.intensity = 1.6;

const state = {scene: params.get("scene") === "room" ? "room" : "shapes", light: params.get("light") === "sun" ? "sun" : "rect", mode: "penumbra"};
let shadows = null;

// The chosen scene enabled (the add-on shadows enabled meshes only), its light and camera placed.
function showScene() {
    const inRoom = state.scene === "room";
    for (const m of outdoor) m.setEnabled(!inRoom);
    for (const m of room) m.setEnabled(inRoom);
    holder.position = inRoom ? new Vector3(0, 2.98, -0.6) : new Vector3(-1, 6, 1);
    rect.width = inRoom ? 1.2 : 3;
    rect.height = inRoom ? 0.6 : 2;
    rect.intensity = inRoom ? 25 : 40;
    // (in the room: the camera by the front wall, the near plane close, for things come close there)
    Object.assign(camera, inRoom ? {alpha: 0.91, beta: 1.38, radius: 4.65, minZ: 0.05} : {alpha: -Math.PI / 3, beta: 1.0, radius: 16, minZ: 1});
    camera.setTarget(inRoom ? new Vector3(-0.4, 0.8, -1.3) : new Vector3(0, 1, 0), false, false, true); // (keeping those angles)
}
showScene();

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
    for (const m of [...shapes, ...post.instances, ...room]) loaded.addShadowCaster(m); // (the disabled ones cast nothing)
    loaded.enabled = state.mode === "penumbra";
    shadows = loaded;
}

async function set(changes) {
    const light = changes.light && changes.light !== state.light;
    const place = changes.scene && changes.scene !== state.scene;
    Object.assign(state, changes);
    if (place) showScene();
    if (light) await attach();
    if (shadows) shadows.enabled = state.mode === "penumbra";
}

function render() {
    if (!shadows) return scene.render();
    shadows.update();
    scene.render();
    status.textContent = `${engine.isWebGPU ? "WebGPU" : "WebGL2"}, ${state.light}: ${shadows.info.casters} casters, ${shadows.info.receivers} receivers, last shadow update ${shadows.info.lastShadowMs.toFixed(1)} ms` +
        (shadows.info.contained ? "" : " (info.contained false: part of the scene lies behind the light or beyond its 70° pyramid)");
}

for (const button of document.querySelectorAll("[data-scene]")) button.onclick = () => set({scene: button.dataset.scene});
for (const button of document.querySelectorAll("[data-light]")) button.onclick = () => set({light: button.dataset.light});
for (const button of document.querySelectorAll("[data-mode]")) button.onclick = () => set({mode: button.dataset.mode});
window.addEventListener("resize", () => engine.resize());

const ready = attach().then(async () => {
    await scene.whenReadyAsync();
    engine.runRenderLoop(render);
});
window.example = {ready, set, render, scene, info: () => ({engine: engine.isWebGPU ? "webgpu" : "webgl2", scene: state.scene, light: state.light, mode: state.mode, shadows: shadows.info})};
