// penumbra_shadows.js — soft shadows for a three.js RectAreaLight (or a DirectionalLight used as a
// sun with an angular size) from Penumbra's occlusion textures. An ES module add-on, no build step:
//
//   import {PenumbraShadows} from "penumbra-three";          // npm; or "./web/three/penumbra_shadows.js"
//   const shadows = await PenumbraShadows.load(renderer, scene, rectLight);
//   // each frame:
//   shadows.update();
//   renderer.render(scene, camera);
//
// What it does:
//   - the emission (essl300 GLSL + layout.json; a folder shipped in emissions/, one you emitted
//     with `penumbra-gen --target essl300`, or an in-memory one) runs on the renderer's own WebGL2
//     context through the layout runner (penumbra_runner.js, beside this module; the playground
//     in web/ uses the same one), which follows layout.json;
//   - its "shadow" phase (slicing + prefilter) draws the casters (meshes with castShadow, their
//     BufferGeometry positions placed by matrixWorld, InstancedMesh instances, skinned and morphed
//     meshes skinned on the CPU) whenever the light, a caster or a receiver moved; with an emission
//     that has the alpha test (load() picks one when the casters' materials cut: penumbra_scene.js's
//     cutOf), each draw binds its material's map, cutoff and texture coordinates, so cut-outs cut;
//   - every MeshStandardMaterial / MeshPhysicalMaterial of a mesh with receiveShadow gets, through
//     onBeforeCompile, the emitted visibility function (penumbra_visibility.glsl) and multiplies
//     the light's contribution by it (RE_Direct_RectArea for the rectangle, directLight.color for
//     the sun), leaving every other light alone; several add-ons (one per light) share a material,
//     each with its own names (penumbra<N>_…) and each scaling its own light's term only;
//   - raw GL is bracketed by renderer.resetState(), so three's state cache stays right.
// On a WebGPURenderer (three/webgpu) the same load() returns a PenumbraShadowsWebGPU
// (penumbra_shadows_webgpu.js: the wgsl emission on the renderer's GPUDevice, the visibility in
// the node materials through TSL). What both do alike (the scene's casters and receivers, when to
// re-run the shadow phase, the light frame, the emission's files) is penumbra_scene.js.
import {DoubleSide, ExternalTexture, FloatType, GLSL3, Matrix4, NoBlending, RGBAFormat, ShaderMaterial,
        WebGLRenderTarget} from "three";
// (ShaderChunk through the namespace: a WebGPU page may map "three" to three.webgpu.js, which has
// no ShaderChunk, and this module must still load there to hand over to penumbra_shadows_webgpu.js)
import * as three from "three";
import {LayoutRunner} from "./penumbra_runner.js";
import {EMISSIONS, PenumbraError, ShadowsBase, casterVertices, cutCoordinates, emissionFollowingCuts, fail, forEachPlacement, isDeformed, kindOf,
        loadEmissionFiles, requestedEmission, loadEmitter, positionVersion, snippetParameters} from "./penumbra_scene.js";

// The emissions shipped in emissions/ (penumbra-gen output, emissions/regenerate.sh): key → {file name: URL};
// "<key>" is essl300 (WebGLRenderer), "<key>-wgsl" the same configuration in WGSL (WebGPURenderer).
export {EMISSIONS, PenumbraError, loadEmitter};
export {EXT_LIGHTS_AREA, GLTFLightsAreaExtension} from "./gltf_lights_area.js"; // glTF area lights (EXT_lights_area) for GLTFLoader


// ---- shader patches -------------------------------------------------------------------------


// The calls of three's lights_fragment_begin that the patch wraps.
const RECT_CALL = "RE_Direct_RectArea( rectAreaLight, geometryPosition, geometryNormal, geometryViewDir, geometryClearcoatNormal, material, reflectedLight );";
const DIR_CALL = "getDirectionalLightInfo( directionalLight, directLight );";

