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
//
// This file holds the page's state (the scene's bundle, the lights, the camera, the sides, the
// renderer) and starts the page. The rest, by concern: bundle.js (what a scene's bundle gives),
// side.js (one configuration and its runner), webgl2_renderer.js and webgpu_renderer.js (a frame),
// controls.js, status.js and emitted_files.js (the page around the canvas), automation.js
// (window.penumbra).
import {loadEmitter} from "./three/penumbra_emitter.js";
import {sunDirection, timeWindow} from "./sun_path.js";
import {SceneGeometry, GBuffer, Composite, perspective, lookAt, multiply} from "./scene_view.js";
import {fetchOk, loadBundle, imageTexture, lightFor} from "./bundle.js";
import {BACKENDS, Side} from "./side.js";
import {renderWebGL2} from "./webgl2_renderer.js";
import {startWebGPU, queueWebGPUFrame} from "./webgpu_renderer.js";
import {buildControls} from "./controls.js";
import {showFiles} from "./emitted_files.js";
import {installAutomation} from "./automation.js";

const $ = (id) => document.getElementById(id);

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
        if (params.get("backend") === "webgpu" && !(await startWebGPU(this))) this.backendNote = "WebGPU unavailable, running WebGL2: " + this.gpuError;

        // Scenes: the built-in bundles (scenes/index.json), and ?bundle=.
        let index = {scenes: []};
        try { index = await (await fetchOk("scenes/index.json")).json(); } catch { /* none published */ }
        this.scenes = index.scenes.map((s) => ({name: s.name, base: `scenes/${s.dir}/`}));
        if (params.get("bundle")) this.scenes.unshift({name: `bundle ${params.get("bundle")}`, base: params.get("bundle")});
        if (!this.scenes.length) throw new Error("no scene: publish the page with scripts/publish_web.sh (built-in scenes) or pass ?bundle=DIR/");
        const wanted = this.scenes.find((s) => s.name === params.get("scene")) || this.scenes[0];
        await this.loadScene(wanted);

        this.sides = [new Side(this, 0, "configuration", {resolution: 256}), null];
        buildControls(this);
        window.penumbraShowFiles = () => showFiles(this);
        this.sides[0].update();
        installAutomation(this);
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

    // The renderer, "webgl2" or "webgpu": every side re-emits for it. False when WebGPU is missing.
    async setBackend(name) {
        if (!BACKENDS[name]) throw new Error(`backend '${name}' unknown; allowed: ${Object.keys(BACKENDS).join(", ")}`);
        this.backendNote = "";
        if (name === "webgpu" && !(await startWebGPU(this))) this.backendNote = "WebGPU unavailable: " + this.gpuError;
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

    // A WebGPU frame is asynchronous, so it is queued; a WebGL2 one is drawn at once.
    render() {
        if (this.backend === "webgpu") queueWebGPUFrame(this);
        else renderWebGL2(this);
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
}

new App().start().catch((error) => {
    $("status").textContent = "error: " + error.message;
    window.penumbra = {error: error.message};
    console.error(error);
});
