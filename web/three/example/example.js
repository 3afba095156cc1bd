// example.js — the add-on's example: a three.js scene lit by a RectAreaLight (or a sun), with
// Penumbra's soft shadows, OrbitControls, and a lil-gui panel to switch the scene (shapes on a ground,
// or a closed room lit by a ceiling panel), move and resize the light, pick the emission and compare
// with three's own PCFSoftShadowMap / VSMShadowMap from a SpotLight placed where the rectangle is.
//
// The third scene, "room (glTF)" (?scene=gltf), is web/rooms/room.gltf loaded by three's GLTFLoader with
// penumbra-three's EXT_lights_area plugin: the add-on shadows the RectAreaLight the file brings.
//
// URL parameters: ?scene=shapes|room|gltf, ?light=rect|sun, ?renderer=webgl|webgpu (three's WebGLRenderer, the default, or
// WebGPURenderer from three/webgpu: the same scene, materials and PenumbraShadows.load(); the panel's
// "renderer" switch reloads the page with the other), ?size=WxH (a fixed canvas size, for screenshots
// and benchmarks), ?wasm=URL (penumbra_emitter.wasm, for the configuration panel, e.g. /build/wasm/penumbra_emitter.wasm),
// ?offscreen=1 (frames into a render target, read by window.example.capture(): headless chromium's
// SwiftShader loses the WebGPU device when a WebGPU canvas is presented, so screenshots go this way).
// window.example (automation): ready, state, set(changes), render(), bench({mode, frames, moving}).
import * as THREE from "three";
import {OrbitControls} from "three/addons/controls/OrbitControls.js";
import {RectAreaLightHelper} from "three/addons/helpers/RectAreaLightHelper.js";
import {RectAreaLightUniformsLib} from "three/addons/lights/RectAreaLightUniformsLib.js";
import GUI from "three/addons/libs/lil-gui.module.min.js";
import {GLTFLoader} from "three/addons/loaders/GLTFLoader.js";
import {PenumbraShadows, EMISSIONS, loadEmitter, GLTFLightsAreaExtension} from "../penumbra_shadows.js"; // "penumbra-three" from npm

const params = new URLSearchParams(location.search);
const fixedSize = params.get("size") ? params.get("size").split("x").map(Number) : null;
const wasm = params.get("wasm"); // the WebAssembly emitter's module, where it is not beside web/three/penumbra_emitter.js

// The renderer: WebGL2, or WebGPU (three/webgpu, loaded only then; a RectAreaLight there needs
// the LTC textures handed to its light node instead of RectAreaLightUniformsLib).
const rendererKind = params.get("renderer") === "webgpu" ? "webgpu" : "webgl";
let renderer;
if (rendererKind === "webgpu") {
    const [{WebGPURenderer, RectAreaLightNode}, {RectAreaLightTexturesLib}] = await Promise.all([
        import("three/webgpu"), import("three/addons/lights/RectAreaLightTexturesLib.js")]);
    renderer = new WebGPURenderer({antialias: true});
    RectAreaLightNode.setLTC(RectAreaLightTexturesLib.init());
    await renderer.init();
} else {
    renderer = new THREE.WebGLRenderer({antialias: true});
    RectAreaLightUniformsLib.init();
}
renderer.setPixelRatio(fixedSize ? 1 : Math.min(window.devicePixelRatio, 2));
renderer.setSize(...(fixedSize || [window.innerWidth, window.innerHeight]));
renderer.toneMapping = THREE.ACESFilmicToneMapping;
document.body.appendChild(renderer.domElement);
// (WebGPURenderer: the output render target, which gets the canvas's tone mapping and sRGB output;
// WebGLRenderer: a plain target, linear)
const offscreen = params.get("offscreen") === "1" && fixedSize ? new THREE.RenderTarget(fixedSize[0], fixedSize[1], {samples: 4}) : null;
if (offscreen && renderer.setOutputRenderTarget) renderer.setOutputRenderTarget(offscreen);

