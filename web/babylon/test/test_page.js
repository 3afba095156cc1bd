// test_page.js — one of Penumbra's built-in scenes rebuilt in Babylon.js from a target bundle
// (penumbra-export-bundle --target essl300, ?bundle=URL/): the same triangles (mesh.f32, flat
// normals, one StandardMaterial, casting and receiving), the same light (a RectAreaLight whose axes
// are the rows of the exported penumbra_lightFromWorld, or a DirectionalLight for the sun), the same
// camera (a right-handed scene: glm::lookAt / glm::perspective), and the add-on with the bundle's
// emission folder; ?engine=webgpu: on a WebGPUEngine (the bundle's emission then a wgsl one).
// window.penumbraBabylon (targets/web/babylon_test.mjs):
//   frameUniforms()   the add-on's light-frame uniforms and the bundle's
//   visibility()      the add-on's visibility at the bundle's size, bottom row first
//   variants()        the visibility with the casters placed by a matrix M five ways (below)
//   materialRatio()   the StandardMaterial lit with the add-on over lit without it, per pixel (0 where unlit)
//   dispose()         {refused}: update() after dispose() throws a PenumbraError
import {Engine} from "@babylonjs/core/Engines/engine.js";
import {WebGPUEngine} from "@babylonjs/core/Engines/webgpuEngine.js";
import {RenderTargetTexture} from "@babylonjs/core/Materials/Textures/renderTargetTexture.js";
import {Color4} from "@babylonjs/core/Maths/math.color.js";
import {Scene} from "@babylonjs/core/scene.js";
import {FreeCamera} from "@babylonjs/core/Cameras/freeCamera.js";
import {RectAreaLight} from "@babylonjs/core/Lights/rectAreaLight.js";
import {DirectionalLight} from "@babylonjs/core/Lights/directionalLight.js";
import {TransformNode} from "@babylonjs/core/Meshes/transformNode.js";
import {Mesh} from "@babylonjs/core/Meshes/mesh.js";
import "@babylonjs/core/Meshes/instancedMesh.js";
import "@babylonjs/core/Meshes/thinInstanceMesh.js";
import {Skeleton} from "@babylonjs/core/Bones/skeleton.js";
import {Bone} from "@babylonjs/core/Bones/bone.js";
import {MorphTargetManager} from "@babylonjs/core/Morph/morphTargetManager.js";
import {MorphTarget} from "@babylonjs/core/Morph/morphTarget.js";
import {VertexData} from "@babylonjs/core/Meshes/mesh.vertexData.js";
import {StandardMaterial} from "@babylonjs/core/Materials/standardMaterial.js";
import {Matrix, Quaternion, Vector3} from "@babylonjs/core/Maths/math.vector.js";
import {PenumbraError, PenumbraShadows} from "../penumbra_babylon.js";

async function fetchOk(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
    return response;
}

