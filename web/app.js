// app.js — the page: loads a target bundle (penumbra-export-bundle --target essl300: the scene's
// triangles, its light, its G-buffers (world positions and normals), and the essl300 emission), runs the emission
// with LayoutRunner, shows the shadowed scene, and lets the light move. Moving the light recomputes
// the light-frame uniforms in JavaScript (light_frame.js) from the rectangle (or the sun) and the
// scene's bounds, then re-runs the shadow phase.
//
// URL parameters: ?bundle=DIR/ (default "bundle/", relative to this page).
// window.penumbra (for automation): ready (a promise), readVisibility(), setLight(), info(), ...
import {LayoutRunner} from "./penumbra_runner.js";
import {rectFrame, sunFrame} from "./light_frame.js";

const $ = (id) => document.getElementById(id);

async function fetchOk(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
    return response;
}

function bounds(triangles) {
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < triangles.length; i += 3)
        for (let a = 0; a < 3; ++a) {
            lo[a] = Math.min(lo[a], triangles[i + a]);
            hi[a] = Math.max(hi[a], triangles[i + a]);
        }
    return {lo, hi};
}

// One normal per triangle, repeated on its three vertices (the scenes are faceted).
function flatNormals(t) {
    const n = new Float32Array(t.length);
    for (let i = 0; i < t.length; i += 9) {
        const e1 = [t[i + 3] - t[i], t[i + 4] - t[i + 1], t[i + 5] - t[i + 2]];
        const e2 = [t[i + 6] - t[i], t[i + 7] - t[i + 1], t[i + 8] - t[i + 2]];
        const c = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
        const l = Math.hypot(...c) || 1;
        for (let v = 0; v < 3; ++v) for (let a = 0; a < 3; ++a) n[i + 3 * v + a] = c[a] / l;
    }
    return n;
}

function perspective(fovY, aspect, near, far) {
    const f = 1 / Math.tan(fovY / 2);
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
}

function lookAt(eye, target, up) {
    const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    const norm = (a) => { const l = Math.hypot(...a); return a.map((x) => x / l); };
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const f = norm(sub(target, eye)), s = norm(cross(f, up)), u = cross(s, f);
    return [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, -dot(s, eye), -dot(u, eye), dot(f, eye), 1];
}

