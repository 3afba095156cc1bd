// penumbra_scene.js — what the add-on does the same on WebGLRenderer (penumbra_shadows.js) and
// WebGPURenderer (penumbra_shadows_webgpu.js): the options, the light's kind, the emission's
// files (shipped, a folder, in memory, or emitted by the WebAssembly emitter), the casters and
// receivers of the scene, when the shadow phase must run again, the light frame from the three.js
// light and the scene's bounds (light_frame.js), the casters' vertices and their materials' cut-outs
// (the alpha test: cutOf, emissionFollowingCuts). Each renderer's module
// subclasses ShadowsBase with its own GPU work: the runner, the caster draws, the material hooks.
import {Box3, Color, Matrix4, Vector3} from "three";
import {rectFrame, sunFrame} from "./light_frame.js";
import {EMISSIONS, PenumbraError, emissionWithCut, fail, loadEmissionFiles, loadEmitter, nextSerial, renamer,
        requestedEmission, snippetParameters} from "./penumbra_emission.js";

// (the renderer-free part lives in penumbra_emission.js, which penumbra-babylon shares)
export {EMISSIONS, PenumbraError, fail, loadEmissionFiles, loadEmitter, requestedEmission, snippetParameters};

export const DEFAULTS = {
    emission: null,           // a key of EMISSIONS, a folder URL (ending in "/"), {layout, files}, or a configuration
                              // object ({slices, resolution, filter, ...}: needs the WebAssembly emitter)
    angularDiameter: 0.0093,  // sun only: the DirectionalLight's angular diameter in radians (our sun: 0.53°)
    autoUpdate: true,         // re-run the shadow phase by itself when something moved (like shadowMap.autoUpdate)
    intensity: 1,             // 0: no shadow, 1: Penumbra's visibility (like LightShadow.intensity)
    wasm: null,               // for a configuration object: the URL of penumbra_emitter.wasm (default: the one beside penumbra_emitter.js)
    alphaTest: undefined,     // cut-out casters (cutOf): undefined follows the scene (on when a caster cuts at load()), true / false forces
};

export function kindOf(light) {
    if (light && light.isRectAreaLight) return "rect";
    if (light && light.isSunLight) fail("a cascaded SunLight has its own light loop in three; use a THREE.DirectionalLight");
    if (light && light.isDirectionalLight) return "sun";
    fail(`the light must be a THREE.RectAreaLight or a THREE.DirectionalLight (got ${light ? light.type : light})`);
}

export function positionVersion(geometry) {
    const p = geometry.attributes.position;
    return p ? (p.isInterleavedBufferAttribute ? p.data.version : p.version) : -1;
}

// A caster's triangles as the slicing pass draws them: positions in the mesh's own space (skinned
// and morphed ones from mesh.getVertexPosition(), as three's own vertex stage places them), the
// index (Uint16Array or Uint32Array, or null) and the draw range. {positions, index, first, count, deformed}.
export function casterVertices(object) {
    const geometry = object.geometry;
    const position = geometry.attributes.position;
    const deformed = isDeformed(object);
    const n = position.count;
    const positions = new Float32Array(3 * n);
    const v = new Vector3();
    for (let i = 0; i < n; ++i) {
        if (deformed) object.getVertexPosition(i, v);
        else v.fromBufferAttribute(position, i);
        positions[3 * i] = v.x;
        positions[3 * i + 1] = v.y;
        positions[3 * i + 2] = v.z;
    }
    const range = geometry.drawRange;
    let index = null, count;
    if (geometry.index) {
        const big = geometry.index.array instanceof Uint32Array || n > 65535;
        index = big ? Uint32Array.from(geometry.index.array) : Uint16Array.from(geometry.index.array);
        count = Math.min(range.count, geometry.index.count - range.start);
    } else {
        count = Math.min(range.count, n - range.start);
    }
    return {positions, index, first: range.start, count, deformed};
}

