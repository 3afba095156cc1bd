// penumbra_babylon_webgpu.js — what penumbra_babylon.js needs on Babylon's WebGPUEngine (users do
// not import it; PenumbraShadows.load picks it when engine.isWebGPU):
//
//   - the wgsl emission (penumbra-gen --target wgsl: WGSL + layout.json) runs on the engine's own
//     GPUDevice (engine._device) through the WebGPU layout runner penumbra-three uses
//     (shared/penumbra_webgpu_runner.js), which follows layout.json. The shadow phase is submitted
//     on the device's queue by update(), before Babylon submits its frame (flushFramebuffer, at the
//     end of the frame), so the frame samples finished occlusion textures;
//   - the runner's textures are handed to Babylon as InternalTextures around their GPUTexture
//     (WebGPUHardwareTexture), sampled as layout.json says (Babylon makes the sampler from the
//     texture's sampling mode and wrap);
//   - penumbra_visibility.wgsl is rewritten for Babylon's WGSL shader processor (wgslForBabylon):
//     its uniform block goes (its members come from the material's uniform buffer, `uniforms.`),
//     its bindings go (Babylon numbers them), and each sampler is renamed <texture>Sampler, the
//     name Babylon binds a texture's sampler by;
//   - cut-out casters (an emission with the alpha test): each draw's bind group gets its material's
//     texture (Babylon's GPUTexture, read as it is), its cutoff and its texture coordinates (a vertex
//     buffer here), through the runner's per-draw textures (setDrawUniforms' third argument).
import {InternalTexture} from "@babylonjs/core/Materials/Textures/internalTexture.js";
import {BaseTexture} from "@babylonjs/core/Materials/Textures/baseTexture.js";
import {WebGPUHardwareTexture} from "@babylonjs/core/Engines/WebGPU/webgpuHardwareTexture.js";
// (the includes of the visibility material's WGSL vertex stage: instances and thin instances)
import "@babylonjs/core/ShadersWGSL/ShadersInclude/instancesDeclaration.js";
import "@babylonjs/core/ShadersWGSL/ShadersInclude/instancesVertex.js";
import {WebGPULayoutRunner} from "./shared/penumbra_webgpu_runner.js";
import {fail, loadEmissionFiles} from "./shared/penumbra_emission.js";

export const WGSL_TYPES = {float: "f32", vec2: "vec2f", vec3: "vec3f", vec4: "vec4f", mat4: "mat4x4f"};

export async function loadRunner(engine, emission, kind, wasm) {
    const files = await loadEmissionFiles(emission, kind, wasm, "wgsl");
    const runner = await WebGPULayoutRunner.fromEmission(engine._device, files);
    runner.sources = files.files;
    return runner;
}

// penumbra_visibility.wgsl (already renamed penumbra<N>…) as module code for a Babylon material:
// no bindings, no uniform block (its loader reads `uniforms.<member>`), samplers named <texture>Sampler.
export function wgslForBabylon(snippet) {
    let code = snippet.replace(/\/\/[^\n]*/g, "");
    const block = /@group\(\s*\d+\s*\)\s*@binding\(\s*\d+\s*\)\s*var<uniform>\s*(\w+)\s*:\s*(\w+)\s*;/.exec(code);
    if (block) {
        code = code.replace(block[0], "").replace(new RegExp(`struct\\s+${block[2]}\\s*\\{[^}]*\\}\\s*;?`), "")
            .replace(new RegExp(`\\b${block[1]}\\.`, "g"), "uniforms.");
    }
    code = code.replace(/@group\(\s*\d+\s*\)\s*@binding\(\s*\d+\s*\)\s*/g, "");
    for (const [, texture] of code.matchAll(/var\s+(\w+)_sampler\s*:\s*sampler\s*;/g))
        code = code.replace(new RegExp(`\\b${texture}_sampler\\b`, "g"), `${texture}Sampler`);
    return withoutSaturate(code).replace(/\n\s*\n\s*\n+/g, "\n\n");
}