async function start() {
    const query = new URLSearchParams(location.search);
    const base = query.get("bundle"), webgpu = query.get("engine") === "webgpu";
    const bundle = await (await fetchOk(base + "uniforms.json")).json();
    const triangles = new Float32Array(await (await fetchOk(base + "mesh.f32")).arrayBuffer());
    const canvas = document.getElementById("view");
    canvas.width = bundle.width;
    canvas.height = bundle.height;
    let engine;
    if (webgpu) {
        engine = new WebGPUEngine(canvas, {antialias: false});
        await engine.initAsync();
    } else {
        engine = new Engine(canvas, false);
    }
    const scene = new Scene(engine);
    scene.useRightHandedSystem = true; // the desktop's conventions (glm)

    const mesh = new Mesh("bundle", scene);
    const data = new VertexData();
    data.positions = triangles;
    data.indices = Array.from({length: triangles.length / 3}, (_, i) => i);
    data.normals = [];
    VertexData.ComputeNormals(data.positions, data.indices, data.normals); // unshared vertices: face normals
    data.applyToMesh(mesh);
    const material = new StandardMaterial("bundle", scene);
    material.backFaceCulling = false;
    mesh.material = material;
    mesh.receiveShadows = true;

    const c = bundle.camera;
    const camera = new FreeCamera("camera", Vector3.FromArray(c.eye), scene);
    camera.upVector = Vector3.FromArray(c.up);
    camera.setTarget(Vector3.FromArray(c.target));
    camera.fov = c.fov_y_degrees * Math.PI / 180;
    camera.minZ = c.near;
    camera.maxZ = c.far;

    let light, options = {emission: base + "emission/"};
    if (bundle.light.kind === "sun") {
        light = new DirectionalLight("sun", Vector3.FromArray(bundle.light.direction).normalize(), scene);
        options.angularDiameter = bundle.light.angular_diameter_degrees * Math.PI / 180;
    } else {
        // Penumbra's u, v (rows 0 and 1 of lightFromWorld) are the rectangle's local x and -y
        const m = bundle.uniforms.penumbra_lightFromWorld;
        const x = new Vector3(m[0], m[4], m[8]), y = new Vector3(m[1], m[5], m[9]).negate();
        const holder = new TransformNode("rectHolder", scene);
        holder.position = Vector3.FromArray(bundle.light.center);
        holder.rotationQuaternion = Quaternion.FromRotationMatrix(Matrix.FromXYZAxesToRef(x, y, Vector3.Cross(x, y), new Matrix()));
        light = new RectAreaLight("rect", Vector3.Zero(), bundle.light.width, bundle.light.height, scene);
        light.parent = holder;
    }
    const shadows = await PenumbraShadows.load(engine, scene, light, options);
    shadows.addShadowCaster(mesh);
    shadows.update();
    const render = async () => Array.from(await shadows.renderVisibility(camera, bundle.width, bundle.height));
    return {
        engine: () => ({name: engine.name, isWebGPU: !!engine.isWebGPU, version: Engine.Version}),
        variants: () => placementVariants(scene, mesh, shadows, render),
        materialRatio: () => materialRatio(scene, camera, mesh, shadows, bundle),
        dispose: () => {
            shadows.dispose();
            try {
                shadows.update();
                return {refused: false};
            } catch (e) {
                return {refused: e instanceof PenumbraError, message: e.message};
            }
        },
        frameUniforms: () => ({computed: shadows._frame.uniforms, bundle: bundle.uniforms}),
        visibility: async () => Array.from(await shadows.renderVisibility(camera, bundle.width, bundle.height)),
        info: () => ({...shadows.info, config: shadows.config}),
    };
}

// The material's light term: the StandardMaterial's image (its red channel, float) with the
// add-on enabled over the one with it disabled ({ratio, unshadowed}, as three_test.mjs's compareRatio reads).
async function materialRatio(scene, camera, mesh, shadows, bundle) {
    const target = new RenderTargetTexture("lit", {width: bundle.width, height: bundle.height}, scene,
                                           {generateMipMaps: false, type: 1 /* Constants.TEXTURETYPE_FLOAT */});
    target.activeCamera = camera;
    target.renderList = [mesh];
    target.clearColor = new Color4(0, 0, 0, 1);
    mesh.material.specularColor.set(0, 0, 0); // (the diffuse term alone: lit-with / lit-without is the visibility)
    mesh.material.twoSidedLighting = true; // (the bundle's faces are lit on the side the camera sees, as the visibility)
    const image = async (enabled) => {
        shadows.enabled = enabled;
        shadows.update();
        for (let i = 0; !target.isReadyForRendering() || !scene.isReady(); ++i) {
            if (i > 600) throw new Error("the scene's materials never got ready");
            await new Promise((resolve) => requestAnimationFrame(resolve));
        }
        scene.render(); // (the frame updates the lights' uniforms)
        target.render();
        return await target.readPixels();
    };
    // (the light scaled so that the brightest pixel is 0.7: the material clamps its diffuse term at
    // 1, which would break the ratio, and a dim image has few pixels to compare)
    let without = await image(false);
    const light = shadows.light, intensity = light.intensity;
    const brightest = without.reduce((m, v, i) => (i % 4 === 0 ? Math.max(m, v) : m), 0);
    if (brightest > 0) {
        light.intensity = intensity * 0.7 / brightest;
        without = await image(false);
    }
    const lit = await image(true);
    light.intensity = intensity;
    shadows.enabled = true;
    target.dispose();
    const n = bundle.width * bundle.height, ratio = new Array(n).fill(0), unshadowed = new Array(n).fill(0);
    for (let o = 0; o < n; ++o) { // (rows as renderVisibility's: bottom row first)
        unshadowed[o] = without[4 * o];
        ratio[o] = without[4 * o] > 1e-3 ? lit[4 * o] / without[4 * o] : 0;
    }
    return {ratio, unshadowed};
}

