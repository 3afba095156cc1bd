// main.js — the page of the npm package test (three_package_test.mjs): a fresh Vite project's
// entry, importing "penumbra-three" and "three" as a user's project does. A ground lit by two
// shadowed lights (two RectAreaLights, or a RectAreaLight and a sun), one add-on each, the same
// material receiving both; a box that casts (on layer 1, which the camera does not see, so that
// every pixel is ground). window.penumbraPackage.run(pair) returns the images the test compares.
// ?renderer=webgpu: the same on a WebGPURenderer (three/webgpu, bundled by Vite as a user's
// project does), the add-on's wgsl path.
import * as THREE from "three";
import {RectAreaLightUniformsLib} from "three/addons/lights/RectAreaLightUniformsLib.js";
import {PenumbraShadows, PenumbraError, EMISSIONS} from "penumbra-three";

const W = 96, H = 96;
const webgpu = new URLSearchParams(location.search).get("renderer") === "webgpu";
let renderer, target;
// (no top-level await: Vite's default build target has none)
async function start() {
    if (webgpu) {
        const [{WebGPURenderer, RectAreaLightNode}, {RectAreaLightTexturesLib}] = await Promise.all([
            import("three/webgpu"), import("three/addons/lights/RectAreaLightTexturesLib.js")]);
        renderer = new WebGPURenderer({antialias: false});
        RectAreaLightNode.setLTC(RectAreaLightTexturesLib.init());
        await renderer.init();
        target = new THREE.RenderTarget(W, H, {type: THREE.FloatType});
    } else {
        renderer = new THREE.WebGLRenderer({antialias: false});
        RectAreaLightUniformsLib.init();
        target = new THREE.WebGLRenderTarget(W, H, {type: THREE.FloatType});
    }
    renderer.setPixelRatio(1);
    renderer.setSize(W, H);
    document.body.appendChild(renderer.domElement);
}

// The light's radiance at each pixel (linear, the mean of r, g, b), bottom row first.
async function render(scene, camera) {
    // WebGPURenderer: one animation frame before each image, as a page rendering from its animation
    // loop has (back-to-back renders without one sometimes drew the sun at its previous intensity:
    // 2 of 4 runs of rect+sun after rect+rect; none in 6 with it)
    if (webgpu) await new Promise((resolve) => requestAnimationFrame(resolve));
    renderer.setRenderTarget(target);
    renderer.setClearColor(0x000000, 1);
    renderer.clear();
    renderer.render(scene, camera);
    renderer.setRenderTarget(null);
    let rgba = new Float32Array(4 * W * H);
    if (webgpu) {
        const top = await renderer.readRenderTargetPixelsAsync(target, 0, 0, W, H); // top row first
        for (let y = 0; y < H; ++y) rgba.set(top.subarray(4 * y * W, 4 * (y + 1) * W), 4 * (H - 1 - y) * W);
    } else {
        renderer.readRenderTargetPixels(target, 0, 0, W, H, rgba);
    }
    const out = new Array(W * H);
    for (let i = 0; i < W * H; ++i) out[i] = (rgba[4 * i] + rgba[4 * i + 1] + rgba[4 * i + 2]) / 3;
    return out;
}

function rectLight(x) {
    const light = new THREE.RectAreaLight(0xffffff, 4, 1.2, 1.2);
    light.position.set(x, 4, 0);
    light.rotation.set(-Math.PI / 2, 0, 0); // facing down
    return light;
}