// The RectAreaLight's contribution: only the loop iterations of shadowed lights are scaled,
// diffuse, specular and clearcoat alike, by lerping from the value before the call to the value
// after it by the product of the visibilities of the add-ons of that light (usually one).
function rectPatch(addons) {
    const factors = addons.map((a) => `if ( UNROLLED_LOOP_INDEX == ${a._names.lightIndex} ) penumbraV *= ${a._names.shadow}( geometryNormal );`);
    // (a block of its own: three's loop unrolling puts the iterations side by side in one scope)
    return `{
		float penumbraV = 1.0;
		${factors.join("\n\t\t")}
		if ( penumbraV < 1.0 ) {
			ReflectedLight penumbraBefore = reflectedLight;
			#ifdef USE_CLEARCOAT
			vec3 penumbraClearcoatBefore = clearcoatSpecularDirect;
			#endif
			${RECT_CALL}
			reflectedLight.directDiffuse = mix( penumbraBefore.directDiffuse, reflectedLight.directDiffuse, penumbraV );
			reflectedLight.directSpecular = mix( penumbraBefore.directSpecular, reflectedLight.directSpecular, penumbraV );
			#ifdef USE_CLEARCOAT
			clearcoatSpecularDirect = mix( penumbraClearcoatBefore, clearcoatSpecularDirect, penumbraV );
			#endif
		} else {
			${RECT_CALL}
		}
		}`;
}
// The sun: the DirectionalLight's colour, as three's own shadow maps scale it.
function dirPatch(addons) {
    return [DIR_CALL, ...addons.map((a) => `if ( UNROLLED_LOOP_INDEX == ${a._names.lightIndex} ) directLight.color *= ${a._names.shadow}( geometryNormal );`)]
        .join("\n\t\t");
}

// World position of the fragment, as three's worldpos_vertex computes it (batching, instancing),
// after skinning and morphing (`transformed`); one varying for every add-on of the material.
const WORLD_VERTEX = `
	vec4 penumbraWorld = vec4( transformed, 1.0 );
	#ifdef USE_BATCHING
		penumbraWorld = batchingMatrix * penumbraWorld;
	#endif
	#ifdef USE_INSTANCING
		penumbraWorld = instanceMatrix * penumbraWorld;
	#endif
	vPenumbraWorldPosition = ( modelMatrix * penumbraWorld ).xyz;`;

// Visibility of one add-on's light at this fragment: the world normal is the view-space one three
// lights with, turned to the side the camera sees (the side whose light the tangent clip keeps);
// an emission without the tangent clip looks up the whole light.
function shadowFunction(names, tangentClip) {
    return `
uniform int ${names.lightIndex};
uniform float ${names.intensity};
float ${names.shadow}( vec3 viewNormal ) {
	vec3 n = normalize( ( vec4( viewNormal, 0.0 ) * viewMatrix ).xyz );
	if ( dot( n, cameraPosition - vPenumbraWorldPosition ) < 0.0 ) n = - n;
	float v = ${names.visibility}( vPenumbraWorldPosition${tangentClip ? ", n" : ""} );
	return mix( 1.0, v, ${names.intensity} );
}
`;
}

function patchChunk(chunk, call, patch, what) {
    if (!chunk.includes(call))
        fail(`three.js's lights_fragment_begin has no '${call}' (${what}); this add-on supports three r180 to r187`);
    return chunk.replace(call, () => patch);
}

