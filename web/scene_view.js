// scene_view.js — what the page draws around a layout: the scene's triangles, the G-buffer the
// layouts leave to the caller (world positions, w = 1 on geometry; world normals of the side the
// camera sees; both RGBA32F, as penumbra-export-bundle writes them), and the composite of the
// layout's result into the canvas (shaded, visibility only, or the difference from a reference).
//
//   const scene = new SceneGeometry(gl, triangles);   // attribute 0 position, 1 flat normal
//   const gbuffer = new GBuffer(gl);
//   gbuffer.render(scene, clipFromWorld, eye, width, height, {positions, normals}); // into those textures
//   composite.draw({...}, viewport)

function compile(gl, vertex, fragment) {
    const program = gl.createProgram();
    for (const [type, text] of [[gl.VERTEX_SHADER, vertex], [gl.FRAGMENT_SHADER, fragment]]) {
        const s = gl.createShader(type);
        gl.shaderSource(s, text);
        gl.compileShader(s);
        if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`scene_view.js shader: ${gl.getShaderInfoLog(s)}`);
        gl.attachShader(program, s);
        gl.deleteShader(s);
    }
    gl.linkProgram(program);
    if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(`scene_view.js program: ${gl.getProgramInfoLog(program)}`);
    return program;
}

export function bounds(triangles) {
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

// Where SceneGeometry's vertex array holds positions and flat normals (the G-buffer shader below
// reads them there; layout.json's vertex_inputs must agree for the runner's draw_scene passes).
export const SCENE_POSITION_LOCATION = 0, SCENE_NORMAL_LOCATION = 1;

export class SceneGeometry {
    constructor(gl, triangles) {
        this.gl = gl;
        this.triangles = triangles;
        this.box = bounds(triangles);
        this.vao = gl.createVertexArray();
        this.buffers = [];
        gl.bindVertexArray(this.vao);
        [[SCENE_POSITION_LOCATION, triangles], [SCENE_NORMAL_LOCATION, flatNormals(triangles)]].forEach(([location, data]) => {
            const buffer = gl.createBuffer();
            gl.bindBuffer(gl.ARRAY_BUFFER, buffer);
            gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
            gl.enableVertexAttribArray(location);
            gl.vertexAttribPointer(location, 3, gl.FLOAT, false, 0, 0);
            this.buffers.push(buffer);
        });
        gl.bindVertexArray(null);
        this.count = triangles.length / 3;
    }

    draw() {
        this.gl.bindVertexArray(this.vao);
        this.gl.drawArrays(this.gl.TRIANGLES, 0, this.count);
        this.gl.bindVertexArray(null);
    }

    dispose() {
        for (const b of this.buffers) this.gl.deleteBuffer(b);
        this.gl.deleteVertexArray(this.vao);
    }
}

const GBUFFER_VS = `#version 300 es
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
uniform mat4 clipFromWorld;
out vec3 worldPosition;
out vec3 worldNormal;
void main() {
    worldPosition = position;
    worldNormal = normal;
    gl_Position = clipFromWorld * vec4(position, 1.0);
}`;
const GBUFFER_FS = `#version 300 es
precision highp float;
uniform vec3 eye;
in vec3 worldPosition;
in vec3 worldNormal;
layout(location = 0) out vec4 positionOut;
layout(location = 1) out vec4 normalOut;
void main() {
    vec3 n = normalize(worldNormal);
    if (dot(n, eye - worldPosition) < 0.0) n = -n; // the side the camera sees
    positionOut = vec4(worldPosition, 1.0);
    normalOut = vec4(n, 0.0);
}`;

// A G-buffer pass into two RGBA32F textures of the caller (the layout's caller textures, or the
// page's own where the layout has none), with a depth renderbuffer of the same size.
export class GBuffer {
    constructor(gl) {
        this.gl = gl;
        this.program = compile(gl, GBUFFER_VS, GBUFFER_FS);
        this.framebuffer = gl.createFramebuffer();
        this.depth = gl.createRenderbuffer();
        this.size = null;
        this.own = {};
    }

    // A page-owned RGBA32F texture of this size, for a G-buffer the layout does not declare.
    ownTexture(name, width, height) {
        const gl = this.gl;
        const key = `${name} ${width}x${height}`;
        if (!this.own[key]) {
            const id = gl.createTexture();
            gl.bindTexture(gl.TEXTURE_2D, id);
            gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, width, height);
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
            gl.bindTexture(gl.TEXTURE_2D, null);
            this.own[key] = {id, target: gl.TEXTURE_2D, width, height};
        }
        return this.own[key];
    }

    render(scene, clipFromWorld, eye, width, height, {positions, normals}) {
        const gl = this.gl;
        if (!this.size || this.size[0] !== width || this.size[1] !== height) {
            gl.bindRenderbuffer(gl.RENDERBUFFER, this.depth);
            gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, width, height);
            gl.bindRenderbuffer(gl.RENDERBUFFER, null);
            this.size = [width, height];
        }
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, positions.id, 0);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT1, gl.TEXTURE_2D, normals.id, 0);
        gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, this.depth);
        gl.drawBuffers([gl.COLOR_ATTACHMENT0, gl.COLOR_ATTACHMENT1]);
        const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
        if (status !== gl.FRAMEBUFFER_COMPLETE) throw new Error(`G-buffer framebuffer incomplete (0x${status.toString(16)})`);
        gl.viewport(0, 0, width, height);
        gl.clearBufferfv(gl.COLOR, 0, [0, 0, 0, 0]);
        gl.clearBufferfv(gl.COLOR, 1, [0, 0, 0, 0]);
        gl.clearBufferfi(gl.DEPTH_STENCIL, 0, 1, 0);
        gl.enable(gl.DEPTH_TEST);
        gl.depthFunc(gl.LESS);
        gl.depthMask(true);
        gl.disable(gl.BLEND);
        gl.disable(gl.CULL_FACE);
        gl.useProgram(this.program);
        gl.uniformMatrix4fv(gl.getUniformLocation(this.program, "clipFromWorld"), false, clipFromWorld);
        gl.uniform3fv(gl.getUniformLocation(this.program, "eye"), eye);
        scene.draw();
        gl.useProgram(null);
        gl.disable(gl.DEPTH_TEST);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT1, gl.TEXTURE_2D, null, 0);
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    }
}

