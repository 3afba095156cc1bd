// penumbra_shadows_webgpu.js — the add-on on three.js's WebGPURenderer (three/webgpu, TSL node
// materials). Users do not import it: PenumbraShadows.load(renderer, scene, light) loads it when
// `renderer` is a WebGPURenderer and returns a PenumbraShadowsWebGPU, used as on WebGL2:
//
//   const renderer = new WebGPURenderer();  await renderer.init();
//   const shadows = await PenumbraShadows.load(renderer, scene, rectLight);
//   // each frame:  shadows.update();  renderer.render(scene, camera);
//
// How it is built, and why:
//   - the wgsl emission (penumbra-gen --target wgsl: WGSL + layout.json) runs on the renderer's
//     own GPUDevice (renderer.backend.device) through the WebGPU layout runner
//     (penumbra_webgpu_runner.js, the one the playground uses), which follows layout.json. Its
//     shadow phase is encoded and submitted by update() on the device's queue, so three's frame,
//     submitted later on the same queue, samples finished occlusion textures (no fences);
//   - the textures the runner made are handed to TSL as three ExternalTextures wrapping their
//     GPUTexture (three r180+ binds an ExternalTexture's sourceTexture as is on WebGPU). The other
//     way (three allocating render targets and the runner drawing into renderer.backend.get(t).texture)
//     would depend on three's internal texture data and on three picking the layout's formats and
//     usages; wrapping keeps layout.json the one description of every texture;
//   - the visibility function (penumbra_visibility.wgsl) enters the materials through wgslFn: its
//     module-scope bindings cannot (three numbers every binding of a material itself), so the
//     snippet is rewritten once (wgslModule below): its uniform block becomes function parameters
//     copied into the snippet's own private variables, and its textures and samplers become
//     parameters threaded through the functions that read them; TSL's texture() and sampler()
//     nodes fill those parameters, so three declares and binds them;
//   - one light's term only: each receiver's lighting model (setupLightingModel, called by
//     NodeMaterial.setupLighting for MeshStandardNodeMaterial / MeshPhysicalNodeMaterial and for
//     the plain MeshStandard/Physical materials WebGPURenderer converts, whose own properties it
//     copies) is wrapped so that direct() (the sun) or directRectArea() (the rectangle) gets
//     lightColor × visibility when lightNode.light is this add-on's light, as three's own shadows
//     scale a light's colour; every other light, and the light on other materials, is untouched.
//     (three's light.shadow.shadowNode hook needs shadowMap.enabled and a LightShadow, which
//     RectAreaLight has not; a light's colorNode would shadow every material, receivers or not.)
//   - cut-out casters (an emission with the alpha test, which load() picks when the casters'
//     materials cut: penumbra_scene.js's cutOf): each draw's bind group gets its map's GPUTexture
//     (three's own, uploaded by renderer.initTexture; a texture read, not written, so three's
//     internal data is only looked up), its cutoff and its texture coordinates (a vertex buffer).
import {ClampToEdgeWrapping, DoubleSide, ExternalTexture, FloatType, LinearFilter, LinearMipmapLinearFilter, LinearMipmapNearestFilter,
        Matrix4, MeshBasicNodeMaterial, MirroredRepeatWrapping, NearestFilter, NearestMipmapLinearFilter, NearestMipmapNearestFilter,
        NoBlending, RepeatWrapping, RenderTarget, Vector2, Vector3, Vector4} from "three/webgpu";
import {cameraPosition, float, normalWorld, positionWorld, renderGroup, sampler, texture, uniform, vec4, wgsl, wgslFn} from "three/tsl";
import {WebGPULayoutRunner} from "./penumbra_webgpu_runner.js";
import {ShadowsBase, casterVertices, cutCoordinates, emissionFollowingCuts, fail, forEachPlacement, isDeformed, kindOf, loadEmissionFiles,
        requestedEmission, positionVersion, snippetParameters} from "./penumbra_scene.js";

// Materials shadowed by add-ons: material → {previous: its own hooks, addons}; one wrapper per
// material applies every add-on's light (several add-ons, one per light, share a material).
const shadowedMaterials = new WeakMap();