// The meshes update() draws as casters (BatchedMesh: not drawn, README).
export function isCaster(object) {
    return object.isMesh && object.castShadow && !object.isBatchedMesh && !!object.geometry.attributes.position;
}

// ---- cut-out casters (the alpha test) ----------------------------------------------------------

// Whether a caster's material cuts, and where: the desktop playground's rule for glTF's alpha modes
// (playground/src/scenes/gltf_loader.cpp), as three's GLTFLoader maps them. MASK is alphaTest > 0
// (cutoff alphaTest), BLEND is transparent (cast as a cut-out at 0.5: a shadow has no partial
// coverage); either cuts through the map's alpha, which three multiplies by opacity, so the cutoff
// the slicing pass compares the map's alpha with is cutoff / opacity (a · opacity < c ⇔ a < c / opacity;
// above 1 nothing of it casts). {map, cutoff}, or null: solid (no map, or neither mode). alphaMap
// (three's green channel, another texture) and a map-less material's opacity are not followed: the
// slicing pass reads one texture's alpha (README).
export function cutOf(material) {
    if (!material || !material.map) return null;
    const cutoff = material.alphaTest > 0 ? material.alphaTest : material.transparent ? 0.5 : 0;
    if (!(cutoff > 0)) return null;
    const opacity = material.opacity ?? 1;
    return {map: material.map, cutoff: opacity > 0 ? Math.min(cutoff / opacity, 2) : 2};
}

export function materialsOf(object) {
    return Array.isArray(object.material) ? object.material : [object.material];
}

// Whether a caster of the scene (visible, castShadow) cuts now: what alphaTest undefined follows.
export function sceneCuts(scene) {
    let cuts = false;
    scene.traverseVisible((object) => {
        if (!cuts && isCaster(object)) cuts = materialsOf(object).some((m) => cutOf(m) !== null);
    });
    return cuts;
}

// The emission for `requested` with the alpha test where `alphaTest` says (undefined: when the scene's
// casters cut now): penumbra_emission.js's emissionWithCut with this scene's test.
export function emissionFollowingCuts(requested, alphaTest, scene) {
    return emissionWithCut(requested, alphaTest, () => sceneCuts(scene));
}

// A caster's draws, each with its material: the whole draw range with its one material, or, for
// an array of materials, each geometry group within the draw range with its own (as three draws
// them; a mesh with an array of materials but no groups: the first). [{first, count, material}]
export function casterDraws(object, first, count) {
    const material = object.material, groups = object.geometry.groups;
    if (!Array.isArray(material)) return [{first, count, material}];
    if (!groups || groups.length === 0) return [{first, count, material: material[0]}];
    const out = [];
    for (const group of groups) {
        const start = Math.max(group.start, first), end = Math.min(group.start + group.count, first + count);
        if (end > start) out.push({first: start, count: end - start, material: material[group.materialIndex]});
    }
    return out;
}

// A cut's texture coordinates, as three's vertex stage gives its map: the uv attribute of the
// map's channel through the map's transform (offset, repeat, rotation, center: map.matrix), done
// here once per geometry and transform, so the emission's slicing pass reads them as they are.
// {key (channel, the attribute's version, the transform), compute(): Float32Array (2 a vertex)}, or
// null where the geometry has no such attribute (that draw is solid).
export function cutCoordinates(geometry, map) {
    const channel = map.channel ?? 0;
    const attribute = geometry.attributes[channel === 0 ? "uv" : `uv${channel}`];
    if (!attribute) return null;
    if (map.matrixAutoUpdate) map.updateMatrix();
    const e = map.matrix.elements;
    const version = attribute.isInterleavedBufferAttribute ? attribute.data.version : attribute.version;
    const key = `${channel} ${version} ${e.join(" ")}`;
    return {key, compute() {
        const n = attribute.count, uvs = new Float32Array(2 * n);
        for (let i = 0; i < n; ++i) {
            const u = attribute.getX(i), v = attribute.getY(i);
            uvs[2 * i] = e[0] * u + e[3] * v + e[6];
            uvs[2 * i + 1] = e[1] * u + e[4] * v + e[7];
        }
        return uvs;
    }};
}