const scene = new THREE.Scene();
scene.background = new THREE.Color(0x20242a);
const size = fixedSize || [window.innerWidth, window.innerHeight];
const camera = new THREE.PerspectiveCamera(45, size[0] / size[1], 0.1, 200);
camera.position.set(9, 8, 11);
const controls = new OrbitControls(camera, renderer.domElement);
controls.target.set(0, 1, 0);
controls.update();

// The first scene: a ground, a few shapes and an InstancedMesh of posts; all cast and receive.
const outdoor = new THREE.Group();
scene.add(outdoor);
const ground = new THREE.Mesh(new THREE.PlaneGeometry(24, 24), new THREE.MeshStandardMaterial({color: 0xb8b8b8, roughness: 0.9}));
ground.rotation.x = -Math.PI / 2;
ground.receiveShadow = true;
outdoor.add(ground);
const shapes = [
    [new THREE.TorusKnotGeometry(0.8, 0.28, 160, 24), new THREE.MeshPhysicalMaterial({color: 0xd0603a, roughness: 0.35, clearcoat: 0.6}), [0, 2.2, 0]],
    [new THREE.BoxGeometry(1.6, 1.6, 1.6), new THREE.MeshStandardMaterial({color: 0x3a78d0, roughness: 0.6}), [-3, 0.8, 1.5]],
    [new THREE.SphereGeometry(0.9, 48, 24), new THREE.MeshStandardMaterial({color: 0xe0c050, roughness: 0.3, metalness: 0.2}), [2.8, 0.9, 1.8]],
    [new THREE.CylinderGeometry(0.5, 0.5, 3, 32), new THREE.MeshStandardMaterial({color: 0x60b070, roughness: 0.5}), [-1.5, 1.5, -2.5]],
];
for (const [geometry, material, position] of shapes) {
    const mesh = new THREE.Mesh(geometry, material);
    mesh.position.fromArray(position);
    mesh.castShadow = mesh.receiveShadow = true;
    outdoor.add(mesh);
}
const posts = new THREE.InstancedMesh(new THREE.BoxGeometry(0.2, 1.2, 0.2), new THREE.MeshStandardMaterial({color: 0x8a8a9a}), 12);
for (let i = 0; i < posts.count; ++i) {
    const a = (i / posts.count) * Math.PI * 2;
    posts.setMatrixAt(i, new THREE.Matrix4().makeTranslation(5 * Math.cos(a), 0.6, 5 * Math.sin(a)));
}
posts.castShadow = posts.receiveShadow = true;
outdoor.add(posts);
scene.add(new THREE.HemisphereLight(0x8090a0, 0x202020, 0.35));

// The second scene: a closed 6 × 3 × 5 room (floor, walls and ceiling: a box seen from inside), a table
// with a box on it, a chair, a bookshelf and a crate, lit by a 1.2 × 0.6 panel 2 cm under the ceiling.
// The ceiling, behind the light's plane, casts nothing; the walls beside the panel lie outside the
// slicing pyramid (info.contained is false: docs/model.md §1.2b). Everything casts and receives.
const room = new THREE.Group();
scene.add(room);
const shell = new THREE.Mesh(new THREE.BoxGeometry(6, 3, 5), new THREE.MeshStandardMaterial({color: 0xd8d4cc, roughness: 0.9, side: THREE.BackSide}));
shell.position.y = 1.5;
room.add(shell);
const block = ([w, h, d], [x, y, z], color) => { // a box standing on (x, y, z)
    const mesh = new THREE.Mesh(new THREE.BoxGeometry(w, h, d), new THREE.MeshStandardMaterial({color, roughness: 0.7}));
    mesh.position.set(x, y + h / 2, z);
    room.add(mesh);
};
const legs = (w, d, h, [x, z], color) => { // four legs under a w × d top
    for (const [dx, dz] of [[-1, -1], [1, -1], [-1, 1], [1, 1]]) block([0.05, h, 0.05], [x + dx * (w / 2 - 0.05), 0, z + dz * (d / 2 - 0.05)], color);
};
block([1.6, 0.05, 0.8], [-0.7, 0.72, -1.9], 0x9a6b43); // the table
legs(1.6, 0.8, 0.72, [-0.7, -1.9], 0x9a6b43);
block([0.35, 0.25, 0.25], [-1.1, 0.77, -2.0], 0x3a78d0); // a box on it
block([0.45, 0.05, 0.45], [-0.5, 0.43, -1.2], 0xd0603a); // a chair: seat, back, legs
block([0.45, 0.5, 0.05], [-0.5, 0.48, -0.99], 0xd0603a);
legs(0.45, 0.45, 0.43, [-0.5, -1.2], 0xd0603a);
block([1.1, 2.0, 0.35], [1.6, 0, -2.3], 0x6f7f60); // a bookshelf, a crate
block([0.5, 0.45, 0.6], [2.4, 0, -1.3], 0xb09060);
room.traverse((o) => { if (o.isMesh) o.castShadow = o.receiveShadow = true; });

