// three.js — the three.js page of the bundler tests (bundle_test.mjs): an entry that imports
// "penumbra-three" and "three" as a user's project does, bundled by Vite, esbuild, webpack 5 or
// Rollup. A ground under a RectAreaLight, a box casting (on layer 1, which the camera does not
// see, so that every pixel is ground). window.bundleCheck.run() returns the images the test
// compares: lit without the add-on, lit with it, and the add-on's visibility (one light: the
// three-package test checks several).
import * as THREE from "three";
import {RectAreaLightUniformsLib} from "three/addons/lights/RectAreaLightUniformsLib.js";
import {PenumbraShadows, PenumbraError} from "penumbra-three";

const W = 96, H = 96;

async function run() {
    const renderer = new THREE.WebGLRenderer({antialias: false});
    RectAreaLightUniformsLib.init();
    renderer.setPixelRatio(1);
    renderer.setSize(W, H);
    document.body.appendChild(renderer.domElement);
    const target = new THREE.WebGLRenderTarget(W, H, {type: THREE.FloatType});
    const scene = new THREE.Scene();
    const ground = new THREE.Mesh(new THREE.PlaneGeometry(10, 10), new THREE.MeshStandardMaterial({roughness: 1, metalness: 0}));
    ground.rotation.x = -Math.PI / 2;
    ground.receiveShadow = true;
    const box = new THREE.Mesh(new THREE.BoxGeometry(1.2, 2, 1.2), new THREE.MeshStandardMaterial());
    box.position.set(0, 1, 0);
    box.castShadow = true;
    box.layers.set(1);
    const light = new THREE.RectAreaLight(0xffffff, 4, 1.2, 1.2);
    light.position.set(-1, 4, 0);
    light.rotation.set(-Math.PI / 2, 0, 0); // facing down
    scene.add(ground, box, light);
    const camera = new THREE.PerspectiveCamera(50, W / H, 0.1, 50);
    camera.position.set(0, 7, 5);
    camera.lookAt(0, 0, 0);
    // the light's radiance at each pixel (the mean of r, g, b), bottom row first
    const image = () => {
        renderer.setRenderTarget(target);
        renderer.render(scene, camera);
        renderer.setRenderTarget(null);
        const rgba = new Float32Array(4 * W * H);
        renderer.readRenderTargetPixels(target, 0, 0, W, H, rgba);
        return Array.from({length: W * H}, (_, i) => (rgba[4 * i] + rgba[4 * i + 1] + rgba[4 * i + 2]) / 3);
    };
    const shadows = await PenumbraShadows.load(renderer, scene, light);
    shadows.update();
    const shadowed = image();
    const visibility = Array.from(shadows.renderVisibility(camera, W, H));
    shadows.dispose();
    let afterDispose;
    try {
        shadows.update();
        afterDispose = "no error";
    } catch (e) {
        afterDispose = e instanceof PenumbraError ? e.message : `not a PenumbraError: ${e}`;
    }
    const unshadowed = image();
    return {width: W, height: H, shadowed: [shadowed], unshadowed: [unshadowed], visibility: [visibility], afterDispose,
            library: `three r${THREE.REVISION}`, lights: ["RectAreaLight"]};
}

window.bundleCheck = {run: () => run().catch((e) => ({error: `${e.message}\n${e.stack}`})), materials: ["standard"]};