export function isDeformed(object) {
    return object.isSkinnedMesh || !!(object.morphTargetInfluences && object.morphTargetInfluences.some((w) => w !== 0));
}

// Calls draw(matrix) with each placement of a caster: its matrixWorld, or matrixWorld × instance
// matrix for each instance of an InstancedMesh.
const instanceMatrix = new Matrix4(), worldMatrix = new Matrix4();
export function forEachPlacement(object, draw) {
    if (!object.isInstancedMesh) return draw(object.matrixWorld);
    for (let k = 0; k < object.count; ++k) {
        object.getMatrixAt(k, instanceMatrix);
        draw(worldMatrix.multiplyMatrices(object.matrixWorld, instanceMatrix));
    }
}

// The scene side of an add-on, whatever the renderer. A subclass gives _patch(material) (hooks a
// receiver's material), _updateUniforms() (every update) and _renderShadow(casters, receivers,
// frame) (the shadow phase with the light frame's uniforms).
export class ShadowsBase {
    constructor(renderer, scene, light, options) {
        if (!scene || !scene.isScene) fail("the second argument must be a THREE.Scene");
        const o = {...DEFAULTS, ...options};
        this.renderer = renderer;
        this.scene = scene;
        this.light = light;
        this.kind = kindOf(light);
        this.angularDiameter = o.angularDiameter;
        this.autoUpdate = o.autoUpdate;
        this.needsUpdate = true;
        this.enabled = true;
        this.wasm = o.wasm;
        this.intensity = o.intensity;
        this.alphaTest = o.alphaTest; // as given: load() and setEmission() pick the emission by it
        this.info = {shadowUpdates: 0, lastShadowMs: 0, casters: 0, receivers: 0, contained: true, alphaTest: false, cutDraws: 0};
        this.disposed = false;
        this._serial = nextSerial();
        this._rename = renamer(`penumbra${this._serial}`);
        this._materials = new Set(); // materials we hooked
        this._geometries = new Map(); // BufferGeometry (or deformed mesh) → its GPU buffers (_geometryOf, _dropGeometry)
        this._signature = null;
        this._frame = null;
    }

    // The emission's light must be the add-on's. Its alpha test decides whether the casters' cuts
    // are drawn (info.alphaTest): an emission with it, unless alphaTest is false.
    _checkLight(layout) {
        const wanted = this.kind === "sun" ? "sun" : "rect";
        if (layout.config.light !== wanted)
            fail(`the emission is for a '${layout.config.light}' light but the light is a ${this.light.type} (needs '${wanted}')`);
        this.info.alphaTest = layout.config.alpha_test === true && this.alphaTest !== false;
    }

    // The casters' draws (casterDraws over drawn[i], the caster's GPU geometry with its first and
    // count), each with its cut (cutOf) where the emission cuts, else null (solid, one draw a caster
    // as before). Warns once where casters cut but the emission cannot (alphaTest not false).
    _casterCuts(casters, drawn) {
        const cutting = this.info.alphaTest;
        let cuts = 0, uncut = false;
        const out = casters.map((object, i) => {
            const g = drawn[i];
            if (!cutting) {
                if (this.alphaTest !== false && !uncut) uncut = materialsOf(object).some((m) => cutOf(m) !== null);
                return [{first: g.first, count: g.count, cut: null}];
            }
            return casterDraws(object, g.first, g.count).map(({first, count, material}) => {
                const cut = cutOf(material);
                if (cut) ++cuts;
                return {first, count, cut};
            });
        });
        this.info.cutDraws = cuts;
        if (uncut && !this._warnedCut) {
            this._warnedCut = true;
            console.warn("PenumbraShadows: casters' materials cut (a map with alphaTest or transparent) but the emission has no alpha test, " +
                         "so they cast solid: load with a shipped emission or a configuration (the add-on picks the cut one), " +
                         "or emit with penumbra-gen --alpha-test; alphaTest: false keeps them solid without this warning");
        }
        return out;
    }