// Babylon's materials declare fn saturate(x: f32) -> f32 (ShadersWGSL helperFunctions), which
// hides WGSL's built-in saturate for vectors: saturate(e) becomes clamp(e, e * 0.0, e * 0.0 + 1.0),
// the same for f32 and vectors (scalar-vector arithmetic splats; e has no side effects in the snippet).
function withoutSaturate(code) {
    for (let at = code.search(/\bsaturate\s*\(/); at >= 0; at = code.search(/\bsaturate\s*\(/)) {
        const open = code.indexOf("(", at);
        let i = open + 1;
        for (let depth = 1; depth > 0; ++i) depth += code[i] === "(" ? 1 : code[i] === ")" ? -1 : 0;
        const e = `(${code.slice(open + 1, i - 1)})`;
        code = `${code.slice(0, at)}clamp(${e}, ${e} * 0.0, ${e} * 0.0 + 1.0)${code.slice(i)}`;
    }
    return code;
}

// The shadow function (the visibility of the side the camera sees, mixed towards 1 by 1 - intensity)
// and the light loop's line, in WGSL; `names` as penumbra_babylon.js's _names.
export function wgslShadowFunction(names, load, visibility, tangentClip) {
    return `
fn ${names.shadow}(normalWorld: vec3f, positionWorld: vec3f, eye: vec3f) -> f32 {
    if (uniforms.${names.intensity} <= 0.0) { return 1.0; }
    ${load ? `${load}();` : ""}
    var n: vec3f = normalize(normalWorld);
    if (dot(n, eye - positionWorld) < 0.0) { n = -n; }
    let v: f32 = ${visibility}${tangentClip ? "WithNormal(positionWorld, n)" : "(positionWorld)"};
    return mix(1.0, v, uniforms.${names.intensity});
}
`;
}

// Babylon's sampling mode for layout.json's GL filters (Constants.TEXTURE_*_SAMPLINGMODE) and
// whether the sampler reads the mip chain.
const SAMPLING = {
    "NEAREST/NEAREST": 1, "LINEAR/LINEAR": 2, "LINEAR_MIPMAP_LINEAR/LINEAR": 3, "NEAREST_MIPMAP_NEAREST/NEAREST": 4,
    "LINEAR_MIPMAP_NEAREST/NEAREST": 5, "LINEAR_MIPMAP_LINEAR/NEAREST": 6, "LINEAR/NEAREST": 7, "NEAREST_MIPMAP_LINEAR/NEAREST": 8,
    "NEAREST_MIPMAP_NEAREST/LINEAR": 9, "NEAREST_MIPMAP_LINEAR/LINEAR": 10, "LINEAR_MIPMAP_NEAREST/LINEAR": 11, "NEAREST/LINEAR": 12,
};

// A texture of the runner as a Babylon texture that binds its GPUTexture as is, sampled as the
// snippet's parameter (or the texture's description) says.
export function wrapTexture(engine, scene, t, sampling) {
    // (Babylon declares a material's textures as filterable float, which 32-bit float formats are not)
    if (t.format.endsWith("32float")) fail(`the emission's ${t.desc.name} is ${t.format}, which WebGPU cannot filter; use level_format rgba8 or rgba16f`);
    const key = `${sampling.min_filter}/${sampling.mag_filter}`;
    const mode = SAMPLING[key] ?? fail(`the emission's ${t.desc.name}: filters ${key} have no Babylon sampling mode`);
    const internal = new InternalTexture(engine, 0 /* InternalTextureSource.Unknown */, true);
    const hardware = new WebGPUHardwareTexture(engine, t.texture);
    hardware.format = hardware.originalFormat = t.format;
    const dimension = t.dimension === "3d" ? "3d" : t.desc.target === "2D_ARRAY" ? "2d-array" : "2d";
    hardware.createView({label: t.desc.name, dimension});
    internal._hardwareTexture = hardware;
    internal.baseWidth = internal.width = t.width;
    internal.baseHeight = internal.height = t.height;
    internal.baseDepth = internal.depth = t.layers;
    internal.is2DArray = dimension === "2d-array";
    internal.is3D = dimension === "3d";
    internal.samplingMode = mode;
    internal.generateMipMaps = internal.useMipMaps = (t.desc.mip_levels || 1) > 1 && /MIPMAP/.test(sampling.min_filter);
    internal.isReady = true;
    const wrap = {CLAMP_TO_EDGE: 0, REPEAT: 1, MIRRORED_REPEAT: 2}[sampling.wrap ?? t.desc.wrap] ?? 0;
    const texture = new BaseTexture(scene, internal);
    texture.wrapU = texture.wrapV = texture.wrapR = wrap;
    texture.anisotropicFilteringLevel = 1;
    return texture;
}

// The casters' GPU buffers and draws in the slicing passes.
export class WebGPUCasters {
    constructor(device) {
        this.device = device;
        this.geometries = new Map(); // Geometry (or deformed mesh) → {position, index, count, vertices}
        this.zeros = null; // a vertex buffer of zeros for vertex inputs other than the position
    }

    _upload(old, data, usage) {
        const size = Math.max(Math.ceil(data.byteLength / 4) * 4, 4); // writeBuffer copies whole 4-byte words
        const buffer = old && old.size === size ? old
            : (old && old.destroy(), this.device.createBuffer({label: "penumbra caster", size, usage: usage | GPUBufferUsage.COPY_DST}));
        const padded = new Uint8Array(size);
        padded.set(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
        this.device.queue.writeBuffer(buffer, 0, padded);
        return buffer;
    }

    // `key`: the Geometry (uploaded once) or a deformed mesh (uploaded at every shadow update);
    // positionsOf(), indicesOf(): its vertex data, read only when uploaded. null without positions.
    geometry(key, positionsOf, indicesOf, once) {
        let g = this.geometries.get(key);
        if (g && once) return g;
        const positions = positionsOf(), indices = indicesOf();
        if (!positions) return null;
        if (!g) this.geometries.set(key, (g = {position: null, index: null}));
        g.position = this._upload(g.position, Float32Array.from(positions), GPUBufferUsage.VERTEX);
        g.vertices = positions.length / 3;
        if (indices && indices.length) {
            g.index = this._upload(g.index, Uint32Array.from(indices), GPUBufferUsage.INDEX);
            g.count = indices.length;
        } else {
            if (g.index) g.index.destroy();
            g.index = null;
            g.count = g.vertices;
        }
        g.indexed = !!g.index;
        return g;
    }

    // The vertex buffer of a cut's texture coordinates (penumbra_babylon.js's cutCoordinates: c) on
    // geometry g, one per uv set and texture transform; null without c (the mesh has no such uv set).
    uvBuffer(g, c) {
        if (!c) return null;
        g.uvs ||= new Map();
        let entry = g.uvs.get(c.key);
        if (!entry || entry.data !== c.data) { // (new, or the uv set's VertexBuffer was replaced)
            const uvs = c.compute();
            if (entry) entry.buffer.destroy();
            g.uvs.set(c.key, (entry = {data: c.data, buffer: this.device.createBuffer({label: "penumbra caster uv", size: Math.max(uvs.byteLength, 4),
                                                                                       usage: GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_DST})}));
            this.device.queue.writeBuffer(entry.buffer, 0, uvs);
        }
        entry.used = true;
        return entry.buffer;
    }

    // After a shadow phase is submitted: the coordinates no draw used go (WebGPU keeps a destroyed
    // buffer's memory until the work submitted with it is done).
    dropUnusedUVs(g) {
        if (!g.uvs) return;
        for (const [key, entry] of g.uvs) {
            if (!entry.used) { entry.buffer.destroy(); g.uvs.delete(key); }
            else entry.used = false;
        }
    }

    // A drawScene callback for the runner: each placement [g, world, source] with each "...FromWorld"
    // matrix of the program times its world matrix, in a uniform buffer of its own, each of its
    // source's draws (draws.get(source): {first, count, cut, texture, uv}). A program with the alpha
    // test (parameters whose source is "draw": the alpha texture and cutoff; vertex input penumbra_uv)
    // gets each cut draw's texture, cutoff and coordinates, or the runner's white texture, cutoff 0 and zeros.
    drawer(runner, drawn, multiply, draws) {
        const needsZeros = runner.layout.programs.some((p) => (p.vertex_inputs || []).some((v) => v.name !== "penumbra_position"));
        if (needsZeros) {
            const bytes = Math.max(16 * drawn.reduce((n, [g]) => Math.max(n, g.vertices), 0), 16);
            if (!this.zeros || this.zeros.size < bytes) {
                if (this.zeros) this.zeros.destroy();
                this.zeros = this.device.createBuffer({label: "penumbra zeros", size: bytes, usage: GPUBufferUsage.VERTEX});
            }
        }
        return (render, program, setDrawUniforms) => {
            const matrices = program.parameters.filter((p) => p.type === "mat4" && /FromWorld$/.test(p.name));
            const alphaTexture = program.parameters.find((p) => p.source === "draw" && p.texture_type !== undefined);
            const cutoff = program.parameters.find((p) => p.source === "draw" && p.block !== undefined);
            let slot = 0;
            for (const [g, world, source] of drawn) {
                const values = {};
                for (const p of matrices) values[p.name] = multiply(runner.uniformValues[p.name], world);
                for (const d of draws.get(source)) {
                    const cut = alphaTexture && d.cut && d.texture && d.uv ? d : null; // (no texture or coordinates yet: solid)
                    if (cutoff) values[cutoff.name] = cut ? cut.cut.cutoff : 0;
                    setDrawUniforms(values, slot++, cut ? {[alphaTexture.name]: cut.texture} : null);
                    (program.vertex_inputs || []).forEach((v, location) =>
                        render.setVertexBuffer(location, v.name === "penumbra_position" ? g.position : v.name === "penumbra_uv" && cut ? cut.uv : this.zeros));
                    if (g.index) {
                        render.setIndexBuffer(g.index, "uint32");
                        render.drawIndexed(d.count, 1, d.first);
                    } else {
                        render.draw(d.count, 1, d.first);
                    }
                }
            }
        };
    }

    dispose() {
        for (const g of this.geometries.values()) {
            g.position.destroy();
            if (g.index) g.index.destroy();
            for (const entry of (g.uvs || new Map()).values()) entry.buffer.destroy();
        }
        this.geometries.clear();
        if (this.zeros) this.zeros.destroy();
        this.zeros = null;
    }
}

// The visibility material's WGSL stages (renderVisibility): `definitions` the snippet and the
// shadow function, `uniforms` their WGSL declarations.
export function visibilityShadersWGSL(definitions, uniforms, names) {
    return {
        vertexSource: `attribute position: vec3f;
attribute normal: vec3f;
#include<instancesDeclaration>
uniform viewProjection: mat4x4f;
varying vPositionW: vec3f;
varying vNormalW: vec3f;
@vertex
fn main(input: VertexInputs) -> FragmentInputs {
#include<instancesVertex>
    let p: vec4f = finalWorld * vec4f(vertexInputs.position, 1.0);
    vertexOutputs.vPositionW = p.xyz;
    vertexOutputs.vNormalW = (finalWorld * vec4f(vertexInputs.normal, 0.0)).xyz;
    vertexOutputs.position = uniforms.viewProjection * p;
}`,
        fragmentSource: `${uniforms}
uniform penumbraEye: vec3f;
${definitions}
varying vPositionW: vec3f;
varying vNormalW: vec3f;
@fragment
fn main(input: FragmentInputs) -> FragmentOutputs {
    var v: f32 = 1.0;
    if (uniforms.${names.lightIndex} >= 0.0) { v = ${names.shadow}(fragmentInputs.vNormalW, fragmentInputs.vPositionW, uniforms.penumbraEye); }
    fragmentOutputs.color = vec4f(v, v, v, 1.0);
}`,
    };
}
