// automation.js — window.penumbra, the page's interface for tests and scripts (targets/web/
// browser_test.mjs drives the page through it): what each side emitted and runs, its visibility,
// the canvas, and setters for the renderer, camera, split view, light and the bundle's inputs.
//
//   await window.penumbra.setBackend("webgpu");  // false when the browser has no WebGPU
//   await window.penumbra.settled();             // WebGPU renders asynchronously
//   const visibility = window.penumbra.readVisibility(0);

import {lightUniforms} from "./three/light_frame.js";
import {floats} from "./bundle.js";

const $ = (id) => document.getElementById(id);

export function installAutomation(app) {
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
