// test_page.js — the browser tests' page (targets/web/three_test.mjs, three_peers.mjs): one of
// Penumbra's scenes rebuilt in three.js from a bundle (?bundle=URL/), with the add-on attached to
// its light, and window.penumbraThree for automation:
//   visibility()           the add-on's visibility at the camera (bottom row first)
//   frameUniforms()        the add-on's light-frame uniforms and the bundle's
//   materialRatio()        the RectAreaLight-only render with the add-on over the one without it
//   peer(type, settings)   three.js's own shadow mask (PCFShadowMap / VSMShadowMap) from a SpotLight
//                          (or DirectionalLight for the sun) placed where the light is
//   moveLight(dx)          moves the light along its x axis by dx (scene units), re-renders
import * as THREE from "three";
import {RectAreaLightUniformsLib} from "three/addons/lights/RectAreaLightUniformsLib.js";
import {PenumbraShadows} from "../penumbra_shadows.js";
import {addonControls, loadBundleScene, materialRatio, placementVariants} from "./bundle_scene.js";

function rendererName(gl) {
    const debug = gl.getExtension("WEBGL_debug_renderer_info");
    return gl.getParameter(debug ? debug.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
}

async function main() {
    const base = new URLSearchParams(location.search).get("bundle");
    if (!base) throw new Error("no ?bundle=URL/");
    RectAreaLightUniformsLib.init();
    const {bundle, scene, camera, light, mesh} = await loadBundleScene(base);
    const W = bundle.width, H = bundle.height;
    const canvas = document.getElementById("view");
    const renderer = new THREE.WebGLRenderer({canvas, antialias: false});
    renderer.setPixelRatio(1);
    renderer.setSize(W, H);
    // ?config=JSON (with ?wasm=URL): the same configuration emitted in the page by the
    // WebAssembly emitter instead of the bundle's emission folder
    const config = new URLSearchParams(location.search).get("config");
    const options = config ? {emission: JSON.parse(config), wasm: new URLSearchParams(location.search).get("wasm")}
                           : {emission: base + "emission/"};
    if (bundle.light.kind === "sun") options.angularDiameter = bundle.light.angular_diameter_degrees * Math.PI / 180;
    const shadows = await PenumbraShadows.load(renderer, scene, light, options);
    shadows.update();

    const target = new THREE.WebGLRenderTarget(W, H, {type: THREE.FloatType});
    const readTarget = () => {
        const rgba = new Float32Array(4 * W * H);
        renderer.readRenderTargetPixels(target, 0, 0, W, H, rgba);
        return rgba;
    };
    const renderInto = () => {
        renderer.setRenderTarget(target);
        renderer.setClearColor(0x000000, 1);
        renderer.clear();
        renderer.render(scene, camera);
        renderer.setRenderTarget(null);
        return readTarget();
    };

    // three.js's own shadows: a SpotLight at the rectangle's centre looking along its normal (the
    // cone covering the scene's bounds), or a DirectionalLight along the sun; its shadow mask
    // (getShadowMask(), the factor three multiplies the light by) through a ShadowMaterial.
    const maskMaterial = new THREE.ShadowMaterial({side: THREE.DoubleSide});
    maskMaterial.transparent = false;
    maskMaterial.blending = THREE.NoBlending;
    maskMaterial.onBeforeCompile = (shader) => {
        const line = "gl_FragColor = vec4( color, opacity * ( 1.0 - getShadowMask() ) );";
        if (!shader.fragmentShader.includes(line)) throw new Error("three's ShadowMaterial changed");
        shader.fragmentShader = shader.fragmentShader.replace(line, "gl_FragColor = vec4( vec3( getShadowMask() ), 1.0 );");
    };
    const box = new THREE.Box3().setFromObject(mesh);
    const peer = (type, settings) => {
        let peerLight;
        const centre = new THREE.Vector3().setFromMatrixPosition(light.matrixWorld);
        if (bundle.light.kind === "sun") {
            peerLight = new THREE.DirectionalLight(0xffffff, 1);
            const d = new THREE.Vector3().fromArray(bundle.light.direction).normalize();
            const c = box.getCenter(new THREE.Vector3()), r = box.getBoundingSphere(new THREE.Sphere()).radius;
            peerLight.position.copy(c).addScaledVector(d, -2 * r);
            peerLight.target.position.copy(c);
            const cam = peerLight.shadow.camera;
            Object.assign(cam, {left: -r, right: r, top: r, bottom: -r, near: 0.5 * r, far: 3.5 * r});
        } else {
            peerLight = new THREE.SpotLight(0xffffff, 1);
            const normal = new THREE.Vector3(0, 0, -1).applyQuaternion(light.quaternion);
            peerLight.position.copy(centre);
            peerLight.target.position.copy(centre).add(normal);
            let angle = 0, near = Infinity, far = 0;
            for (let i = 0; i < 8; ++i) {
                const p = new THREE.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z).sub(centre);
                const along = p.dot(normal);
                angle = Math.max(angle, Math.acos(Math.min(1, along / p.length())));
                near = Math.min(near, Math.max(along, 0));
                far = Math.max(far, p.length());
            }
            peerLight.angle = Math.min(angle * 1.05, Math.PI / 2 - 0.01);
            peerLight.penumbra = 0;
            peerLight.shadow.camera.near = Math.max(near * 0.5, 0.01 * far);
            peerLight.shadow.camera.far = far * 1.05;
        }
        peerLight.castShadow = true;
        peerLight.shadow.mapSize.set(settings.mapSize, settings.mapSize);
        peerLight.shadow.radius = settings.radius;
        if (settings.blurSamples) peerLight.shadow.blurSamples = settings.blurSamples;
        peerLight.shadow.bias = settings.bias;
        peerLight.shadow.normalBias = settings.normalBias;
        renderer.shadowMap.enabled = true;
        renderer.shadowMap.type = THREE[type === "PCFSoftShadowMap" ? "PCFShadowMap" : type]; // r187: the same, without the warning
        maskMaterial.needsUpdate = true; // three recompiles for another shadow map type only so
        scene.add(peerLight, peerLight.target);
        scene.overrideMaterial = maskMaterial;
        const light0 = light.visible;
        light.visible = false;
        scene.updateMatrixWorld();
        const rgba = renderInto();
        light.visible = light0;
        scene.overrideMaterial = null;
        scene.remove(peerLight, peerLight.target);
        peerLight.shadow.dispose();
        renderer.shadowMap.enabled = false;
        // background: the clear colour 0; geometry pixels carry the mask
        const out = new Float32Array(W * H);
        for (let i = 0; i < out.length; ++i) out[i] = rgba[4 * i];
        return out;
    };

    window.penumbraThree = {
        info: () => ({config: shadows.config, width: W, height: H, renderer: rendererName(renderer.getContext()),
                      three: THREE.REVISION, casters: shadows.info.casters, receivers: shadows.info.receivers}),
        visibility: () => Array.from(shadows.renderVisibility(camera, W, H)),
        frameUniforms: () => ({computed: shadows._frame.uniforms, bundle: bundle.uniforms}),
        materialRatio: () => materialRatio(scene, shadows, renderInto),
        peer: (type, settings) => Array.from(peer(type, settings)),
        ...addonControls(light, shadows), // moveLight(dx), shadowUpdates(), update()
        variants: () => placementVariants(scene, mesh, shadows, () => shadows.renderVisibility(camera, W, H)),
        // dispose(): the runner's textures and programs are deleted, the materials restored
        dispose: () => {
            const gl = renderer.getContext();
            const textures = Object.values(shadows.runner.textures).map((t) => t.id);
            const programs = Object.values(shadows.runner.programs).map((p) => p.id);
            shadows.dispose();
            return {textures: textures.length, texturesAlive: textures.filter((t) => gl.isTexture(t)).length,
                    programs: programs.length, programsAlive: programs.filter((p) => gl.isProgram(p)).length,
                    restored: mesh.material.customProgramCacheKey() === THREE.Material.prototype.customProgramCacheKey.call(mesh.material)};
        },
    };
}

main().catch((e) => { window.penumbraThree = {error: `${e.message}\n${e.stack}`}; console.error(e); });
