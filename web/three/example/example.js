// example.js — the add-on's example: a three.js scene lit by a RectAreaLight (or a sun), with
// Penumbra's soft shadows, OrbitControls, and a lil-gui panel to move and resize the light, pick
// the emission and compare with three's own PCFSoftShadowMap / VSMShadowMap from a SpotLight
// placed where the rectangle is.
//
// URL parameters: ?light=rect|sun, ?renderer=webgl|webgpu (three's WebGLRenderer, the default, or
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
import {PenumbraShadows, EMISSIONS, loadEmitter} from "../penumbra_shadows.js"; // "penumbra-three" from npm

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

// The scene: a ground, a few shapes and an InstancedMesh of posts; all cast and receive.
const ground = new THREE.Mesh(new THREE.PlaneGeometry(24, 24), new THREE.MeshStandardMaterial({color: 0xb8b8b8, roughness: 0.9}));
ground.rotation.x = -Math.PI / 2;
ground.receiveShadow = true;
scene.add(ground);
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
    scene.add(mesh);
}
const posts = new THREE.InstancedMesh(new THREE.BoxGeometry(0.2, 1.2, 0.2), new THREE.MeshStandardMaterial({color: 0x8a8a9a}), 12);
for (let i = 0; i < posts.count; ++i) {
    const a = (i / posts.count) * Math.PI * 2;
    posts.setMatrixAt(i, new THREE.Matrix4().makeTranslation(5 * Math.cos(a), 0.6, 5 * Math.sin(a)));
}
posts.castShadow = posts.receiveShadow = true;
scene.add(posts);
scene.add(new THREE.HemisphereLight(0x8090a0, 0x202020, 0.35));

// The lights: the rectangle (Penumbra's), the sun (Penumbra's, ?light=sun), and three's SpotLight
// / DirectionalLight for the comparison modes.
const state = {
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

function placeLights() {
    rect.position.set(state.x, state.y, state.z);
    rect.rotation.set(-Math.PI / 2 + state.tiltX * Math.PI / 180, 0, state.tiltZ * Math.PI / 180);
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
    const normal = new THREE.Vector3(0, 0, -1).applyQuaternion(rect.quaternion);
    spot.position.copy(rect.position);
    spot.target.position.copy(rect.position).add(normal);
    spot.angle = 80 * Math.PI / 180; // penumbra 1: a smooth fall-off towards the cone's edge
    spot.shadow.radius = state.pcfRadius;
    sunShadow.position.copy(sun.position);
    Object.assign(sunShadow.shadow.camera, {left: -13, right: 13, top: 13, bottom: -13, near: 1, far: 45});
    sunShadow.shadow.camera.updateProjectionMatrix();
}

// Which light lights the scene, and whose shadows: Penumbra's add-on, or three's own shadow maps.
function applyMode() {
    const isRect = state.light === "rect";
    if (isRect ? !rect.parent : rect.parent) isRect ? scene.add(rect) : scene.remove(rect);
    if (!isRect ? !sun.parent : sun.parent) !isRect ? scene.add(sun) : scene.remove(sun);
    helper.visible = state.helper;
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
    const light = state.light === "rect" ? rect : sun;
    // the shipped emissions of this light that this renderer runs (WebGPU: those with a "-wgsl" twin)
    const keys = Object.keys(EMISSIONS).filter((k) => k.startsWith(state.light) && !k.endsWith("-wgsl") &&
                                                      (rendererKind === "webgl" || Object.hasOwn(EMISSIONS, `${k}-wgsl`)));
    if (!keys.includes(state.emission)) state.emission = `${state.light}-nbuffer-16x512`;
    const loaded = await PenumbraShadows.load(renderer, scene, light, {emission: state.emission, angularDiameter: state.diameter * Math.PI / 180, wasm});
    if (light !== (state.light === "rect" ? rect : sun)) { // switched again while loading
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
        ` — shadow phase runs: ${shadows.info.shadowUpdates}` + (shadows.info.contained ? "" : " — the scene reaches the light's plane: move it up");
}

function onResize() {
    if (fixedSize) return;
    camera.aspect = window.innerWidth / window.innerHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(window.innerWidth, window.innerHeight);
    if (shadows) shadows.setSize(window.innerWidth, window.innerHeight);
}

let gui = null, emissionFolder = null, emissionController = null, folders = null;
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
    folders.rect.add(state, "intensity", 0, 20, 0.1).onChange(changed);
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
    info: () => ({shadows: {...shadows.info}, config: shadows.config, memory: {...renderer.info.memory}, three: THREE.REVISION,
                  renderer: rendererKind, backend: renderer.isWebGPURenderer ? (renderer.backend.isWebGPUBackend ? "webgpu" : "webgl2") : "webgl2"}),
};
ready.catch((e) => { window.example = {error: `${e.message}\n${e.stack}`}; console.error(e); });
