// cutout_page.js — the cut-out casters' page of targets/web/babylon_test.mjs (cutout.html; ?engine=webgpu:
// on a WebGPUEngine), as penumbra-three's test/cutout_page.js: a RectAreaLight 1 × 1 two units above
// a ground, and between them a 1.2 × 1.2 plane whose StandardMaterial's diffuseTexture is opaque but
// for a transparent square hole in its middle (0.6 wide), alpha-tested (transparencyMode ALPHATEST,
// hasAlpha, useAlphaFromDiffuseTexture, alphaCutOff 0.5). Through the hole the whole light reaches
// the ground's centre; drawn solid, the plane hides all of it there.
// window.penumbraCut:
//   run(options, offset = 0)  loads an add-on with `options` (PenumbraShadows.load), adds the plane as a
//                 caster, updates it twice, reads its visibility from above and disposes it; the
//                 diffuseTexture's uOffset and vOffset are `offset` meanwhile (0.5: the hole at the
//                 plane's edges, the middle opaque):
//                 {alphaTest: info.alphaTest, cutDraws: info.cutDraws, emissionCuts: the emission's
//                  config.alpha_test, hole: mean visibility under the hole's middle, error, warnings: console.warn texts}
//   rule()        the detection rule (cutOf) on Babylon's materials as its glTF loader makes them:
//                 [failure texts]
import {Engine} from "@babylonjs/core/Engines/engine.js";
import {WebGPUEngine} from "@babylonjs/core/Engines/webgpuEngine.js";
import {Scene} from "@babylonjs/core/scene.js";
import {FreeCamera} from "@babylonjs/core/Cameras/freeCamera.js";
import {Camera} from "@babylonjs/core/Cameras/camera.js";
import {RectAreaLight} from "@babylonjs/core/Lights/rectAreaLight.js";
import {TransformNode} from "@babylonjs/core/Meshes/transformNode.js";
import {CreateGround} from "@babylonjs/core/Meshes/Builders/groundBuilder.js";
import {CreatePlane} from "@babylonjs/core/Meshes/Builders/planeBuilder.js";
import {Mesh} from "@babylonjs/core/Meshes/mesh.js";
import {StandardMaterial} from "@babylonjs/core/Materials/standardMaterial.js";
import {PBRMaterial} from "@babylonjs/core/Materials/PBR/pbrMaterial.js";
import {Material} from "@babylonjs/core/Materials/material.js";
import {RawTexture} from "@babylonjs/core/Materials/Textures/rawTexture.js";
import {Vector3} from "@babylonjs/core/Maths/math.vector.js";
import {PenumbraShadows, cutOf} from "../penumbra_babylon.js";

const SIZE = 32; // the visibility image: the ground's [-2, 2]² seen from above

function holeTexture(scene) {
    const n = 8, data = new Uint8Array(4 * n * n).fill(255);
    for (let y = 2; y < 6; ++y) for (let x = 2; x < 6; ++x) data[4 * (y * n + x) + 3] = 0;
    const texture = RawTexture.CreateRGBATexture(data, n, n, scene, false, false, 1 /* Texture.NEAREST_SAMPLINGMODE */);
    texture.hasAlpha = true;
    return texture;
}

// The rule on the materials Babylon's glTF loader makes (MASK: ALPHATEST, alphaCutOff, the albedo
// texture's hasAlpha; BLEND: ALPHABLEND, hasAlpha and useAlphaFromAlbedoTexture) and StandardMaterial's.
function checkRule(scene, texture) {
    const failures = [];
    const expect = (name, material, cutoff) => {
        const cut = cutOf(material);
        const got = cut ? cut.cutoff : null;
        if (cutoff === null ? got !== null : !(got !== null && Math.abs(got - cutoff) < 1e-6))
            failures.push(`cutOf(${name}) gave ${got === null ? "solid" : `cutoff ${got}`}, expected ${cutoff === null ? "solid" : `cutoff ${cutoff}`}`);
    };
    const pbr = (mode, setup = () => {}) => {
        const m = new PBRMaterial(`rule ${mode}`, scene);
        m.albedoTexture = texture;
        m.transparencyMode = mode;
        setup(m);
        return m;
    };
    expect("PBR MASK (alphaCutOff 0.3)", pbr(Material.MATERIAL_ALPHATEST, (m) => (m.alphaCutOff = 0.3)), 0.3);
    expect("PBR BLEND", pbr(Material.MATERIAL_ALPHABLEND, (m) => (m.useAlphaFromAlbedoTexture = true)), 0.5);
    expect("PBR BLEND, alpha 0.5", pbr(Material.MATERIAL_ALPHABLEND, (m) => { m.useAlphaFromAlbedoTexture = true; m.alpha = 0.5; }), 1);
    expect("PBR BLEND without useAlphaFromAlbedoTexture", pbr(Material.MATERIAL_ALPHABLEND), null);
    expect("PBR OPAQUE", pbr(Material.MATERIAL_OPAQUE), null);
    expect("PBR without an albedo texture", new PBRMaterial("rule bare", scene), null);
    const standard = (mode, setup = () => {}) => {
        const m = new StandardMaterial(`rule standard ${mode}`, scene);
        m.diffuseTexture = texture;
        m.transparencyMode = mode;
        setup(m);
        return m;
    };
    expect("Standard ALPHATEST (default alphaCutOff)", standard(Material.MATERIAL_ALPHATEST, (m) => (m.useAlphaFromDiffuseTexture = true)), 0.4);
    expect("Standard ALPHATEST without useAlphaFromDiffuseTexture", standard(Material.MATERIAL_ALPHATEST), null);
    expect("Standard, no transparencyMode (Babylon tests hasAlpha)", standard(null), 0.4);
    expect("Standard, no transparencyMode, useAlphaFromDiffuseTexture (blended)", standard(null, (m) => (m.useAlphaFromDiffuseTexture = true)), 0.5);
    return failures;
}

