// bundle_scene.js — one of Penumbra's built-in scenes rebuilt in three.js from a target bundle
// (penumbra-export-bundle --target essl300): the same triangles (mesh.f32, flat normals, one
// MeshStandardMaterial), the same light (a RectAreaLight whose axes are the rows of the exported
// penumbra_lightFromWorld, or a DirectionalLight for the sun) and the same camera (uniforms.json's
// camera: glm::lookAt / glm::perspective are three's lookAt / PerspectiveCamera).
import * as THREE from "three";

async function fetchOk(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
    return response;
}

export async function loadBundleScene(base) {
    const bundle = await (await fetchOk(base + "uniforms.json")).json();
    if (!bundle.camera) throw new Error(`${base}uniforms.json has no camera (re-export the bundle)`);
    const triangles = new Float32Array(await (await fetchOk(base + "mesh.f32")).arrayBuffer());
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute("position", new THREE.BufferAttribute(triangles, 3));
    geometry.computeVertexNormals(); // non-indexed: the face normal on each vertex
    const material = new THREE.MeshStandardMaterial({color: 0xffffff, roughness: 1, metalness: 0, side: THREE.DoubleSide});
    const mesh = new THREE.Mesh(geometry, material);
    mesh.castShadow = true;
    mesh.receiveShadow = true;
    const scene = new THREE.Scene();
    scene.add(mesh);

    const c = bundle.camera;
    const camera = new THREE.PerspectiveCamera(c.fov_y_degrees, bundle.width / bundle.height, c.near, c.far);
    camera.position.fromArray(c.eye);
    camera.up.fromArray(c.up);
    camera.lookAt(new THREE.Vector3().fromArray(c.target));
    camera.updateMatrixWorld();

    let light;
    if (bundle.light.kind === "sun") {
        light = new THREE.DirectionalLight(0xffffff, 1);
        const d = new THREE.Vector3().fromArray(bundle.light.direction).normalize();
        light.position.copy(d).multiplyScalar(-10);
        light.target.position.set(0, 0, 0);
        scene.add(light.target);
    } else {
        // Penumbra's u, v (rows 0 and 1 of lightFromWorld) are three's local x and -y.
        const m = bundle.uniforms.penumbra_lightFromWorld;
        const u = new THREE.Vector3(m[0], m[4], m[8]), v = new THREE.Vector3(m[1], m[5], m[9]);
        const x = u.clone(), y = v.clone().negate(), z = new THREE.Vector3().crossVectors(x, y);
        light = new THREE.RectAreaLight(0xffffff, 1, bundle.light.width, bundle.light.height);
        light.position.fromArray(bundle.light.center);
        light.quaternion.setFromRotationMatrix(new THREE.Matrix4().makeBasis(x, y, z));
    }
    scene.add(light);
    scene.updateMatrixWorld();
    return {bundle, scene, camera, light, mesh, triangles};
}

// The same casters and receivers placed by matrix M four ways: a Mesh at M, an InstancedMesh
// (identity) with instance matrix M, a SkinnedMesh whose one bone is at M, and morph target
// (positions × M, influence 1) on a Mesh at identity. Their visibility images (render(): the
// add-on's renderVisibility, a Float32Array or its Promise) must agree. Arrays by name.
export async function placementVariants(scene, mesh, shadows, render) {
    const box = new THREE.Box3().setFromObject(mesh);
    const M = new THREE.Matrix4().makeTranslation(0.05 * (box.max.x - box.min.x), 0, 0.03 * (box.max.z - box.min.z));
    const geometry = mesh.geometry;
    const material = mesh.material;
    let current = mesh;
    const swap = async (object) => {
        scene.remove(current);
        current = object;
        object.castShadow = object.receiveShadow = true;
        scene.add(object);
        scene.updateMatrixWorld(true);
        shadows.update();
        return render();
    };
    const out = {};
    out.unmoved = await swap(mesh);
    const moved = new THREE.Mesh(geometry, material);
    moved.applyMatrix4(M);
    out.mesh = await swap(moved);
    const instanced = new THREE.InstancedMesh(geometry, material, 1);
    instanced.setMatrixAt(0, M);
    out.instanced = await swap(instanced);
    const skinnedGeometry = geometry.clone();
    const n = geometry.attributes.position.count;
    skinnedGeometry.setAttribute("skinIndex", new THREE.Uint16BufferAttribute(new Uint16Array(4 * n), 4));
    skinnedGeometry.setAttribute("skinWeight", new THREE.Float32BufferAttribute(new Float32Array(4 * n).map((_, i) => (i % 4 === 0 ? 1 : 0)), 4));
    const bone = new THREE.Bone();
    const skinned = new THREE.SkinnedMesh(skinnedGeometry, material);
    skinned.add(bone);
    skinned.bind(new THREE.Skeleton([bone]));
    bone.applyMatrix4(M);
    out.skinned = await swap(skinned);
    const morphGeometry = geometry.clone();
    morphGeometry.morphAttributes.position = [geometry.attributes.position.clone().applyMatrix4(M)];
    const morphed = new THREE.Mesh(morphGeometry, material);
    morphed.morphTargetInfluences = [1];
    out.morphed = await swap(morphed);
    await swap(mesh);
    for (const k of Object.keys(out)) out[k] = Array.from(out[k]);
    return out;
}

// The render with the add-on over the one without it (render(): RGBA floats of the frame, or their
// Promise, in the bundle's row order): {ratio, unshadowed} a pixel, the light's term scaled by the
// visibility where the scene has no other light.
export async function materialRatio(scene, shadows, render) {
    if (scene.children.some((o) => o.isAmbientLight)) throw new Error("the bundle scene has an ambient light");
    const frame = async (enabled) => {
        shadows.enabled = enabled;
        shadows.update();
        return render();
    };
    const on = await frame(true), off = await frame(false);
    shadows.enabled = true;
    shadows.update();
    const n = on.length / 4, ratio = new Array(n), unshadowed = new Array(n);
    for (let i = 0; i < n; ++i) {
        const a = on[4 * i] + on[4 * i + 1] + on[4 * i + 2], b = off[4 * i] + off[4 * i + 1] + off[4 * i + 2];
        unshadowed[i] = b / 3;
        ratio[i] = b > 0 ? a / b : NaN;
    }
    return {ratio, unshadowed};
}

// What both test pages give the drivers to move the light and count the add-on's shadow phases.
export function addonControls(light, shadows) {
    return {
        moveLight: (dx) => {
            light.translateX(dx);
            light.updateMatrixWorld();
            shadows.update();
            return shadows.info.shadowUpdates;
        },
        shadowUpdates: () => shadows.info.shadowUpdates,
        update: () => { shadows.update(); return shadows.info.shadowUpdates; },
    };
}
