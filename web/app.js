// app.js — the browser playground: the emitter in WebAssembly (penumbra_emitter.js) re-emits on
// every change of the panel (config_panel.js: every field of `penumbra-gen --config`), the page
// runs the essl300 emission by its layout.json (penumbra_runner.js) over the scene, and shows the
// shaded scene, the visibility, or its difference from the bundle's desktop run; a split view runs
// a second configuration on the right half. Scenes: the built-in ones of scenes/index.json (small
// bundles written at publish time by scripts/publish_web.sh) or ?bundle=DIR/ (penumbra-export-bundle
// --target essl300). Light: sliders, or drag with the shift key; camera: drag to orbit.
//
// The renderer switch runs WebGL2 (the essl300 emission, penumbra_runner.js) or WebGPU (the wgsl
// emission of the same configuration, three/penumbra_webgpu_runner.js; for the techniques that have WGSL): WebGPU
// computes the visibility, the page reads it back and shows it through the same WebGL2 composite.
//
// URL parameters: ?bundle=DIR/, ?scene=NAME (a built-in scene), ?wasm=URL, ?backend=webgl2|webgpu.
// window.penumbra (for automation): ready (a promise), readVisibility(side), setLight(), info(),
// setBackend(name), settled() (WebGPU renders asynchronously: await it before reading), ...
// The emitter, the layout runner and the light frame are the three.js add-on's (three/, the npm
// package penumbra-three): one copy, which the playground imports from there.
import {loadEmitter} from "./three/penumbra_emitter.js";
import {LayoutRunner} from "./three/penumbra_runner.js";
import {WebGPULayoutRunner} from "./three/penumbra_webgpu_runner.js";
import {lightUniforms} from "./three/light_frame.js";
import {sunDirection, timeWindow} from "./sun_path.js";
import {ConfigPanel} from "./config_panel.js";
import {SceneGeometry, GBuffer, Composite, perspective, lookAt, multiply, SCENE_POSITION_LOCATION} from "./scene_view.js";

const $ = (id) => document.getElementById(id);
const STALE = Symbol("stale WebGPU frame");

// The page's renderers: the emission each one runs.
const BACKENDS = {
    webgl2: {name: "WebGL2", target: "essl300", language: "ES 3.00"},
    webgpu: {name: "WebGPU", target: "wgsl", language: "WGSL"},
};

// An RGBA32F texture's texels (bottom row first) through a read framebuffer.
function readFloatTexture(gl, texture, width, height) {
    const framebuffer = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, texture.id, 0);
    gl.readBuffer(gl.COLOR_ATTACHMENT0);
    const out = new Float32Array(4 * width * height);
    gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, out);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.deleteFramebuffer(framebuffer);
    return out;
}

async function fetchOk(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
    return response;
}
const floats = async (url) => new Float32Array(await (await fetchOk(url)).arrayBuffer());

// Everything of a bundle the page uses (targets/bundle/README.md): triangles, light, G-buffers at
// its camera, the desktop run's visibility; the oracle's value and bound (occlusion textures), the
// ray-traced truth (--reference), the bake (oim) where it has them.
async function loadBundle(base) {
    const info = await (await fetchOk(base + "uniforms.json")).json();
    const bundle = {base, info, width: info.width, height: info.height, triangles: await floats(base + "mesh.f32"), callerTextures: {},
                    bake: {}, gl: await floats(base + "visibility_gl.f32"), oracle: null, bound: null, truth: null};
    for (const [name, file] of Object.entries(info.caller_textures || {})) bundle.callerTextures[name] = await floats(base + file);
    for (const [name, file] of Object.entries(info.bake_textures || {})) bundle.bake[name] = await floats(base + file);
    if (info.config.technique === "occlusion") {
        bundle.oracle = await floats(base + "oracle.f32");
        bundle.bound = await floats(base + "bound.f32");
    }
    if (info.truth) bundle.truth = await floats(base + info.truth.file);
    return bundle;
}

// An R32F texture of a bundle image (bottom row first), for the difference and error views.
function imageTexture(gl, width, height, values) {
    const id = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, id);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.R32F, width, height);
    // one level: NEAREST, or the texture is incomplete and texelFetch reads 0
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RED, gl.FLOAT, values);
    gl.bindTexture(gl.TEXTURE_2D, null);
    return id;
}

// The light of a bundle, or a default one of the other kind over the bounds.
function lightFor(kind, bundle, box) {
    const span = Math.max(box.hi[0] - box.lo[0], box.hi[2] - box.lo[2], 1e-3);
    const centre = [0, 2].map((i) => 0.5 * (box.lo[i] + box.hi[i]));
    const given = bundle.info.light;
    if (kind === "sun") {
        if (given.kind === "sun") return {kind: "sun", direction: [...given.direction], angularDiameter: given.angular_diameter_degrees * Math.PI / 180};
        return {kind: "sun", direction: [0.3, -1, 0.2], angularDiameter: 5 * Math.PI / 180};
    }
    if (given.kind === "rect") {
        const m = bundle.info.uniforms.penumbra_lightFromWorld;
        return {kind: "rect", center: [...given.center], u: [m[0], m[4], m[8]], v: [m[1], m[5], m[9]], width: given.width, height: given.height};
    }
    return {kind: "rect", center: [centre[0], box.hi[1] + span, centre[1]], u: [1, 0, 0], v: [0, 0, 1], width: 0.2 * span, height: 0.2 * span};
}