export class PenumbraShadowsWebGPU extends ShadowsBase {
    static async load(renderer, scene, light, options = {}) {
        if (!renderer || !renderer.isWebGPURenderer) fail("the first argument must be a WebGPURenderer (three/webgpu)");
        // (r187's init() returns its first promise again; r180's throws once initialized, and has only
        // the private _initialized to tell)
        if (!(renderer.initialized ?? renderer._initialized)) await renderer.init();
        if (!renderer.backend.isWebGPUBackend || !renderer.backend.device)
            fail("this WebGPURenderer runs its WebGL2 fallback backend (no WebGPU in this browser, or forceWebGL), " +
                 "where the add-on has no GPUDevice to run the wgsl emission on; use a THREE.WebGLRenderer there");
        const kind = kindOf(light);
        const emission = emissionFollowingCuts(requestedEmission(options, kind), options.alphaTest, scene);
        const runner = await loadRunner(renderer.backend.device, emission, kind, options.wasm ?? null);
        return new PenumbraShadowsWebGPU(renderer, scene, light, {...options, runner});
    }

    constructor(renderer, scene, light, options = {}) {
        if (!renderer || !renderer.isWebGPURenderer) fail("the first argument must be a WebGPURenderer (three/webgpu)");
        super(renderer, scene, light, options);
        if (!options.runner) fail("no emission: use `await PenumbraShadows.load(renderer, scene, light, options)`");
        this.device = renderer.backend.device;
        this._zeros = null;           // a vertex buffer of zeros for vertex inputs we have no data for
        this._intensity = uniform(this.intensity).setGroup(renderGroup);
        this._visibilityTarget = null;
        this._visibilityMaterial = null;
        this.info.error = null;       // WebGPU's validation message of the last shadow phase that failed
        this._setRunner(options.runner);
    }

    // The runner of the current emission: its textures as ExternalTextures, its snippet as a wgslFn,
    // the snippet's uniforms as TSL uniforms; the materials rebuild.
    _setRunner(runner) {
        const layout = runner.layout;
        this._checkLight(layout);
        this.runner = runner;
        this.config = layout.config;
        const snippet = runner.sources["penumbra_visibility.wgsl"];
        const module = wgslModule(this._rename(snippet));
        // (in the render group, updated once a frame, as three's own light uniforms: the values are
        // the light's, the same for every receiver)
        const values = {float: () => uniform(0), int: () => uniform(0, "int"), vec2: () => uniform(new Vector2()),
                        vec3: () => uniform(new Vector3()), vec4: () => uniform(new Vector4()), mat4: () => uniform(new Matrix4())};
        this._uniforms = {}; // the emission's name → {node, type}
        this._textures = [];
        const args = {};
        for (const p of snippetParameters(layout)) {
            const ours = this._rename(p.name);
            if (p.texture_type !== undefined) {
                const t = module.textures.find((x) => x.name === ours);
                if (!t) fail(`penumbra_visibility.wgsl has no texture '${p.name}' that layout.json lists`);
                if (t.type !== "texture_2d<f32>")
                    fail(`the emission's ${p.name} is a ${t.type}; on WebGPURenderer the add-on samples texture_2d<f32> only (packing 'atlas'; got '${layout.config.packing}')`);
                const external = this._externalTexture(runner, p);
                this._textures.push(external);
                args[t.name] = texture(external); // (passed whole: the wgslFn parameter gets the texture's name)
                if (t.sampler) args[t.sampler] = sampler(args[t.name]);
            } else {
                const make = values[p.type] || fail(`layout.json: uniform ${p.name} of type ${p.type}, which the add-on cannot pass`);
                const node = make().setGroup(renderGroup);
                this._uniforms[p.name] = {node, type: p.type};
                args[`${ours}_value`] = node;
            }
        }
        for (const t of module.textures) if (!(t.name in args)) fail(`penumbra_visibility.wgsl samples '${t.name}', which layout.json does not list`);
        const tangentClip = layout.config.tangent_clip !== false;
        const shadow = wgslFn(module.wrapper(this._rename("penumbraShadow"), tangentClip), [wgsl(module.code)]);
        // the world normal three lights with (normal maps included), as the WebGL2 add-on's geometryNormal
        this._visibility = shadow({worldPos: positionWorld, worldNormal: normalWorld, eye: cameraPosition,
                                   intensity: this._intensity, ...args});
        this._cacheKey = `penumbra${this._serial}:${this.kind}:${JSON.stringify(layout.config)}:${PenumbraShadowsWebGPU._generation = (PenumbraShadowsWebGPU._generation || 0) + 1}`;
        this._warnTextures();
        this.needsUpdate = true;
        for (const material of this._materials) material.needsUpdate = true;
    }