const FULLSCREEN_VS = `#version 300 es
void main() { vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2); gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0); }`;
// mode 0 shaded, 1 visibility, 2 |visibility − reference| (red: brighter, blue: darker; grey where
// the reference is NaN: a truth that sees none of the light)
const COMPOSITE_FS = `#version 300 es
precision highp float;
uniform highp sampler2D visibility;
uniform highp sampler2D positions;
uniform highp sampler2D normals;
uniform highp sampler2D reference;
uniform vec4 area;      // x, y, width, height of the canvas rectangle the images cover
uniform vec4 toLight;   // (centre, 1) for a rectangle, (direction to the sun, 0)
uniform int mode;
out vec4 color;
void main() {
    ivec2 size = textureSize(visibility, 0);
    vec2 uv = (gl_FragCoord.xy - area.xy) / area.zw;
    ivec2 texel = clamp(ivec2(uv * vec2(size)), ivec2(0), size - 1);
    float v = texelFetch(visibility, texel, 0).r;
    vec4 p = texelFetch(positions, texel, 0);
    if (mode == 1) { color = vec4(vec3(p.w > 0.5 ? v : 0.0), 1.0); return; }
    if (mode == 2) {
        float r = texelFetch(reference, texel, 0).r;
        if (isnan(r)) { color = vec4(0.3, 0.3, 0.3, 1.0); return; } // the truth is undefined there
        float d = v - r;
        float e = clamp(abs(d) * 4.0, 0.0, 1.0);
        color = p.w > 0.5 ? vec4(d > 0.0 ? vec3(1.0, 1.0 - e, 1.0 - e) : vec3(1.0 - e, 1.0 - e, 1.0), 1.0) : vec4(0.1, 0.1, 0.1, 1.0);
        return;
    }
    if (p.w < 0.5) { color = vec4(0.13, 0.14, 0.17, 1.0); return; }
    vec3 n = normalize(texelFetch(normals, texel, 0).xyz);
    vec3 l = toLight.w > 0.5 ? normalize(toLight.xyz - p.xyz) : normalize(toLight.xyz);
    float lit = max(dot(n, l), 0.0);
    color = vec4(vec3(0.82, 0.8, 0.76) * (0.12 + 0.88 * lit * v), 1.0);
}`;

