// two_lights_webgpu.js — the page of three_webgpu_test.mjs --two-lights: a RectAreaLight and a sun,
// each with its own add-on (?rect=URL/ and ?sun=URL/: wgsl emission folders small enough that both
// fit WebGPU's 16 sampled textures a stage), on one MeshStandardNodeMaterial shared by a ground and
// a box. window.result: for each light alone, (lit with its add-on) / (lit without) against its own
// visibility; both lights on against the sum of each alone; the add-ons' WebGPU errors.
import * as THREE from "three/webgpu";
import {RectAreaLightTexturesLib} from "three/addons/lights/RectAreaLightTexturesLib.js";
import {PenumbraShadows} from "../penumbra_shadows.js";

async function main() {
    const query = new URLSearchParams(location.search);
    THREE.RectAreaLightNode.setLTC(RectAreaLightTexturesLib.init());
    const W = 96, H = 96;
    const renderer = new THREE.WebGPURenderer();
    renderer.setSize(W, H);
    const scene = new THREE.Scene();
    const camera = new THREE.PerspectiveCamera(50, 1, 0.1, 100);
    camera.position.set(0, 8, 8);
    camera.lookAt(0, 0, 0);
    const material = new THREE.MeshStandardNodeMaterial({color: 0xffffff, roughness: 1});
    const ground = new THREE.Mesh(new THREE.PlaneGeometry(10, 10), material);
    ground.rotation.x = -Math.PI / 2;
    ground.receiveShadow = true;
    const box = new THREE.Mesh(new THREE.BoxGeometry(1, 1, 1), material);
    box.position.set(0, 0.5, 0);
    box.castShadow = box.receiveShadow = true;
    scene.add(ground, box);
    const rect = new THREE.RectAreaLight(0xffffff, 4, 2, 2);
    rect.position.set(-1, 4, 0);
    rect.lookAt(-1, 0, 0);
    const sun = new THREE.DirectionalLight(0xffffff, 1.5);
    sun.position.set(3, 5, 1);
    scene.add(rect, sun, sun.target);
    const a = await PenumbraShadows.load(renderer, scene, rect, {emission: query.get("rect")});
    const b = await PenumbraShadows.load(renderer, scene, sun, {emission: query.get("sun")});
    a.update();
    b.update();
    const target = new THREE.RenderTarget(W, H, {type: THREE.FloatType});
    // frames top row first; renderVisibility bottom row first
    const frame = async (shadowed, rectOn, sunOn) => {
        a.enabled = b.enabled = shadowed;
        rect.visible = rectOn;
        sun.visible = sunOn;
        a.update();
        b.update();
        renderer.setRenderTarget(target);
        renderer.render(scene, camera);
        renderer.setRenderTarget(null);
        const px = await renderer.readRenderTargetPixelsAsync(target, 0, 0, W, H);
        return Array.from({length: W * H}, (_, i) => px[4 * ((H - 1 - Math.floor(i / W)) * W + (i % W))]);
    };
    const visibility = {rect: await a.renderVisibility(camera, W, H), sun: await b.renderVisibility(camera, W, H)};
    const alone = {rect: [await frame(true, true, false), await frame(false, true, false)],
                   sun: [await frame(true, false, true), await frame(false, false, true)]};
    const both = await frame(true, true, true);
    const out = {errors: [a.info.error, b.info.error].filter(Boolean), sum: 0};
    for (const light of ["rect", "sun"]) {
        const [on, off] = alone[light], v = visibility[light];
        const r = out[light] = {lit: 0, shadowed: 0, worst: 0};
        for (let i = 0; i < W * H; ++i) {
            if (!(off[i] > 1e-3)) continue;
            ++r.lit;
            if (v[i] < 0.5) ++r.shadowed;
            r.worst = Math.max(r.worst, Math.abs(on[i] / off[i] - v[i]));
        }
    }
    for (let i = 0; i < W * H; ++i) out.sum = Math.max(out.sum, Math.abs(both[i] - alone.rect[0][i] - alone.sun[0][i]));
    // the shadows differ: each add-on scales its own light only
    out.distinct = visibility.rect.reduce((n, x, i) => n + (Math.abs(x - visibility.sun[i]) > 0.1 ? 1 : 0), 0);
    window.result = out;
}

main().catch((e) => { window.result = {error: `${e.message}\n${e.stack}`}; console.error(e); });