    // A texture of the runner (the parameter's `texture`) as a three ExternalTexture: same
    // GPUTexture, sampled as layout.json says (three makes the sampler from these fields).
    _externalTexture(runner, p) {
        const t = runner.texture(p.texture ?? p.name);
        // (three declares an ExternalTexture's binding as filterable float, which 32-bit float formats are not)
        if (t.format.endsWith("32float")) fail(`the emission's ${t.desc.name} is ${t.format}, which WebGPU cannot filter; use level_format rgba8 or rgba16f`);
        const d = p.sampling ?? t.desc;
        const texture = new ExternalTexture(t.texture);
        // (a mip chain's LINEAR_MIPMAP_LINEAR: the mipmap filter interpolates between the levels it reads)
        const filter = (f) => ({LINEAR: LinearFilter, NEAREST: NearestFilter, LINEAR_MIPMAP_LINEAR: LinearMipmapLinearFilter,
                                LINEAR_MIPMAP_NEAREST: LinearMipmapNearestFilter, NEAREST_MIPMAP_NEAREST: NearestMipmapNearestFilter,
                                NEAREST_MIPMAP_LINEAR: NearestMipmapLinearFilter})[f] ?? NearestFilter;
        const wrap = {CLAMP_TO_EDGE: ClampToEdgeWrapping, REPEAT: RepeatWrapping, MIRRORED_REPEAT: MirroredRepeatWrapping}[d.wrap] ?? ClampToEdgeWrapping;
        texture.minFilter = filter(d.min_filter);
        texture.magFilter = filter(d.mag_filter);
        texture.wrapS = texture.wrapT = wrap;
        texture.generateMipmaps = false;
        texture.flipY = false;
        return texture;
    }

    // Every add-on's textures are sampled in the receivers' fragment stage, which WebGPU limits to
    // maxSampledTexturesPerShaderStage (16 unless the renderer asked for more: requiredLimits), and
    // three's lit material needs some (the RectAreaLight's LTC textures, the maps).
    _warnTextures(material = null) {
        const shared = material && shadowedMaterials.get(material);
        const textures = shared ? shared.addons.reduce((n, a) => n + a._textures.length, 0) : this._textures.length;
        const limit = this.device.limits.maxSampledTexturesPerShaderStage;
        if (textures + 4 > limit && !this._warnedTextures) {
            this._warnedTextures = true;
            console.warn(`PenumbraShadows: ${shared ? `a material shadowed by ${shared.addons.length} add-ons` : "the emission"} samples ${textures} textures ` +
                         `and a WebGPU shader stage has ${limit}, of which three needs some: use emissions with fewer levels (a lower resolution), ` +
                         "or a WebGPURenderer({requiredLimits: {maxSampledTexturesPerShaderStage: …}}) where the adapter allows more");
        }
    }

    async setEmission(emission) {
        this._alive("setEmission()");
        const runner = await loadRunner(this.device, emissionFollowingCuts(emission, this.alphaTest, this.scene), this.kind, this.wasm);
        const old = this.runner, textures = this._textures;
        this._setRunner(runner);
        for (const t of textures) t.dispose();
        if (old) old.dispose();
    }

    setSize(width, height) {
        if (this._visibilityTarget) this._visibilityTarget.setSize(width, height);
    }

    _updateUniforms() {
        this._intensity.value = this.enabled ? this.intensity : 0;
    }