// The third scene: a room from a glTF file (web/rooms/room.gltf), its ceiling panel an EXT_lights_area
// light that the plugin makes a RectAreaLight; loaded when first chosen. Its light is the one the add-on
// shadows there (and the sliders move); the file's camera, if any, gives the view.
const gltfRoom = new THREE.Group();
scene.add(gltfRoom);
let gltfLight = null, gltfLoading = null;
const GLTF_ROOM = new URL("../../rooms/room.gltf", import.meta.url);
function loadGltfRoom() {
    gltfLoading ??= new GLTFLoader().register((parser) => new GLTFLightsAreaExtension(parser)).loadAsync(GLTF_ROOM.href).then((gltf) => {
        gltf.scene.traverse((o) => { if (o.isMesh) o.castShadow = o.receiveShadow = true; });
        gltf.scene.traverse((o) => { if (o.isRectAreaLight && !gltfLight) gltfLight = o; });
        if (!gltfLight) throw new Error(`${GLTF_ROOM}: no EXT_lights_area rect light`);
        gltfRoom.add(gltf.scene);
        gltfRoom.updateMatrixWorld(true);
        gltfLight.add(new RectAreaLightHelper(gltfLight));
        const base = gltfLight.quaternion.clone();
        const eye = gltf.cameras[0] ? gltf.cameras[0].getWorldPosition(new THREE.Vector3()) : new THREE.Vector3(2.5, 1.9, 2.3);
        const look = gltf.cameras[0] ? gltf.cameras[0].getWorldDirection(new THREE.Vector3()) : new THREE.Vector3(-0.5, -0.3, -1).normalize();
        const box = new THREE.Box3().setFromObject(gltf.scene);
        // the file's units: intensity in nits (1000 for an office panel), shown at the exposure that makes
        // the built-in room's 30 look alike
        SCENES.gltf = {light: {x: gltfLight.position.x, y: gltfLight.position.y, z: gltfLight.position.z, width: gltfLight.width,
                               height: gltfLight.height, intensity: gltfLight.intensity}, base,
                       y: [box.min.y + 0.5, gltfLight.position.y], xz: Math.max(-box.min.x, box.max.x, -box.min.z, box.max.z) - 0.2,
                       size: 2.5, intensityMax: 2 * gltfLight.intensity, exposure: 30 / gltfLight.intensity,
                       eye: eye.toArray(), target: eye.clone().addScaledVector(look, 3).toArray()};
    });
    return gltfLoading;
}
// The rectangle the add-on shadows: the glTF's light in the glTF room, the example's own elsewhere.
const rectLight = () => (state.scene === "gltf" && gltfLight ? gltfLight : rect);
const RECT_BASE = new THREE.Quaternion().setFromEuler(new THREE.Euler(-Math.PI / 2, 0, 0)); // facing down