async function main() {
    const webgpu = new URLSearchParams(location.search).get("engine") === "webgpu";
    const canvas = document.getElementById("view");
    canvas.width = canvas.height = SIZE;
    let engine;
    if (webgpu) {
        engine = new WebGPUEngine(canvas, {antialias: false});
        await engine.initAsync();
    } else {
        engine = new Engine(canvas, false);
    }
    const scene = new Scene(engine);
    // the light: local -z (its emitting side) turned to -y
    const holder = new TransformNode("lightHolder", scene);
    holder.position = new Vector3(0, 2, 0);
    holder.rotation.x = -Math.PI / 2;
    const light = new RectAreaLight("rect", Vector3.Zero(), 1, 1, scene);
    light.parent = holder;
    const ground = CreateGround("ground", {width: 4, height: 4}, scene);
    ground.material = new StandardMaterial("ground", scene);
    ground.receiveShadows = true;
    const plane = CreatePlane("plane", {size: 1.2, sideOrientation: Mesh.DOUBLESIDE}, scene);
    plane.rotation.x = Math.PI / 2;
    plane.position.y = 1;
    const material = new StandardMaterial("plane", scene);
    material.diffuseTexture = holeTexture(scene);
    material.useAlphaFromDiffuseTexture = true;
    material.transparencyMode = Material.MATERIAL_ALPHATEST;
    material.alphaCutOff = 0.5;
    plane.material = material;
    const camera = new FreeCamera("camera", new Vector3(0, 5, 0), scene);
    camera.mode = Camera.ORTHOGRAPHIC_CAMERA;
    camera.orthoLeft = camera.orthoBottom = -2;
    camera.orthoRight = camera.orthoTop = 2;
    camera.minZ = 0.1;
    camera.maxZ = 10;
    camera.upVector = new Vector3(0, 0, 1);
    camera.setTarget(Vector3.Zero());
    scene.activeCamera = camera;

    // mean visibility over the pixels whose ground point (x, z) is within r of (cx, cz)
    const mean = (v, cx, cz, r) => {
        let sum = 0, n = 0;
        for (let j = 0; j < SIZE; ++j)
            for (let i = 0; i < SIZE; ++i) {
                const x = -2 + 4 * (i + 0.5) / SIZE, z = -2 + 4 * (j + 0.5) / SIZE; // (rows and columns: either order, the scene is symmetric)
                if (Math.abs(x - cx) <= r && Math.abs(z - cz) <= r) { sum += v[j * SIZE + i]; ++n; }
            }
        return sum / n;
    };
    window.penumbraCut = {
        renderer: webgpu ? "WebGPUEngine" : "Engine (WebGL2)",
        plane, // (for checks by hand: its material, texture and geometry)
        rule: () => checkRule(scene, material.diffuseTexture),
        run: async (options = {}, offset = 0) => {
            const texture = material.diffuseTexture;
            texture.uOffset = texture.vOffset = offset;
            const warnings = [];
            const warn = console.warn;
            console.warn = (...args) => { warnings.push(args.join(" ")); warn.apply(console, args); };
            try {
                const shadows = await PenumbraShadows.load(engine, scene, light, options);
                shadows.addShadowCaster(plane);
                shadows.update();
                shadows.needsUpdate = true;
                shadows.update(); // (a second shadow phase: the warning stays one)
                const v = await shadows.renderVisibility(camera, SIZE, SIZE);
                const out = {alphaTest: shadows.info.alphaTest, cutDraws: shadows.info.cutDraws, emissionCuts: shadows.config.alpha_test === true,
                             hole: mean(v, 0, 0, 0.1), error: shadows.info.error ?? null, warnings};
                shadows.dispose();
                return out;
            } finally {
                console.warn = warn;
                texture.uOffset = texture.vOffset = 0;
            }
        },
    };
}

main().catch((e) => { window.penumbraCut = {error: `${e.message}\n${e.stack}`}; console.error(e); });
