// webgpu_renderer.js — the WebGPU renderer: each side runs the wgsl emission of its configuration
// (three/penumbra_webgpu_runner.js) on a WebGPU device; the page reads the visibility back and
// shows it through the WebGL2 composite, so every view works alike on both renderers.

import {WebGPULayoutRunner} from "./three/penumbra_webgpu_runner.js";
import {lightUniforms} from "./three/light_frame.js";
import {imageTexture} from "./bundle.js";
import {finishFrame} from "./webgl2_renderer.js";

const STALE = Symbol("stale WebGPU frame");

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

// A WebGPU device (once); false, with gpuError saying why, when the browser has none.
export async function startWebGPU(app) {
    if (!app.gpu) {
        try {
            if (!navigator.gpu) throw new Error("navigator.gpu is undefined (no WebGPU, or not a secure context)");
            const adapter = await navigator.gpu.requestAdapter();
            if (!adapter) throw new Error("navigator.gpu.requestAdapter() gave no adapter");
            app.gpu = {device: await adapter.requestDevice(), adapter: WebGPULayoutRunner.describeAdapter(adapter)};
        } catch (e) {
            app.gpuError = e.message;
            return false;
        }
    }
    app.backend = "webgpu";
    return true;
}

// A frame on WebGPU: one at a time; requests while one waits are merged into it.
export function queueWebGPUFrame(app) {
    if (app.frameQueued) return;
    app.frameQueued = true;
    app.frames = (app.frames || Promise.resolve()).then(() => {
        app.frameQueued = false;
        return renderWebGPU(app);
    });
    app.track(app.frames);
}

// The WebGPU frame: each side's visibility computed by WebGPU, read back, and composited in WebGL2
// as the WebGL2 frame is (webgl2_renderer.js).
async function renderWebGPU(app) {
    if (app.backend !== "webgpu") return; // switched back to WebGL2 while this frame waited
    const gl = app.gl;
    const started = performance.now();
    const sides = app.state.split && app.sides[1] ? app.sides : [app.sides[0]];
    const w = app.canvas.width, h = app.canvas.height;
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
            if (!(await renderSideWebGPU(app, side, area))) messages.push(label + "the bounds reach the light plane: move the light up");
        } catch (e) {
            if (e === STALE) return; // the side's runner (or the renderer) changed meanwhile: a newer frame follows
            messages.push(`${label}cannot run on WebGPU: ${e.message}`);
            side.reason = e.message;
            side.failed = true;
        }
    }
    finishFrame(app, sides.length, started, messages);
}

// One side on WebGPU: shadow phase, the G-buffer (the page's WebGL2 pass, read back, or the
// bundle's), screen phase, read-back, and its part of the canvas.
async function renderSideWebGPU(app, side, area) {
    const gl = app.gl, runner = side.runner;
    const current = () => { if (side.runner !== runner || app.backend !== "webgpu") throw STALE; };
    const config = runner.layout.config;
    const light = app.light(config.light);
    const frame = lightUniforms(light, app.geometry.box.lo, app.geometry.box.hi, config.slices);
    runner.setUniforms(app.state.useBundleUniforms && app.state.camera === "bundle" ? app.bundle.info.uniforms : frame.uniforms);
    const {eye, clip} = app.camera();
    const toLight = light.kind === "sun" ? [-light.direction[0], -light.direction[1], -light.direction[2], 0] : [...light.center, 1];
    runner.setUniforms({penumbra_clipFromWorld: clip, penumbra_toLight: toLight});
    if (!side.drawer || side.drawer.runner !== runner || side.drawer.triangles !== app.bundle.triangles) // the scene's vertex buffer
        side.drawer = {runner, triangles: app.bundle.triangles, draw: runner.sceneDrawer(app.bundle.triangles)};
    await runner.runPhase("shadow", side.drawer.draw);
    current();

    const bundleCamera = app.state.camera === "bundle";
    const width = bundleCamera ? app.bundle.width : app.canvas.width, height = bundleCamera ? app.bundle.height : app.canvas.height;
    const positions = app.gbuffer.ownTexture("positions", width, height), normals = app.gbuffer.ownTexture("normals", width, height);
    let data;
    if (bundleCamera) {
        data = app.bundle.callerTextures;
        for (const [t, texels] of [[positions, data.penumbra_worldPositions], [normals, data.penumbra_worldNormals]]) {
            gl.bindTexture(gl.TEXTURE_2D, t.id);
            gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
            gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, texels);
            gl.bindTexture(gl.TEXTURE_2D, null);
        }
    } else {
        app.gbuffer.render(app.geometry, clip, eye, width, height, {positions, normals});
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
    app.webgpuResults ??= {};
    let result = app.webgpuResults[side.index];
    if (!result || result.width !== width || result.height !== height) {
        if (result) gl.deleteTexture(result.id);
        result = app.webgpuResults[side.index] = {id: imageTexture(gl, width, height, side.lastVisibility), width, height};
    } else {
        gl.bindTexture(gl.TEXTURE_2D, result.id);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
        gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RED, gl.FLOAT, side.lastVisibility);
        gl.bindTexture(gl.TEXTURE_2D, null);
    }
    app.composite.draw({visibility: result.id, positions: positions.id, normals: normals.id,
                        reference: bundleCamera ? app.references[app.state.view] : null}, [app.canvas.width, app.canvas.height], area,
                       app.state.view, toLight);
    return frame.contained;
}