    _alive(what) {
        if (this.disposed) fail(`${what} after dispose(): this add-on freed its resources; make another with PenumbraShadows.load()`);
    }

    // Call once per frame before renderer.render(): hooks new receivers' materials, re-runs the
    // shadow phase when the light or a caster or receiver changed.
    update() {
        this._alive("update()");
        const scene = this.scene;
        scene.updateMatrixWorld();
        this.light.updateMatrixWorld();
        if (this.light.target) this.light.target.updateMatrixWorld();
        const casters = [], receivers = [];
        scene.traverseVisible((object) => {
            if (!object.isMesh) return;
            if (isCaster(object)) casters.push(object);
            if (object.receiveShadow) {
                receivers.push(object);
                for (const material of Array.isArray(object.material) ? object.material : [object.material]) this._patch(material);
            }
        });
        this.info.casters = casters.length;
        this.info.receivers = receivers.length;
        this._updateUniforms();
        const signature = this._signatureOf(casters, receivers);
        const changed = !this._signature || signature.length !== this._signature.length || signature.some((v, i) => v !== this._signature[i]);
        if (this.needsUpdate || (this.autoUpdate && changed)) {
            this._signature = signature;
            this.needsUpdate = false;
            const t0 = performance.now();
            const box = this._bounds(casters, receivers);
            if (box.isEmpty()) box.set(new Vector3(-1, -1, -1), new Vector3(1, 1, 1));
            const frame = this._lightFrame(box);
            this.info.contained = frame.contained;
            this._frame = frame;
            this._renderShadow(casters, receivers, frame);
            this.info.shadowUpdates++;
            this.info.lastShadowMs = performance.now() - t0;
        }
    }

    // The debug view of renderVisibility(): the receivers alone, drawn with the visibility material
    // (made by makeMaterial(), again when the emission changed) into the visibility target (made by
    // makeTarget(width, height)) cleared to white (1: no receiver); the renderer's target and clear
    // colour and the scene's override, background and visibilities are restored. Returns the target
    // for the renderer's own read-back.
    _renderReceivers(camera, width, height, makeTarget, makeMaterial) {
        const renderer = this.renderer;
        if (!this._visibilityTarget) this._visibilityTarget = makeTarget(width, height);
        const target = this._visibilityTarget;
        if (target.width !== width || target.height !== height) target.setSize(width, height);
        if (!this._visibilityMaterial || this._visibilityMaterial.userData.key !== this._cacheKey) {
            if (this._visibilityMaterial) this._visibilityMaterial.dispose();
            this._visibilityMaterial = makeMaterial();
            this._visibilityMaterial.userData.key = this._cacheKey;
        }
        const hidden = [];
        this.scene.traverse((o) => { if (o.isMesh && o.visible && !o.receiveShadow) { hidden.push(o); o.visible = false; } });
        const previous = {target: renderer.getRenderTarget(), override: this.scene.overrideMaterial, background: this.scene.background,
                          clear: renderer.getClearColor(new Color()), alpha: renderer.getClearAlpha()};
        this.scene.overrideMaterial = this._visibilityMaterial;
        this.scene.background = null;
        try {
            renderer.setRenderTarget(target);
            renderer.setClearColor(0xffffff, 1);
            renderer.clear();
            renderer.render(this.scene, camera);
        } finally {
            renderer.setRenderTarget(previous.target);
            renderer.setClearColor(previous.clear, previous.alpha);
            this.scene.overrideMaterial = previous.override;
            this.scene.background = previous.background;
            for (const o of hidden) o.visible = true;
        }
        return target;
    }