// The snippet without its #version line; the precision lines stay (ES 3.00 wants them).
function snippetBody(text) {
    return text.replace(/^#version[^\n]*\n/, "");
}


// Materials shadowed by add-ons: material → {previous: its own hooks, addons: the add-ons, in order}.
// One onBeforeCompile per material puts in the snippets of all its add-ons.
const shadowedMaterials = new WeakMap();

function patchShader(shader, addons) {
    for (const a of addons) Object.assign(shader.uniforms, a.uniforms);
    shader.vertexShader = shader.vertexShader
        .replace("#include <common>", "#include <common>\nout vec3 vPenumbraWorldPosition;")
        .replace("#include <project_vertex>", `#include <project_vertex>${WORLD_VERTEX}`);
    let lights = three.ShaderChunk.lights_fragment_begin;
    const rects = addons.filter((a) => a.kind === "rect"), suns = addons.filter((a) => a.kind === "sun");
    if (rects.length) lights = patchChunk(lights, RECT_CALL, rectPatch(rects), "the rect-area light loop");
    if (suns.length) lights = patchChunk(lights, DIR_CALL, dirPatch(suns), "the directional light loop");
    const snippets = addons.map((a) => `${a._snippet}\n${shadowFunction(a._names, a._tangentClip)}`).join("\n");
    shader.fragmentShader = shader.fragmentShader
        .replace("#include <common>", () => `#include <common>\nin vec3 vPenumbraWorldPosition;\n${snippets}`)
        .replace("#include <lights_fragment_begin>", () => lights);
}

// ---- the add-on -----------------------------------------------------------------------------

export class PenumbraShadows extends ShadowsBase {
    // Loads the emission (options.emission: a key of EMISSIONS, a folder URL, {layout, files} or a
    // configuration) and returns the add-on attached to `renderer`, `scene` and `light`: this class
    // on a WebGLRenderer, PenumbraShadowsWebGPU (penumbra_shadows_webgpu.js, loaded only then, so
    // that a WebGL2 page needs no three/webgpu) on a WebGPURenderer. options.alphaTest (undefined:
    // the scene's casters cut now) picks the emission with the alpha test (emissionFollowingCuts).
    static async load(renderer, scene, light, options = {}) {
        if (renderer && renderer.isWebGPURenderer) {
            const {PenumbraShadowsWebGPU} = await import("./penumbra_shadows_webgpu.js");
            return PenumbraShadowsWebGPU.load(renderer, scene, light, options);
        }
        if (!renderer || !renderer.isWebGLRenderer) fail("the first argument must be a THREE.WebGLRenderer or a WebGPURenderer (three/webgpu)");
        const gl = renderer.getContext();
        const kind = kindOf(light);
        const emission = emissionFollowingCuts(requestedEmission(options, kind), options.alphaTest, scene);
        const runner = await loadRunner(gl, emission, kind, options.wasm ?? null);
        return new PenumbraShadows(renderer, scene, light, {...options, runner});
    }

    constructor(renderer, scene, light, options = {}) {
        if (!renderer || !renderer.isWebGLRenderer) fail("the first argument must be a THREE.WebGLRenderer (a WebGPURenderer: use PenumbraShadows.load)");
        if (!renderer.capabilities.isWebGL2) fail("needs a WebGL2 context");
        super(renderer, scene, light, options);
        if (!options.runner) fail("no emission: use `await PenumbraShadows.load(renderer, scene, light, options)`");
        this._names = {lightIndex: `penumbra${this._serial}LightIndex`, intensity: `penumbra${this._serial}Intensity`,
                       shadow: `penumbra${this._serial}Shadow`, visibility: this._rename("penumbraVisibility")};
        this._visibilityTarget = null;
        this._visibilityMaterial = null;
        this._setRunner(options.runner);
    }

    // The layout runner of the current emission; the materials recompile with its snippet.
    _setRunner(runner) {
        const layout = runner.layout;
        this._checkLight(layout);
        this.runner = runner;
        this.config = layout.config;
        const snippet = runner.sources["penumbra_visibility.glsl"] || fail("the emission has no penumbra_visibility.glsl");
        this._tangentClip = layout.config.tangent_clip !== false;
        this._snippet = this._rename(snippetBody(snippet));
        // The snippet's parameters (from layout.json), under this add-on's names, shared by every
        // patched material (the same uniform objects).
        this.uniforms = {[this._names.lightIndex]: {value: -1}, [this._names.intensity]: {value: this.intensity}};
        this._uniformNames = {}; // the emission's name → ours
        this._samplers = [];
        const zeros = {float: 0, int: 0, vec2: [0, 0], vec3: [0, 0, 0], vec4: [0, 0, 0, 0],
                       mat4: [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]};
        for (const {name, type} of snippetParameters(layout)) {
            const ours = this._rename(name);
            if (!snippet.includes(name)) fail(`penumbra_visibility.glsl has no uniform '${name}' that layout.json lists`);
            this._uniformNames[name] = ours;
            if (type.startsWith("sampler")) {
                const id = runner.texture(name).id;
                const texture = new ExternalTexture(id);
                this._bindExternal(texture, id);
                this.uniforms[ours] = {value: texture};
                this._samplers.push(texture);
            } else {
                // a value of the right shape until the first update() (three cannot upload null)
                this.uniforms[ours] = {value: zeros[type] ?? 0};
            }
        }
        this._cacheKey = `penumbra${this._serial}:${this.kind}:${JSON.stringify(layout.config)}:${PenumbraShadows._generation = (PenumbraShadows._generation || 0) + 1}`;
        this.needsUpdate = true;
        for (const material of this._materials) material.needsUpdate = true;
    }

    // three binds an ExternalTexture's sourceTexture for 2D and 2D-array samplers, and
    // properties.__webglTexture of a never-uploaded texture (version 0) for 3D ones.
    _bindExternal(texture, id) {
        if (texture.isExternalTexture) texture.sourceTexture = id;
        this.renderer.properties.get(texture).__webglTexture = id;
    }

    // Replaces the emission (a key of EMISSIONS, a folder URL, {layout, files} or a configuration),
    // with the alpha test as load() picks it; the old GPU resources are freed once the new ones work.
    async setEmission(emission) {
        this._alive("setEmission()");
        const runner = await loadRunner(this.renderer.getContext(), emissionFollowingCuts(emission, this.alphaTest, this.scene), this.kind, this.wasm);
        const old = this.runner;
        this._setRunner(runner);
        old.dispose();
        this.renderer.resetState();
    }

    // Kept for three.js conventions: the visibility is computed in the materials, so nothing
    // depends on the output size but the debug target of renderVisibility().
    setSize(width, height) {
        if (this._visibilityTarget) this._visibilityTarget.setSize(width, height);
    }

    // Every update(): the light's index among three's lights (it changes as lights come and go).
    _updateUniforms() {
        this.uniforms[this._names.lightIndex].value = this.enabled ? this._lightIndex() : -1;
        this.uniforms[this._names.intensity].value = this.intensity;
    }

    // three's light order: lights in traversal order, shadow-casting (then textured) ones first
    // (WebGLLights.setup); our light's index among the lights of its kind.
    _lightIndex() {
        const lights = [];
        this.scene.traverseVisible((object) => object.isLight && lights.push(object));
        lights.sort((a, b) => (b.castShadow ? 2 : 0) - (a.castShadow ? 2 : 0) + (b.map ? 1 : 0) - (a.map ? 1 : 0));
        const same = lights.filter((l) => (this.kind === "sun" ? l.isDirectionalLight && !l.isSunLight : l.isRectAreaLight));
        return same.indexOf(this.light);
    }

    _renderShadow(casters, receivers, frame) {
        for (const [name, value] of Object.entries(frame.uniforms)) {
            const ours = this._uniformNames[name];
            if (ours) this.uniforms[ours].value = value;
        }
        const renderer = this.renderer, gl = renderer.getContext(), runner = this.runner;
        renderer.resetState();
        // the runner reports any GL error after the phase: start from none (one three left behind
        // is three's, and is passed on with a warning)
        for (let e = gl.getError(), n = 0; e !== gl.NO_ERROR && n < 8; e = gl.getError(), ++n)
            console.warn(`PenumbraShadows: a WebGL error 0x${e.toString(16)} was pending before the shadow phase (not the add-on's)`);
        runner.setUniforms(frame.uniforms);
        const drawn = casters.map((object) => this._geometryOf(object));
        const draws = this._casterCuts(casters, drawn);
        if (this.info.alphaTest) {
            // the maps' GL textures, which three uploads now if it has not yet (with its state cache
            // right again after our raw GL), and each cut draw's texture coordinates (cutCoordinates)
            renderer.resetState();
            for (const [i, list] of draws.entries())
                for (const d of list) {
                    if (!d.cut) continue;
                    d.texture = this._mapTexture(d.cut.map);
                    d.uv = this._uvBuffer(drawn[i], casters[i].geometry, d.cut.map);
                }
        }
        runner.runPhase("shadow", (programId) => this._drawCasters(programId, casters, drawn, draws), null);
        for (const g of drawn) this._dropUnusedUVs(g);
        gl.bindVertexArray(null);
        renderer.resetState();
    }

    // Draws every caster with each "...FromWorld" matrix of the program times its model matrix
    // (and instance matrix), so that attribute 0 can stay in object space. A program with the
    // alpha test (parameters whose source is "draw": the alpha texture and cutoff; vertex input
    // penumbra_uv) gets each draw's map, cutoff and coordinates, or, solid, the runner's white texture
    // and cutoff 0 (LayoutRunner.alphaTestInputs).
    _drawCasters(programId, casters, drawn, draws) {
        const gl = this.renderer.getContext();
        const program = Object.values(this.runner.programs).find((p) => p.id === programId);
        const matrices = program.desc.parameters.filter((p) => p.type === "mat4" && /FromWorld$/.test(p.name));
        const locations = matrices.map((p) => program.locations[p.name] || gl.getUniformLocation(programId, p.name));
        const base = matrices.map((p) => new Matrix4().fromArray(this.runner.uniformValues[p.name]));
        const alphaTest = this.runner.alphaTestInputs(program);
        const m = new Matrix4();
        const draw = (g, d, objectMatrix) => {
            matrices.forEach((p, k) => {
                if (!locations[k]) return;
                m.multiplyMatrices(base[k], objectMatrix);
                gl.uniformMatrix4fv(locations[k], false, m.elements);
            });
            gl.bindVertexArray(g.vao);
            if (alphaTest) alphaTest.bind(d);
            if (g.indexType) gl.drawElements(gl.TRIANGLES, d.count, g.indexType, d.first * g.indexBytes);
            else gl.drawArrays(gl.TRIANGLES, d.first, d.count);
        };
        // (skinned and morphed positions come in the mesh's own space: casterVertices)
        casters.forEach((object, i) => forEachPlacement(object, (matrix) => { for (const d of draws[i]) draw(drawn[i], d, matrix); }));
        gl.bindVertexArray(null);
        if (alphaTest) alphaTest.end();
    }

    // A map's GL texture, uploaded by three (initTexture) if it was not yet; null while its image
    // is not there (version 0), or for a texture that is no 2D texture: that draw is solid until
    // the map's version changes (which re-runs the shadow phase: _signatureOf).
    _mapTexture(map) {
        if (!map.isTexture || map.isCubeTexture || map.isData3DTexture || map.isDataArrayTexture || map.isRenderTargetTexture) return null;
        if (map.version === 0 && !map.isExternalTexture) return null;
        this.renderer.initTexture(map);
        return this.renderer.properties.get(map).__webglTexture ?? null;
    }

    // The buffer of a cut's texture coordinates on GPU geometry g (one per channel and map
    // transform: casters sharing a geometry may cut through differently placed maps); null where the
    // geometry has none.
    _uvBuffer(g, geometry, map) {
        const c = cutCoordinates(geometry, map);
        if (!c) return null;
        g.uvs ||= new Map();
        let entry = g.uvs.get(c.key);
        if (!entry) {
            const gl = this.renderer.getContext();
            entry = {buffer: gl.createBuffer()};
            gl.bindBuffer(gl.ARRAY_BUFFER, entry.buffer);
            gl.bufferData(gl.ARRAY_BUFFER, c.compute(), gl.STATIC_DRAW);
            gl.bindBuffer(gl.ARRAY_BUFFER, null);
            g.uvs.set(c.key, entry);
        }
        entry.used = true;
        return entry.buffer;
    }

    // After a shadow phase: the coordinates no draw used (an old transform or uv version) go.
    _dropUnusedUVs(g) {
        if (!g.uvs) return;
        const gl = this.renderer.getContext();
        for (const [key, entry] of g.uvs) {
            if (!entry.used) { gl.deleteBuffer(entry.buffer); g.uvs.delete(key); }
            else entry.used = false;
        }
    }

    // Our vertex array for a caster: its geometry's positions (attribute 0) and index, uploaded
    // once per geometry and again when the position attribute's version changes; skinned and
    // morphed meshes get theirs (casterVertices) at every shadow update.
    _geometryOf(object) {
        const geometry = object.geometry;
        const deformed = isDeformed(object);
        const key = deformed ? object : geometry;
        const gl = this.renderer.getContext();
        let g = this._geometries.get(key);
        const version = positionVersion(geometry);
        if (g && !deformed && g.version === version) return g;
        if (!g) {
            g = {vao: gl.createVertexArray(), position: gl.createBuffer(), index: null, version: -1, key};
            this._geometries.set(key, g);
            if (!deformed) geometry.addEventListener("dispose", () => this._dropGeometry(key));
        }
        const v = casterVertices(object);
        gl.bindVertexArray(g.vao);
        gl.bindBuffer(gl.ARRAY_BUFFER, g.position);
        gl.bufferData(gl.ARRAY_BUFFER, v.positions, deformed ? gl.DYNAMIC_DRAW : gl.STATIC_DRAW);
        gl.enableVertexAttribArray(0);
        gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 0, 0);
        g.first = v.first;
        g.count = v.count;
        g.indexType = 0;
        if (v.index) {
            if (!g.index) g.index = gl.createBuffer();
            gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, g.index);
            gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, v.index, gl.STATIC_DRAW);
            g.indexType = v.index instanceof Uint32Array ? gl.UNSIGNED_INT : gl.UNSIGNED_SHORT;
            g.indexBytes = v.index.BYTES_PER_ELEMENT;
        }
        gl.bindVertexArray(null);
        gl.bindBuffer(gl.ARRAY_BUFFER, null);
        g.version = version;
        return g;
    }

    _dropGeometry(key) {
        const g = this._geometries.get(key);
        if (!g) return;
        const gl = this.renderer.getContext();
        gl.deleteVertexArray(g.vao);
        gl.deleteBuffer(g.position);
        if (g.index) gl.deleteBuffer(g.index);
        for (const entry of (g.uvs || new Map()).values()) gl.deleteBuffer(entry.buffer);
        this._geometries.delete(key);
    }

    // onBeforeCompile on a MeshStandardMaterial / MeshPhysicalMaterial (others are left alone); a
    // material shadowed by other add-ons (other lights) gets this one's snippet beside theirs.
    _patch(material) {
        if (this._materials.has(material) || !material || !material.isMeshStandardMaterial) return;
        let shared = shadowedMaterials.get(material);
        if (!shared) {
            shared = {previous: {onBeforeCompile: material.onBeforeCompile, customProgramCacheKey: material.customProgramCacheKey}, addons: []};
            shadowedMaterials.set(material, shared);
            const {onBeforeCompile, customProgramCacheKey} = shared.previous;
            material.onBeforeCompile = function (shader, renderer) {
                onBeforeCompile.call(this, shader, renderer);
                patchShader(shader, shared.addons);
            };
            material.customProgramCacheKey = function () {
                return customProgramCacheKey.call(this) + shared.addons.map((a) => a._cacheKey).join("|");
            };
        }
        shared.addons.push(this);
        this._materials.add(material);
        const units = shared.addons.reduce((n, a) => n + a._samplers.length, 0);
        const max = this.renderer.capabilities.maxTextures;
        if (units + 4 > max && !this._warnedUnits) {
            this._warnedUnits = true;
            console.warn(`PenumbraShadows: a material shadowed by ${shared.addons.length} add-ons samples ${units} of their textures, ` +
                         `and three needs some of the ${max} texture units too; use emissions with one texture ('…-mipmap-…')`);
        }
        material.needsUpdate = true;
    }

    // Takes this add-on out of a material; the last one out restores the material's own hooks.
    _unpatch(material) {
        const shared = shadowedMaterials.get(material);
        if (shared) {
            shared.addons = shared.addons.filter((a) => a !== this);
            if (shared.addons.length === 0) {
                material.onBeforeCompile = shared.previous.onBeforeCompile;
                material.customProgramCacheKey = shared.previous.customProgramCacheKey;
                shadowedMaterials.delete(material);
            }
        }
        material.needsUpdate = true;
    }

    // The add-on's visibility (0 shadowed … 1 lit) as the camera sees the receivers, for debugging
    // and tests: Float32Array of width × height, bottom row first; 1 where no receiver is.
    renderVisibility(camera, width, height) {
        this._alive("renderVisibility()");
        const target = this._renderReceivers(camera, width, height,
            (w, h) => new WebGLRenderTarget(w, h, {type: FloatType, format: RGBAFormat, depthBuffer: true}), () => this._makeVisibilityMaterial());
        const rgba = new Float32Array(4 * width * height);
        this.renderer.readRenderTargetPixels(target, 0, 0, width, height, rgba);
        const out = new Float32Array(width * height);
        for (let i = 0; i < out.length; ++i) out[i] = rgba[4 * i];
        return out;
    }

    _makeVisibilityMaterial() {
        const material = new ShaderMaterial({
            glslVersion: GLSL3,
            uniforms: this.uniforms,
            side: DoubleSide,
            blending: NoBlending,
            vertexShader: `#include <common>
#include <batching_pars_vertex>
#include <morphtarget_pars_vertex>
#include <skinning_pars_vertex>
out vec3 vPenumbraWorldPosition;
out vec3 vPenumbraViewNormal;
void main() {
	#include <batching_vertex>
	#include <beginnormal_vertex>
	#include <morphinstance_vertex>
	#include <morphnormal_vertex>
	#include <skinbase_vertex>
	#include <skinnormal_vertex>
	#include <defaultnormal_vertex>
	#include <begin_vertex>
	#include <morphtarget_vertex>
	#include <skinning_vertex>
	#include <project_vertex>
	${WORLD_VERTEX}
	vPenumbraViewNormal = transformedNormal;
}`,
            fragmentShader: `${this._snippet}
#include <common>
in vec3 vPenumbraWorldPosition;
${shadowFunction(this._names, this._tangentClip)}
in vec3 vPenumbraViewNormal;
layout(location = 0) out vec4 penumbraOut;
void main() {
	float v = ${this._names.lightIndex} >= 0 ? ${this._names.shadow}( normalize( vPenumbraViewNormal ) ) : 1.0;
	penumbraOut = vec4( v, v, v, 1.0 );
}`,
        });
        return material;
    }

    // dispose(): the external textures' GL names (the runner deleted them), three's state
    _disposeResources() {
        for (const t of this._samplers) {
            this.renderer.properties.get(t).__webglTexture = undefined;
            if (t.isExternalTexture) t.sourceTexture = null;
            t.dispose();
        }
        this._samplers = [];
        this.renderer.resetState();
    }
}

// The WebGL2 layout runner for an emission (loadEmissionFiles: a key of EMISSIONS, a folder URL,
// {layout, files} or a configuration), with the emission's files as `sources` (the snippet).
async function loadRunner(gl, emission, kind, wasm) {
    const files = await loadEmissionFiles(emission, kind, wasm, "essl300");
    const runner = LayoutRunner.fromEmission(gl, files);
    runner.sources = files.files;
    return runner;
}

