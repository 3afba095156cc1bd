// penumbra_babylon.js — soft shadows for a Babylon.js RectAreaLight (or a DirectionalLight used as a
// sun with an angular size) from Penumbra's occlusion textures, on Babylon's WebGL2 Engine and
// WebGPUEngine:
//
//   import {PenumbraShadows} from "penumbra-babylon";
//   const shadows = await PenumbraShadows.load(engine, scene, rectLight);
//   shadows.addShadowCaster(box);          // like ShadowGenerator; receivers: mesh.receiveShadows = true
//   scene.onBeforeRenderObservable.add(() => shadows.update());
//
// What it does:
//   - the emission (essl300 GLSL + layout.json: one shipped in emissions/, a folder, an in-memory one,
//     or a configuration emitted in the page) runs on the engine's own WebGL2 context through the
//     layout runner shared with penumbra-three (shared/penumbra_runner.js), which follows layout.json;
//     on WebGPUEngine the wgsl emission runs on the engine's GPUDevice through the WebGPU layout
//     runner shared with penumbra-three (shared/penumbra_webgpu_runner.js; penumbra_babylon_webgpu.js);
//     its "shadow" phase (slicing + prefilter) draws the casters (their vertex data placed by their
//     world matrices, instances and thin instances, skinned and morphed ones from the CPU) whenever
//     the light, a caster or a receiver moved; with an emission that has the alpha test (load() picks
//     one when a mesh's material cuts: cutOf), each draw binds its material's diffuse / albedo
//     texture (Babylon's own GL texture or GPUTexture), cutoff and texture coordinates, so cut-outs cut;
//   - every StandardMaterial / PBRMaterial of a mesh with receiveShadows gets a material plugin
//     (MaterialPluginBase, Babylon's documented way to add shader code) that puts the emitted
//     visibility function in and multiplies that light's `shadow` factor by it, in the light loop
//     (lightFragment) where Babylon's own shadow generators scale the light's diffuse, specular,
//     clear coat and sheen terms; other lights are left alone, and several add-ons (one per light)
//     share a material, each under its own names (penumbra<N>_…);
//     on WebGPUEngine the same plugin injects WGSL (Babylon's WGSL materials, ShaderLanguage.WGSL);
//   - raw GL is followed by engine.wipeCaches(true), so Babylon's state cache stays right.
import {MaterialPluginBase} from "@babylonjs/core/Materials/materialPluginBase.js";
import {ShaderMaterial} from "@babylonjs/core/Materials/shaderMaterial.js";
import {BaseTexture} from "@babylonjs/core/Materials/Textures/baseTexture.js";
import {InternalTexture} from "@babylonjs/core/Materials/Textures/internalTexture.js";
import {RenderTargetTexture} from "@babylonjs/core/Materials/Textures/renderTargetTexture.js";
import {WebGLHardwareTexture} from "@babylonjs/core/Engines/WebGL/webGLHardwareTexture.js";
import {Color4} from "@babylonjs/core/Maths/math.color.js";
import {Vector3} from "@babylonjs/core/Maths/math.vector.js";
// (the includes of the visibility material's vertex stage: instances and thin instances)
import "@babylonjs/core/Shaders/ShadersInclude/instancesDeclaration.js";
import "@babylonjs/core/Shaders/ShadersInclude/instancesVertex.js";
import {LayoutRunner} from "./shared/penumbra_runner.js";
import {rectFrame, sunFrame} from "./shared/light_frame.js";
import {EMISSIONS, PenumbraError, emissionWithCut, fail, loadEmissionFiles, loadEmitter, nextSerial, renamer,
        requestedEmission, snippetParameters} from "./shared/penumbra_emission.js";

export {EMISSIONS, PenumbraError, loadEmitter};
// (cutOf, below, is exported too: whether a material cuts, as the add-on decides it)

const DEFAULTS = {
    emission: null,           // a key of EMISSIONS, a folder URL (ending in "/"), {layout, files}, or a configuration
                              // object ({slices, resolution, filter, ...}: needs the WebAssembly emitter)
    angularDiameter: 0.0093,  // sun only: the DirectionalLight's angular diameter in radians (our sun: 0.53°)
    autoUpdate: true,         // re-run the shadow phase by itself when something moved
    intensity: 1,             // 0: no shadow, 1: Penumbra's visibility (like ShadowGenerator.darkness, inverted)
    wasm: null,               // for a configuration object: the URL of penumbra_emitter.wasm (default: the one beside penumbra_emitter.js)
    alphaTest: undefined,     // cut-out casters (cutOf): undefined follows the scene (on when a mesh's material cuts at load()), true / false forces
};

function kindOf(light) {
    const name = light && typeof light.getClassName === "function" ? light.getClassName() : null;
    if (name === "RectAreaLight") return "rect";
    if (name === "DirectionalLight") return "sun";
    fail(`the light must be a RectAreaLight or a DirectionalLight (got ${name ?? light})`);
}

const RECEIVING_MATERIALS = ["StandardMaterial", "PBRMaterial"];

// column-major 4×4 product a · b (Babylon's Matrix.m is laid out as GL reads it)
function multiply(a, b) {
    const m = new Float32Array(16);
    for (let c = 0; c < 4; ++c)
        for (let r = 0; r < 4; ++r) {
            let s = 0;
            for (let k = 0; k < 4; ++k) s += a[k * 4 + r] * b[c * 4 + k];
            m[c * 4 + r] = s;
        }
    return m;
}

function transformPoint(m, x, y, z) {
    return [m[0] * x + m[4] * y + m[8] * z + m[12], m[1] * x + m[5] * y + m[9] * z + m[13], m[2] * x + m[6] * y + m[10] * z + m[14]];
}

function isDeformed(mesh) {
    const morph = mesh.morphTargetManager;
    return !!mesh.skeleton || !!(morph && morph.numInfluencers > 0);
}