// One side of the view: its panel, its emission (as asked), the essl300 emission it runs, its runner.
class Side {
    constructor(app, index, title, initial) {
        this.app = app;
        this.index = index;
        this.emissions = 0;
        this.runner = null;
        this.reason = "";
        this.generation = 0;        // WebGPU runners are built asynchronously: only the latest one is kept
        this.lastVisibility = null; // WebGPU: the last result read back
        this.panel = new ConfigPanel($("panels"), app.emitter, {
            id: index ? "right" : "left", title, defaults: app.defaults, initial, onChange: () => this.update(),
        });
    }

    // Re-emits from the panel, rebuilds the runner, re-renders.
    update(render = true) {
        const config = this.panel.config();
        const emission = this.app.emitter.emit(config);
        ++this.emissions;
        this.emission = emission;
        this.reason = "";
        let note = emission.ok ? `emitted ${Object.keys(emission.files).length} files in ${emission.ms.toFixed(1)} ms` : "";
        let runnable = emission;
        const backend = BACKENDS[this.app.backend];
        if (emission.ok && emission.layout.config.target !== backend.target) {
            runnable = this.app.emitter.emit({...config, target: backend.target});
            note += runnable.ok ? `; the page runs the ${backend.target} emission of the same configuration (${backend.name} runs ${backend.language})`
                                : `; ${backend.name} runs only ${backend.target}, where this configuration is refused: ${runnable.error}`;
        }
        this.panel.showResult(emission, note);
        if (this.runner) this.runner.dispose();
        this.runner = null;
        this.lastVisibility = null;
        const generation = ++this.generation;
        if (!emission.ok) this.reason = "invalid configuration: " + emission.error;
        else if (!runnable.ok) this.reason = `cannot run on ${backend.name}: ` + runnable.error;
        else {
            this.reason = this.app.cannotRun(runnable.layout);
            if (!this.reason && this.app.backend === "webgpu") {
                this.reason = "building the WebGPU pipelines…";
                this.app.track(WebGPULayoutRunner.fromEmission(this.app.gpu.device, runnable).then((runner) => {
                    if (generation !== this.generation) return runner.dispose();
                    this.runner = runner;
                    this.reason = "";
                    this.app.render();
                }, (e) => {
                    if (generation !== this.generation) return;
                    this.reason = "cannot run on WebGPU: " + e.message;
                    this.app.render();
                }));
            } else if (!this.reason) {
                try {
                    this.runner = LayoutRunner.fromEmission(this.app.gl, runnable);
                    this.runner.enableTiming();
                    // Baked textures (oim) from the bundle, once per runner.
                    for (const t of runnable.layout.textures)
                        if (t.source === "bake") this.runner.uploadTexture(t.name, 0, -1, this.app.bundle.bake[t.name]);
                } catch (e) {
                    this.reason = "cannot run on WebGL2: " + e.message;
                }
            }
        }
        this.app.showFiles();
        if (render) this.app.render();
    }
}

class App {
    async start() {
        const params = new URLSearchParams(location.search);
        this.canvas = $("view");
        this.gl = this.canvas.getContext("webgl2", {antialias: false, preserveDrawingBuffer: true});
        if (!this.gl) throw new Error("this browser has no WebGL2");
        // The G-buffer is RGBA32F, as the layouts declare their caller textures.
        if (!this.gl.getExtension("EXT_color_buffer_float")) throw new Error("this browser lacks EXT_color_buffer_float (rendering the RGBA32F G-buffer)");
        // The module beside three/penumbra_emitter.js (published), else the build folder's when the
        // repository's root is served (python3 -m http.server, then /web/); a relative ?wasm= is
        // relative to three/penumbra_emitter.js.
        this.emitter = await loadEmitter(params.get("wasm") || undefined)
            .catch((first) => loadEmitter("../../build/wasm/penumbra_emitter.wasm").catch(() => { throw first; }));
        // The emitter's defaults (Config{}), for WebGL2: target essl300, 256² occlusion textures.
        this.defaults = this.emitter.emit({target: "essl300"}).layout.config;
        // With ?bundle= the page starts at the bundle's camera (its G-buffers): what the desktop ran.
        this.state = {view: "shaded", camera: params.get("bundle") ? "bundle" : "orbit", split: false, yaw: 0.6, pitch: 0.6, useBundleUniforms: false, bundleSlices: null,
                      renders: 0, frameMs: 0};
        this.gbuffer = new GBuffer(this.gl);
        this.composite = new Composite(this.gl);
        this.timer = !!this.gl.getExtension("EXT_disjoint_timer_query_webgl2");
        this.inflight = Promise.resolve(); // WebGPU work in progress (settled() waits for it)
        this.backend = "webgl2";
        this.backendNote = "";
        if (params.get("backend") === "webgpu" && !(await this.startWebGPU())) this.backendNote = "WebGPU unavailable, running WebGL2: " + this.gpuError;

        // Scenes: the built-in bundles (scenes/index.json), and ?bundle=.
        let index = {scenes: []};
        try { index = await (await fetchOk("scenes/index.json")).json(); } catch { /* none published */ }
        this.scenes = index.scenes.map((s) => ({name: s.name, base: `scenes/${s.dir}/`}));
        if (params.get("bundle")) this.scenes.unshift({name: `bundle ${params.get("bundle")}`, base: params.get("bundle")});
        if (!this.scenes.length) throw new Error("no scene: publish the page with scripts/publish_web.sh (built-in scenes) or pass ?bundle=DIR/");
        const wanted = this.scenes.find((s) => s.name === params.get("scene")) || this.scenes[0];
        await this.loadScene(wanted);

        this.sides = [new Side(this, 0, "configuration", {resolution: 256}), null];
        this.buildControls();
        window.penumbraShowFiles = () => this.showFiles();
        this.sides[0].update();
        this.installAutomation();
    }