export class Composite {
    constructor(gl) {
        this.gl = gl;
        this.program = compile(gl, FULLSCREEN_VS, COMPOSITE_FS);
        this.vao = gl.createVertexArray();
        this.white = gl.createTexture();
        gl.bindTexture(gl.TEXTURE_2D, this.white);
        gl.texStorage2D(gl.TEXTURE_2D, 1, gl.R32F, 1, 1);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
        gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
        gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, 1, 1, gl.RED, gl.FLOAT, new Float32Array([1]));
        gl.bindTexture(gl.TEXTURE_2D, null);
    }

    // textures: {visibility, positions, normals, reference (optional)} GL texture ids, images of
    // the whole canvas; canvas: [width, height]; area: the rectangle [x, y, w, h] of the canvas to
    // draw (a split view's half); mode "shaded" | "visibility" | "difference" | "error".
    draw(textures, canvas, area, mode, toLight) {
        const gl = this.gl;
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
        gl.viewport(0, 0, canvas[0], canvas[1]);
        gl.enable(gl.SCISSOR_TEST);
        gl.scissor(area[0], area[1], area[2], area[3]);
        gl.disable(gl.DEPTH_TEST);
        gl.disable(gl.BLEND);
        gl.colorMask(true, true, true, true);
        gl.useProgram(this.program);
        const units = ["visibility", "positions", "normals", "reference"];
        units.forEach((name, unit) => {
            gl.activeTexture(gl.TEXTURE0 + unit);
            gl.bindTexture(gl.TEXTURE_2D, textures[name] ?? this.white);
            gl.uniform1i(gl.getUniformLocation(this.program, name), unit);
        });
        gl.uniform4fv(gl.getUniformLocation(this.program, "area"), [0, 0, canvas[0], canvas[1]]);
        gl.uniform4fv(gl.getUniformLocation(this.program, "toLight"), toLight);
        gl.uniform1i(gl.getUniformLocation(this.program, "mode"), {shaded: 0, visibility: 1, difference: 2, error: 2}[mode]);
        gl.bindVertexArray(this.vao);
        gl.drawArrays(gl.TRIANGLES, 0, 3);
        gl.bindVertexArray(null);
        for (let unit = 0; unit < units.length; ++unit) {
            gl.activeTexture(gl.TEXTURE0 + unit);
            gl.bindTexture(gl.TEXTURE_2D, null);
        }
        gl.activeTexture(gl.TEXTURE0);
        gl.useProgram(null);
        gl.disable(gl.SCISSOR_TEST);
    }
}

// Camera helpers (column-major 4×4).
export function perspective(fovY, aspect, near, far) {
    const f = 1 / Math.tan(fovY / 2);
    return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, 2 * far * near / (near - far), 0];
}

export function lookAt(eye, target, up) {
    const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    const norm = (a) => { const l = Math.hypot(...a); return a.map((x) => x / l); };
    const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    const f = norm(sub(target, eye)), s = norm(cross(f, up)), u = cross(s, f);
    return [s[0], u[0], -f[0], 0, s[1], u[1], -f[1], 0, s[2], u[2], -f[2], 0, -dot(s, eye), -dot(u, eye), dot(f, eye), 1];
}

export function multiply(a, b) {
    const m = new Array(16).fill(0);
    for (let c = 0; c < 4; ++c) for (let r = 0; r < 4; ++r) for (let k = 0; k < 4; ++k) m[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
    return m;
}
