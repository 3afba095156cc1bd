// cutout_page.js — the cut-out casters' page of targets/web/three_test.mjs (cutout.html, WebGLRenderer)
// and three_webgpu_test.mjs (cutout_webgpu.html, WebGPURenderer: "three" is three.webgpu.js there):
// a RectAreaLight 1 × 1 two units above a ground, and between them a 1.2 × 1.2 plane whose map is
// opaque but for a transparent square hole in its middle (0.6 wide) with alphaTest 0.5. Through the
// hole the whole light reaches the ground's centre; drawn solid, the plane hides all of it there.
// window.penumbraCut.run(options) loads an add-on with `options` (PenumbraShadows.load), updates it
// twice, reads its visibility from above and disposes it:
//   {alphaTest: info.alphaTest, cutDraws: info.cutDraws, emissionCuts: the emission's config.alpha_test,
//    hole: mean visibility under the hole's middle, warnings: console.warn texts}
import * as THREE from "three";
import {PenumbraShadows} from "../penumbra_shadows.js";

const SIZE = 32; // the visibility image: the ground's [-2, 2]² seen from above

function holeTexture() {
    const n = 8, data = new Uint8Array(4 * n * n).fill(255);
    for (let y = 2; y < 6; ++y) for (let x = 2; x < 6; ++x) data[4 * (y * n + x) + 3] = 0;
    const texture = new THREE.DataTexture(data, n, n, THREE.RGBAFormat);
    texture.magFilter = texture.minFilter = THREE.NearestFilter;
    texture.needsUpdate = true;
    return texture;
}

async function main() {
    const webgpu = !!THREE.WebGPURenderer && /webgpu/.test(location.pathname);
    if (webgpu) { // (the RectAreaLight's tables, which three's node lighting needs once it builds a lit material)
        const {RectAreaLightTexturesLib} = await import("three/addons/lights/RectAreaLightTexturesLib.js");
        THREE.RectAreaLightNode.setLTC(RectAreaLightTexturesLib.init());
    }
    const scene = new THREE.Scene();
    const light = new THREE.RectAreaLight(0xffffff, 1, 1, 1);
    light.position.set(0, 2, 0);
    light.rotation.x = -Math.PI / 2; // emitting towards -y
    scene.add(light);
    const ground = new THREE.Mesh(new THREE.PlaneGeometry(4, 4).rotateX(-Math.PI / 2),
                                  new THREE.MeshStandardMaterial({color: 0xffffff, roughness: 1, metalness: 0}));
    ground.receiveShadow = true;
    scene.add(ground);
    const plane = new THREE.Mesh(new THREE.PlaneGeometry(1.2, 1.2).rotateX(-Math.PI / 2),
                                 new THREE.MeshStandardMaterial({map: holeTexture(), alphaTest: 0.5, side: THREE.DoubleSide}));
    plane.position.y = 1;
    plane.castShadow = true;
    scene.add(plane);
    const camera = new THREE.OrthographicCamera(-2, 2, 2, -2, 0.1, 10);
    camera.position.set(0, 5, 0);
    camera.up.set(0, 0, -1);
    camera.lookAt(0, 0, 0);
    camera.updateMatrixWorld();

    const canvas = document.getElementById("view");
    const renderer = webgpu ? new THREE.WebGPURenderer({canvas, antialias: false}) : new THREE.WebGLRenderer({canvas, antialias: false});
    renderer.setPixelRatio(1);
    renderer.setSize(SIZE, SIZE);
    if (webgpu) await renderer.init();

    // mean visibility over the pixels whose ground point (x, z) is within r of (cx, cz)
    const mean = (v, cx, cz, r) => {
        let sum = 0, n = 0;
        for (let j = 0; j < SIZE; ++j)
            for (let i = 0; i < SIZE; ++i) {
                const x = -2 + 4 * (i + 0.5) / SIZE, z = -2 + 4 * (j + 0.5) / SIZE; // (rows: either order, the scene is symmetric in z)
                if (Math.abs(x - cx) <= r && Math.abs(z - cz) <= r) { sum += v[j * SIZE + i]; ++n; }
            }
        return sum / n;
    };
    window.penumbraCut = {
        renderer: webgpu ? "webgpu" : "webgl2",
        plane, // (for checks by hand: its material, map and geometry)
        run: async (options = {}) => {
            const warnings = [];
            const warn = console.warn;
            console.warn = (...args) => { warnings.push(args.join(" ")); warn.apply(console, args); };
            try {
                const shadows = await PenumbraShadows.load(renderer, scene, light, options);
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
            }
        },
    };
}

main().catch((e) => { window.penumbraCut = {error: `${e.message}\n${e.stack}`}; console.error(e); });