// Every placement of a caster or receiver: [mesh whose vertex data it draws, world matrix (Float32Array 16)].
// An InstancedMesh draws its source's data; a Mesh with thin instances draws each of them (as Babylon
// does, not the mesh itself), a Mesh with instances each instance too.
function placements(mesh) {
    if (mesh.sourceMesh) return [[mesh.sourceMesh, mesh.getWorldMatrix().m]];
    const world = mesh.getWorldMatrix();
    if (mesh.hasThinInstances) return mesh.thinInstanceGetWorldMatrices().map((t) => [mesh, t.multiply(world).m]);
    const out = [[mesh, world.m]];
    for (const instance of mesh.instances || []) if (instance.isEnabled()) out.push([mesh, instance.getWorldMatrix().m]);
    return out;
}

// ---- cut-out casters (the alpha test) ----------------------------------------------------------

// Babylon's transparency modes (Material.MATERIAL_OPAQUE … MATERIAL_ALPHATESTANDBLEND)
const OPAQUE = 0, ALPHATEST = 1, ALPHABLEND = 2, ALPHATESTANDBLEND = 3;

// Whether a caster's material cuts, and where: as Babylon draws it, through its alpha-test texture
// (getAlphaTestTexture: StandardMaterial's diffuseTexture, PBRMaterial's albedoTexture), whose alpha
// Babylon's glTF loader turns on for MASK (transparencyMode ALPHATEST, alphaCutOff; texture hasAlpha)
// and BLEND (ALPHABLEND; hasAlpha and useAlphaFromAlbedoTexture). ALPHATEST / ALPHATESTANDBLEND cut
// at alphaCutOff where the texture's alpha reaches Babylon's test (PBRMaterial: hasAlpha;
// StandardMaterial: hasAlpha and useAlphaFromDiffuseTexture); ALPHABLEND, where the texture's alpha
// blends (hasAlpha and useAlphaFrom…Texture), is cast as a cut-out at 0.5 (a shadow has no partial
// coverage); no transparencyMode: Babylon's own choice (hasAlpha: blended when useAlphaFrom…Texture,
// else tested at alphaCutOff); OPAQUE: solid. The material's alpha multiplies the texture's (but in
// StandardMaterial's test without a transparencyMode), so the cutoff the slicing pass compares the
// texture's alpha with is cutoff / alpha (above 1 nothing of it casts). {texture, cutoff}, or null:
// solid. opacityTexture, vertex alpha and a texture-less material's alpha are not followed (README).
export function cutOf(material) {
    const texture = material && typeof material.getAlphaTestTexture === "function" ? material.getAlphaTestTexture() : null;
    if (!texture || !texture.hasAlpha) return null;
    const standard = "useAlphaFromDiffuseTexture" in material;
    const blends = !!(standard ? material.useAlphaFromDiffuseTexture : material.useAlphaFromAlbedoTexture);
    const mode = material.transparencyMode ?? null;
    let cutoff = 0;
    if (mode === ALPHATEST || mode === ALPHATESTANDBLEND) cutoff = !standard || blends ? material.alphaCutOff ?? 0.4 : 0;
    else if (mode === ALPHABLEND) cutoff = blends ? 0.5 : 0;
    else if (mode === null) cutoff = blends ? 0.5 : material.alphaCutOff ?? 0.4;
    if (!(cutoff > 0)) return null;
    const alpha = standard && mode === null && !blends ? 1 : material.alpha ?? 1;
    return {texture, cutoff: alpha > 0 ? Math.min(cutoff / alpha, 2) : 2};
}

function materialsOf(mesh) {
    const material = mesh.sourceMesh ? mesh.sourceMesh.material : mesh.material;
    return material && material.subMaterials ? material.subMaterials : [material];
}

// Whether an enabled mesh of the scene has a material that cuts: what alphaTest undefined follows
// at load(), before the casters are added (addShadowCaster comes after load()).
function sceneCuts(scene) {
    return scene.meshes.some((mesh) => mesh.isEnabled() && materialsOf(mesh).some((m) => cutOf(m) !== null));
}

// The draws of a caster's vertex data (`source`, the mesh whose data a placement draws; g its GPU
// geometry): one whole draw, or with `cutting` each sub-mesh's index range with its material
// (MultiMaterial), each {first, count, cut} (cut: cutOf, or null).
function casterDraws(source, g, cutting) {
    if (!cutting) return [{first: 0, count: g.count, cut: null}];
    const subMeshes = source.subMeshes || [];
    if (!g.indexed || subMeshes.length === 0) return [{first: 0, count: g.count, cut: cutOf(materialsOf(source)[0])}];
    return subMeshes.filter((s) => s.indexCount > 0).map((s) => ({first: s.indexStart, count: s.indexCount, cut: cutOf(s.getMaterial())}));
}

