// webgl2_renderer.js — the WebGL2 renderer: each side runs the essl300 emission by its layout.json
// (three/penumbra_runner.js) on the page's own context, between the page's G-buffer and composite.

import {lightUniforms} from "./three/light_frame.js";
import {SCENE_POSITION_LOCATION} from "./scene_view.js";
import {showStatus} from "./status.js";

// The WebGL2 frame: each side's layout run on the page's context and composited where it ran.
export function renderWebGL2(app) {
    const gl = app.gl;
    const started = performance.now();
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.viewport(0, 0, app.canvas.width, app.canvas.height);
    gl.clearColor(0.05, 0.05, 0.06, 1);
    gl.clear(gl.COLOR_BUFFER_BIT);
    const sides = app.state.split && app.sides[1] ? app.sides : [app.sides[0]];
    const w = app.canvas.width, h = app.canvas.height;
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
            if (!renderSide(app, side, area)) messages.push(label + "the bounds reach the light plane: move the light up");
        } catch (e) {
            messages.push(`${label}cannot run on WebGL2: ${e.message}`);
            side.reason = e.message;
            side.failed = true;
        }
    });
    finishFrame(app, sides.length, started, messages);
    if (app.timer) setTimeout(() => showStatus(app), 100); // timer queries arrive later
}

// The end of a frame of either renderer: the split line between two sides, the frame's time, the
// sides' messages in the status line.
export function finishFrame(app, sideCount, started, messages) {
    const gl = app.gl, w = app.canvas.width, h = app.canvas.height;
    if (sideCount > 1) { // the split line
        gl.enable(gl.SCISSOR_TEST);
        gl.scissor((w >> 1) - 1, 0, 2, h);
        gl.clearColor(0.9, 0.75, 0.2, 1);
        gl.clear(gl.COLOR_BUFFER_BIT);
        gl.disable(gl.SCISSOR_TEST);
    }
    gl.finish();
    app.state.frameMs = performance.now() - started;
    ++app.state.renders;
    app.messages = messages;
    showStatus(app);
}

// One side: shadow phase, G-buffer, screen phase; then its part of the canvas.
function renderSide(app, side, area) {
    const runner = side.runner;
    const config = runner.layout.config;
    const light = app.light(config.technique === "oim" ? "sun" : config.light); // oim follows the sun of its bake
    const frame = lightUniforms(light, app.geometry.box.lo, app.geometry.box.hi, config.slices);
    runner.setUniforms(app.state.useBundleUniforms && app.state.camera === "bundle" ? app.bundle.info.uniforms : frame.uniforms);
    const {eye, clip} = app.camera();
    const toLight = light.kind === "sun" ? [-light.direction[0], -light.direction[1], -light.direction[2], 0] : [...light.center, 1];
    runner.setUniforms({penumbra_clipFromWorld: clip, penumbra_toLight: toLight});
    // oim: the sun's window along the path the bake traced, at the page's instant.
    if (config.technique === "oim" && app.bundle.info.sun_path) runner.setUniforms(app.oimUniforms(light));
    const replace = app.state.bundleSlices && app.state.camera === "bundle" ? {slicing: (pass) => injectSlices(app, runner, pass)} : {};
    // the scene's vertex array holds positions at SCENE_POSITION_LOCATION: the layout must read them there
    const position = runner.vertexLocation("penumbra_position");
    if (position !== SCENE_POSITION_LOCATION)
        throw new Error(`layout.json reads penumbra_position at location ${position}; the page's scene geometry provides it at ${SCENE_POSITION_LOCATION}`);
    runner.runPhase("shadow", () => app.geometry.draw(), null, replace);

    const bundleCamera = app.state.camera === "bundle";
    const width = bundleCamera ? app.bundle.width : app.canvas.width, height = bundleCamera ? app.bundle.height : app.canvas.height;
    const positions = runner.callerTarget("penumbra_worldPositions", width, height) || app.gbuffer.ownTexture("positions", width, height);
    const normals = runner.callerTarget("penumbra_worldNormals", width, height) || app.gbuffer.ownTexture("normals", width, height);
    if (bundleCamera) {
        const gl = app.gl;
        const upload = (t, texels) => {
            gl.bindTexture(gl.TEXTURE_2D, t.id);
            gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
            gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RGBA, gl.FLOAT, texels);
            gl.bindTexture(gl.TEXTURE_2D, null);
        };
        upload(positions, app.bundle.callerTextures.penumbra_worldPositions);
        upload(normals, app.bundle.callerTextures.penumbra_worldNormals);
        for (const [name, texels] of Object.entries(app.bundle.callerTextures))
            if (!name.startsWith("penumbra_world") && runner.callerTarget(name, width, height)) upload(runner.callerTarget(name, width, height), texels);
    } else {
        app.gbuffer.render(app.geometry, clip, eye, width, height, {positions, normals});
    }
    runner.runPhase("screen", null, {width, height});
    app.composite.draw({visibility: runner.texture(runner.layout.result).id, positions: positions.id, normals: normals.id,
                        reference: bundleCamera ? app.references[app.state.view] : null}, [app.canvas.width, app.canvas.height], area,
                       app.state.view, toLight);
    return frame.contained;
}

// The bundle's slicing output (slices.f32) in place of the browser's own slicing pass.
function injectSlices(app, runner, pass) {
    const R = runner.layout.config.resolution, S = runner.layout.config.slices;
    if (R !== app.bundle.info.config.resolution || S !== app.bundle.info.config.slices)
        throw new Error("the bundle's slices are for another slice count or resolution");
    pass.outputs.forEach((out, t) => {
        const rgba = new Float32Array(4 * R * R);
        for (let c = 0; c < 4 && 4 * t + c < S; ++c)
            for (let i = 0; i < R * R; ++i) rgba[4 * i + c] = app.state.bundleSlices[(4 * t + c) * R * R + i];
        runner.uploadTexture(out.texture, out.level, out.layer, rgba);
    });
}
