// test_page_webgpu.js — the page of targets/web/three_webgpu_test.mjs: one of Penumbra's scenes
// rebuilt in three.js from a wgsl bundle (?bundle=URL/) on a WebGPURenderer, the add-on attached to
// its light through the same PenumbraShadows.load() as on WebGL2, and window.penumbraThree:
//   info()              the add-on's configuration, three's revision, the backend and the adapter
//   visibility()        the add-on's visibility at the camera (bottom row first)
//   frameUniforms()     the add-on's light-frame uniforms and the bundle's
//   materialRatio()     the render with the add-on over the one without it (RectAreaLight or sun only)
//   variants()          the mesh moved as a Mesh, InstancedMesh, SkinnedMesh and morph target
//   moveLight(dx), update(), shadowUpdates(), dispose()
// ?material=physical-node: the receivers get a MeshPhysicalNodeMaterial instead of the bundle
// scene's plain MeshStandardMaterial (which WebGPURenderer converts).
import * as THREE from "three/webgpu";
import {RectAreaLightTexturesLib} from "three/addons/lights/RectAreaLightTexturesLib.js";
import {PenumbraShadows} from "../penumbra_shadows.js";
import {addonControls, loadBundleScene, materialRatio, placementVariants} from "./bundle_scene.js";

async function main() {
    const query = new URLSearchParams(location.search);
    const base = query.get("bundle");
    if (!base) throw new Error("no ?bundle=URL/");
    THREE.RectAreaLightNode.setLTC(RectAreaLightTexturesLib.init());
    const {bundle, scene, camera, light, mesh} = await loadBundleScene(base);
    if (query.get("material") === "physical-node")
        mesh.material = new THREE.MeshPhysicalNodeMaterial({color: 0xffffff, roughness: 1, metalness: 0, side: THREE.DoubleSide});
    const W = bundle.width, H = bundle.height;
    const canvas = document.getElementById("view");
    const renderer = new THREE.WebGPURenderer({canvas, antialias: false});
    renderer.setPixelRatio(1);
    renderer.setSize(W, H);
    await renderer.init();
    const options = {emission: base + "emission/"};
    if (bundle.light.kind === "sun") options.angularDiameter = bundle.light.angular_diameter_degrees * Math.PI / 180;
    const shadows = await PenumbraShadows.load(renderer, scene, light, options);
    shadows.update();

    const target = new THREE.RenderTarget(W, H, {type: THREE.FloatType});
    const renderInto = async () => {
        renderer.setRenderTarget(target);
        renderer.setClearColor(0x000000, 1);
        renderer.clear();
        renderer.render(scene, camera);
        renderer.setRenderTarget(null);
        return renderer.readRenderTargetPixelsAsync(target, 0, 0, W, H); // top row first
    };
    const flip = (rgba) => { // → bottom row first, as the bundles
        const out = new Float32Array(rgba.length);
        for (let y = 0; y < H; ++y) out.set(rgba.subarray(4 * y * W, 4 * (y + 1) * W), 4 * (H - 1 - y) * W);
        return out;
    };
    const adapter = renderer.backend.device.adapterInfo || {};
    window.penumbraThree = {
        info: () => ({config: shadows.config, width: W, height: H, three: THREE.REVISION, backend: renderer.backend.isWebGPUBackend ? "webgpu" : "webgl2",
                      adapter: `${adapter.vendor || "?"} ${adapter.architecture || ""}`.trim(), casters: shadows.info.casters,
                      receivers: shadows.info.receivers, addon: shadows.constructor.name, material: mesh.material.type}),
        visibility: async () => Array.from(await shadows.renderVisibility(camera, W, H)),
        frameUniforms: () => ({computed: shadows._frame.uniforms, bundle: bundle.uniforms}),
        materialRatio: () => materialRatio(scene, shadows, async () => flip(await renderInto())),
        variants: () => placementVariants(scene, mesh, shadows, () => shadows.renderVisibility(camera, W, H)),
        ...addonControls(light, shadows), // moveLight(dx), shadowUpdates(), update()
        error: undefined,
        shadowError: () => shadows.info.error,
        // dispose(): the material's hooks gone, update() refused
        dispose: () => {
            const material = mesh.material;
            const hooked = Object.hasOwn(material, "setupLightingModel") && Object.hasOwn(material, "customProgramCacheKey");
            shadows.dispose();
            let refused = false;
            try { shadows.update(); } catch (e) { refused = /after dispose/.test(e.message); }
            return {hooked, refused, restored: !Object.hasOwn(material, "setupLightingModel") && !Object.hasOwn(material, "customProgramCacheKey")};
        },
    };
}

main().catch((e) => { window.penumbraThree = {error: `${e.message}\n${e.stack}`}; console.error(e); });
