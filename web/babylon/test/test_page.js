// test_page.js — one of Penumbra's built-in scenes rebuilt in Babylon.js from a target bundle
// (penumbra-export-bundle --target essl300, ?bundle=URL/): the same triangles (mesh.f32, flat
// normals, one StandardMaterial, casting and receiving), the same light (a RectAreaLight whose axes
// are the rows of the exported penumbra_lightFromWorld, or a DirectionalLight for the sun), the same
// camera (a right-handed scene: glm::lookAt / glm::perspective), and the add-on with the bundle's
// emission folder. window.penumbraBabylon (targets/web/babylon_test.mjs):
//   frameUniforms()   the add-on's light-frame uniforms and the bundle's
//   visibility()      the add-on's visibility at the bundle's size, bottom row first
import {Engine} from "@babylonjs/core/Engines/engine.js";
import {Scene} from "@babylonjs/core/scene.js";
import {FreeCamera} from "@babylonjs/core/Cameras/freeCamera.js";
import {RectAreaLight} from "@babylonjs/core/Lights/rectAreaLight.js";
import {DirectionalLight} from "@babylonjs/core/Lights/directionalLight.js";
import {TransformNode} from "@babylonjs/core/Meshes/transformNode.js";
import {Mesh} from "@babylonjs/core/Meshes/mesh.js";
import {VertexData} from "@babylonjs/core/Meshes/mesh.vertexData.js";
import {StandardMaterial} from "@babylonjs/core/Materials/standardMaterial.js";
import {Matrix, Quaternion, Vector3} from "@babylonjs/core/Maths/math.vector.js";
import {PenumbraShadows} from "../penumbra_babylon.js";

async function fetchOk(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
    return response;
}

async function start() {
    const base = new URLSearchParams(location.search).get("bundle");
    const bundle = await (await fetchOk(base + "uniforms.json")).json();
    const triangles = new Float32Array(await (await fetchOk(base + "mesh.f32")).arrayBuffer());
    const canvas = document.getElementById("view");
    canvas.width = bundle.width;
    canvas.height = bundle.height;
    const engine = new Engine(canvas, false);
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
    return {
        frameUniforms: () => ({computed: shadows._frame.uniforms, bundle: bundle.uniforms}),
        visibility: async () => Array.from(await shadows.renderVisibility(camera, bundle.width, bundle.height)),
        info: () => ({...shadows.info, config: shadows.config}),
    };
}

start().then((api) => { window.penumbraBabylon = api; },
              (e) => { window.penumbraBabylon = {error: `${e.message}\n${e.stack}`}; });