// pair: "rect+rect" (the second with the one-texture mipmap emission: two default emissions
// would sample 20 textures in one material, over WebGL2's 16 units) or "rect+sun". On WebGPU (no
// mipmap filter in WGSL) both are configurations emitted in the page at 32² (six textures each;
// the sun at 64²).
async function run(pair) {
    const scene = new THREE.Scene();
    const material = new THREE.MeshStandardMaterial({color: 0xffffff, roughness: 1, metalness: 0});
    const ground = new THREE.Mesh(new THREE.PlaneGeometry(10, 10), material);
    ground.rotation.x = -Math.PI / 2;
    ground.receiveShadow = true;
    const box = new THREE.Mesh(new THREE.BoxGeometry(1.2, 2, 1.2), new THREE.MeshStandardMaterial());
    box.position.set(0, 1, 0);
    box.castShadow = true;
    box.layers.set(1); // casts (the add-ons take meshes whatever their layers), the camera does not see it
    scene.add(ground, box);
    const first = rectLight(-2);
    let second, options;
    if (pair === "rect+rect") {
        second = rectLight(2);
        options = {emission: "rect-mipmap-16x512"};
    } else {
        second = new THREE.DirectionalLight(0xffffff, 3);
        second.position.set(4, 4, 0);
        second.target.position.set(0, 0, 0);
        scene.add(second.target);
        options = {emission: "sun-mipmap-16x512", angularDiameter: 0.05};
    }
    scene.add(first, second);
    const camera = new THREE.PerspectiveCamera(50, W / H, 0.1, 50);
    camera.position.set(0, 7, 5);
    camera.lookAt(0, 0, 0);
    // (the sun at 64², seven textures: six + seven + three's three still fit 16)
    const small = {slices: 16, resolution: 32, filter: "nbuffer"};
    if (webgpu) options = {...options, emission: pair === "rect+rect" ? small : {...small, resolution: 64}};
    const a = await PenumbraShadows.load(renderer, scene, first, webgpu ? {emission: small} : {});
    const b = await PenumbraShadows.load(renderer, scene, second, options);
    const intensities = [first.intensity, second.intensity];
    const image = async (lights, shadowed) => {
        first.intensity = lights[0] ? intensities[0] : 0;
        second.intensity = lights[1] ? intensities[1] : 0;
        for (const s of [a, b]) {
            if (s.disposed) continue;
            s.enabled = shadowed;
            s.update();
        }
        return render(scene, camera);
    };
    const out = {pair, width: W, height: H, three: THREE.REVISION, emissions: Object.keys(EMISSIONS),
                 configs: [a.config, b.config].map((c) => `${c.light} ${c.filter} ${c.slices}x${c.resolution}`)};
    out.unshadowed = [await image([1, 0], false), await image([0, 1], false)];
    out.shadowed = [await image([1, 0], true), await image([0, 1], true)];
    out.both = await image([1, 1], true);
    // (renderVisibility: a Float32Array on WebGL2, its Promise on WebGPU)
    out.visibility = [Array.from(await a.renderVisibility(camera, W, H)), Array.from(await b.renderVisibility(camera, W, H))];
    // dispose(): the other add-on keeps shadowing; update() afterwards throws
    b.dispose();
    try {
        b.update();
        out.updateAfterDispose = "no error";
    } catch (e) {
        out.updateAfterDispose = e instanceof PenumbraError ? e.message : `not a PenumbraError: ${e}`;
    }
    b.dispose(); // a second time: nothing
    out.afterDispose = await image([1, 0], true);
    // a configuration emitted in the page by the WebAssembly emitter the package ships
    if (pair === "rect+rect") {
        await a.setEmission({slices: 8, resolution: webgpu ? 64 : 256, filter: webgpu ? "nbuffer" : "mipmap"});
        a.update();
        const c = a.config;
        out.emitted = {config: `${c.light} ${c.filter} ${c.slices}x${c.resolution}`,
                       shadowed: Array.from(await a.renderVisibility(camera, W, H)).filter((v) => v < 0.5).length};
    }
    a.dispose();
    out.restored = material.onBeforeCompile === THREE.Material.prototype.onBeforeCompile &&
                   material.customProgramCacheKey === THREE.Material.prototype.customProgramCacheKey &&
                   !Object.hasOwn(material, "setupLightingModel");
    first.intensity = intensities[0];
    return out;
}

start().then(() => {
    window.penumbraPackage = {run, renderer: webgpu ? (renderer.backend.isWebGPUBackend ? "WebGPU" : "WebGPURenderer's WebGL2 fallback")
                                                    : renderer.getContext().getParameter(renderer.getContext().RENDERER)};
}, (e) => { window.penumbraPackage = {error: `${e.message}\n${e.stack}`}; });
