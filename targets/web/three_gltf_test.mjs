// three_gltf_test.mjs — the `three-gltf-lights-area` test: penumbra-three's GLTFLoader plugin for
// EXT_lights_area (web/three/gltf_lights_area.js), in node (no browser: the glTF is JSON with its
// buffer embedded as a data: URI, no textures). web/three/test/lights_area.gltf is loaded through
// three's own GLTFLoader with the plugin registered, with three r187 (web/three/node_modules) and,
// given --three-r180, with three r180 (the other end of the peer range: the plugin copied beside a
// node_modules/three linking to it), and each time:
//   - "Panel" (a rect light, size 0.4, aspect 2.5, under a node translated, turned 90° about y and
//     scaled 1.5, itself translated and tilted −60° about x) is a RectAreaLight at the node's world
//     position, width size·aspect·1.5 and height size·1.5 (the extension's world scale), facing
//     the node's world −Z: the normal of the rectangle three's shader builds (lights_physical_pars:
//     cross(corner1 − corner0, corner3 − corner0) from the light's rotation, halfWidth along x,
//     halfHeight along y), which is the light's world −Z too; its width along the node's world x;
//     colour (linear) and intensity as the file says; all against transforms computed here from the
//     glTF's numbers, not by three;
//   - "Fixture" (a mesh and the same light): a Group holding the mesh and a clone of the light at
//     the identity;
//   - "Plain" (a rect light with no size, aspect, colour or intensity): the extension's defaults
//     (1 × 1, white, 1000 nits);
//   - "Lamp" (a disk light): no light, and exactly one console.warn, naming "Round lamp" and "disk";
//   - the extension is not left in any object's userData.gltfExtensions (the loader knows it).
//
//   node targets/web/three_gltf_test.mjs --three web/three [--three-r180 DIR]
//
// Exit 0 pass, 1 fail, 2 bad arguments.
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import {pathToFileURL} from "node:url";

const TOLERANCE = 1e-5;

// three's FileLoader (which reads the data: URI of the buffer) reports progress with the DOM's
// ProgressEvent, which node 20 lacks (node 22 has it)
globalThis.ProgressEvent ??= class ProgressEvent extends Event {
    constructor(type, init = {}) { super(type); Object.assign(this, init); }
};

function parseArguments(argv) {
    const out = {three: null, "three-r180": null};
    for (let i = 0; i < argv.length; i += 2) {
        const key = argv[i].replace(/^--/, "");
        if (!(key in out) || i + 1 >= argv.length) usage(`bad argument '${argv[i]}'`);
        out[key] = argv[i + 1];
    }
    if (!out.three) usage("--three is required");
    return out;
}

function usage(message) {
    console.error(`error: ${message}\nusage: node three_gltf_test.mjs --three web/three [--three-r180 DIR]`);
    process.exit(2);
}

// --- a little linear algebra of our own (the expectations do not go through three) ---
const rotate = ([x, y, z, w], v) => {     // unit quaternion (glTF order x, y, z, w) applied to v
    const t = [2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])];
    return [v[0] + w * t[0] + (y * t[2] - z * t[1]), v[1] + w * t[1] + (z * t[0] - x * t[2]), v[2] + w * t[2] + (x * t[1] - y * t[0])];
};
const add = (a, b) => a.map((x, i) => x + b[i]);
const scale = (a, s) => a.map((x) => x * s);
const sub = (a, b) => a.map((x, i) => x - b[i]);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const normalize = (a) => scale(a, 1 / Math.hypot(...a));
const far = (a, b) => a.some((x, i) => Math.abs(x - b[i]) > TOLERANCE);
const fmt = (a) => `(${a.map((x) => x.toFixed(5)).join(", ")})`;