// Each scene's light, camera and slider ranges.
const SCENES = {
    shapes: {light: {x: 0, y: 6.5, z: 0, width: 3, height: 2, intensity: 6}, y: [3.5, 12], xz: 6, size: 8, eye: [9, 8, 11], target: [0, 1, 0]},
    room: {light: {x: 0, y: 2.98, z: -0.6, width: 1.2, height: 0.6, intensity: 30}, y: [1.5, 2.98], xz: 2.8, size: 2.5,
           eye: [2.5, 1.9, 2.3], target: [0.6, 0.9, -1.6]},
};

// The lights: the rectangle (Penumbra's), the sun (Penumbra's, ?light=sun), and three's SpotLight
// / DirectionalLight for the comparison modes.
const state = {
    scene: ["room", "gltf"].includes(params.get("scene")) ? params.get("scene") : "shapes",
    light: params.get("light") === "sun" ? "sun" : "rect",
    mode: "penumbra", // penumbra | pcf | vsm | none
    x: 0, y: 6.5, z: 0, tiltX: 0, tiltZ: 0, width: 3, height: 2, intensity: 6,
    azimuth: -60, elevation: 50, diameter: 5,
    emission: null, shadowIntensity: 1, animate: false, helper: true, renderer: rendererKind,
    pcfRadius: 8, vsmRadius: 16, mapSize: 1024,
};
const rect = new THREE.RectAreaLight(0xffffff, state.intensity, state.width, state.height);
const helper = new RectAreaLightHelper(rect);
rect.add(helper);
const sun = new THREE.DirectionalLight(0xffffff, 2.5);
scene.add(sun.target);
const spot = new THREE.SpotLight(0xffffff, 0, 0, Math.PI / 3, 1, 2);
spot.castShadow = true;
scene.add(spot, spot.target);
const sunShadow = new THREE.DirectionalLight(0xffffff, 0);
sunShadow.castShadow = true;
scene.add(sunShadow, sunShadow.target);

let shadows = null;
const status = document.getElementById("status");

// The chosen scene shown (the add-on shadows what is visible), its light and camera placed.
function showScene() {
    const preset = SCENES[state.scene];
    outdoor.visible = state.scene === "shapes";
    room.visible = state.scene === "room";
    gltfRoom.visible = state.scene === "gltf";
    renderer.toneMappingExposure = preset.exposure ?? 1;
    Object.assign(state, preset.light, {tiltX: 0, tiltZ: 0});
    camera.position.fromArray(preset.eye);
    controls.target.fromArray(preset.target);
    controls.update();
    sliderRanges();
}

// The light's sliders: outdoors above the ground, in the room under its ceiling.
function sliderRanges() {
    if (!folders) return;
    const preset = SCENES[state.scene];
    const [x, y, z, width, height, intensity] = ["x", "y", "z", "width", "height", "intensity"].map((name) => folders.rect.controllers.find((c) => c.property === name));
    y.min(preset.y[0]).max(preset.y[1]);
    for (const c of [x, z]) c.min(-preset.xz).max(preset.xz);
    for (const c of [width, height]) c.max(preset.size);
    intensity.max(preset.intensityMax ?? 40);
}