    // Frees every GPU resource of the add-on and restores the materials it hooked (other add-ons'
    // shadows on them stay). Afterwards update(), setEmission() and renderVisibility() throw; a
    // second dispose() does nothing. The subclass's _disposeResources() frees its own.
    dispose() {
        if (this.disposed) return;
        this.disposed = true;
        for (const key of [...this._geometries.keys()]) this._dropGeometry(key);
        for (const material of this._materials) this._unpatch(material);
        this._materials.clear();
        if (this._visibilityTarget) this._visibilityTarget.dispose();
        if (this._visibilityMaterial) this._visibilityMaterial.dispose();
        if (this.runner) this.runner.dispose(); // its textures, samplers, programs or pipelines, framebuffers, buffers
        this.runner = null;
        this._disposeResources(); // (last: on WebGL2 it resets three's state after the runner's raw GL)
    }

    // Everything the shadow phase depends on, as numbers.
    _signatureOf(casters, receivers) {
        const out = [];
        const light = this.light;
        out.push(...light.matrixWorld.elements);
        if (this.kind === "rect") out.push(light.width, light.height);
        else out.push(...light.target.matrixWorld.elements, this.angularDiameter);
        for (const list of [casters, receivers]) {
            out.push(list.length);
            for (const object of list) {
                out.push(object.id, ...object.matrixWorld.elements, object.geometry.id, positionVersion(object.geometry));
                if (object.isInstancedMesh) out.push(object.count, object.instanceMatrix.version);
                if (object.isSkinnedMesh) for (const bone of object.skeleton.bones) out.push(...bone.matrixWorld.elements);
                if (object.morphTargetInfluences) out.push(...object.morphTargetInfluences);
            }
        }
        // what the casters' cuts read: the map (its pixels' version, transform, channel) and cutoff
        if (this.info.alphaTest)
            for (const object of casters)
                for (const material of materialsOf(object)) {
                    const cut = cutOf(material);
                    if (!cut) { out.push(-1); continue; }
                    const map = cut.map;
                    if (map.matrixAutoUpdate) map.updateMatrix();
                    out.push(map.id, map.version, cut.cutoff, map.channel ?? 0, ...map.matrix.elements);
                }
        return out;
    }

    _bounds(casters, receivers) {
        const box = new Box3();
        // exact (vertex by vertex) where the geometry's box is not the drawn one: skinned, instanced, morphed
        const exact = (o) => o.isInstancedMesh || isDeformed(o);
        for (const object of [...casters, ...receivers]) box.expandByObject(object, exact(object));
        return box;
    }

    // The light-frame uniforms (light_frame.js) from the three.js light and the scene's bounds.
    _lightFrame(box) {
        const light = this.light;
        const lo = box.min.toArray(), hi = box.max.toArray();
        const slices = this.config.slices;
        if (this.kind === "sun") {
            const from = new Vector3().setFromMatrixPosition(light.matrixWorld);
            const to = new Vector3().setFromMatrixPosition(light.target.matrixWorld);
            const direction = to.sub(from).normalize().toArray();
            return sunFrame({direction, angularDiameter: this.angularDiameter}, lo, hi, slices);
        }
        // RectAreaLight: width along local x, height along local y, emitting towards local -z; like
        // three's own lighting, the object's scale is ignored.
        // Penumbra's frame wants n = u × v towards the scene: u = x, v = -y.
        const e = light.matrixWorld.elements;
        const x = new Vector3(e[0], e[1], e[2]).normalize(), y = new Vector3(e[4], e[5], e[6]).normalize();
        const center = new Vector3().setFromMatrixPosition(light.matrixWorld).toArray();
        return rectFrame({center, u: x.toArray(), v: y.negate().toArray(), width: light.width, height: light.height},
                         lo, hi, slices);
    }
}