// The casters placed by M (a shift across the scene) five ways, under one receiver (the triangles
// moved by M, casting nothing): a Mesh at M ("mesh"), an InstancedMesh at M ("instanced"), a thin
// instance M ("thin"), a skeleton whose one bone is at M ("skinned"), a morph target of the
// positions × M at influence 1 ("morphed"); and a Mesh at identity ("unmoved", whose shadow must
// differ). Their visibility images must agree (babylon_test.mjs, as three_test.mjs's).
async function placementVariants(scene, mesh, shadows, render) {
    const info = mesh.getBoundingInfo().boundingBox;
    const size = info.maximum.subtract(info.minimum);
    const M = Matrix.Translation(0.05 * size.x, 0, 0.03 * size.z);
    const positions = mesh.getVerticesData("position"), count = positions.length / 3;
    const copy = (name) => {
        const m = mesh.clone(name);
        m.makeGeometryUnique();
        m.setEnabled(true); // (a clone of the disabled original)
        m.receiveShadows = false;
        return m;
    };
    mesh.setEnabled(false);
    shadows.removeShadowCaster(mesh);
    const receiver = mesh.clone("receiver");
    receiver.setEnabled(true);
    receiver.position = M.getTranslation();
    receiver.receiveShadows = true;
    const out = {};
    const one = async (name, caster, hide = []) => {
        shadows.addShadowCaster(caster);
        shadows.update();
        out[name] = await render();
        shadows.removeShadowCaster(caster);
        for (const m of [caster, ...hide]) m.dispose();
    };
    const unmoved = copy("unmoved");
    await one("unmoved", unmoved);
    const moved = copy("moved");
    moved.position = M.getTranslation();
    await one("mesh", moved);
    const source = copy("source");
    const instance = source.createInstance("instance");
    instance.position = M.getTranslation();
    await one("instanced", instance, [source]);
    const thin = copy("thin");
    thin.thinInstanceAdd(M);
    await one("thin", thin);
    const skinned = copy("skinned");
    const skeleton = new Skeleton("skeleton", "skeleton", scene);
    const bone = new Bone("bone", skeleton, null, Matrix.Identity());
    skinned.setVerticesData("matricesIndices", new Float32Array(4 * count));
    skinned.setVerticesData("matricesWeights", new Float32Array(4 * count).map((_, i) => (i % 4 === 0 ? 1 : 0)));
    skinned.skeleton = skeleton;
    bone.setPosition(M.getTranslation());
    await one("skinned", skinned);
    const morphed = copy("morphed");
    const manager = new MorphTargetManager(scene);
    const target = new MorphTarget("shifted", 1, scene);
    const shifted = Float32Array.from(positions);
    const t = M.getTranslation();
    for (let i = 0; i < count; ++i) { shifted[3 * i] += t.x; shifted[3 * i + 1] += t.y; shifted[3 * i + 2] += t.z; }
    target.setPositions(shifted);
    manager.addTarget(target);
    morphed.morphTargetManager = manager;
    await one("morphed", morphed);
    receiver.dispose();
    mesh.setEnabled(true);
    shadows.addShadowCaster(mesh);
    shadows.update();
    return out;
}

start().then((api) => { window.penumbraBabylon = api; },
              (e) => { window.penumbraBabylon = {error: `${e.message}\n${e.stack}`}; });