function placeLights() {
    // (the built-in rectangle faces down; the glTF's keeps the file's orientation; the tilts turn either)
    const rect = rectLight(), base = rect === gltfLight ? SCENES.gltf.base : RECT_BASE;
    rect.position.set(state.x, state.y, state.z);
    rect.quaternion.copy(base).multiply(new THREE.Quaternion().setFromEuler(new THREE.Euler(state.tiltX * Math.PI / 180, 0, state.tiltZ * Math.PI / 180)));
    rect.width = state.width;
    rect.height = state.height;
    rect.intensity = state.intensity;
    const az = state.azimuth * Math.PI / 180, el = state.elevation * Math.PI / 180;
    const toSun = new THREE.Vector3(Math.cos(el) * Math.cos(az), Math.sin(el), Math.cos(el) * Math.sin(az));
    sun.position.copy(toSun).multiplyScalar(20);
    sun.target.position.set(0, 0, 0);
    if (shadows) {
        shadows.angularDiameter = state.diameter * Math.PI / 180;
        shadows.intensity = state.shadowIntensity;
    }
    // three's peers: where the rectangle is, looking along its normal; the sun's direction.
    rect.updateMatrixWorld();
    const normal = new THREE.Vector3(0, 0, -1).transformDirection(rect.matrixWorld);
    rect.getWorldPosition(spot.position);
    spot.target.position.copy(spot.position).add(normal);
    spot.angle = 80 * Math.PI / 180; // penumbra 1: a smooth fall-off towards the cone's edge
    spot.shadow.radius = state.pcfRadius;
    sunShadow.position.copy(sun.position);
    Object.assign(sunShadow.shadow.camera, {left: -13, right: 13, top: 13, bottom: -13, near: 1, far: 45});
    sunShadow.shadow.camera.updateProjectionMatrix();
}

// Which light lights the scene, and whose shadows: Penumbra's add-on, or three's own shadow maps.
function applyMode() {
    const isRect = state.light === "rect";
    const own = isRect && rectLight() === rect; // the example's rectangle in the scene (not in the glTF room)
    if (own ? !rect.parent : rect.parent) own ? scene.add(rect) : scene.remove(rect);
    if (gltfLight) gltfLight.visible = isRect && rectLight() === gltfLight;
    if (!isRect ? !sun.parent : sun.parent) !isRect ? scene.add(sun) : scene.remove(sun);
    helper.visible = state.helper;
    if (gltfLight) gltfLight.children.forEach((c) => { c.visible = state.helper; });
    const three = state.mode === "pcf" || state.mode === "vsm";
    renderer.shadowMap.enabled = three;
    const type = state.mode === "vsm" ? THREE.VSMShadowMap : THREE.PCFShadowMap; // PCFSoftShadowMap is PCFShadowMap in r187
    if (renderer.shadowMap.type !== type) {
        renderer.shadowMap.type = type;
        scene.traverse((o) => o.material && (o.material.needsUpdate = true));
    }
    for (const l of [spot, sunShadow]) {
        l.shadow.radius = state.mode === "vsm" ? state.vsmRadius : state.pcfRadius;
        if (l.shadow.mapSize.x !== state.mapSize) {
            l.shadow.mapSize.set(state.mapSize, state.mapSize);
            l.shadow.dispose();
            l.shadow.map = null;
        }
    }
    // three's shadow maps darken only the light they belong to: in those modes the SpotLight
    // carries the rectangle's light (intensity in candela = radiance × area, decay 2)
    if (isRect) {
        const rect = rectLight();
        spot.visible = three;
        spot.intensity = three ? state.intensity * rect.width * rect.height : 0;
        rect.intensity = three ? 0 : state.intensity;
        sunShadow.visible = false;
    } else {
        sunShadow.visible = three;
        sunShadow.intensity = three ? sun.intensity : 0;
        sun.intensity = three ? 0 : 2.5;
        spot.visible = false;
    }
    if (shadows) shadows.enabled = state.mode === "penumbra";
}

// The add-on of the chosen light: the old one is disposed first and no frame uses it after that
// (update() after dispose() throws); until the new one is loaded, frames render unshadowed.
async function attach() {
    if (shadows) {
        const old = shadows;
        shadows = null;
        old.dispose();
    }
    const light = state.light === "rect" ? rectLight() : sun;
    // the shipped emissions of this light that this renderer runs (WebGPU: those with a "-wgsl" twin)
    const keys = Object.keys(EMISSIONS).filter((k) => k.startsWith(state.light) && !k.endsWith("-wgsl") &&
                                                      (rendererKind === "webgl" || Object.hasOwn(EMISSIONS, `${k}-wgsl`)));
    if (!keys.includes(state.emission)) state.emission = `${state.light}-nbuffer-16x512`;
    const loaded = await PenumbraShadows.load(renderer, scene, light, {emission: state.emission, angularDiameter: state.diameter * Math.PI / 180, wasm});
    if (light !== (state.light === "rect" ? rectLight() : sun)) { // switched again while loading
        loaded.dispose();
        return keys;
    }
    shadows = loaded;
    placeLights();
    applyMode();
    return keys;
}