    async loadScene(scene) {
        this.bundle = await loadBundle(scene.base);
        this.sceneName = scene.name;
        if (this.geometry) this.geometry.dispose();
        this.geometry = new SceneGeometry(this.gl, this.bundle.triangles);
        this.lights = {};
        this.state.bundleSlices = null;
        this.state.sunTime = this.bundle.info.sun_time ?? null; // oim: the instant on the bake's path
        // The difference view compares with the desktop run of the bundle's own configuration, the
        // error view with the ray-traced truth where the bundle carries one.
        for (const id of Object.values(this.references || {})) this.gl.deleteTexture(id);
        const {width, height} = this.bundle;
        this.references = {difference: imageTexture(this.gl, width, height, this.bundle.gl)};
        if (this.bundle.truth) this.references.error = imageTexture(this.gl, width, height, this.bundle.truth);
    }

    // A WebGPU device (once); false, with gpuError saying why, when the browser has none.
    async startWebGPU() {
        if (!this.gpu) {
            try {
                if (!navigator.gpu) throw new Error("navigator.gpu is undefined (no WebGPU, or not a secure context)");
                const adapter = await navigator.gpu.requestAdapter();
                if (!adapter) throw new Error("navigator.gpu.requestAdapter() gave no adapter");
                this.gpu = {device: await adapter.requestDevice(), adapter: WebGPULayoutRunner.describeAdapter(adapter)};
            } catch (e) {
                this.gpuError = e.message;
                return false;
            }
        }
        this.backend = "webgpu";
        return true;
    }

    // The renderer, "webgl2" or "webgpu": every side re-emits for it. False when WebGPU is missing.
    async setBackend(name) {
        if (!BACKENDS[name]) throw new Error(`backend '${name}' unknown; allowed: ${Object.keys(BACKENDS).join(", ")}`);
        this.backendNote = "";
        if (name === "webgpu" && !(await this.startWebGPU())) this.backendNote = "WebGPU unavailable: " + this.gpuError;
        else if (name === "webgl2") this.backend = "webgl2";
        if ($("backend")) $("backend").value = this.backend;
        this.sides.forEach((s) => s && s.update(false));
        this.render();
        await this.settled();
        return this.backend === name;
    }

    // Tracks asynchronous WebGPU work (runner builds, renders) for settled().
    track(promise) {
        this.inflight = Promise.all([this.inflight, promise.catch(() => {})]);
        return promise;
    }

    async settled() {
        let current;
        do {
            current = this.inflight;
            await current;
        } while (current !== this.inflight);
    }

    // Why a layout cannot run on this page with this scene ("" when it can).
    cannotRun(layout) {
        const baked = layout.textures.filter((t) => t.source === "bake");
        if (baked.length) {
            const c = layout.config, b = this.bundle.info.config;
            const missing = baked.filter((t) => !this.bundle.bake[t.name]).map((t) => t.name);
            if (missing.length)
                return `cannot run here: ${c.technique} reads textures baked offline (${missing.join(", ")}), which this scene's bundle does not ` +
                       "carry (penumbra-export-bundle --technique oim writes a bundle with its bake)";
            if (b.oim.resolution !== c.oim.resolution || b.oim.intervals !== c.oim.intervals || b.oim.samples !== c.oim.samples)
                return `cannot run here: the bundle's bake is for oim.resolution ${b.oim.resolution}, oim.intervals ${b.oim.intervals}, ` +
                       `oim.samples ${b.oim.samples}`;
        }
        for (const t of layout.textures) {
            if (t.source !== "caller" || ["penumbra_worldPositions", "penumbra_worldNormals"].includes(t.name)) continue;
            if (!this.bundle.callerTextures[t.name]) return `cannot run here: the layout reads a G-buffer (${t.name}) that this page does not draw`;
            if (this.state.camera !== "bundle")
                return `runs only at the bundle's camera here: the layout reads ${t.name}, which the bundle carries for its camera (camera: the bundle's)`;
        }
        return "";
    }

    // penumbra_timeWindow of the bake's path at the page's sun time (sun_path.js).
    oimUniforms(light) {
        return {penumbra_timeWindow: timeWindow(this.bundle.info.sun_path, this.state.sunTime, light.angularDiameter)};
    }

    // Moves the sun along the bake's path (oim): the window and the direction the page shades with.
    setSunTime(t) {
        this.state.sunTime = t;
        const towards = sunDirection(this.bundle.info.sun_path, t);
        this.light("sun").direction = towards.map((x) => -x);
        this.render();
    }

    light(kind) {
        return (this.lights[kind] ??= lightFor(kind, this.bundle, this.geometry.box));
    }

    // The camera: an orbit around the bounds, or the bundle's own (its G-buffers, its size).
    camera() {
        const box = this.geometry.box;
        const centre = [0, 1, 2].map((i) => 0.5 * (box.lo[i] + box.hi[i]));
        const radius = 0.5 * Math.hypot(...[0, 1, 2].map((i) => box.hi[i] - box.lo[i]));
        const distance = 1.05 * radius / Math.sin(Math.PI / 8);
        const {yaw, pitch} = this.state;
        const eye = [centre[0] + distance * Math.cos(pitch) * Math.sin(yaw), centre[1] + distance * Math.sin(pitch),
                     centre[2] + distance * Math.cos(pitch) * Math.cos(yaw)];
        const clip = multiply(perspective(Math.PI / 4, this.canvas.width / this.canvas.height, 0.01 * distance, distance + 3 * radius),
                              lookAt(eye, centre, [0, 1, 0]));
        return {eye, clip};
    }

