// gltf_lights_area.js — a GLTFLoader plugin for the glTF vendor extension EXT_lights_area (area
// lights; three's GLTFLoader reads KHR_lights_punctual only): a THREE.RectAreaLight for each node
// that references a light of type "rect".
//
//   import {GLTFLoader} from "three/addons/loaders/GLTFLoader.js";
//   import {GLTFLightsAreaExtension} from "penumbra-three";
//   const loader = new GLTFLoader().register((parser) => new GLTFLightsAreaExtension(parser));
//   const gltf = await loader.loadAsync("room.gltf");
//   gltf.scene.traverse((o) => { if (o.isRectAreaLight) ... PenumbraShadows.load(renderer, scene, o) });
//
// What it reads (the extension's README, extensions/2.0/Vendor/EXT_lights_area in KhronosGroup/glTF):
// the root's extensions.EXT_lights_area.lights[] ({type, color, intensity, size, rect: {aspect}, name,
// extras}) and each node's extensions.EXT_lights_area.light (an index into it).
//   - rect: RectAreaLight(color, intensity, width = size·aspect·s, height = size·s), s the largest
//     absolute component of the node's world scale once the glTF's scenes are built (three ignores an
//     object's scale for RectAreaLight, so the size carries it). Defaults as the extension says:
//     color [1, 1, 1] (linear), intensity 1000 (nits: three's RectAreaLight intensity is the
//     surface's luminance too, its `power` intensity·area·π the extension's flux), size 1, aspect 1.
//     (Babylon.js's loader takes intensity 1 when it is absent.)
//   - Placement: the light emits from the local XY plane towards local −Z in glTF; a three.js
//     RectAreaLight spans its local XY plane (width along x, height along y) and emits towards its
//     local −Z as well, so the light takes the node's transform as it is: like three's own
//     KHR_lights_punctual, the light is the node's object when it is the node's only content, or a
//     child at the identity beside the node's mesh or camera. (Babylon.js, whose RectAreaLight emits
//     towards +Z, puts a 180° turn about y between node and light instead.)
//   - disk: skipped (three has no disk area light), with one console.warn naming the light; an
//     unknown type likewise.
// A light referenced by several nodes is cloned for each, as three does for shared meshes and lights.
import {Color, LinearSRGBColorSpace, RectAreaLight, Vector3} from "three";

export const EXT_LIGHTS_AREA = "EXT_lights_area";

export class GLTFLightsAreaExtension {
    constructor(parser) {
        this.parser = parser;
        this.name = EXT_LIGHTS_AREA;
        this.cache = {refs: {}, uses: {}};   // GLTFParser's node-reference counts (shared lights are cloned)
        this._placed = [];                   // [light, size, aspect] for each light put into the scene graph
        this._warned = new Set();            // light indices already warned about
    }

    _lightDefs() {
        const root = this.parser.json.extensions && this.parser.json.extensions[this.name];
        return (root && root.lights) || [];
    }

    _lightIndex(nodeIndex) {
        const nodeDef = this.parser.json.nodes[nodeIndex];
        const ext = nodeDef.extensions && nodeDef.extensions[this.name];
        return ext && ext.light !== undefined ? ext.light : undefined;
    }

    // Counts the nodes that use each light (GLTFParser clones a light used more than once).
    _markDefs() {
        const nodeDefs = this.parser.json.nodes || [];
        for (let i = 0; i < nodeDefs.length; ++i) this.parser._addNodeRef(this.cache, this._lightIndex(i));
    }

    // The light definition when three can place it (type "rect"), else null after one warning.
    _supported(lightIndex) {
        const def = this._lightDefs()[lightIndex];
        if (def && def.type === "rect") return def;
        if (!this._warned.has(lightIndex)) {
            this._warned.add(lightIndex);
            const name = def && def.name ? ` "${def.name}"` : "";
            const why = !def ? "does not exist"
                : def.type === "disk" ? "is a disk, which three.js has no area light for"
                : `has type ${JSON.stringify(def.type)}, not "rect"`;
            console.warn(`penumbra-three: ${this.name} light ${lightIndex}${name} ${why}: skipped`);
        }
        return null;
    }

    _loadLight(lightIndex) {
        const key = `${this.name}:${lightIndex}`;
        let dependency = this.parser.cache.get(key);
        if (dependency) return dependency;
        const def = this._lightDefs()[lightIndex];
        const color = new Color(1, 1, 1);
        if (def.color !== undefined) color.setRGB(def.color[0], def.color[1], def.color[2], LinearSRGBColorSpace);
        const intensity = def.intensity !== undefined ? def.intensity : 1000;
        const size = def.size !== undefined ? def.size : 1;
        const aspect = def.rect && def.rect.aspect !== undefined ? def.rect.aspect : 1;
        const light = new RectAreaLight(color, intensity, size * aspect, size);
        light.name = this.parser.createUniqueName(def.name || `area_light_${lightIndex}`);
        if (def.extras && typeof def.extras === "object") Object.assign(light.userData, def.extras);
        dependency = Promise.resolve(light);
        this.parser.cache.add(key, dependency);
        return dependency;
    }

    getDependency(type, index) {
        if (type !== "areaLight" || !this._supported(index)) return;
        return this._loadLight(index);
    }

    // GLTFParser.loadNode's hook: the object this extension adds to a node (null: nothing).
    createNodeAttachment(nodeIndex) {
        const lightIndex = this._lightIndex(nodeIndex);
        if (lightIndex === undefined) return null;
        const def = this._supported(lightIndex);
        if (!def) return null;
        return this._loadLight(lightIndex).then((light) => {
            const placed = this.parser._getNodeRef(this.cache, lightIndex, light);
            const size = def.size !== undefined ? def.size : 1;
            const aspect = def.rect && def.rect.aspect !== undefined ? def.rect.aspect : 1;
            this._placed.push([placed, size, aspect]);
            return placed;
        });
    }

    // Once the scenes are built: the size times the node's world scale (its largest absolute component).
    afterRoot() {
        const scale = new Vector3();
        for (const [light, size, aspect] of this._placed) {
            light.getWorldScale(scale);
            const s = Math.max(Math.abs(scale.x), Math.abs(scale.y), Math.abs(scale.z));
            light.width = size * aspect * s;
            light.height = size * s;
        }
        this._placed.length = 0;
        return null;
    }
}