function render() {
    if (state.animate) {
        const t = performance.now() / 1000;
        state.x = 2.5 * Math.sin(0.5 * t);
        state.z = 2.0 * Math.cos(0.4 * t);
        placeLights();
    }
    if (offscreen && !renderer.setOutputRenderTarget) renderer.setRenderTarget(offscreen);
    if (shadows) shadows.update(); // (none between two lights' add-ons)
    renderer.render(scene, camera);
    if (offscreen && !renderer.setOutputRenderTarget) renderer.setRenderTarget(null);
    if (!shadows) return;
    const c = shadows.config;
    status.textContent = `${rendererKind === "webgpu" ? "WebGPURenderer" : "WebGLRenderer"}: ${state.mode === "penumbra" ? `Penumbra ${c.slices} slices ${c.resolution}² ${c.filter} (${state.emitted ? "emitted in the page" : state.emission})` : state.mode === "none" ? "no shadows" : `three ${state.mode.toUpperCase()} shadow map, radius ${state.mode === "vsm" ? state.vsmRadius : state.pcfRadius}`}` +
        ` — shadow phase runs: ${shadows.info.shadowUpdates}` + (shadows.info.contained ? "" : " — info.contained false: part of the scene lies behind the light or beyond its 70° pyramid");
}

function onResize() {
    if (fixedSize) return;
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
    if (shadows) shadows.setSize(window.innerWidth, window.innerHeight);
}

let gui = null, emissionFolder = null, emissionController = null, folders = null;
if (state.scene === "gltf") await loadGltfRoom().catch((e) => { console.error(e); state.scene = "room"; });
showScene();

// Another scene: the glTF room loaded first (the built-in room if it cannot be), and the add-on moved
// to the scene's rectangle when that changed (the glTF room has its own light).
async function switchScene() {
    if (state.scene === "gltf") {
        try {
            await loadGltfRoom();
        } catch (e) {
            console.error(e);
            status.textContent = `room (glTF): ${e.message}`;
            state.scene = "room";
        }
    }
    showScene();
    if (state.light === "rect" && shadows && shadows.light !== rectLight()) await attach();
    placeLights();
    applyMode();
}
const onEmission = async (v) => { if (shadows) { await shadows.setEmission(v); state.emitted = false; } };

// The emissions of the light's kind in the GUI, and the light's own folder.
function showLight(keys) {
    emissionController = emissionController.options(keys).name("emission").onChange(onEmission);
    emissionController.updateDisplay(); // (attach() loaded state.emission: setValue would load it again, racing a later setEmission)
    folders.rect.show(state.light === "rect");
    folders.sun.show(state.light === "sun");
}