    // One side: shadow phase, G-buffer, screen phase; then its part of the canvas.
    renderSide(side, area) {
        const runner = side.runner;
        const config = runner.layout.config;
        const light = this.light(config.technique === "oim" ? "sun" : config.light); // oim follows the sun of its bake
        const frame = lightUniforms(light, this.geometry.box.lo, this.geometry.box.hi, config.slices);
        runner.setUniforms(this.state.useBundleUniforms && this.state.camera === "bundle" ? this.bundle.info.uniforms : frame.uniforms);
        const {eye, clip} = this.camera();
        const toLight = light.kind === "sun" ? [-light.direction[0], -light.direction[1], -light.direction[2], 0] : [...light.center, 1];
        runner.setUniforms({penumbra_clipFromWorld: clip, penumbra_toLight: toLight});
        // oim: the sun's window along the path the bake traced, at the page's instant.
        if (config.technique === "oim" && this.bundle.info.sun_path) runner.setUniforms(this.oimUniforms(light));
        const replace = this.state.bundleSlices && this.state.camera === "bundle" ? {slicing: (pass) => this.injectSlices(runner, pass)} : {};
        // the scene's vertex array holds positions at SCENE_POSITION_LOCATION: the layout must read them there
        const position = runner.vertexLocation("penumbra_position");
        if (position !== SCENE_POSITION_LOCATION)
            throw new Error(`layout.json reads penumbra_position at location ${position}; the page's scene geometry provides it at ${SCENE_POSITION_LOCATION}`);
        runner.runPhase("shadow", () => this.geometry.draw(), null, replace);

        const bundleCamera = this.state.camera === "bundle";
        const width = bundleCamera ? this.bundle.width : this.canvas.width, height = bundleCamera ? this.bundle.height : this.canvas.height;
        const positions = runner.callerTarget("penumbra_worldPositions", width, height) || this.gbuffer.ownTexture("positions", width, height);
        const normals = runner.callerTarget("penumbra_worldNormals", width, height) || this.gbuffer.ownTexture("normals", width, height);
        if (bundleCamera) {
            const gl = this.gl;
            const upload = (t, texels) => {
                gl.bindTexture(gl.TEXTURE_2D, t.id);
                gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
                gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, texels);
                gl.bindTexture(gl.TEXTURE_2D, null);
            };
            upload(positions, this.bundle.callerTextures.penumbra_worldPositions);
            upload(normals, this.bundle.callerTextures.penumbra_worldNormals);
            for (const [name, texels] of Object.entries(this.bundle.callerTextures))
                if (!name.startsWith("penumbra_world") && runner.callerTarget(name, width, height)) upload(runner.callerTarget(name, width, height), texels);
        } else {
            this.gbuffer.render(this.geometry, clip, eye, width, height, {positions, normals});
        }
        runner.runPhase("screen", null, {width, height});
        this.composite.draw({visibility: runner.texture(runner.layout.result).id, positions: positions.id, normals: normals.id,
                             reference: bundleCamera ? this.references[this.state.view] : null}, [this.canvas.width, this.canvas.height], area,
                            this.state.view, toLight);
        return frame.contained;
    }

    // The WebGPU frame: each side's visibility computed by WebGPU, read back, and composited in WebGL2
    // as render() does.
    async renderWebGPU() {
        if (this.backend !== "webgpu") return; // switched back to WebGL2 while this frame waited
        const gl = this.gl;
        const started = performance.now();
        const sides = this.state.split && this.sides[1] ? this.sides : [this.sides[0]];
        const w = this.canvas.width, h = this.canvas.height;
        const messages = [];
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.viewport(0, 0, w, h);
        gl.clearColor(0.05, 0.05, 0.06, 1);
        gl.clear(gl.COLOR_BUFFER_BIT);
        for (const [i, side] of sides.entries()) {
            const area = sides.length === 1 ? [0, 0, w, h] : [i * (w >> 1), 0, w >> 1, h];
            const label = sides.length === 1 ? "" : i ? "right: " : "left: ";
            if (!side.runner) {
                messages.push(label + side.reason);
                continue;
            }
            side.failed = false;
            try {
                if (!(await this.renderSideWebGPU(side, area))) messages.push(label + "the bounds reach the light plane: move the light up");
            } catch (e) {
                if (e === STALE) return; // the side's runner (or the renderer) changed meanwhile: a newer frame follows
                messages.push(`${label}cannot run on WebGPU: ${e.message}`);
                side.reason = e.message;
                side.failed = true;
            }
        }
        if (sides.length > 1) {
            gl.enable(gl.SCISSOR_TEST);
            gl.scissor((w >> 1) - 1, 0, 2, h);
            gl.clearColor(0.9, 0.75, 0.2, 1);
            gl.clear(gl.COLOR_BUFFER_BIT);
            gl.disable(gl.SCISSOR_TEST);
        }
        gl.finish();
        this.state.frameMs = performance.now() - started;
        ++this.state.renders;
        this.messages = messages;
        this.showStatus();
    }

    // One side on WebGPU: shadow phase, the G-buffer (the page's WebGL2 pass, read back, or the
    // bundle's), screen phase, read-back, and its part of the canvas.
    async renderSideWebGPU(side, area) {
        const gl = this.gl, runner = side.runner;
        const current = () => { if (side.runner !== runner || this.backend !== "webgpu") throw STALE; };
        const config = runner.layout.config;
        const light = this.light(config.light);
        const frame = lightUniforms(light, this.geometry.box.lo, this.geometry.box.hi, config.slices);
        runner.setUniforms(this.state.useBundleUniforms && this.state.camera === "bundle" ? this.bundle.info.uniforms : frame.uniforms);
        const {eye, clip} = this.camera();
        const toLight = light.kind === "sun" ? [-light.direction[0], -light.direction[1], -light.direction[2], 0] : [...light.center, 1];
        runner.setUniforms({penumbra_clipFromWorld: clip, penumbra_toLight: toLight});
        if (!side.drawer || side.drawer.runner !== runner || side.drawer.triangles !== this.bundle.triangles) // the scene's vertex buffer
            side.drawer = {runner, triangles: this.bundle.triangles, draw: runner.sceneDrawer(this.bundle.triangles)};
        await runner.runPhase("shadow", side.drawer.draw);
        current();

        const bundleCamera = this.state.camera === "bundle";
        const width = bundleCamera ? this.bundle.width : this.canvas.width, height = bundleCamera ? this.bundle.height : this.canvas.height;
        const positions = this.gbuffer.ownTexture("positions", width, height), normals = this.gbuffer.ownTexture("normals", width, height);
        let data;
        if (bundleCamera) {
            data = this.bundle.callerTextures;
            for (const [t, texels] of [[positions, data.penumbra_worldPositions], [normals, data.penumbra_worldNormals]]) {
                gl.bindTexture(gl.TEXTURE_2D, t.id);
                gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
                gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, texels);
                gl.bindTexture(gl.TEXTURE_2D, null);
            }
        } else {
            this.gbuffer.render(this.geometry, clip, eye, width, height, {positions, normals});
            data = {penumbra_worldPositions: readFloatTexture(gl, positions, width, height),
                    penumbra_worldNormals: readFloatTexture(gl, normals, width, height)};
        }
        runner.allocateOutputSized(width, height);
        for (const t of runner.layout.textures) {
            if (t.source !== "caller") continue;
            if (!data[t.name]) throw new Error(`the layout reads a G-buffer (${t.name}) that this page does not draw`);
            runner.fillTexture(t.name, width, height, data[t.name]);
        }
        await runner.runPhase("screen", null, {width, height});
        current();
        const visibility = await runner.readResult();
        current();
        side.lastVisibility = visibility;
        // the read-back result as a WebGL2 texture for the composite (same rows: bottom first)
        this.webgpuResults ??= {};
        let result = this.webgpuResults[side.index];
        if (!result || result.width !== width || result.height !== height) {
            if (result) gl.deleteTexture(result.id);
            result = this.webgpuResults[side.index] = {id: imageTexture(gl, width, height, side.lastVisibility), width, height};
        } else {
            gl.bindTexture(gl.TEXTURE_2D, result.id);
            gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
            gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RED, gl.FLOAT, side.lastVisibility);
            gl.bindTexture(gl.TEXTURE_2D, null);
        }
        this.composite.draw({visibility: result.id, positions: positions.id, normals: normals.id,
                             reference: bundleCamera ? this.references[this.state.view] : null}, [this.canvas.width, this.canvas.height], area,
                            this.state.view, toLight);
        return frame.contained;
    }

    // The bundle's slicing output (slices.f32) in place of the browser's own slicing pass.
    injectSlices(runner, pass) {
        const R = runner.layout.config.resolution, S = runner.layout.config.slices;
        if (R !== this.bundle.info.config.resolution || S !== this.bundle.info.config.slices)
            throw new Error("the bundle's slices are for another slice count or resolution");
        pass.outputs.forEach((out, t) => {
            const rgba = new Float32Array(4 * R * R);
            for (let c = 0; c < 4 && 4 * t + c < S; ++c)
                for (let i = 0; i < R * R; ++i) rgba[4 * i + c] = this.state.bundleSlices[(4 * t + c) * R * R + i];
            runner.uploadTexture(out.texture, out.level, out.layer, rgba);
        });
    }

    render() {
        if (this.backend === "webgpu") {
            // one frame at a time; requests while one waits are merged into it
            if (this.frameQueued) return;
            this.frameQueued = true;
            this.frames = (this.frames || Promise.resolve()).then(() => {
                this.frameQueued = false;
                return this.renderWebGPU();
            });
            this.track(this.frames);
            return;
        }
        const gl = this.gl;
        const started = performance.now();
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.viewport(0, 0, this.canvas.width, this.canvas.height);
        gl.clearColor(0.05, 0.05, 0.06, 1);
        gl.clear(gl.COLOR_BUFFER_BIT);
        const sides = this.state.split && this.sides[1] ? this.sides : [this.sides[0]];
        const w = this.canvas.width, h = this.canvas.height;
        const messages = [];
        sides.forEach((side, i) => {
            const area = sides.length === 1 ? [0, 0, w, h] : [i * (w >> 1), 0, w >> 1, h];
            const label = sides.length === 1 ? "" : i ? "right: " : "left: ";
            if (!side.runner) {
                messages.push(label + side.reason);
                return;
            }
            side.failed = false;
            try {
                if (!this.renderSide(side, area)) messages.push(label + "the bounds reach the light plane: move the light up");
            } catch (e) {
                messages.push(`${label}cannot run on WebGL2: ${e.message}`);
                side.reason = e.message;
                side.failed = true;
            }
        });
        if (sides.length > 1) { // the split line
            gl.enable(gl.SCISSOR_TEST);
            gl.scissor((w >> 1) - 1, 0, 2, h);
            gl.clearColor(0.9, 0.75, 0.2, 1);
            gl.clear(gl.COLOR_BUFFER_BIT);
            gl.disable(gl.SCISSOR_TEST);
        }
        gl.finish();
        this.state.frameMs = performance.now() - started;
        ++this.state.renders;
        this.messages = messages;
        this.showStatus();
        if (this.timer) setTimeout(() => this.showStatus(), 100); // timer queries arrive later
    }

    showStatus() {
        const sides = this.state.split && this.sides[1] ? this.sides : [this.sides[0]];
        const lines = this.backend === "webgpu"
            ? [`${this.sceneName}: ${this.geometry.count / 3} triangles; WebGPU (adapter ${this.gpu.adapter.vendor} ${this.gpu.adapter.architecture}, ` +
               `the wgsl emission); frame ${this.state.frameMs.toFixed(1)} ms (CPU, with the read-back)`]
            : [`${this.sceneName}: ${this.geometry.count / 3} triangles; ` +
               `frame ${this.state.frameMs.toFixed(1)} ms (CPU, with gl.finish)` +
               (this.timer ? "" : "; no EXT_disjoint_timer_query_webgl2 in this browser, so no GPU pass times")];
        if (this.backendNote) lines.push(this.backendNote);
        sides.forEach((side, i) => {
            if (!side.runner || !side.runner.passTimes) return;
            const times = side.runner.passTimes();
            if (!times || !Object.keys(times).length) return;
            const total = Object.values(times).reduce((a, b) => a + b, 0);
            const byName = new Map(); // passes of one name (nbuffer_level, erosion_reduce, ...) summed
            for (const [key, ms] of Object.entries(times)) {
                const name = key.split(" ")[1], entry = byName.get(name) || {ms: 0, count: 0};
                byName.set(name, {ms: entry.ms + ms, count: entry.count + 1});
            }
            lines.push(`${sides.length > 1 ? (i ? "right" : "left") + " " : ""}GPU ${total.toFixed(2)} ms (timer queries): ` +
                       [...byName].map(([name, e]) => `${name}${e.count > 1 ? " ×" + e.count : ""} ${e.ms.toFixed(2)}`).join(", "));
        });
        const against = {difference: this.bundle.gl, error: this.bundle.truth}[this.state.view];
        if (this.state.view === "error" && !this.bundle.truth)
            lines.push("this bundle carries no ray-traced truth (penumbra-export-bundle --reference N writes one)");
        const shown = this.backend === "webgpu" ? this.sides[0].lastVisibility : this.sides[0].runner && this.sides[0].runner.readResult();
        if (against && this.state.camera === "bundle" && this.sides[0].runner && shown) {
            const v = shown, geometry = this.bundle.callerTextures.penumbra_worldPositions;
            let sum = 0, n = 0;
            for (let i = 0; i < v.length; ++i)
                if (geometry[4 * i + 3] > 0.5 && Number.isFinite(against[i])) { sum += Math.abs(v[i] - against[i]); ++n; }
            lines.push(this.state.view === "error"
                ? `MAE against the truth (${this.bundle.info.truth.kind}, ${this.bundle.info.truth.samples}² rays) ${(sum / Math.max(n, 1)).toFixed(4)} over ${n} pixels`
                : `mean |browser − desktop| ${(sum / Math.max(n, 1)).toFixed(4)} over ${n} pixels (the desktop ran the bundle's configuration: ` +
                  `${describe(this.bundle.info.config)})`);
        }
        for (const m of this.messages || []) lines.push(m);
        $("status").textContent = lines.join("\n");
    }

    // The emitted files of either side: a list, the text of the chosen one, a download link.
    showFiles() {
        const select = $("file"), side = this.sides[Number($("file-side").value)] || this.sides[0];
        const files = side.emission && side.emission.ok ? side.emission.files : {};
        const current = select.value;
        select.replaceChildren(...Object.keys(files).map((name) => Object.assign(document.createElement("option"), {value: name, textContent: name})));
        if (files[current] !== undefined) select.value = current;
        else if (files["layout.json"] !== undefined) select.value = "layout.json";
        const text = files[select.value] ?? (side.emission ? side.emission.error : "");
        $("file-text").textContent = text;
        const link = $("download");
        if (link.href) URL.revokeObjectURL(link.href);
        link.href = URL.createObjectURL(new Blob([text], {type: "text/plain"}));
        link.download = select.value || "error.txt";
        $("download-all").onclick = (event) => {
            event.preventDefault();
            for (const [name, body] of Object.entries(files)) {
                const a = Object.assign(document.createElement("a"), {href: URL.createObjectURL(new Blob([body])), download: name});
                a.click();
                URL.revokeObjectURL(a.href);
            }
        };
    }

    buildControls() {
        const controls = $("controls");
        const row = (...items) => {
            const div = document.createElement("div");
            div.className = "row";
            div.append(...items);
            controls.append(div);
            return div;
        };
        const select = (id, options, value, onChange) => {
            const s = Object.assign(document.createElement("select"), {id});
            for (const [v, text] of options) s.append(Object.assign(document.createElement("option"), {value: v, textContent: text}));
            s.value = value;
            s.addEventListener("change", () => onChange(s.value));
            return s;
        };
        row("scene ", select("scene", this.scenes.map((s) => [s.name, s.name]), this.sceneName, async (name) => {
            await this.loadScene(this.scenes.find((s) => s.name === name));
            this.buildLightControls();
            this.sides.forEach((s) => s && s.update(false));
            this.render();
        }));
        row("view ", select("view-mode", [["shaded", "shaded"], ["visibility", "visibility"], ["difference", "difference from the bundle's desktop run"],
                                           ["error", "error against the bundle's ray-traced truth"]],
                            this.state.view, (v) => {
                                this.state.view = v;
                                if (v === "difference" || v === "error") this.setCamera("bundle"); else this.render();
                            }));
        row("renderer ", select("backend", Object.entries(BACKENDS).map(([key, b]) => [key, `${b.name} (the ${b.target} emission)`]), this.backend,
                                (v) => this.setBackend(v)));
        row("camera ", select("camera", [["orbit", "orbit (drag the image)"], ["bundle", "the bundle's camera and G-buffers"]], this.state.camera,
                              (v) => this.setCamera(v)));
        const split = Object.assign(document.createElement("input"), {type: "checkbox", id: "split"});
        split.addEventListener("change", () => this.setSplit(split.checked));
        const label = document.createElement("label");
        label.append(split, " split view: a second configuration on the right half");
        row(label);
        this.lightRow = document.createElement("div");
        controls.append(this.lightRow);
        this.buildLightControls();

        // Orbit by dragging; with shift, the light moves over the scene.
        let drag = null;
        this.canvas.addEventListener("pointerdown", (e) => { drag = {x: e.clientX, y: e.clientY, shift: e.shiftKey}; this.canvas.setPointerCapture(e.pointerId); });
        this.canvas.addEventListener("pointerup", () => { drag = null; });
        this.canvas.addEventListener("pointermove", (e) => {
            if (!drag) return;
            const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
            drag.x = e.clientX;
            drag.y = e.clientY;
            if (drag.shift) {
                const kind = this.sides[0].runner ? this.sides[0].runner.layout.config.light : "rect";
                const light = this.light(kind);
                const span = Math.max(this.geometry.box.hi[0] - this.geometry.box.lo[0], 1e-3);
                if (kind === "rect") { light.center[0] += dx * span / 300; light.center[2] += dy * span / 300; }
                else light.direction = [light.direction[0] + dx / 200, light.direction[1], light.direction[2] + dy / 200];
            } else {
                this.state.yaw -= dx / 150;
                this.state.pitch = Math.min(1.5, Math.max(-0.2, this.state.pitch + dy / 150));
            }
            this.render();
        });
    }

    buildLightControls() {
        const panel = this.lightRow;
        panel.replaceChildren();
        const box = this.geometry.box;
        const span = Math.max(box.hi[0] - box.lo[0], box.hi[2] - box.lo[2], 1e-3);
        const slider = (label, id, min, max, value, onInput) => {
            const row = document.createElement("label");
            row.className = "row";
            const input = Object.assign(document.createElement("input"), {type: "range", id, min, max, step: (max - min) / 200, value});
            const shown = Object.assign(document.createElement("span"), {textContent: Number(value).toFixed(2)});
            input.addEventListener("input", () => { shown.textContent = Number(input.value).toFixed(2); onInput(Number(input.value)); this.render(); });
            row.append(label + " ", input, " ", shown);
            panel.append(row);
        };
        const rect = this.light("rect");
        ["x", "y", "z"].forEach((axis, i) => {
            const lo = i === 1 ? box.hi[1] + 0.05 * span : box.lo[i] - 0.5 * span;
            const hi = i === 1 ? box.hi[1] + 2 * span : box.hi[i] + 0.5 * span;
            slider(`rect light ${axis}`, `light-${axis}`, lo, hi, rect.center[i], (v) => { rect.center[i] = v; });
        });
        const aspect = rect.height / rect.width;
        slider("rect light width", "light-width", 0.01 * span, span, rect.width, (v) => { rect.width = v; rect.height = v * aspect; });
        const sun = this.light("sun");
        const d = sun.direction;
        let azimuth = Math.atan2(d[2], d[0]), elevation = Math.asin(Math.min(1, -d[1] / Math.hypot(...d)));
        const set = () => { sun.direction = [Math.cos(elevation) * Math.cos(azimuth), -Math.sin(elevation), Math.cos(elevation) * Math.sin(azimuth)]; };
        slider("sun azimuth", "sun-azimuth", -Math.PI, Math.PI, azimuth, (v) => { azimuth = v; set(); });
        slider("sun elevation", "sun-elevation", 0.2, Math.PI / 2, elevation, (v) => { elevation = v; set(); });
        slider("sun diameter (°)", "sun-diameter", 0.1, 20, sun.angularDiameter * 180 / Math.PI, (v) => { sun.angularDiameter = v * Math.PI / 180; });
        if (this.bundle.info.sun_path) // oim: the sun can only move along the path its bake traced
            slider("oim sun time t (the bake's path)", "sun-time", 0, 1, this.state.sunTime, (v) => this.setSunTime(v));
    }

    setCamera(camera) {
        this.state.camera = camera;
        $("camera").value = camera;
        this.sides.forEach((s) => s && s.update(false)); // what runs may depend on the camera (oim)
        this.render();
    }

    setSplit(on) {
        this.state.split = on;
        $("split").checked = on;
        if (on && !this.sides[1]) {
            // The right half starts as PCSS 16/16, as the window's split does.
            this.sides[1] = new Side(this, 1, "right half", {resolution: 256, technique: "pcss"});
            this.sides[1].update(false);
        }
        if (this.sides[1]) this.sides[1].panel.root.hidden = !on;
        this.render();
    }

    installAutomation() {
        const app = this;
        window.penumbra = {
            ready: true,
            emissions: (side = 0) => app.sides[side].emissions,
            renders: () => app.state.renders,
            config: (side = 0) => app.sides[side].panel.config(),
            emission: (side = 0) => ({ok: app.sides[side].emission.ok, error: app.sides[side].emission.error,
                                      diagnostics: app.sides[side].emission.diagnostics, files: Object.keys(app.sides[side].emission.files),
                                      layoutConfig: app.sides[side].emission.layout && app.sides[side].emission.layout.config}),
            reason: (side = 0) => app.sides[side].reason,
            running: (side = 0) => !!app.sides[side].runner,
            // The side's result; an error when its last render failed (the texture would be stale).
            readVisibility: (side = 0) => {
                if (!app.sides[side].runner || app.sides[side].failed) throw new Error(`side ${side} did not render: ${app.sides[side].reason}`);
                if (app.backend === "webgpu") {
                    if (!app.sides[side].lastVisibility) throw new Error(`side ${side}: no WebGPU frame yet (await window.penumbra.settled())`);
                    return app.sides[side].lastVisibility;
                }
                return app.sides[side].runner.readResult();
            },
            backend: () => app.backend,
            setBackend: (name) => app.setBackend(name),
            settled: () => app.settled(),
            setCamera: (camera) => app.setCamera(camera),
            setSplit: (on) => app.setSplit(on),
            setLight: (kind, changes) => { Object.assign(app.light(kind), changes); app.render(); },
            setSunTime: (t) => app.setSunTime(t),
            useBundleUniforms: (on) => { app.state.useBundleUniforms = on; app.render(); },
            useBundleSlices: async (on) => {
                app.state.bundleSlices = on ? await floats(app.bundle.base + "slices.f32") : null;
                app.render();
            },
            compareSlices: async () => {
                const desktop = await floats(app.bundle.base + "slices.f32");
                const runner = app.sides[0].runner, {resolution: R, slices: S} = runner.layout.config;
                const pass = runner.layout.passes.find((p) => p.name === "slicing");
                let differing = 0, covered = 0;
                for (const [t, out] of pass.outputs.entries()) {
                    const ours = await runner.readTexture(out.texture, out.level, out.layer); // (a promise on WebGPU)
                    for (let c = 0; c < 4 && 4 * t + c < S; ++c)
                        for (let i = 0; i < R * R; ++i) {
                            const d = desktop[(4 * t + c) * R * R + i];
                            covered += d > 0.5 ? 1 : 0;
                            differing += Math.abs(ours[4 * i + c] - d) > 0.5 ? 1 : 0;
                        }
                }
                return {differing, covered, texels: S * R * R};
            },
            uniforms: () => {
                const config = app.sides[0].runner.layout.config;
                const light = app.light(config.technique === "oim" ? "sun" : config.light);
                const computed = lightUniforms(light, app.geometry.box.lo, app.geometry.box.hi, config.slices).uniforms;
                if (config.technique === "oim" && app.bundle.info.sun_path) Object.assign(computed, app.oimUniforms(light));
                return {computed, bundle: app.bundle.info.uniforms};
            },
            // The canvas as RGBA bytes, bottom row first (what the views show).
            readCanvas: () => {
                const gl = app.gl, out = new Uint8Array(4 * app.canvas.width * app.canvas.height);
                gl.bindFramebuffer(gl.FRAMEBUFFER, null);
                gl.readPixels(0, 0, app.canvas.width, app.canvas.height, gl.RGBA, gl.UNSIGNED_BYTE, out);
                return {width: app.canvas.width, height: app.canvas.height, rgba: Array.from(out)};
            },
            passTimes: (side = 0) => app.sides[side].runner && app.sides[side].runner.passTimes(),
            status: () => $("status").textContent,
            info: () => {
                const gl = app.gl, debug = gl.getExtension("WEBGL_debug_renderer_info");
                const runner = app.sides[0].runner;
                return {renderer: gl.getParameter(debug ? debug.UNMASKED_RENDERER_WEBGL : gl.RENDERER), version: gl.getParameter(gl.VERSION),
                        backend: app.backend, adapter: app.gpu ? app.gpu.adapter : null,
                        timer: app.timer, bundle: app.bundle.info.config, width: app.bundle.width, height: app.bundle.height,
                        resultFormat: runner ? runner.texture(runner.layout.result).desc.internal_format : null,
                        emitterLoadMs: app.emitter.compileMs};
            },
            emitter: app.emitter,
        };
    }
}

function describe(c) {
    if (c.technique !== "occlusion") return c.technique;
    return `${c.slices} slices, ${c.resolution}², ${c.filter}, ${c.fusion}, ${c.packing}, ${c.light}${c.tangent_clip ? ", tangent clip" : ""}`;
}

new App().start().catch((error) => {
    $("status").textContent = "error: " + error.message;
    window.penumbra = {error: error.message};
    console.error(error);
});