function multiply(a, b) {
    const m = new Array(16).fill(0);
    for (let c = 0; c < 4; ++c) for (let r = 0; r < 4; ++r) for (let k = 0; k < 4; ++k) m[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
    return m;
}

async function main() {
    const params = new URLSearchParams(location.search);
    const base = params.get("bundle") || "bundle/";
    const canvas = $("view");
    const gl = canvas.getContext("webgl2", {antialias: false});
    if (!gl) throw new Error("this browser has no WebGL2");

    const bundle = await (await fetchOk(base + "uniforms.json")).json();
    const triangles = new Float32Array(await (await fetchOk(base + "mesh.f32")).arrayBuffer());
    const runner = await LayoutRunner.load(gl, base + "emission/");
    // The G-buffers the layout leaves to the caller (source "caller": world positions, and the
    // normals with the tangent clip), from the bundle's files for them (uniforms.json caller_textures).
    const callerTextures = {};
    for (const t of runner.layout.textures) {
        if (t.source !== "caller") continue;
        const file = (bundle.caller_textures || {})[t.name];
        if (!file) throw new Error(`the layout's caller texture ${t.name} has no file in the bundle's caller_textures`);
        const texels = new Float32Array(await (await fetchOk(base + file)).arrayBuffer());
        if (texels.length !== 4 * bundle.width * bundle.height)
            throw new Error(`${file}: ${texels.length} floats, expected 4 × ${bundle.width} × ${bundle.height}`);
        callerTextures[t.name] = texels;
    }
    const config = runner.layout.config;
    const box = bounds(triangles);

    // Vertex arrays: attribute 0 = world position (slicing, shading), 1 = normal (shading).
    const attribute = (vao, location, data) => {
        gl.bindVertexArray(vao);
        const buffer = gl.createBuffer();
        gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
        gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
        gl.enableVertexAttribArray(location);
        gl.vertexAttribPointer(location, 3, gl.FLOAT, false, 0, 0);
        gl.bindVertexArray(null);
    };
    const sceneVao = gl.createVertexArray();
    attribute(sceneVao, 0, triangles);
    attribute(sceneVao, 1, flatNormals(triangles));
    const vertexCount = triangles.length / 3;
    const drawScene = () => {
        gl.bindVertexArray(sceneVao);
        gl.drawArrays(gl.TRIANGLES, 0, vertexCount);
        gl.bindVertexArray(null);
    };

    // The light. The rectangle's axes are the rows of the exported penumbra_lightFromWorld.
    const exported = bundle.uniforms;
    const m = exported.penumbra_lightFromWorld;
    const light = bundle.light.kind === "sun"
        ? {kind: "sun", direction: [...bundle.light.direction], angularDiameter: bundle.light.angular_diameter_degrees * Math.PI / 180}
        : {kind: "rect", center: [...bundle.light.center], u: [m[0], m[4], m[8]], v: [m[1], m[5], m[9]],
           width: bundle.light.width, height: bundle.light.height};
    const state = {useBundleUniforms: false, bundleSlices: null, view: "shaded", yaw: 0.6, pitch: 0.6, frame: null};

    // With the bundle's slices.f32 (the desktop run's slicing output) in place of our own slicing
    // pass: colour attachment t of the slicing pass holds slices 4t .. 4t + 3 in its channels.
    const R = config.resolution;
    const replaceSlicing = (pass) => pass.outputs.forEach((out, t) => {
        const rgba = new Float32Array(4 * R * R);
        for (let c = 0; c < 4 && 4 * t + c < config.slices; ++c)
            for (let i = 0; i < R * R; ++i) rgba[4 * i + c] = state.bundleSlices[(4 * t + c) * R * R + i];
        runner.uploadTexture(out.texture, out.level, out.layer, rgba);
    });

    const frameOf = () => (light.kind === "sun" ? sunFrame(light, box.lo, box.hi, config.slices)
                                                : rectFrame(light, box.lo, box.hi, config.slices));
    // Shadow phase: slicing and prefilter, then the deferred visibility over the bundle's G-buffers.
    const rebuild = () => {
        state.frame = frameOf();
        runner.setUniforms(state.useBundleUniforms ? exported : state.frame.uniforms);
        const t0 = performance.now();
        runner.runPhase("shadow", drawScene, null, state.bundleSlices ? {slicing: replaceSlicing} : {});
        for (const [name, texels] of Object.entries(callerTextures)) runner.fillTexture(name, bundle.width, bundle.height, texels);
        runner.runPhase("screen", null, {width: bundle.width, height: bundle.height});
        gl.finish();
        state.shadowMs = performance.now() - t0;
    };

    // Display: the example phase with an orbit camera, or the deferred visibility image.
    const centre = [0, 1, 2].map((i) => 0.5 * (box.lo[i] + box.hi[i]));
    const radius = 0.5 * Math.hypot(...[0, 1, 2].map((i) => box.hi[i] - box.lo[i]));
    const visibilityProgram = makeBlitProgram(gl);
    const draw = () => {
        gl.viewport(0, 0, canvas.width, canvas.height);
        if (state.view === "visibility") {
            blit(gl, visibilityProgram, runner.texture(runner.layout.result).id);
            return;
        }
        const distance = 1.05 * radius / Math.sin(Math.PI / 8);
        const eye = [centre[0] + distance * Math.cos(state.pitch) * Math.sin(state.yaw), centre[1] + distance * Math.sin(state.pitch),
                     centre[2] + distance * Math.cos(state.pitch) * Math.cos(state.yaw)];
        const clip = multiply(perspective(Math.PI / 4, canvas.width / canvas.height, 0.01 * distance, distance + 3 * radius),
                              lookAt(eye, centre, [0, 1, 0]));
        const toLight = light.kind === "sun" ? [-light.direction[0], -light.direction[1], -light.direction[2], 0] : [...light.center, 1];
        runner.setUniforms({penumbra_clipFromWorld: clip, penumbra_toLight: toLight});
        runner.runPhase("example", drawScene, {width: canvas.width, height: canvas.height});
    };

    const update = () => {
        rebuild();
        draw();
        $("status").textContent = `${config.slices} slices, ${config.resolution}², ${config.filter}, ${config.packing}, ${light.kind}` +
            ` — shadow + screen phases ${state.shadowMs.toFixed(1)} ms` +
            (state.frame.contained ? "" : " — the bounds reach the light plane: move the light up") +
            (state.useBundleUniforms ? " — uniforms from the bundle (light controls ignored)" : " — uniforms computed in JavaScript");
    };
    buildControls(light, box, state, update, draw);
    update();

    // Automation.
    window.penumbra = {
        readVisibility: () => runner.readResult(),
        readTexture: (name, level, layer) => runner.readTexture(name, level, layer),
        setLight: (changes) => { Object.assign(light, changes); update(); },
        useBundleUniforms: (on) => { state.useBundleUniforms = on; update(); },
        // Texels where our own slicing output differs from the desktop run's (slices.f32).
        compareSlices: async () => {
            const desktop = new Float32Array(await (await fetchOk(base + "slices.f32")).arrayBuffer());
            const pass = runner.layout.passes.find((p) => p.name === "slicing");
            let differing = 0, covered = 0;
            pass.outputs.forEach((out, t) => {
                const ours = runner.readTexture(out.texture, out.level, out.layer);
                for (let c = 0; c < 4 && 4 * t + c < config.slices; ++c)
                    for (let i = 0; i < R * R; ++i) {
                        const d = desktop[(4 * t + c) * R * R + i];
                        covered += d > 0.5 ? 1 : 0;
                        differing += Math.abs(ours[4 * i + c] - d) > 0.5 ? 1 : 0;
                    }
            });
            return {differing, covered, texels: config.slices * R * R};
        },
        // The desktop run's slicing output instead of the browser's own rasterization (slices.f32).
        useBundleSlices: async (on) => {
            state.bundleSlices = on ? new Float32Array(await (await fetchOk(base + "slices.f32")).arrayBuffer()) : null;
            update();
        },
        uniforms: () => ({computed: state.frame.uniforms, bundle: exported}),
        render: () => { update(); return state.shadowMs; },
        info: () => {
            const debug = gl.getExtension("WEBGL_debug_renderer_info");
            return {renderer: gl.getParameter(debug ? debug.UNMASKED_RENDERER_WEBGL : gl.RENDERER),
                    version: gl.getParameter(gl.VERSION), extensions: runner.extensions, config,
                    width: bundle.width, height: bundle.height, resultFormat: runner.texture(runner.layout.result).desc.internal_format};
        },
    };
}

function makeBlitProgram(gl) {
    const vs = `#version 300 es
void main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2); gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0); }`;
    const fs = `#version 300 es
precision highp float;
uniform sampler2D image;
uniform vec2 size;
out vec4 color;
void main() { color = vec4(vec3(texture(image, gl_FragCoord.xy / size).r), 1.0); }`;
    const program = gl.createProgram();
    for (const [type, text] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
        const s = gl.createShader(type);
        gl.shaderSource(s, text);
        gl.compileShader(s);
        gl.attachShader(program, s);
    }
    gl.linkProgram(program);
    return {program, vao: gl.createVertexArray()};
}

function blit(gl, {program, vao}, texture) {
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.useProgram(program);
    gl.uniform2f(gl.getUniformLocation(program, "size"), gl.drawingBufferWidth, gl.drawingBufferHeight);
    gl.activeTexture(gl.TEXTURE0);
    gl.bindTexture(gl.TEXTURE_2D, texture);
    gl.bindVertexArray(vao);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.bindVertexArray(null);
    gl.useProgram(null);
}

function buildControls(light, box, state, update, draw) {
    const panel = $("controls");
    const span = Math.max(box.hi[0] - box.lo[0], box.hi[2] - box.lo[2], 1e-3);
    const slider = (label, min, max, value, onInput) => {
        const row = document.createElement("label");
        const input = Object.assign(document.createElement("input"), {type: "range", min, max, step: (max - min) / 200, value});
        const shown = document.createElement("span");
        shown.textContent = Number(value).toFixed(2);
        input.addEventListener("input", () => { shown.textContent = Number(input.value).toFixed(2); onInput(Number(input.value)); });
        row.append(label + " ", input, " ", shown);
        panel.append(row);
    };
    if (light.kind === "rect") {
        ["x", "y", "z"].forEach((axis, i) => {
            const lo = i === 1 ? box.hi[1] + 0.05 * span : box.lo[i] - 0.5 * span;
            const hi = i === 1 ? box.hi[1] + 2 * span : box.hi[i] + 0.5 * span;
            slider(`light ${axis}`, lo, hi, light.center[i], (v) => { light.center[i] = v; update(); });
        });
        const aspect = light.height / light.width;
        slider("light width", 0.01 * span, span, light.width, (v) => { light.width = v; light.height = v * aspect; update(); });
    } else {
        const d = light.direction;
        let azimuth = Math.atan2(d[2], d[0]), elevation = Math.asin(Math.min(1, -d[1] / Math.hypot(...d)));
        const set = () => {
            light.direction = [Math.cos(elevation) * Math.cos(azimuth), -Math.sin(elevation), Math.cos(elevation) * Math.sin(azimuth)];
            update();
        };
        slider("sun azimuth", -Math.PI, Math.PI, azimuth, (v) => { azimuth = v; set(); });
        slider("sun elevation", 0.2, Math.PI / 2, elevation, (v) => { elevation = v; set(); });
        slider("sun diameter (°)", 0.1, 10, light.angularDiameter * 180 / Math.PI, (v) => { light.angularDiameter = v * Math.PI / 180; update(); });
    }
    slider("camera yaw", -Math.PI, Math.PI, state.yaw, (v) => { state.yaw = v; draw(); });
    slider("camera pitch", 0.05, 1.5, state.pitch, (v) => { state.pitch = v; draw(); });
    const view = document.createElement("select");
    for (const [value, text] of [["shaded", "shaded scene (shading_example)"], ["visibility", "visibility (shading_deferred over the bundle's G-buffer)"]])
        view.append(Object.assign(document.createElement("option"), {value, textContent: text}));
    view.addEventListener("change", () => { state.view = view.value; draw(); });
    const source = Object.assign(document.createElement("input"), {type: "checkbox"});
    source.addEventListener("change", () => { state.useBundleUniforms = source.checked; update(); });
    const sourceLabel = document.createElement("label");
    sourceLabel.append(source, " use the bundle's exported uniforms");
    panel.append(view, sourceLabel);
}

main().catch((error) => {
    $("status").textContent = "error: " + error.message;
    window.penumbra = {error: error.message};
    console.error(error);
});