    _renderShadow(casters, receivers, frame) {
        for (const [name, {node}] of Object.entries(this._uniforms)) {
            const value = frame.uniforms[name];
            if (value === undefined) continue;
            if (typeof node.value === "object") node.value.fromArray(value); // Vector2/3/4, Matrix4 (column-major, as ours)
            else node.value = value;
        }
        const runner = this.runner;
        runner.setUniforms(frame.uniforms);
        const drawn = casters.map((object) => this._geometryOf(object));
        const draws = this._casterCuts(casters, drawn);
        // each cut draw's map (three's GPUTexture) and texture coordinates (cutCoordinates)
        if (this.info.alphaTest)
            for (const [i, list] of draws.entries())
                for (const d of list) {
                    if (!d.cut) continue;
                    d.texture = this._mapTexture(d.cut.map);
                    d.uv = this._uvBuffer(drawn[i], casters[i].geometry, d.cut.map);
                }
        // zeros for vertex inputs other than the position (made before encoding: a draw must not see it replaced)
        const zeros = runner.layout.programs.some((p) => (p.vertex_inputs || []).some((v) => v.name !== "penumbra_position"))
            ? this._zeroBuffer(drawn.reduce((n, g) => Math.max(n, g.vertices), 0)) : null;
        const {done} = runner.submitPhase("shadow", (render, program, setDrawUniforms) =>
            this._drawCasters(render, program, setDrawUniforms, casters, drawn, draws, zeros));
        for (const g of drawn) this._dropUnusedUVs(g);
        done.then(() => (this.info.error = null), (e) => {
            this.info.error = e.message;
            console.error(`PenumbraShadows: the shadow phase failed: ${e.message}`);
        });
    }

    // Each placement of each caster, with each "...FromWorld" matrix of the program times its model
    // (and instance) matrix in a uniform buffer of its own, so that the vertices stay in object space.
    // A program with the alpha test (parameters whose source is "draw": the alpha texture and
    // cutoff; vertex input penumbra_uv) gets each draw's map, cutoff and coordinates, or the
    // runner's white texture, cutoff 0 and zeros.
    _drawCasters(render, program, setDrawUniforms, casters, drawn, draws, zeros) {
        const matrices = program.parameters.filter((p) => p.type === "mat4" && /FromWorld$/.test(p.name));
        const base = matrices.map((p) => new Matrix4().fromArray(this.runner.uniformValues[p.name]));
        const alphaTexture = program.parameters.find((p) => p.source === "draw" && p.texture_type !== undefined);
        const cutoff = program.parameters.find((p) => p.source === "draw" && p.block !== undefined);
        const m = new Matrix4();
        let slot = 0;
        casters.forEach((object, i) => {
            const g = drawn[i];
            forEachPlacement(object, (matrix) => {
                const values = {};
                matrices.forEach((p, k) => (values[p.name] = m.multiplyMatrices(base[k], matrix).toArray()));
                for (const d of draws[i]) {
                    const cut = alphaTexture && d.cut && d.texture && d.uv ? d : null; // (no texture or coordinates yet: solid)
                    if (cutoff) values[cutoff.name] = cut ? cut.cut.cutoff : 0;
                    setDrawUniforms(values, slot++, cut ? {[alphaTexture.name]: cut.texture} : null);
                    (program.vertex_inputs || []).forEach((v, location) =>
                        render.setVertexBuffer(location, v.name === "penumbra_position" ? g.position : v.name === "penumbra_uv" && cut ? cut.uv : zeros));
                    if (g.index) {
                        render.setIndexBuffer(g.index, g.indexFormat);
                        render.drawIndexed(d.count, 1, d.first);
                    } else {
                        render.draw(d.count, 1, d.first);
                    }
                }
            });
        });
    }

    // A map's GPUTexture: three's own, uploaded by initTexture if it was not yet; null while its
    // image is not there (version 0) or for a texture that is no 2D one: that draw is solid until
    // the map's version changes (which re-runs the shadow phase: _signatureOf).
    _mapTexture(map) {
        if (!map.isTexture || map.isCubeTexture || map.isData3DTexture || map.isDataArrayTexture || map.isRenderTargetTexture) return null;
        if (map.version === 0) return null;
        this.renderer.initTexture(map);
        const texture = this.renderer.backend.get(map).texture;
        return texture && texture.dimension === "2d" && texture.depthOrArrayLayers === 1 ? texture : null;
    }

    // The vertex buffer of a cut's texture coordinates on GPU geometry g (one per channel and map
    // transform, as on WebGL2); null where the geometry has none.
    _uvBuffer(g, geometry, map) {
        const c = cutCoordinates(geometry, map);
        if (!c) return null;
        g.uvs ||= new Map();
        let entry = g.uvs.get(c.key);
        if (!entry) {
            const uvs = c.compute();
            entry = {buffer: this.device.createBuffer({label: "penumbra caster uv", size: Math.max(uvs.byteLength, 4),
                                                       usage: GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_DST})};
            this.device.queue.writeBuffer(entry.buffer, 0, uvs);
            g.uvs.set(c.key, entry);
        }
        entry.used = true;
        return entry.buffer;
    }