function buildGui(keys) {
    gui = new GUI({title: "Penumbra soft shadows"});
    const changed = () => { placeLights(); applyMode(); };
    gui.add(state, "scene", {"shapes on a ground": "shapes", "room (ceiling panel)": "room", "room (glTF)": "gltf"}).onChange(async () => {
        await switchScene();
        for (const c of gui.controllersRecursive()) c.updateDisplay();
    });
    gui.add(state, "mode", {"Penumbra (occlusion textures)": "penumbra", "three PCFSoftShadowMap (SpotLight)": "pcf", "three VSMShadowMap (SpotLight)": "vsm", "no shadows": "none"}).onChange(changed);
    gui.add(state, "light", {"RectAreaLight": "rect", "DirectionalLight (sun)": "sun"}).onChange(async () => showLight(await attach()));
    gui.add(state, "renderer", {"WebGLRenderer": "webgl", "WebGPURenderer (three/webgpu)": "webgpu"}).onChange((v) => {
        params.set("renderer", v);
        params.set("light", state.light);
        location.search = params.toString(); // another renderer: the page again, with it
    });
    emissionFolder = gui.addFolder("emission (shipped)");
    emissionController = emissionFolder.add(state, "emission", keys).name("emission").onChange(onEmission);
    gui.add(state, "shadowIntensity", 0, 1, 0.01).name("shadow intensity").onChange(changed);
    folders = {rect: gui.addFolder("RectAreaLight"), sun: gui.addFolder("Sun")};
    folders.rect.add(state, "x", -6, 6, 0.05).onChange(changed);
    folders.rect.add(state, "y", 3.5, 12, 0.05).onChange(changed);
    folders.rect.add(state, "z", -6, 6, 0.05).onChange(changed);
    folders.rect.add(state, "tiltX", -45, 45, 1).name("tilt x (°)").onChange(changed);
    folders.rect.add(state, "tiltZ", -45, 45, 1).name("tilt z (°)").onChange(changed);
    folders.rect.add(state, "width", 0.2, 8, 0.05).onChange(changed);
    folders.rect.add(state, "height", 0.2, 8, 0.05).onChange(changed);
    folders.rect.add(state, "intensity", 0, 40, 0.1).onChange(changed);
    folders.rect.add(state, "helper").name("show the rectangle").onChange(changed);
    folders.rect.add(state, "animate").name("move the light");
    folders.sun.add(state, "azimuth", -180, 180, 1).name("azimuth (°)").onChange(changed);
    folders.sun.add(state, "elevation", 15, 90, 1).name("elevation (°)").onChange(changed);
    folders.sun.add(state, "diameter", 0.2, 15, 0.1).name("angular diameter (°)").onChange(changed);
    // Any configuration, emitted in the page, where the WebAssembly emitter is there.
    loadEmitter(wasm).then(() => {
        const custom = {slices: 16, resolution: 512, filter: "nbuffer", fusion: "extent", packing: "atlas", tangentClip: true};
        const folder = gui.addFolder("configuration (emitted)");
        folder.add(custom, "slices", 1, 16, 1);
        folder.add(custom, "resolution", [128, 256, 512, 1024]);
        // (sat needs float textures ES 3.00 lacks; WGSL has no mipmap filter)
        folder.add(custom, "filter", rendererKind === "webgpu" ? ["nbuffer", "gaussian"] : ["mipmap", "nbuffer", "gaussian"]);
        folder.add(custom, "fusion", ["probabilistic", "additive", "maximum", "average", "chained", "correlated", "extent", "clustered"]);
        folder.add(custom, "packing", ["atlas", "array", "volume"]);
        folder.add(custom, "tangentClip").name("tangent clip");
        const message = {text: ""};
        folder.add(message, "text").name("emitter").disable();
        folder.add({emit: async () => {
            try {
                await shadows.setEmission({slices: custom.slices, resolution: custom.resolution, filter: custom.filter, fusion: custom.fusion,
                                           packing: custom.packing, tangent_clip: custom.tangentClip});
                state.emitted = true;
                message.text = "ok";
            } catch (e) {
                message.text = e.message.replace("PenumbraShadows: ", "");
            }
            for (const c of folder.controllers) c.updateDisplay();
        }}, "emit").name("emit and use");
    }).catch(() => {}); // no emitter: the shipped emissions only
    const peers = gui.addFolder("three.js shadow maps");
    peers.add(state, "pcfRadius", 1, 32, 1).name("PCF radius (texels)").onChange(changed);
    peers.add(state, "vsmRadius", 1, 32, 1).name("VSM radius (texels)").onChange(changed);
    peers.add(state, "mapSize", [512, 1024, 2048]).name("map size").onChange(changed);
    peers.close();
    folders.rect.show(state.light === "rect");
    folders.sun.show(state.light === "sun");
    sliderRanges();
    return gui;
}