// A cut's texture coordinates, as Babylon's vertex stage gives the texture: the uv set of its
// coordinatesIndex (uv, uv2, …) through its texture matrix (uOffset, vOffset, uScale, vScale, the
// angles: getTextureMatrix), done here once per vertex data and transform, so the emission's slicing
// pass reads them as they are. {key, data, compute()} or null where the mesh has no such uv set.
function cutCoordinates(source, texture) {
    const index = texture.coordinatesIndex ?? 0;
    const buffer = source.getVertexBuffer(index === 0 ? "uv" : `uv${index + 1}`);
    if (!buffer) return null;
    const m = typeof texture.getTextureMatrix === "function" ? texture.getTextureMatrix().m : [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
    const key = `${index} ${m[0]} ${m[1]} ${m[4]} ${m[5]} ${m[8]} ${m[9]}`;
    return {key, data: buffer, compute() {
        const uv = source.getVerticesData(index === 0 ? "uv" : `uv${index + 1}`), n = uv.length / 2, out = new Float32Array(2 * n);
        for (let i = 0; i < n; ++i) {
            const u = uv[2 * i], v = uv[2 * i + 1];
            out[2 * i] = m[0] * u + m[4] * v + m[8];
            out[2 * i + 1] = m[1] * u + m[5] * v + m[9];
        }
        return out;
    }};
}

// A cut texture's Babylon InternalTexture when it can be read now (a ready 2D texture), else null:
// that draw is solid until it is ready (its readiness is in the signature: the shadow phase runs again).
function cutInternal(texture) {
    const internal = texture.getInternalTexture ? texture.getInternalTexture() : null;
    if (!internal || !internal.isReady || internal.isCube || internal.is3D || internal.is2DArray || !internal._hardwareTexture) return null;
    return internal;
}

// ---- the material plugin ------------------------------------------------------------------------

// One per (material, add-on). Once added, a Babylon plugin stays on its material: after the
// add-on's dispose() it injects nothing, and its define changes so that the material compiles again.
class PenumbraShadowsPlugin extends MaterialPluginBase {
    constructor(material, addon) {
        // (added to the material once the add-on is known: adding asks getCustomCode for its points)
        super(material, `PenumbraShadows${addon._serial}`, 200, {[addon._define]: 0}, false, false);
        this._addon = addon;
        this.registerForExtraEvents = true; // hardBindForSubMesh: the light's index is the mesh's
        this._pluginManager._addPlugin(this);
        this._enable(true);
    }

    getClassName() {
        return "PenumbraShadowsPlugin";
    }

    // ShaderLanguage.GLSL (0) on WebGL2, ShaderLanguage.WGSL (1) on WebGPUEngine: the language of the add-on's snippet
    isCompatible(shaderLanguage) {
        return shaderLanguage === (this._addon.webgpu ? 1 : 0);
    }

    prepareDefines(defines) {
        defines[this._addon._define] = this._addon.disposed ? 0 : this._addon._generation;
    }

    getSamplers(samplers) {
        samplers.push(...this._addon._samplerNames);
    }

    // The snippet's values, the light's index and the intensity in the material's uniform buffer
    // (Babylon's documented way; the snippet's own declarations of them are taken out).
    // (WGSL: Babylon declares the uniform buffer's members itself, read as uniforms.<name>)
    getUniforms() {
        const a = this._addon;
        if (a.webgpu) return {ubo: a._uboUniforms};
        return {ubo: a._uboUniforms, fragment: a._uboUniforms.map((u) => `uniform ${u.type} ${u.name};`).join("\n")};
    }

    // The snippet and the add-on's shadow function among the fragment stage's declarations; in the
    // light loop, before `aggShadow+=shadow;` (where each light's shadow factor is final), this
    // light's factor times the visibility. Light blocks are told apart by the index in their
    // LIGHTMAPEXCLUDED<index> define further on, which the regular expression captures as $1.
    // Babylon's WGSL light loop (ShadersWGSL/ShadersInclude/lightFragment) has the same line and
    // define; there the values are the uniform buffer's (uniforms.), the eye the scene's (scene.).
    getCustomCode(shaderType) {
        const a = this._addon, n = a._names;
        if (shaderType !== "fragment" || a.disposed) return null;
        const call = a.webgpu
            ? `if (uniforms.${n.lightIndex}==f32($1)) {shadow*=${n.shadow}(normalW,fragmentInputs.vPositionW,scene.vEyePosition.xyz);}`
            : `if (${n.lightIndex}==float($1)) shadow*=${n.shadow}(normalW,vPositionW,vEyePosition.xyz);`;
        return {
            CUSTOM_FRAGMENT_DEFINITIONS: a._fragmentDefinitions,
            // (each add-on's key differs by its always-true look-ahead: keys of equal text would be joined)
            [`!aggShadow\\+=shadow;(?=[\\s\\S]*?LIGHTMAPEXCLUDED(\\d+))(?!${n.shadow})`]: `${call}\naggShadow+=shadow;`,
        };
    }

    // Every draw (the light's index is the mesh's), before Babylon uploads the uniform buffer.
    hardBindForSubMesh(uniformBuffer, scene, engine, subMesh) {
        if (this._addon.disposed) return;
        const mesh = subMesh.getMesh();
        const index = this._addon.enabled ? (mesh.lightSources || []).indexOf(this._addon.light) : -1;
        this._addon._bind(uniformBuffer, index);
    }
}

// ---- the add-on ---------------------------------------------------------------------------------

export class PenumbraShadows {
    // Loads the emission (options.emission: a key of EMISSIONS, a folder URL, {layout, files} or a
    // configuration) and returns the add-on attached to `engine`, `scene` and `light`. options.alphaTest
    // (undefined: a mesh of the scene has a material that cuts now) picks the emission with the alpha
    // test (shared/penumbra_emission.js's emissionWithCut).
    static async load(engine, scene, light, options = {}) {
        if (!engine || typeof engine.getClassName !== "function") fail("the first argument must be a Babylon.js Engine");
        if (!scene || typeof scene.getClassName !== "function" || scene.getClassName() !== "Scene") fail("the second argument must be a Babylon.js Scene");
        const kind = kindOf(light);
        const emission = emissionWithCut(requestedEmission(options, kind), options.alphaTest, () => sceneCuts(scene));
        if (engine.isWebGPU) {
            if (!engine._device) fail("the WebGPUEngine has no GPUDevice yet: await engine.initAsync() first");
            // (imported here: bundlers split it off, and WebGL2 pages never load it)
            const gpu = await import("./penumbra_babylon_webgpu.js");
            const runner = await gpu.loadRunner(engine, emission, kind, options.wasm ?? null);
            return new PenumbraShadows(engine, scene, light, {...options, runner, gpu});
        }
        if (!engine._gl || engine.webGLVersion < 2) fail("needs a WebGL2 Engine or a WebGPUEngine");
        const files = await loadEmissionFiles(emission, kind, options.wasm ?? null, "essl300");
        const runner = LayoutRunner.fromEmission(engine._gl, files);
        runner.sources = files.files;
        engine.wipeCaches(true);
        return new PenumbraShadows(engine, scene, light, {...options, runner});
    }

    constructor(engine, scene, light, options = {}) {
        if (!options.runner) fail("no emission: use `await PenumbraShadows.load(engine, scene, light, options)`");
        const o = {...DEFAULTS, ...options};
        this.engine = engine;
        this.webgpu = !!engine.isWebGPU;
        if (this.webgpu && !options.gpu) fail("no WebGPU module: use `await PenumbraShadows.load(engine, scene, light, options)`");
        this._gpu = options.gpu ?? null; // penumbra_babylon_webgpu.js on WebGPUEngine
        this.scene = scene;
        this.light = light;
        this.kind = kindOf(light);
        this.angularDiameter = o.angularDiameter;
        this.autoUpdate = o.autoUpdate;
        this.intensity = o.intensity;
        this.enabled = true;
        this.needsUpdate = true;
        this.disposed = false;
        this.alphaTest = o.alphaTest; // as given: load() picked the emission by it
        this.info = {shadowUpdates: 0, lastShadowMs: 0, casters: 0, receivers: 0, contained: true, alphaTest: false, cutDraws: 0};
        this._serial = nextSerial();
        this._rename = renamer(`penumbra${this._serial}`);
        this._define = `PENUMBRA${this._serial}`;
        this._generation = 1;
        this._names = {lightIndex: `penumbra${this._serial}LightIndex`, intensity: `penumbra${this._serial}Intensity`,
                       shadow: `penumbra${this._serial}Shadow`, visibility: this._rename("penumbraVisibility")};
        this._casters = new Set();
        this._plugins = new Map(); // material → its plugin
        this._geometries = new Map(); // Geometry (or deformed mesh) → its GPU buffers (WebGL2)
        this._gpuCasters = this.webgpu ? new this._gpu.WebGPUCasters(engine._device) : null; // (WebGPU)
        this._signature = null;
        this._setRunner(options.runner);
    }

    _setRunner(runner) {
        const layout = runner.layout;
        const wanted = this.kind === "sun" ? "sun" : "rect";
        if (layout.config.light !== wanted)
            fail(`the emission is for a '${layout.config.light}' light but the light is a ${this.light.getClassName()} (needs '${wanted}')`);
        // its alpha test decides whether the casters' cuts are drawn: an emission with it, unless alphaTest is false
        this.info.alphaTest = layout.config.alpha_test === true && this.alphaTest !== false;
        this.runner = runner;
        this.config = layout.config;
        const file = this.webgpu ? "penumbra_visibility.wgsl" : "penumbra_visibility.glsl";
        const snippet = runner.sources[file] || fail(`the emission has no ${file}`);
        const tangentClip = layout.config.tangent_clip !== false;
        this._uniformNames = {}; // the emission's name → ours
        this._values = {}; // ours → {type, value}
        this._samplerNames = [];
        this._textures = {};
        for (const p of snippetParameters(layout)) {
            const ours = this._rename(p.name);
            if (!snippet.includes(p.name)) fail(`${file} has no parameter '${p.name}' that layout.json lists`);
            this._uniformNames[p.name] = ours;
            if (p.type.startsWith("sampler")) {
                this._samplerNames.push(ours);
                const t = runner.texture(p.texture ?? p.name);
                this._textures[ours] = this.webgpu ? this._gpu.wrapTexture(this.engine, this.scene, t, p.sampling ?? t.desc) : this._wrap(t);
            } else {
                this._values[ours] = {type: p.type, value: null};
            }
        }
        this._valueNames = [...Object.keys(this._values), this._names.lightIndex, this._names.intensity];
        const n = this._names;
        if (this.webgpu) {
            // WGSL (penumbra_babylon_webgpu.js): the snippet reads the values from the material's
            // uniform buffer (uniforms.<name>), loaded into its private variables by its loader
            const code = this._gpu.wgslForBabylon(this._rename(snippet));
            const load = (/\bfn\s+(penumbra\d*_loadVisibility)\s*\(/.exec(code) || [])[1] ?? null;
            this._fragmentDefinitions = `${code}\n${this._gpu.wgslShadowFunction(n, load, n.visibility, tangentClip)}`;
            this._visibilityDefinitions = this._fragmentDefinitions;
        } else {
            // (without its float precision line: Babylon puts its own first only where the shader has none)
            this._snippet = this._rename(snippet.replace(/^#version[^\n]*\n/, "").replace(/^precision highp float;\n/m, ""));
            // the visibility at a fragment: the world normal turned to the side the camera sees (the
            // side whose light the tangent clip keeps); an emission without the clip looks up the whole light
            this._shadowFunction = `
uniform float ${n.lightIndex};
uniform float ${n.intensity};
float ${n.shadow}(vec3 normalWorld, vec3 positionWorld, vec3 eye) {
	vec3 n = normalize(normalWorld);
	if (dot(n, eye - positionWorld) < 0.0) n = -n;
	float v = ${n.visibility}(positionWorld${tangentClip ? ", n" : ""});
	return mix(1.0, v, ${n.intensity});
}
`;
            // (the material's copy: the values' declarations come from the uniform buffer)
            const declared = new RegExp(`^uniform \\w+ (${[...Object.keys(this._values)].join("|")});[^\\n]*\\n`, "gm");
            this._fragmentDefinitions = `${this._snippet.replace(declared, "")}\n${this._shadowFunction.replace(/^uniform [^\n]*\n/gm, "")}`;
            this._visibilityDefinitions = `${this._snippet}\n${this._shadowFunction}`;
        }
        const sizes = {float: 1, vec2: 2, vec3: 3, vec4: 4, mat4: 16};
        this._uboUniforms = [{name: this._names.lightIndex, size: 1, type: "float"}, {name: this._names.intensity, size: 1, type: "float"},
                             ...Object.entries(this._values).map(([name, {type}]) => ({name, type, size: sizes[type] ?? fail(`the snippet's uniform ${name} has type ${type}, which this add-on does not set`)}))];
    }

    // A texture the runner made, as a Babylon texture that binds it as is: Babylon sets a
    // texture's wrap and anisotropy only where they differ from what it cached, so both are cached
    // at the values set, and the runner's filters and wraps stay.
    _wrap(t) {
        const gl = this.engine._gl;
        const internal = new InternalTexture(this.engine, 0 /* InternalTextureSource.Unknown */, true);
        internal._hardwareTexture = new WebGLHardwareTexture(t.id, gl);
        internal.baseWidth = internal.width = t.width;
        internal.baseHeight = internal.height = t.height;
        internal.baseDepth = internal.depth = t.desc.depth || 1;
        internal.is2DArray = t.target === gl.TEXTURE_2D_ARRAY;
        internal.is3D = t.target === gl.TEXTURE_3D;
        internal.isReady = true;
        internal._cachedWrapU = internal._cachedWrapV = internal._cachedWrapR = 0;
        internal._cachedAnisotropicFilteringLevel = 1;
        const texture = new BaseTexture(this.scene, internal);
        texture.wrapU = texture.wrapV = texture.wrapR = 0;
        texture.anisotropicFilteringLevel = 1;
        return texture;
    }

    // The add-on's uniforms and textures into a receiver's uniform buffer, or onto the visibility
    // material's effect (the same calls: updateX on a UniformBuffer, setX on an Effect).
    _bind(target, lightIndex) {
        const ubo = typeof target.updateFloat === "function";
        const float = (name, x) => (ubo ? target.updateFloat(name, x) : target.setFloat(name, x));
        for (const [name, {type, value}] of Object.entries(this._values)) {
            if (value === null) continue;
            if (type === "mat4") (ubo ? target.updateMatrices(name, value) : target.setMatrices(name, value));
            else if (type === "float") float(name, value);
            else if (type === "vec2") (ubo ? target.updateFloat2(name, value[0], value[1]) : target.setFloat2(name, value[0], value[1]));
            else if (type === "vec3") (ubo ? target.updateFloat3 : target.setFloat3).call(target, name, value[0], value[1], value[2]);
            else if (type === "vec4") (ubo ? target.updateFloat4 : target.setFloat4).call(target, name, value[0], value[1], value[2], value[3]);
        }
        for (const name of this._samplerNames) target.setTexture(name, this._textures[name]);
        float(this._names.lightIndex, lightIndex);
        float(this._names.intensity, this.intensity);
    }

    _alive(what) {
        if (this.disposed) fail(`${what} after dispose(): this add-on freed its resources; make another with PenumbraShadows.load()`);
    }

    // Casters, as ShadowGenerator's: the mesh (and, by default, its descendants).
    addShadowCaster(mesh, includeDescendants = true) {
        this._alive("addShadowCaster()");
        this._casters.add(mesh);
        if (includeDescendants) for (const child of mesh.getChildMeshes(false)) this._casters.add(child);
        return this;
    }

    removeShadowCaster(mesh, includeDescendants = true) {
        this._casters.delete(mesh);
        if (includeDescendants) for (const child of mesh.getChildMeshes(false)) this._casters.delete(child);
        return this;
    }

    getShadowCasters() {
        return [...this._casters];
    }

    // Call once per frame before scene.render() (scene.onBeforeRenderObservable): hooks new
    // receivers' materials, re-runs the shadow phase when the light or a caster or receiver changed.
    update() {
        this._alive("update()");
        const casters = [...this._casters].filter((m) => !m.isDisposed() && m.isEnabled() && (m.isVisible || (m.instances || []).length));
        const receivers = this.scene.meshes.filter((m) => m.receiveShadows && m.isEnabled() && m.isVisible);
        for (const mesh of [...casters, ...receivers]) {
            mesh.computeWorldMatrix(true);
            if (mesh.skeleton) mesh.skeleton.prepare(true); // its bones' matrices now, for the CPU skinning below
        }
        for (const mesh of receivers) {
            const material = mesh.sourceMesh ? mesh.sourceMesh.material : mesh.material;
            for (const m of material && material.subMaterials ? material.subMaterials : [material]) this._patch(m);
        }
        this.info.casters = casters.length;
        this.info.receivers = receivers.length;
        const signature = this._signatureOf(casters, receivers);
        const changed = !this._signature || signature.length !== this._signature.length || signature.some((v, i) => v !== this._signature[i]);
        if (!(this.needsUpdate || (this.autoUpdate && changed))) return;
        this._signature = signature;
        this.needsUpdate = false;
        const t0 = performance.now();
        const frame = this._lightFrame(this._bounds(casters, receivers));
        this.info.contained = frame.contained;
        this._frame = frame;
        for (const [name, value] of Object.entries(frame.uniforms)) {
            const ours = this._uniformNames[name];
            if (ours) this._values[ours].value = value;
        }
        this._renderShadow(casters, frame);
        this.info.shadowUpdates++;
        this.info.lastShadowMs = performance.now() - t0;
    }

    _patch(material) {
        if (!material || this._plugins.has(material) || !RECEIVING_MATERIALS.includes(material.getClassName())) return;
        this._plugins.set(material, new PenumbraShadowsPlugin(material, this));
        // the add-ons' textures on this material beside Babylon's own (a few), within the stage's units
        const ours = material.pluginManager._plugins.filter((p) => p instanceof PenumbraShadowsPlugin && !p._addon.disposed)
            .reduce((n, p) => n + p._addon._samplerNames.length, 0);
        const max = this.engine.getCaps().maxTexturesImageUnits;
        if (ours + 4 > max && !this._warnedUnits) {
            this._warnedUnits = true;
            console.warn(`PenumbraShadows: the add-ons on material '${material.name}' sample ${ours} textures, and Babylon needs some of the ` +
                         `${max} texture units too; use emissions with one texture ('…-mipmap-…')`);
        }
    }

    _signatureOf(casters, receivers) {
        const out = [];
        const light = this.light;
        const parent = light.parent ? light.parent.getWorldMatrix().m : [];
        out.push(...parent);
        if (this.kind === "rect") out.push(light.position.x, light.position.y, light.position.z, light.width, light.height);
        else out.push(light.direction.x, light.direction.y, light.direction.z, this.angularDiameter);
        for (const list of [casters, receivers]) {
            out.push(list.length);
            for (const mesh of list) {
                out.push(mesh.uniqueId, ...mesh.getWorldMatrix().m, mesh.getTotalVertices());
                if (mesh.hasThinInstances) out.push(mesh.thinInstanceCount, ...mesh.thinInstanceGetWorldMatrices().flatMap((t) => Array.from(t.m)));
                for (const instance of mesh.instances || []) out.push(instance.uniqueId, ...instance.getWorldMatrix().m);
                if (mesh.skeleton) out.push(...mesh.skeleton.getTransformMatrices(mesh));
                if (mesh.morphTargetManager) for (let i = 0; i < mesh.morphTargetManager.numTargets; ++i) out.push(mesh.morphTargetManager.getTarget(i).influence);
            }
        }
        // what the casters' cuts read: the texture (its readiness, transform, uv set) and cutoff
        if (this.info.alphaTest)
            for (const mesh of casters)
                for (const material of materialsOf(mesh)) {
                    const cut = cutOf(material);
                    if (!cut) { out.push(-1); continue; }
                    const t = cut.texture, m = typeof t.getTextureMatrix === "function" ? t.getTextureMatrix().m : [];
                    out.push(t.uniqueId, cutInternal(t) ? 1 : 0, cut.cutoff, t.coordinatesIndex ?? 0, ...m);
                }
        return out;
    }

    // The scene's bounds: each placement's box (deformed casters: their CPU positions).
    _bounds(casters, receivers) {
        const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
        const add = (p) => { for (let k = 0; k < 3; ++k) { lo[k] = Math.min(lo[k], p[k]); hi[k] = Math.max(hi[k], p[k]); } };
        for (const mesh of [...casters, ...receivers]) {
            for (const [source, world] of placements(mesh)) {
                if (isDeformed(source)) {
                    const p = source.getPositionData(true, true);
                    if (p) for (let i = 0; i < p.length; i += 3) add(transformPoint(world, p[i], p[i + 1], p[i + 2]));
                    continue;
                }
                // (the box without thin instances, which Babylon folds into the mesh's own box)
                const box = (source.getRawBoundingInfo ? source.getRawBoundingInfo() : source.getBoundingInfo()).boundingBox;
                const a = box.minimum, b = box.maximum;
                for (let i = 0; i < 8; ++i) add(transformPoint(world, i & 1 ? b.x : a.x, i & 2 ? b.y : a.y, i & 4 ? b.z : a.z));
            }
        }
        if (!(lo[0] <= hi[0])) return {lo: [-1, -1, -1], hi: [1, 1, 1]};
        return {lo, hi};
    }

    // The light-frame uniforms (light_frame.js) from the Babylon light and the scene's bounds.
    _lightFrame({lo, hi}) {
        const light = this.light, slices = this.config.slices;
        const parent = light.parent ? light.parent.getWorldMatrix() : null;
        const normal = (v) => (parent ? Vector3.TransformNormal(v, parent) : v.clone()).normalize();
        if (this.kind === "sun") return sunFrame({direction: normal(light.direction).asArray(), angularDiameter: this.angularDiameter}, lo, hi, slices);
        // RectAreaLight: width along local x, height along local y, emitting towards local -z;
        // Penumbra's frame wants n = u × v towards the scene: u = x, v = -y.
        const center = parent ? Vector3.TransformCoordinates(light.position, parent) : light.position.clone();
        return rectFrame({center: center.asArray(), u: normal(new Vector3(1, 0, 0)).asArray(), v: normal(new Vector3(0, -1, 0)).asArray(),
                          width: light.width, height: light.height}, lo, hi, slices);
    }

    // The shadow phase on the engine's context, from a default GL state; Babylon's caches wiped after.
    // On WebGPU: submitted on the engine's queue now, before Babylon submits the frame that samples it.
    _renderShadow(casters, frame) {
        if (this.webgpu) return this._renderShadowWebGPU(casters, frame);
        const gl = this.engine._gl, runner = this.runner;
        gl.bindVertexArray(null);
        for (const cap of [gl.SCISSOR_TEST, gl.STENCIL_TEST, gl.POLYGON_OFFSET_FILL, gl.SAMPLE_ALPHA_TO_COVERAGE, gl.RASTERIZER_DISCARD]) gl.disable(cap);
        gl.frontFace(gl.CCW);
        runner.setUniforms(frame.uniforms);
        const drawn = [], sources = new Map();
        for (const mesh of casters) for (const [source, world] of placements(mesh)) {
            const g = this._geometryOf(source);
            if (!g) continue;
            drawn.push([g, world, source]);
            sources.set(source, g);
        }
        const draws = this._casterCuts(sources, (texture) => cutInternal(texture)?._hardwareTexture.underlyingResource ?? null,
                                       (g, source, texture) => this._uvBuffer(g, source, texture));
        runner.runPhase("shadow", (programId) => this._drawCasters(programId, drawn, draws), null);
        for (const g of sources.values()) this._dropUnusedUVs(g);
        gl.bindVertexArray(null);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 4);
        this.engine.wipeCaches(true);
    }

    _renderShadowWebGPU(casters, frame) {
        const runner = this.runner;
        runner.setUniforms(frame.uniforms);
        const drawn = [], sources = new Map();
        for (const mesh of casters) for (const [source, world] of placements(mesh)) {
            const deformed = isDeformed(source);
            const key = deformed ? source : source.geometry;
            const g = key && this._gpuCasters.geometry(key, () => (deformed ? source.getPositionData(true, true) : source.getVerticesData("position")),
                                                       () => source.getIndices(), !deformed);
            if (!g) continue;
            drawn.push([g, world, source]);
            sources.set(source, g);
        }
        // each cut draw's texture (Babylon's GPUTexture) and coordinates (cutCoordinates)
        const draws = this._casterCuts(sources, (texture) => cutInternal(texture)?._hardwareTexture.underlyingResource ?? null,
                                       (g, source, texture) => this._gpuCasters.uvBuffer(g, cutCoordinates(source, texture)));
        const {done} = runner.submitPhase("shadow", this._gpuCasters.drawer(runner, drawn, multiply, draws));
        for (const g of sources.values()) this._gpuCasters.dropUnusedUVs(g);
        done.then(() => (this.info.error = null), (e) => {
            this.info.error = e.message;
            console.error(`PenumbraShadows: the shadow phase failed: ${e.message}`);
        });
    }

    // Each caster's draws (casterDraws), by the mesh whose vertex data they draw (`sources`: mesh →
    // its GPU geometry), with each cut's texture(cut texture) and coordinates uv(g, mesh, texture)
    // where the emission cuts (info.alphaTest). Warns once where casters cut but the emission cannot
    // (alphaTest not false).
    _casterCuts(sources, texture, uv) {
        const cutting = this.info.alphaTest;
        let cuts = 0, uncut = false;
        const out = new Map();
        for (const [source, g] of sources) {
            if (!cutting && this.alphaTest !== false && !uncut) uncut = materialsOf(source).some((m) => cutOf(m) !== null);
            const list = casterDraws(source, g, cutting);
            for (const d of list) {
                if (!d.cut) continue;
                ++cuts;
                d.texture = texture(d.cut.texture);
                d.uv = d.texture ? uv(g, source, d.cut.texture) : null;
            }
            out.set(source, list);
        }
        this.info.cutDraws = cuts;
        if (uncut && !this._warnedCut) {
            this._warnedCut = true;
            console.warn("PenumbraShadows: casters' materials cut (a diffuse or albedo texture with alpha, alpha-tested or blended) but the emission " +
                         "has no alpha test, so they cast solid: load with a shipped emission or a configuration (the add-on picks the cut one), " +
                         "or emit with penumbra-gen --alpha-test; alphaTest: false keeps them solid without this warning");
        }
        return out;
    }

    // Every placement with each "...FromWorld" matrix of the program times its world matrix. A
    // program with the alpha test (parameters whose source is "draw": the alpha texture and cutoff;
    // vertex input penumbra_uv) gets each draw's texture, cutoff and coordinates, or, solid, the
    // runner's white texture and cutoff 0 (LayoutRunner.alphaTestInputs).
    _drawCasters(programId, drawn, draws) {
        const gl = this.engine._gl;
        const program = Object.values(this.runner.programs).find((p) => p.id === programId);
        const matrices = program.desc.parameters.filter((p) => p.type === "mat4" && /FromWorld$/.test(p.name));
        const locations = matrices.map((p) => program.locations[p.name] || gl.getUniformLocation(programId, p.name));
        const alphaTest = this.runner.alphaTestInputs(program);
        for (const [g, world, source] of drawn) {
            matrices.forEach((p, k) => {
                if (locations[k]) gl.uniformMatrix4fv(locations[k], false, multiply(this.runner.uniformValues[p.name], world));
            });
            gl.bindVertexArray(g.vao);
            for (const d of draws.get(source)) {
                if (alphaTest) alphaTest.bind(d);
                if (g.indexType) gl.drawElements(gl.TRIANGLES, d.count, g.indexType, d.first * g.indexBytes);
                else gl.drawArrays(gl.TRIANGLES, d.first, d.count);
            }
        }
        gl.bindVertexArray(null);
        if (alphaTest) alphaTest.end();
    }

    // The buffer of a cut's texture coordinates on GPU geometry g (one per uv set and texture
    // transform: meshes sharing a Geometry may cut through differently placed textures); null where
    // the mesh has no such uv set.
    _uvBuffer(g, source, texture) {
        const c = cutCoordinates(source, texture);
        if (!c) return null;
        g.uvs ||= new Map();
        let entry = g.uvs.get(c.key);
        if (!entry || entry.data !== c.data) { // (new, or the uv set's VertexBuffer was replaced)
            const gl = this.engine._gl;
            if (!entry) g.uvs.set(c.key, (entry = {buffer: gl.createBuffer()}));
            entry.data = c.data;
            gl.bindBuffer(gl.ARRAY_BUFFER, entry.buffer);
            gl.bufferData(gl.ARRAY_BUFFER, c.compute(), gl.STATIC_DRAW);
            gl.bindBuffer(gl.ARRAY_BUFFER, null);
        }
        entry.used = true;
        return entry.buffer;
    }

    // After a shadow phase: the coordinates no draw used (an old transform) go.
    _dropUnusedUVs(g) {
        if (!g.uvs) return;
        const gl = this.engine._gl;
        for (const [key, entry] of g.uvs) {
            if (!entry.used) { gl.deleteBuffer(entry.buffer); g.uvs.delete(key); }
            else entry.used = false;
        }
    }

    // Our vertex array for a mesh's vertex data (positions as attribute 0, its indices), uploaded
    // once per Geometry; skinned and morphed meshes' positions from the CPU at every shadow update.
    _geometryOf(mesh) {
        const deformed = isDeformed(mesh);
        const key = deformed ? mesh : mesh.geometry;
        if (!key) return null;
        let g = this._geometries.get(key);
        if (g && !deformed) return g;
        const positions = deformed ? mesh.getPositionData(true, true) : mesh.getVerticesData("position");
        if (!positions) return null;
        const gl = this.engine._gl;
        if (!g) {
            g = {vao: gl.createVertexArray(), position: gl.createBuffer(), index: null};
            this._geometries.set(key, g);
        }
        gl.bindVertexArray(g.vao);
        gl.bindBuffer(gl.ARRAY_BUFFER, g.position);
        gl.bufferData(gl.ARRAY_BUFFER, Float32Array.from(positions), deformed ? gl.DYNAMIC_DRAW : gl.STATIC_DRAW);
        gl.enableVertexAttribArray(0);
        gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 0, 0);
        const indices = mesh.getIndices();
        g.indexType = 0;
        g.indexed = false;
        g.count = positions.length / 3;
        if (indices && indices.length) {
            const big = positions.length / 3 > 65535;
            if (!g.index) g.index = gl.createBuffer();
            gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, g.index);
            gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, big ? Uint32Array.from(indices) : Uint16Array.from(indices), gl.STATIC_DRAW);
            g.indexType = big ? gl.UNSIGNED_INT : gl.UNSIGNED_SHORT;
            g.indexBytes = big ? 4 : 2;
            g.indexed = true;
            g.count = indices.length;
        }
        gl.bindVertexArray(null);
        gl.bindBuffer(gl.ARRAY_BUFFER, null);
        return g;
    }

    // The add-on's visibility (0 shadowed … 1 lit) as `camera` sees the receivers, for debugging and
    // tests: a Promise of a Float32Array of width × height, bottom row first; 1 where no receiver is.
    async renderVisibility(camera, width, height) {
        this._alive("renderVisibility()");
        if (!this._visibilityMaterial) this._visibilityMaterial = this._makeVisibilityMaterial();
        const receivers = this.scene.meshes.filter((m) => m.receiveShadows && m.isEnabled() && m.isVisible);
        const target = new RenderTargetTexture("penumbraVisibility", {width, height}, this.scene,
                                               {generateMipMaps: false, type: 1 /* Constants.TEXTURETYPE_FLOAT */});
        try {
            target.activeCamera = camera;
            target.clearColor = new Color4(1, 1, 1, 1);
            target.renderList = receivers;
            target.setMaterialForRendering(receivers, this._visibilityMaterial);
            await new Promise((resolve) => {
                const check = () => (this._visibilityMaterial.isReady(receivers[0]) && target.isReadyForRendering() ? resolve() : setTimeout(check, 10));
                check();
            });
            target.render();
            const rgba = await target.readPixels();
            const out = new Float32Array(width * height);
            for (let i = 0; i < out.length; ++i) out[i] = rgba[4 * i]; // (bottom row first on both engines: Babylon's readPixels)
            return out;
        } finally {
            target.dispose();
        }
    }

    _makeVisibilityMaterial() {
        const n = this._names;
        const wgslUniforms = () => [...Object.entries(this._values).map(([name, {type}]) => [name, type]), [n.lightIndex, "float"], [n.intensity, "float"]]
            .map(([name, type]) => `uniform ${name}: ${this._gpu.WGSL_TYPES[type]};`).join("\n");
        const material = new ShaderMaterial(`penumbra${this._serial}Visibility`, this.scene, this.webgpu
            ? this._gpu.visibilityShadersWGSL(this._visibilityDefinitions, wgslUniforms(), n) : {
            vertexSource: `precision highp float;
attribute vec3 position;
attribute vec3 normal;
#include<instancesDeclaration>
uniform mat4 viewProjection;
varying vec3 vPositionW;
varying vec3 vNormalW;
void main(void) {
#include<instancesVertex>
	vec4 p = finalWorld * vec4(position, 1.0);
	vPositionW = p.xyz;
	vNormalW = mat3(finalWorld) * normal;
	gl_Position = viewProjection * p;
}`,
            fragmentSource: `precision highp float;
${this._visibilityDefinitions}
uniform vec3 penumbraEye;
varying vec3 vPositionW;
varying vec3 vNormalW;
void main(void) {
	float v = ${this._names.lightIndex} >= 0.0 ? ${this._names.shadow}(vNormalW, vPositionW, penumbraEye) : 1.0;
	gl_FragColor = vec4(v, v, v, 1.0);
}`,
        }, {attributes: ["position", "normal"], uniforms: ["world", "viewProjection", "penumbraEye", ...this._valueNames],
            samplers: this._samplerNames, shaderLanguage: this.webgpu ? 1 /* ShaderLanguage.WGSL */ : 0});
        material.backFaceCulling = false;
        material.onBindObservable.add(() => {
            const effect = material.getEffect();
            this._bind(effect, this.enabled ? 0 : -1);
            const eye = this.scene.activeCamera.globalPosition;
            effect.setFloat3("penumbraEye", eye.x, eye.y, eye.z);
        });
        return material;
    }

    // Frees every GPU resource of the add-on; its plugins inject nothing any more (the materials
    // compile again without it; other add-ons' shadows on them stay). Afterwards update() and
    // renderVisibility() throw; a second dispose() does nothing.
    dispose() {
        if (this.disposed) return;
        this.disposed = true;
        const gl = this.engine._gl;
        for (const g of this._geometries.values()) {
            gl.deleteVertexArray(g.vao);
            gl.deleteBuffer(g.position);
            if (g.index) gl.deleteBuffer(g.index);
            for (const entry of (g.uvs || new Map()).values()) gl.deleteBuffer(entry.buffer);
        }
        this._geometries.clear();
        if (this._gpuCasters) this._gpuCasters.dispose();
        for (const plugin of this._plugins.values()) plugin.markAllDefinesAsDirty();
        this._plugins.clear();
        if (this._visibilityMaterial) this._visibilityMaterial.dispose();
        for (const texture of Object.values(this._textures)) {
            texture.getInternalTexture()._hardwareTexture = null; // the runner deletes its textures
            texture.dispose();
        }
        this._textures = {};
        this.runner.dispose();
        this.runner = null;
        this._casters.clear();
        if (!this.webgpu) this.engine.wipeCaches(true);
    }
}