    // After a shadow phase is submitted: the coordinates no draw used go (WebGPU keeps a destroyed
    // buffer's memory until the work submitted with it is done).
    _dropUnusedUVs(g) {
        if (!g.uvs) return;
        for (const [key, entry] of g.uvs) {
            if (!entry.used) { entry.buffer.destroy(); g.uvs.delete(key); }
            else entry.used = false;
        }
    }

    _zeroBuffer(vertices) {
        const bytes = Math.max(16 * vertices, 16);
        if (!this._zeros || this._zeros.size < bytes)  {
            if (this._zeros) this._zeros.destroy();
            this._zeros = this.device.createBuffer({label: "penumbra zeros", size: bytes, usage: GPUBufferUsage.VERTEX});
        }
        return this._zeros;
    }

    // GPU buffers of a caster's vertices (casterVertices), made once per geometry and again when
    // its position attribute changes; skinned and morphed meshes' at every shadow update.
    _geometryOf(object) {
        const geometry = object.geometry;
        const deformed = isDeformed(object);
        const key = deformed ? object : geometry;
        const version = positionVersion(geometry);
        let g = this._geometries.get(key);
        if (g && !deformed && g.version === version) return g;
        if (!g) {
            g = {position: null, index: null, version: -1};
            this._geometries.set(key, g);
            if (!deformed) geometry.addEventListener("dispose", () => this._dropGeometry(key));
        }
        const v = casterVertices(object);
        const upload = (old, data, usage) => {
            const size = Math.ceil(data.byteLength / 4) * 4; // writeBuffer copies whole 4-byte words
            const buffer = old && old.size === Math.max(size, 4) ? old
                : (old && old.destroy(), this.device.createBuffer({label: "penumbra caster", size: Math.max(size, 4), usage: usage | GPUBufferUsage.COPY_DST}));
            const padded = new Uint8Array(size);
            padded.set(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
            this.device.queue.writeBuffer(buffer, 0, padded);
            return buffer;
        };
        g.position = upload(g.position, v.positions, GPUBufferUsage.VERTEX);
        if (v.index) {
            g.index = upload(g.index, v.index, GPUBufferUsage.INDEX);
            g.indexFormat = v.index instanceof Uint32Array ? "uint32" : "uint16";
        } else if (g.index) {
            g.index.destroy();
            g.index = null;
        }
        g.first = v.first;
        g.count = v.count;
        g.vertices = v.positions.length / 3;
        g.version = version;
        return g;
    }

    _dropGeometry(key) {
        const g = this._geometries.get(key);
        if (!g) return;
        g.position.destroy();
        if (g.index) g.index.destroy();
        for (const entry of (g.uvs || new Map()).values()) entry.buffer.destroy();
        this._geometries.delete(key);
    }

    // Wraps a receiver's lighting model (see the top of this file); other materials are left alone.
    _patch(material) {
        if (this._materials.has(material) || !material || !(material.isMeshStandardMaterial || material.isMeshStandardNodeMaterial)) return;
        let shared = shadowedMaterials.get(material);
        if (!shared) {
            const own = (name) => (Object.hasOwn(material, name) ? {value: material[name]} : null);
            shared = {previous: {setupLightingModel: own("setupLightingModel"), customProgramCacheKey: own("customProgramCacheKey")}, addons: []};
            shadowedMaterials.set(material, shared);
            const previousModel = shared.previous.setupLightingModel?.value;
            const previousKey = shared.previous.customProgramCacheKey?.value;
            // (`this`: the node material three builds, the material itself or the node material
            // a plain one was converted to; its class gives the lighting model)
            material.setupLightingModel = function (builder) {
                const model = (previousModel || Object.getPrototypeOf(this).setupLightingModel).call(this, builder);
                if (model) for (const a of shared.addons) a._wrapLightingModel(model);
                return model;
            };
            material.customProgramCacheKey = function () {
                return (previousKey || Object.getPrototypeOf(this).customProgramCacheKey).call(this) + shared.addons.map((a) => a._cacheKey).join("|");
            };
        }
        shared.addons.push(this);
        this._materials.add(material);
        this._warnTextures(material);
        material.needsUpdate = true;
    }

    _wrapLightingModel(model) {
        const light = this.light, visibility = this._visibility;
        const method = this.kind === "rect" ? "directRectArea" : "direct";
        const original = model[method];
        model[method] = function (data, builder) {
            const ours = data.lightNode && data.lightNode.light === light;
            return original.call(this, ours ? {...data, lightColor: data.lightColor.mul(visibility)} : data, builder);
        };
    }

    _unpatch(material) {
        const shared = shadowedMaterials.get(material);
        if (shared) {
            shared.addons = shared.addons.filter((a) => a !== this);
            if (shared.addons.length === 0) {
                for (const [name, was] of Object.entries(shared.previous)) {
                    if (was) material[name] = was.value;
                    else delete material[name];
                }
                shadowedMaterials.delete(material);
            }
        }
        material.needsUpdate = true;
    }

    // The add-on's visibility (0 shadowed … 1 lit) as the camera sees the receivers, for debugging
    // and tests: a Promise of a Float32Array of width × height, bottom row first (as on WebGL2);
    // 1 where no receiver is. Asynchronous: WebGPU reads textures back asynchronously.
    async renderVisibility(camera, width, height) {
        this._alive("renderVisibility()");
        const target = this._renderReceivers(camera, width, height, (w, h) => new RenderTarget(w, h, {type: FloatType, depthBuffer: true}), () => {
            const material = new MeshBasicNodeMaterial({side: DoubleSide, blending: NoBlending});
            material.colorNode = vec4(this._visibility, this._visibility, this._visibility, float(1));
            return material;
        });
        const rgba = await this.renderer.readRenderTargetPixelsAsync(target, 0, 0, width, height);
        // WebGPU's rows: top row first; ours (WebGL2's): bottom row first
        const out = new Float32Array(width * height);
        for (let y = 0; y < height; ++y)
            for (let x = 0; x < width; ++x) out[(height - 1 - y) * width + x] = rgba[4 * (y * width + x)];
        return out;
    }

    // dispose(): the ExternalTextures (not their GPUTextures: the runner destroys those), our buffer of zeros
    _disposeResources() {
        for (const t of this._textures) t.dispose();
        this._textures = [];
        if (this._zeros) this._zeros.destroy();
    }
}

async function loadRunner(device, emission, kind, wasm) {
    const files = await loadEmissionFiles(emission, kind, wasm, "wgsl");
    const runner = await WebGPULayoutRunner.fromEmission(device, files);
    runner.sources = files.files;
    return runner;
}


// ---- the snippet, rewritten for wgslFn --------------------------------------------------------

// penumbra_visibility.wgsl (already renamed penumbra<N>…) as module code without bindings:
// {code, textures: [{name, type, sampler}], wrapper(name, tangentClip)}. The uniform block and the
// function that loads it go; its members stay private variables, which the wrapper sets from its
// parameters (<member>_value); every function that samples a texture (or calls one that does)
// gets the textures and samplers as leading parameters, and every call of it the arguments.
export function wgslModule(snippet) {
    let code = snippet.replace(/\/\*[\s\S]*?\*\//g, "").replace(/\/\/[^\n]*/g, "");
    const block = /@group\(\s*\d+\s*\)\s*@binding\(\s*\d+\s*\)\s*var<uniform>\s*(\w+)\s*:\s*(\w+)\s*;/.exec(code);
    const privates = [...code.matchAll(/var<private>\s+(\w+)\s*:\s*([^;]+);/g)].map((m) => ({name: m[1], type: m[2].trim()}));
    const handles = [...code.matchAll(/@group\(\s*\d+\s*\)\s*@binding\(\s*\d+\s*\)\s*var\s+(\w+)\s*:\s*([^;]+);/g)]
        .map((m) => ({name: m[1], type: m[2].trim()}));
    code = code.replace(/@group\(\s*\d+\s*\)\s*@binding\(\s*\d+\s*\)\s*var(<uniform>)?\s+\w+\s*:\s*[^;]+;/g, "");
    if (block) code = code.replace(new RegExp(`struct\\s+${block[2]}\\s*\\{[^}]*\\}\\s*;?`), "");
    const textures = handles.filter((h) => h.type.startsWith("texture")).map((h) => ({
        ...h, sampler: handles.some((s) => s.name === `${h.name}_sampler`) ? `${h.name}_sampler` : null}));
    const handleNames = handles.map((h) => h.name);
    // the top-level functions: name, parameter list span, body span
    const functions = [];
    for (const m of code.matchAll(/\bfn\s+(\w+)\s*\(/g)) {
        let i = m.index + m[0].length, depth = 1;
        while (depth > 0) depth += code[i] === "(" ? 1 : code[i] === ")" ? -1 : 0, ++i;
        const paramsEnd = i - 1;
        const open = code.indexOf("{", i);
        let j = open + 1;
        depth = 1;
        while (depth > 0 && j < code.length) depth += code[j] === "{" ? 1 : code[j] === "}" ? -1 : 0, ++j;
        functions.push({name: m[1], start: m.index, paramsStart: m.index + m[0].length, paramsEnd, bodyStart: open, end: j});
    }
    const body = (f) => code.slice(f.bodyStart, f.end);
    const mentions = (text, name) => new RegExp(`\\b${name}\\b`).test(text);
    // the loader of the uniform block goes (the wrapper sets the private variables)
    const loaders = block ? functions.filter((f) => mentions(body(f), block[1])) : [];
    // which functions need the handles: those naming one, then their callers, to a fixed point
    const needs = new Set(functions.filter((f) => handleNames.some((h) => mentions(body(f), h))).map((f) => f.name));
    for (let grew = true; grew;) {
        grew = false;
        for (const f of functions)
            if (!needs.has(f.name) && [...needs].some((n) => new RegExp(`\\b${n}\\s*\\(`).test(body(f)))) needs.add(f.name), (grew = true);
    }
    const handleParams = handles.map((h) => `${h.name}: ${h.type}`).join(", ");
    const handleArgs = handleNames.join(", ");
    const withHandles = (text) => text.replace(/\b(\w+)\s*\(\s*(\)?)/g, (all, name, close) =>
        (needs.has(name) ? `${name}(${handleArgs}${close ? ")" : ", "}` : all));
    let out = "";
    let at = 0;
    for (const f of functions) {
        out += code.slice(at, f.start);
        at = f.end;
        if (loaders.includes(f)) continue;
        const params = code.slice(f.paramsStart, f.paramsEnd).trim();
        const signature = needs.has(f.name) ? `${handleParams}${params ? ", " + params : ""}` : params;
        out += `fn ${f.name}(${signature})${code.slice(f.paramsEnd + 1, f.bodyStart)}${withHandles(body(f))}`;
    }
    out += code.slice(at);
    out = out.replace(/\n\s*\n\s*\n+/g, "\n\n").trim() + "\n";
    const members = privates; // the uniform block's members, as the snippet's private variables
    // penumbra<N>VisibilityWithNormal (the tangent clip) or penumbra<N>Visibility
    const entry = (tangentClip) => (tangentClip && functions.find((f) => /^penumbra\d*VisibilityWithNormal$/.test(f.name)))
        || functions.find((f) => /^penumbra\d*Visibility$/.test(f.name));
    return {
        code: out,
        textures,
        // fn NAME(worldPos, worldNormal, eye, intensity, <member>_value..., handles...) -> f32: the
        // visibility of the side of the surface the camera sees, mixed towards 1 by (1 - intensity)
        wrapper(name, tangentClip) {
            const f = entry(tangentClip);
            if (!f) fail("penumbra_visibility.wgsl has no penumbraVisibility function");
            const withNormal = /WithNormal$/.test(f.name);
            return `fn ${name}(worldPos: vec3f, worldNormal: vec3f, eye: vec3f, intensity: f32, ` +
                members.map((p) => `${p.name}_value: ${p.type}`).concat(handles.map((h) => `${h.name}: ${h.type}`)).join(", ") + `) -> f32 {
    if (intensity <= 0.0) { return 1.0; }
${members.map((p) => `    ${p.name} = ${p.name}_value;`).join("\n")}
    var n: vec3f = normalize(worldNormal);
    if (dot(n, eye - worldPos) < 0.0) { n = -n; }
    let v: f32 = ${f.name}(${handleArgs ? handleArgs + ", " : ""}worldPos${withNormal ? ", n" : ""});
    return mix(1.0, v, intensity);
}
`;
        },
    };
}