async function check(label, three, plugin, gltfText) {
    const THREE = await import(pathToFileURL(path.join(three, "build/three.module.js")));
    const {GLTFLoader} = await import(pathToFileURL(path.join(three, "examples/jsm/loaders/GLTFLoader.js")));
    const {GLTFLightsAreaExtension} = await import(pathToFileURL(plugin));
    const json = JSON.parse(gltfText);
    const failures = [];
    const expect = (ok, message) => { if (!ok) failures.push(`${label}: ${message}`); };

    const warnings = [];
    const warn = console.warn;
    console.warn = (...args) => warnings.push(args.join(" "));
    let gltf;
    const started = Date.now();
    try {
        const loader = new GLTFLoader().register((parser) => new GLTFLightsAreaExtension(parser));
        gltf = await loader.parseAsync(gltfText, "");
    } finally {
        console.warn = warn;
    }
    const seconds = (Date.now() - started) / 1000;
    gltf.scene.updateMatrixWorld(true);
    const byNode = (name) => gltf.scene.getObjectByName(name);
    const lights = [];
    gltf.scene.traverse((o) => { if (o.isLight) lights.push(o); });
    expect(lights.length === 3 && lights.every((l) => l.isRectAreaLight),
           `3 RectAreaLights expected (Panel, Fixture, Plain), got ${lights.map((l) => `${l.type} ${l.name}`).join(", ")}`);

    // "Panel": the light is the node's object (its only content)
    const [rig, panelNode] = json.nodes;
    const def = json.extensions.EXT_lights_area.lights[0];
    const panel = byNode("Panel");
    expect(panel && panel.isRectAreaLight, `node Panel is ${panel ? panel.type : "missing"}, not a RectAreaLight`);
    if (panel && panel.isRectAreaLight) {
        const s = rig.scale[0];
        const position = add(rig.translation, rotate(rig.rotation, scale(panelNode.translation, s)));
        const facing = rotate(rig.rotation, rotate(panelNode.rotation, [0, 0, -1]));
        const along = rotate(rig.rotation, rotate(panelNode.rotation, [1, 0, 0]));
        const got = new THREE.Vector3().setFromMatrixPosition(panel.matrixWorld).toArray();
        // the rectangle three's shader lights with: corners from halfWidth / halfHeight turned by the
        // light's world rotation (scale removed, as WebGLLights does), normal cross(v1, v2)
        const rotation = new THREE.Matrix4().extractRotation(panel.matrixWorld);
        const hw = new THREE.Vector3(panel.width / 2, 0, 0).applyMatrix4(rotation).toArray();
        const hh = new THREE.Vector3(0, panel.height / 2, 0).applyMatrix4(rotation).toArray();
        const corners = [add(sub(got, hh), hw), sub(sub(got, hw), hh), add(sub(got, hw), hh), add(add(got, hw), hh)];
        const normal = normalize(cross(sub(corners[1], corners[0]), sub(corners[3], corners[0])));
        const minusZ = new THREE.Vector3(0, 0, -1).transformDirection(panel.matrixWorld).toArray();
        const xAxis = new THREE.Vector3(1, 0, 0).transformDirection(panel.matrixWorld).toArray();
        expect(!far(got, position), `Panel's world position ${fmt(got)}, expected ${fmt(position)}`);
        expect(!far(normal, facing), `Panel's rectangle (as three's shader builds it) faces ${fmt(normal)}, expected the node's world -Z ${fmt(facing)}`);
        expect(!far(minusZ, facing), `Panel's world -Z ${fmt(minusZ)}, expected ${fmt(facing)}`);
        expect(!far(xAxis, along), `Panel's width axis ${fmt(xAxis)}, expected the node's world x ${fmt(along)}`);
        expect(Math.abs(panel.width - def.size * def.rect.aspect * s) < TOLERANCE && Math.abs(panel.height - def.size * s) < TOLERANCE,
               `Panel is ${panel.width} × ${panel.height}, expected ${def.size * def.rect.aspect * s} × ${def.size * s} (size·aspect·scale × size·scale)`);
        const color = [panel.color.r, panel.color.g, panel.color.b];   // three's working space: linear sRGB
        expect(!far(color, def.color) && panel.intensity === def.intensity,
               `Panel's colour ${fmt(color)} and intensity ${panel.intensity}, expected ${fmt(def.color)} and ${def.intensity}`);
        console.log(`     Panel: at ${fmt(got)}, facing ${fmt(normal)}, ${panel.width.toFixed(3)} × ${panel.height.toFixed(3)}`);
    }

    // "Fixture": mesh and light under a Group; the light a clone at the identity, unscaled size
    const fixture = byNode("Fixture");
    const fixtureLight = fixture && fixture.children.find((c) => c.isRectAreaLight);
    expect(fixture && fixture.children.some((c) => c.isMesh) && fixtureLight,
           `node Fixture should hold its mesh and a RectAreaLight, holds ${fixture ? fixture.children.map((c) => c.type).join(", ") : "nothing"}`);
    if (fixtureLight) {
        expect(fixtureLight !== panel, "Fixture's light is Panel's object, not a clone");
        const got = new THREE.Vector3().setFromMatrixPosition(fixtureLight.matrixWorld).toArray();
        const minusZ = new THREE.Vector3(0, 0, -1).transformDirection(fixtureLight.matrixWorld).toArray();
        expect(!far(got, json.nodes[3].translation) && !far(minusZ, [0, 0, -1]),
               `Fixture's light at ${fmt(got)} facing ${fmt(minusZ)}, expected ${fmt(json.nodes[3].translation)} facing (0, 0, -1)`);
        expect(Math.abs(fixtureLight.width - def.size * def.rect.aspect) < TOLERANCE && Math.abs(fixtureLight.height - def.size) < TOLERANCE,
               `Fixture's light is ${fixtureLight.width} × ${fixtureLight.height}, expected ${def.size * def.rect.aspect} × ${def.size}`);
    }

    // "Plain": the extension's defaults
    const plain = byNode("Plain");
    expect(plain && plain.isRectAreaLight && plain.width === 1 && plain.height === 1 && plain.intensity === 1000 &&
           plain.color.r === 1 && plain.color.g === 1 && plain.color.b === 1,
           `Plain: expected a white 1 × 1 RectAreaLight of intensity 1000, got ${plain ? `${plain.type} ${plain.width} × ${plain.height}, ` +
           `intensity ${plain.intensity}, colour ${plain.color ? plain.color.getHexString() : "-"}` : "nothing"}`);

    // "Lamp": the disk is skipped, with one warning naming it
    const lamp = byNode("Lamp");
    let lampLights = 0;
    if (lamp) lamp.traverse((o) => { if (o.isLight) ++lampLights; });
    expect(lamp && lampLights === 0, `node Lamp (a disk light) should hold no light, holds ${lampLights}`);
    const ours = warnings.filter((w) => w.includes("EXT_lights_area"));
    expect(ours.length === 1 && /Round lamp/.test(ours[0]) && /disk/.test(ours[0]),
           `one warning naming the disk light "Round lamp" expected, got ${JSON.stringify(warnings)}`);
    let leftover = 0;
    gltf.scene.traverse((o) => { if (o.userData.gltfExtensions && o.userData.gltfExtensions.EXT_lights_area) ++leftover; });
    expect(leftover === 0, `${leftover} object(s) keep EXT_lights_area in userData.gltfExtensions`);

    console.log(`${failures.length ? "FAIL" : "ok  "} three ${THREE.REVISION}: ${lights.length} RectAreaLights from EXT_lights_area ` +
                `(parsed in ${seconds.toFixed(3)} s); the disk skipped: ${ours[0] || "no warning"}`);
    return failures;
}

const args = parseArguments(process.argv.slice(2));
const three = path.resolve(args.three);
const gltfText = fs.readFileSync(path.join(three, "test/lights_area.gltf"), "utf8");
const plugin = path.join(three, "gltf_lights_area.js");
const failures = await check("r187", path.join(three, "node_modules/three"), plugin, gltfText);
if (args["three-r180"]) {
    // the plugin imports "three": copied beside a node_modules/three that is r180
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), "penumbra-gltf-r180-"));
    try {
        fs.mkdirSync(path.join(dir, "node_modules"));
        fs.symlinkSync(path.resolve(args["three-r180"]), path.join(dir, "node_modules/three"), "dir");
        fs.copyFileSync(plugin, path.join(dir, "gltf_lights_area.js"));
        fs.writeFileSync(path.join(dir, "package.json"), JSON.stringify({type: "module"}));
        failures.push(...await check("r180", path.resolve(args["three-r180"]), path.join(dir, "gltf_lights_area.js"), gltfText));
    } finally {
        fs.rmSync(dir, {recursive: true, force: true});
    }
}
for (const f of failures) console.error(`FAIL ${f}`);
process.exit(failures.length ? 1 : 0);