const ready = (async () => {
    const keys = await attach();
    buildGui(keys);
    window.addEventListener("resize", onResize);
    renderer.setAnimationLoop(fixedSize ? null : render);
    render();
})();

// Frame time: `frames` frames, each synchronised by a one-pixel readPixels (SwiftShader: compare
// ratios only). moving: the light moves every frame, so the add-on re-runs its shadow phase.
async function bench({mode, frames = 30, moving = false}) {
    await ready;
    if (rendererKind !== "webgl") throw new Error("bench(): times WebGL2 frames (readPixels); open the page without ?renderer=webgpu");
    renderer.setAnimationLoop(null);
    const saved = {...state};
    state.mode = mode;
    applyMode();
    const gl = renderer.getContext(), pixel = new Uint8Array(4);
    const frame = (i) => {
        if (moving) {
            if (state.light === "rect") state.x = 2 * Math.sin(0.1 * i);
            else state.azimuth = saved.azimuth + 10 * Math.sin(0.1 * i);
            placeLights();
        }
        render();
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    };
    for (let i = 0; i < 3; ++i) frame(i); // warm-up: shader compiles, shadow map allocation
    const times = [];
    for (let i = 0; i < frames; ++i) {
        const t0 = performance.now();
        frame(i + 3);
        times.push(performance.now() - t0);
    }
    Object.assign(state, saved);
    placeLights();
    applyMode();
    times.sort((a, b) => a - b);
    return {mode, moving, frames, medianMs: times[frames >> 1], meanMs: times.reduce((s, t) => s + t, 0) / frames};
}

window.example = {
    ready,
    state,
    set: async (changes) => {
        await ready;
        const light = state.light;
        if (changes.scene && changes.scene !== state.scene) {
            state.scene = changes.scene;
            await switchScene(); // (its light and camera; the changes below may move them)
            changes = {...changes, scene: state.scene}; // (the built-in room where the glTF could not load)
        }
        Object.assign(state, changes);
        if (state.light !== light) { showLight(await attach()); state.emitted = false; }
        if (changes.emission) await shadows.setEmission(state.emission);
        placeLights();
        applyMode();
        for (const c of gui.controllersRecursive()) c.updateDisplay();
        render();
    },
    render: () => render(),
    // ?offscreen=1: the last frame as a PNG data URL (top row first, as the canvas would show it)
    capture: async () => {
        if (!offscreen) throw new Error("capture(): open the page with ?offscreen=1&size=WxH");
        const [w, h] = fixedSize;
        const pixels = await renderer.readRenderTargetPixelsAsync(offscreen, 0, 0, w, h);
        const canvas = document.createElement("canvas");
        canvas.width = w;
        canvas.height = h;
        const image = new ImageData(w, h);
        // WebGL2 reads bottom row first, WebGPU top row first
        for (let y = 0; y < h; ++y) {
            const row = rendererKind === "webgl" ? h - 1 - y : y;
            image.data.set(pixels.subarray(4 * row * w, 4 * (row + 1) * w), 4 * y * w);
        }
        canvas.getContext("2d").putImageData(image, 0, 0);
        return canvas.toDataURL("image/png");
    },
    emit: async (config) => { await ready; await shadows.setEmission(config); state.emitted = true; render(); return shadows.config; },
    bench,
    info: () => ({shadows: {...shadows.info}, light: `${shadows.light.type} ${shadows.light.name}`, config: shadows.config, memory: {...renderer.info.memory}, three: THREE.REVISION,
                  renderer: rendererKind, backend: renderer.isWebGPURenderer ? (renderer.backend.isWebGPUBackend ? "webgpu" : "webgl2") : "webgl2"}),
};
ready.catch((e) => { window.example = {error: `${e.message}\n${e.stack}`}; console.error(e); });
