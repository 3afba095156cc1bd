// penumbra_webgpu_runner.js — runs a `wgsl` emission on WebGPU by following its layout.json alone, as
// three/penumbra_runner.js does for the essl300 emission on WebGL2: the textures of `textures` (their
// `webgpu` format and usage), the programs of `programs` (one WGSL module a stage, entry point
// `main`; one bind group layout a program, from its parameters' `group`, `binding`,
// `sampler_binding`, `block_binding`, `offset`), and the passes of `passes` in order with their
// render state, inputs and attachments. It reads nothing of Penumbra's C++ source.
//
//   const adapter = await navigator.gpu.requestAdapter(), device = await adapter.requestDevice();
//   const runner = await WebGPULayoutRunner.load(device, "emission/");      // layout.json + its files
//   const runner = await WebGPULayoutRunner.fromEmission(device, emission);  // or {files, layout} in memory
//   runner.setUniforms({penumbra_lightFromWorld: [...16], ...});            // by parameter name
//   await runner.runPhase("shadow", runner.sceneDrawer(positions));          // the depth / slicing passes
//   runner.fillTexture("penumbra_worldPositions", w, h, positions);          // a "caller" texture
//   await runner.runPhase("screen", null, {width: w, height: h});            // deferred visibility
//   const visibility = await runner.readResult();                           // Float32Array, bottom row first
//
// A test or a debugging tool can put its own data in place of a pass's output: load with
// {writable: [texture names]} (those textures get COPY_DST besides the layout's usage), then
// runPhase(phase, draw, size, {<pass name>: (pass) => runner.uploadTexture(...)}) calls the callback
// where that pass would run.
//
// Rows: the runner uploads and reads back texture rows in memory order, as WebGL2's runner does
// (row 0 first); a caller texture filled bottom row first gives a result bottom row first. Clip
// space is WebGPU's; the emitted vertex stages write it (WGSL.md), the runner changes nothing.

const LAYOUT_VERSION = 3;

// WebGPU texture formats the runner reads back or fills: bytes a texel, channels, component type.
const FORMATS = {
    "r8unorm": {bytes: 1, channels: 1, type: "unorm8"},
    "rgba8unorm": {bytes: 4, channels: 4, type: "unorm8"},
    "r32float": {bytes: 4, channels: 1, type: "float32"},
    "rg32float": {bytes: 8, channels: 2, type: "float32"},
    "rgba32float": {bytes: 16, channels: 4, type: "float32"},
    "r32uint": {bytes: 4, channels: 1, type: "uint32"},
    "rgba32uint": {bytes: 16, channels: 4, type: "uint32"},
    "r16float": {bytes: 2, channels: 1, type: "float16"},
    "rg16float": {bytes: 4, channels: 2, type: "float16"},
    "rgba16float": {bytes: 8, channels: 4, type: "float16"},
    "depth32float": {bytes: 4, channels: 1, type: "float32", depth: true},
    "depth24plus": {bytes: 4, channels: 1, type: null, depth: true},
};

// Plain uniform types: bytes in the uniform address space (WGSL.md: std140 sizes for these types)
// and how the values are written (matrices column-major; mat3 columns padded to 16 bytes).
const UNIFORM_TYPES = {
    float: {size: 4, kind: "f32"}, int: {size: 4, kind: "i32"}, uint: {size: 4, kind: "u32"}, bool: {size: 4, kind: "u32"},
    vec2: {size: 8, kind: "f32"}, vec3: {size: 12, kind: "f32"}, vec4: {size: 16, kind: "f32"},
    ivec2: {size: 8, kind: "i32"}, ivec3: {size: 12, kind: "i32"}, ivec4: {size: 16, kind: "i32"},
    uvec2: {size: 8, kind: "u32"}, uvec3: {size: 12, kind: "u32"}, uvec4: {size: 16, kind: "u32"},
    mat4: {size: 64, kind: "f32"}, mat3: {size: 48, kind: "f32", columns: 3},
};

const TEXTURE_USAGE = ["COPY_SRC", "COPY_DST", "TEXTURE_BINDING", "STORAGE_BINDING", "RENDER_ATTACHMENT"];
const COMPARE = {NEVER: "never", LESS: "less", EQUAL: "equal", LEQUAL: "less-equal", GREATER: "greater", NOTEQUAL: "not-equal",
                 GEQUAL: "greater-equal", ALWAYS: "always"};
const WRAP = {CLAMP_TO_EDGE: "clamp-to-edge", REPEAT: "repeat", MIRRORED_REPEAT: "mirror-repeat"};
const CULL = {NONE: "none", BACK: "back", FRONT: "front"};
const BLEND_OPERATION = {ADD: "add", FUNC_ADD: "add", SUBTRACT: "subtract", FUNC_SUBTRACT: "subtract",
                         REVERSE_SUBTRACT: "reverse-subtract", FUNC_REVERSE_SUBTRACT: "reverse-subtract", MIN: "min", MAX: "max"};
const BLEND_FACTOR = {ZERO: "zero", ONE: "one", SRC_COLOR: "src", ONE_MINUS_SRC_COLOR: "one-minus-src", SRC_ALPHA: "src-alpha",
                      ONE_MINUS_SRC_ALPHA: "one-minus-src-alpha", DST_COLOR: "dst", ONE_MINUS_DST_COLOR: "one-minus-dst",
                      DST_ALPHA: "dst-alpha", ONE_MINUS_DST_ALPHA: "one-minus-dst-alpha"};
const VERTEX_FORMATS = {float: "float32", vec2: "float32x2", vec3: "float32x3", vec4: "float32x4"};
// WGSL texture types (layout.json `texture_type`) to a view dimension.
const VIEW_DIMENSION = {texture_2d: "2d", texture_depth_2d: "2d", texture_2d_array: "2d-array", texture_depth_2d_array: "2d-array",
                        texture_3d: "3d", texture_cube: "cube"};

export class LayoutError extends Error {}

// Runs `work` in a validation error scope: the runner's own error first (it says more, e.g. Tint's
// line and column), else WebGPU's validation message.
async function validated(device, where, work) {
    device.pushErrorScope("validation");
    let failure = null;
    try {
        await work();
    } catch (e) {
        failure = e;
    }
    const error = await device.popErrorScope();
    if (failure) throw failure;
    if (error) fail(`WebGPU validation error ${where}: ${error.message}`);
}

function fail(message) {
    throw new LayoutError(message);
}

// The value of `table[key]`, or a clear error naming the field, the value and what is allowed.
function lookUp(table, key, what) {
    if (!(key in table)) fail(`${what}: '${key}' unknown; allowed: ${Object.keys(table).join(", ")}`);
    return table[key];
}

export class WebGPULayoutRunner {
    // What the adapter is, for a test's report: {vendor, architecture, device, description, isFallbackAdapter}.
    static describeAdapter(adapter) {
        const info = adapter.info || {};
        return {vendor: info.vendor || "", architecture: info.architecture || "", device: info.device || "",
                description: info.description || "", isFallbackAdapter: !!(info.isFallbackAdapter ?? adapter.isFallbackAdapter)};
    }

    // Fetches `${base}layout.json` and every program file it names. options.writable: names of
    // textures the caller will fill with uploadTexture although passes write them.
    static async load(device, base, options = {}) {
        const fetchText = async (name) => {
            const response = await fetch(base + name);
            if (!response.ok) fail(`${base}${name}: HTTP ${response.status}`);
            return response.text();
        };
        const layout = JSON.parse(await fetchText("layout.json"));
        const sources = {};
        for (const program of layout.programs || [])
            for (const file of program.files) if (!(file in sources)) sources[file] = await fetchText(file);
        return WebGPULayoutRunner.create(device, layout, sources, options);
    }

    // From an emission in memory: {files: {"<name>": text, ...}, layout} (layout: layout.json parsed;
    // taken from files["layout.json"] when absent), as penumbra_emitter.js's emit() returns it.
    static async fromEmission(device, {files, layout}, options = {}) {
        if (!files) fail("fromEmission: no files (an emission that failed? see its diagnostics)");
        const parsed = layout ?? (files["layout.json"] !== undefined ? JSON.parse(files["layout.json"]) : null);
        if (!parsed) fail("fromEmission: no layout and no layout.json among the files");
        for (const program of parsed.programs || [])
            for (const file of program.files) if (typeof files[file] !== "string") fail(`fromEmission: program ${program.name}: no file ${file}`);
        return WebGPULayoutRunner.create(device, parsed, files, options);
    }

    // Compiles every module (Tint's errors with file, line and column), makes the textures, bind
    // group layouts and pipelines; any WebGPU validation error fails here with its message.
    static async create(device, layout, sources, options = {}) {
        const runner = new WebGPULayoutRunner(device, layout, options);
        await validated(device, "while creating the layout's objects", async () => {
            await runner.compile(sources);
            for (const t of layout.textures) if (t.size !== "output") runner.textures[t.name] = runner.allocate(t, t.width, t.height);
            // (the example phase draws into the caller's own framebuffer, whose format the layout cannot give)
            layout.passes.forEach((pass, index) => pass.phase !== "example" && runner.pipeline(pass, index));
        });
        return runner;
    }

    constructor(device, layout, {writable = []} = {}) {
        if (layout.layout_version !== LAYOUT_VERSION)
            fail(`layout.json: layout_version ${layout.layout_version}; this runner reads version ${LAYOUT_VERSION}`);
        if (layout.config && layout.config.target !== "wgsl")
            fail(`layout.json: target '${layout.config.target}'; WebGPU runs the wgsl emission (penumbra-gen --target wgsl)`);
        this.device = device;
        this.layout = layout;
        for (const name of writable) this.description(name);
        this.writable = new Set(writable);
        this.uniformValues = {};
        this.outputSize = null;
        this.textures = {};
        this.modules = {};
        this.programs = {};
        this.pipelines = [];
        this.uniformBuffers = new Map(); // "<pass index> <block>" -> GPUBuffer
        this.samplers = {};
        this.drawTextures = {};
        this.passCount = 0;
    }

    description(name) {
        const t = this.layout.textures.find((d) => d.name === name);
        if (!t) fail(`no texture '${name}' in layout.json`);
        return t;
    }

    texture(name) {
        const t = this.textures[name];
        if (!t) fail(`no texture '${name}' in layout.json (or its size is "output" and no screen pass ran yet)`);
        return t;
    }

    async compile(sources) {
        const problems = [];
        for (const p of this.layout.programs) {
            for (const file of p.files) {
                if (this.modules[file]) continue;
                if (!file.endsWith(".wgsl")) fail(`program ${p.name}: file ${file} is not WGSL`);
                const module = this.device.createShaderModule({label: file, code: sources[file]});
                const info = await module.getCompilationInfo();
                for (const m of info.messages)
                    if (m.type === "error") problems.push(`${file}:${m.lineNum}:${m.linePos}: error: ${m.message}`);
                this.modules[file] = module;
            }
            this.programs[p.name] = this.program(p);
        }
        if (problems.length) fail(problems.join("\n"));
    }

    // One program's bind group layout from its parameters: a uniform buffer per block, a texture
    // (and a sampler where sampler_binding >= 0) per sampler parameter.
    program(p) {
        const stages = p.stages || [];
        const compute = stages.includes("compute");
        const visibility = compute ? GPUShaderStage.COMPUTE : GPUShaderStage.VERTEX | GPUShaderStage.FRAGMENT;
        const entries = [], blocks = {}, textures = [];
        const seen = new Map();
        const add = (binding, entry, what) => {
            if (!(binding >= 0)) fail(`program ${p.name}: ${what}: no binding`);
            if (seen.has(binding)) fail(`program ${p.name}: binding ${binding} given to both ${seen.get(binding)} and ${what}`);
            seen.set(binding, what);
            entries.push({binding, visibility, ...entry});
        };
        for (const param of p.parameters) {
            const group = param.group ?? param.set ?? 0;
            if (group !== 0) fail(`program ${p.name}: parameter ${param.name} in group ${group}; this runner reads group 0 (WGSL.md)`);
            if (param.block !== undefined) {
                const type = lookUp(UNIFORM_TYPES, param.type, `program ${p.name}: uniform ${param.name}: type`);
                if (!(param.offset >= 0)) fail(`program ${p.name}: uniform ${param.name}: no offset`);
                const block = blocks[param.block] ||= {name: param.block, binding: param.block_binding, size: 0, members: []};
                if (block.binding !== param.block_binding)
                    fail(`program ${p.name}: block ${param.block} at bindings ${block.binding} and ${param.block_binding}`);
                block.members.push(param);
                block.size = Math.max(block.size, param.offset + type.size);
            } else if (param.texture_type !== undefined || param.binding !== undefined && param.type.includes("sampler")) {
                if (param.texture_type === undefined) fail(`program ${p.name}: ${param.name}: no texture_type (a layout of another target?)`);
                if (param.texture_type.startsWith("texture_storage"))
                    fail(`program ${p.name}: ${param.name}: storage textures (${param.texture_type}) are not supported by this runner yet`);
                const viewDimension = lookUp(VIEW_DIMENSION, param.texture_type.replace(/<.*>$/, ""), `program ${p.name}: ${param.name}: texture_type`);
                add(param.binding, {texture: {sampleType: param.sample_type, viewDimension}}, `texture ${param.name}`);
                if (param.sampler_binding >= 0) add(param.sampler_binding, {sampler: {type: param.sampler_type}}, `sampler of ${param.name}`);
                textures.push({param, viewDimension});
            }
        }
        for (const block of Object.values(blocks)) {
            block.size = Math.ceil(block.size / 16) * 16;
            add(block.binding, {buffer: {type: "uniform"}}, `block ${block.name}`);
        }
        const bindGroupLayout = this.device.createBindGroupLayout({label: p.name, entries});
        return {desc: p, blocks, textures, bindGroupLayout,
                pipelineLayout: this.device.createPipelineLayout({label: p.name, bindGroupLayouts: [bindGroupLayout]})};
    }

    allocate(t, width, height) {
        if (!t.webgpu) fail(`texture ${t.name}: no "webgpu" {format, usage} (a layout of another target?)`);
        const format = t.webgpu.format;
        let usage = 0;
        for (const u of t.webgpu.usage) usage |= GPUTextureUsage[lookUp(Object.fromEntries(TEXTURE_USAGE.map((x) => [x, x])), u, `texture ${t.name}: usage`)];
        if (this.writable.has(t.name)) usage |= GPUTextureUsage.COPY_DST;
        if (t.wrap === "CLAMP_TO_BORDER") fail(`texture ${t.name}: wrap CLAMP_TO_BORDER does not exist in WebGPU`);
        const dimension = t.target === "3D" ? "3d" : "2d";
        const layers = t.target === "2D" ? 1 : t.depth;
        const texture = this.device.createTexture({label: t.name, format, usage, dimension, mipLevelCount: t.mip_levels,
                                                   size: [width, height, layers]});
        // WebGPU zero-initialises texture storage, as the layout's textures expect.
        return {texture, desc: t, format, width, height, layers, dimension};
    }

    // Textures whose size is "output": (re)allocated at the output size of the screen phase.
    allocateOutputSized(width, height) {
        if (this.outputSize && this.outputSize.width === width && this.outputSize.height === height) return;
        for (const t of this.layout.textures) {
            if (t.size !== "output") continue;
            if (this.textures[t.name]) this.textures[t.name].texture.destroy();
            this.textures[t.name] = this.allocate(t, width, height);
        }
        this.outputSize = {width, height};
    }

    // A texture whose source is "caller", filled with `data` (a typed array matching its format,
    // rows in memory order).
    fillTexture(name, width, height, data) {
        const desc = this.description(name);
        if (desc.source !== "caller") fail(`texture ${name}: source '${desc.source}', not one the caller fills`);
        if (desc.size === "output") this.allocateOutputSized(width, height);
        const t = this.texture(name);
        const f = lookUp(FORMATS, t.format, `texture ${name}: format`);
        if (data.byteLength !== f.bytes * width * height) fail(`fillTexture ${name}: ${data.byteLength} bytes, expected ${f.bytes * width * height}`);
        this.device.queue.writeTexture({texture: t.texture}, data, {bytesPerRow: f.bytes * width, rowsPerImage: height}, [width, height, 1]);
    }

    // One level (and layer) of a texture the runner was loaded with as writable, from RGBA values in
    // memory row order (as readTexture gives them; unorm8 formats store round(255·x), uint32 formats
    // the values as they are: pass them in an Array or a Uint32Array, a Float32Array would round them).
    uploadTexture(name, level, layer, rgba) {
        if (!this.writable.has(name)) fail(`uploadTexture ${name}: not loaded as writable (load(device, base, {writable: ["${name}"]}))`);
        const t = this.texture(name);
        const f = lookUp(FORMATS, t.format, `texture ${name}: format`);
        const width = Math.max(t.width >> level, 1), height = Math.max(t.height >> level, 1);
        if (rgba.length !== 4 * width * height) fail(`uploadTexture ${name}: ${rgba.length} values, expected ${4 * width * height} (RGBA ${width}×${height})`);
        let data;
        if (f.type === "unorm8") {
            data = new Uint8Array(f.channels * width * height);
            for (let i = 0; i < width * height; ++i)
                for (let c = 0; c < f.channels; ++c) data[f.channels * i + c] = Math.round(255 * Math.min(Math.max(rgba[4 * i + c], 0), 1));
        } else if (f.type === "float32") {
            data = new Float32Array(f.channels * width * height);
            for (let i = 0; i < width * height; ++i) for (let c = 0; c < f.channels; ++c) data[f.channels * i + c] = rgba[4 * i + c];
        } else if (f.type === "uint32") {
            data = new Uint32Array(f.channels * width * height);
            for (let i = 0; i < width * height; ++i) for (let c = 0; c < f.channels; ++c) data[f.channels * i + c] = rgba[4 * i + c];
        } else {
            fail(`uploadTexture ${name}: format ${t.format} is not uploaded by this runner (unorm8, float32 and uint32 formats are)`);
        }
        this.device.queue.writeTexture({texture: t.texture, mipLevel: level, origin: [0, 0, Math.max(layer, 0)]}, data,
                                       {bytesPerRow: f.bytes * width, rowsPerImage: height}, [width, height, 1]);
    }

    // A texture for a parameter whose source is "draw" (alpha test: the caster's material texture)
    // for every draw that gives none of its own (setDrawUniforms' `textures`); without either, the
    // parameter reads a 1×1 opaque white texture.
    setDrawTexture(name, texture) {
        this.drawTextures[name] = texture;
    }

    setUniforms(values) {
        Object.assign(this.uniformValues, values);
    }

    // Parameters whose value the caller must give (source "light" or "camera"), over every program.
    parameters() {
        const out = {};
        for (const p of this.layout.programs)
            for (const param of p.parameters)
                if (param.block !== undefined && param.source !== "pass") out[param.name] = param;
        return out;
    }

    // The location layout.json's programs give vertex input `name` (penumbra_position, …); -1 if none.
    vertexLocation(name) {
        for (const p of this.layout.programs)
            for (const v of p.vertex_inputs || []) if (v.name === name) return v.location;
        return -1;
    }

    sampler(sampling, where) {
        const key = JSON.stringify(sampling);
        if (this.samplers[key]) return this.samplers[key];
        const filter = (f) => (f.startsWith("LINEAR") ? "linear" : "nearest");
        const mipmapped = sampling.min_filter.includes("MIPMAP");
        const addressMode = lookUp(WRAP, sampling.wrap, `${where}: wrap`);
        const descriptor = {label: where, magFilter: filter(sampling.mag_filter), minFilter: filter(sampling.min_filter),
                            mipmapFilter: sampling.min_filter.endsWith("MIPMAP_LINEAR") ? "linear" : "nearest",
                            addressModeU: addressMode, addressModeV: addressMode, addressModeW: addressMode};
        if (!mipmapped) descriptor.lodMaxClamp = 0; // GL's NEAREST / LINEAR min filters read the base level only
        if (sampling.compare) descriptor.compare = lookUp(COMPARE, sampling.compare, `${where}: compare`);
        return (this.samplers[key] = this.device.createSampler(descriptor));
    }

    // The render or compute pipeline of a pass, made once (at creation, so that errors show there).
    pipeline(pass, index) {
        if (this.pipelines[index] !== undefined) return this.pipelines[index];
        if (pass.action === "copy") return (this.pipelines[index] = null); // a texture copy: no pipeline
        if (pass.action !== "draw_scene" && pass.action !== "fullscreen") {
            if (pass.action === "dispatch") fail(`pass ${pass.name}: action 'dispatch' (compute) is not supported by this runner yet`);
            if (pass.action === "generate_mipmap") fail(`pass ${pass.name}: action 'generate_mipmap' does not exist in WebGPU (no generateMipmap): the wgsl emission builds levels with passes`);
            fail(`pass ${pass.name}: action '${pass.action}' unknown; this runner runs draw_scene, fullscreen and copy`);
        }
        const program = this.programs[pass.program];
        if (!program) fail(`pass ${pass.name}: no program '${pass.program}' in layout.json`);
        const p = program.desc, s = pass.state;
        if (s.logic_op && s.logic_op !== "NONE") fail(`pass ${pass.name}: logic_op ${s.logic_op} does not exist in WebGPU`);
        const stageFile = (stage) => {
            const i = (p.stages || ["vertex", "fragment"]).indexOf(stage);
            if (i < 0) fail(`program ${p.name}: no ${stage} stage`);
            return this.modules[p.files[i]];
        };
        const buffers = pass.action === "draw_scene"
            ? (p.vertex_inputs || []).map((v) => ({arrayStride: 4 * {float: 1, vec2: 2, vec3: 3, vec4: 4}[v.type],
                                                   attributes: [{shaderLocation: v.location, offset: 0,
                                                                 format: lookUp(VERTEX_FORMATS, v.type, `program ${p.name}: vertex input ${v.name}`)}]}))
            : [];
        const writeMask = s.color_mask.reduce((m, on, i) => m | (on ? [GPUColorWrite.RED, GPUColorWrite.GREEN, GPUColorWrite.BLUE, GPUColorWrite.ALPHA][i] : 0), 0);
        const blend = s.blend ? (() => {
            const component = {operation: lookUp(BLEND_OPERATION, s.blend_equation, `pass ${pass.name}: blend_equation`),
                               srcFactor: lookUp(BLEND_FACTOR, s.blend_src, `pass ${pass.name}: blend_src`),
                               dstFactor: lookUp(BLEND_FACTOR, s.blend_dst, `pass ${pass.name}: blend_dst`)};
            if (component.operation === "min" || component.operation === "max") component.srcFactor = component.dstFactor = "one";
            return {color: component, alpha: {...component}};
        })() : undefined;
        const targets = [];
        let depthStencil;
        for (const out of pass.outputs) {
            const format = this.description(out.texture).webgpu?.format;
            if (!format) fail(`pass ${pass.name}: output ${out.texture} has no webgpu format`);
            if (out.kind === "depth") {
                depthStencil = {format, depthWriteEnabled: !!s.depth_write,
                                depthCompare: s.depth_test ? lookUp(COMPARE, s.depth_func, `pass ${pass.name}: depth_func`) : "always",
                                depthBias: Math.round(s.polygon_offset_units || 0), depthBiasSlopeScale: s.polygon_offset_factor || 0};
            } else {
                targets.push({format, writeMask, ...(blend ? {blend} : {})});
            }
        }
        const pipeline = this.device.createRenderPipeline({
            label: pass.name,
            layout: program.pipelineLayout,
            vertex: {module: stageFile("vertex"), entryPoint: "main", buffers},
            fragment: {module: stageFile("fragment"), entryPoint: "main", targets},
            primitive: {topology: "triangle-list", cullMode: lookUp(CULL, s.cull, `pass ${pass.name}: cull`), frontFace: "ccw"},
            ...(depthStencil ? {depthStencil} : {}),
        });
        return (this.pipelines[index] = {pipeline, program});
    }

    // The uniform buffer of one block for one pass (its values: setUniforms and the pass's int_uniforms;
    // `draw`: {slot, values} of one draw of drawScene, its own buffer with `values` over those).
    writeUniforms(index, pass, block, draw = null) {
        const key = draw ? `${index} ${block.name} draw ${draw.slot}` : `${index} ${block.name}`;
        let buffer = this.uniformBuffers.get(key);
        if (!buffer) {
            buffer = this.device.createBuffer({label: key, size: block.size, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST});
            this.uniformBuffers.set(key, buffer);
        }
        const bytes = new ArrayBuffer(block.size);
        const views = {f32: new Float32Array(bytes), i32: new Int32Array(bytes), u32: new Uint32Array(bytes)};
        for (const param of block.members) {
            const value = draw && param.name in draw.values ? draw.values[param.name]
                : pass.int_uniforms && param.name in pass.int_uniforms ? pass.int_uniforms[param.name] : this.uniformValues[param.name];
            if (value === undefined) continue;
            const type = UNIFORM_TYPES[param.type];
            const v = typeof value === "number" || typeof value === "boolean" ? [Number(value)] : Array.from(value);
            const base = param.offset / 4;
            if (type.columns === 3) { // mat3: three columns of vec3, each padded to 16 bytes
                for (let c = 0; c < 3; ++c) for (let r = 0; r < 3; ++r) views.f32[base + 4 * c + r] = v[3 * c + r];
            } else {
                if (v.length !== type.size / 4) fail(`uniform ${param.name} (${param.type}): ${v.length} values, expected ${type.size / 4}`);
                views[type.kind].set(v, base);
            }
        }
        this.device.queue.writeBuffer(buffer, 0, bytes);
        return buffer;
    }

    whiteTexture() {
        if (!this.white) {
            this.white = this.device.createTexture({label: "penumbra white", format: "rgba8unorm", size: [1, 1, 1],
                                                    usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST});
            this.device.queue.writeTexture({texture: this.white}, new Uint8Array([255, 255, 255, 255]), {bytesPerRow: 4}, [1, 1, 1]);
        }
        return this.white;
    }

    // The pass's bind group: each texture parameter reads the texture (and level) its pass input names
    // (or the parameter's own `texture`), through a sampler of the input's sampling.
    bindGroup(index, pass, program, draw = null) {
        const entries = [];
        for (const block of Object.values(program.blocks))
            entries.push({binding: block.binding, resource: {buffer: this.writeUniforms(index, pass, block, draw)}});
        for (const {param, viewDimension} of program.textures) {
            const input = pass.inputs.find((i) => i.sampler === param.name);
            let view;
            if (param.source === "draw") {
                view = (draw?.textures?.[param.name] || this.drawTextures[param.name] || this.whiteTexture()).createView();
            } else {
                const name = input?.texture ?? param.texture;
                if (!name) fail(`pass ${pass.name}: parameter ${param.name} has no input and no texture`);
                const t = this.texture(name);
                const level = input && input.level >= 0 ? input.level : undefined;
                view = t.texture.createView({dimension: viewDimension, ...(level !== undefined ? {baseMipLevel: level, mipLevelCount: 1} : {})});
            }
            entries.push({binding: param.binding, resource: view});
            if (param.sampler_binding >= 0) {
                const sampling = input?.sampling ?? param.sampling ?? (() => {
                    if (param.source === "draw") { // the caller's texture: filtered as its sampler type allows
                        const f = param.sampler_type === "filtering" ? "LINEAR" : "NEAREST";
                        return {min_filter: f, mag_filter: f, wrap: "REPEAT", compare: ""};
                    }
                    const t = this.description(param.texture);
                    return {min_filter: param.filter || t.min_filter, mag_filter: param.filter || t.mag_filter, wrap: t.wrap, compare: ""};
                })();
                entries.push({binding: param.sampler_binding, resource: this.sampler(sampling, `pass ${pass.name} ${param.name}`)});
            }
        }
        return this.device.createBindGroup({label: pass.name, layout: program.bindGroupLayout, entries});
    }

    // Encodes one pass. `drawScene(renderPass, program, setDrawUniforms)` draws the caller's triangles
    // with the vertex buffers in the order of the program's vertex_inputs (sceneDrawer makes one);
    // setDrawUniforms(values, slot, textures) before a draw gives it uniform values of its own (e.g. a
    // caster's model matrix in penumbra_lightFromWorld), in a buffer kept per pass and slot (queue
    // writes land before the submission, so draws of one pass cannot share a buffer), and textures
    // {name: GPUTexture} of its own for parameters whose source is "draw" (the alpha test's).
    encodePass(encoder, pass, index, drawScene, size) {
        if (pass.action === "copy") return this.encodeCopy(encoder, pass);
        const {pipeline, program} = this.pipeline(pass, index);
        const s = pass.state;
        const colorAttachments = [];
        let depthStencilAttachment;
        for (const out of pass.outputs) {
            const t = this.texture(out.texture);
            // a layer of an array texture is a 2D view of it; a slice of a 3D texture is the view's depthSlice
            const view = t.dimension === "3d"
                ? t.texture.createView({dimension: "3d", baseMipLevel: Math.max(out.level, 0), mipLevelCount: 1})
                : t.texture.createView({dimension: "2d", baseMipLevel: Math.max(out.level, 0), mipLevelCount: 1,
                                        baseArrayLayer: Math.max(out.layer, 0), arrayLayerCount: 1});
            if (out.kind === "depth") {
                depthStencilAttachment = {view, depthLoadOp: s.clear_depth !== null && s.clear_depth !== undefined ? "clear" : "load",
                                          depthClearValue: s.clear_depth ?? 1, depthStoreOp: "store"};
            } else {
                const c = s.clear_color;
                colorAttachments.push({view, loadOp: c ? "clear" : "load", storeOp: "store",
                                       clearValue: c ? {r: c[0], g: c[1], b: c[2], a: c[3]} : undefined,
                                       ...(t.dimension === "3d" ? {depthSlice: Math.max(out.layer, 0)} : {})});
            }
        }
        const render = encoder.beginRenderPass({label: pass.name, colorAttachments, depthStencilAttachment});
        render.setPipeline(pipeline);
        render.setBindGroup(0, this.bindGroup(index, pass, program));
        const [vw, vh] = pass.viewport;
        if (vw > 0) render.setViewport(0, 0, vw, vh, 0, 1);
        else if (size) render.setViewport(0, 0, size.width, size.height, 0, 1);
        if (pass.action === "draw_scene") {
            if (!drawScene) fail(`pass ${pass.name} draws the scene: runPhase needs a drawScene callback`);
            drawScene(render, program.desc, (values, slot, textures = null) =>
                render.setBindGroup(0, this.bindGroup(index, pass, program, {values, slot, textures})));
        } else {
            render.draw(3);
        }
        render.end();
    }

    // A copy pass: the region "copy" names (levels, layers, size) from the input's texture to the
    // output's, texel for texel (copyTextureToTexture: the layout gives the source COPY_SRC and the target COPY_DST).
    encodeCopy(encoder, pass) {
        const c = pass.copy;
        if (!c) fail(`pass ${pass.name}: a copy pass needs "copy" (levels, layers, size)`);
        const source = this.texture(pass.inputs[0].texture), target = this.texture(pass.outputs[0].texture);
        for (const [t, usage] of [[source, "COPY_SRC"], [target, "COPY_DST"]])
            if (!t.desc.webgpu.usage.includes(usage))
                fail(`pass ${pass.name}: texture ${t.desc.name} is copied ${usage === "COPY_SRC" ? "from" : "to"}, but layout.json's usage has no ${usage}`);
        encoder.copyTextureToTexture({texture: source.texture, mipLevel: Math.max(c.source_level, 0), origin: [0, 0, Math.max(c.source_layer, 0)]},
                                     {texture: target.texture, mipLevel: Math.max(c.target_level, 0), origin: [0, 0, Math.max(c.target_layer, 0)]},
                                     [c.width, c.height, 1]);
    }

    // A drawScene callback for triangles `positions` (Float32Array, 3 floats a vertex, world units),
    // with `attributes` {penumbra_normal: Float32Array, penumbra_uv: ...} where the caller has them;
    // a vertex input without data reads zeros.
    sceneDrawer(positions, attributes = {}) {
        const count = positions.length / 3;
        const buffer = (data) => {
            const b = this.device.createBuffer({size: Math.max(data.byteLength, 4), usage: GPUBufferUsage.VERTEX | GPUBufferUsage.COPY_DST});
            this.device.queue.writeBuffer(b, 0, data);
            return b;
        };
        const buffers = {penumbra_position: buffer(positions)};
        for (const [name, data] of Object.entries(attributes)) buffers[name] = buffer(data);
        return (render, program) => {
            (program.vertex_inputs || []).forEach((v, slot) => {
                if (!buffers[v.name]) buffers[v.name] = buffer(new Float32Array(count * {float: 1, vec2: 2, vec3: 3, vec4: 4}[v.type]));
                render.setVertexBuffer(slot, buffers[v.name]);
            });
            render.draw(count);
        };
    }

    // Runs every pass of `phase` in layout order ("shadow": when the scene or light changes;
    // "screen": every frame at the output size) in one submission; fails with WebGPU's validation
    // message. Returns how many passes ran.
    // `replace`: {<pass name>: callback} called where that pass would run (a test's own data in place
    // of a pass's output, through uploadTexture).
    async runPhase(phase, drawScene, size, replace = {}) {
        const {count, done} = this.submitPhase(phase, drawScene, size, replace);
        await done;
        return count;
    }

    // runPhase without waiting: the passes are encoded and submitted now (so that work submitted
    // later on the same queue, e.g. a renderer's frame, sees their results); `done` settles when
    // WebGPU has validated them (rejects with its message). {count, done}.
    submitPhase(phase, drawScene, size, replace = {}) {
        if (phase === "example") fail("runPhase('example'): the example phase draws into the caller's framebuffer; this runner runs shadow and screen");
        if (phase === "screen") {
            if (!size) fail("runPhase('screen'): needs the output size {width, height}");
            this.allocateOutputSized(size.width, size.height);
        }
        let count = 0;
        // (an error scope opened and closed here, synchronously: nothing else lands in it)
        this.device.pushErrorScope("validation");
        let failure = null;
        try {
            let encoder = this.device.createCommandEncoder({label: phase});
            this.layout.passes.forEach((pass, index) => {
                if (pass.phase !== phase) return;
                if (replace[pass.name]) {
                    // what was encoded so far runs first, then the caller's uploads (queue order)
                    this.device.queue.submit([encoder.finish()]);
                    replace[pass.name](pass);
                    encoder = this.device.createCommandEncoder({label: phase});
                } else {
                    this.encodePass(encoder, pass, index, drawScene, size);
                }
                ++count;
            });
            this.device.queue.submit([encoder.finish()]);
        } catch (e) {
            failure = e;
        }
        const popped = this.device.popErrorScope();
        if (failure) throw failure;
        this.passCount += count;
        const done = popped.then((error) => {
            if (error) fail(`WebGPU validation error in phase ${phase}: ${error.message}`);
        });
        return {count, done};
    }

    // One level (and layer) of a colour texture as RGBA floats in memory row order (bottom row first
    // for results of caller textures filled bottom row first); one-channel formats read as (r, 0, 0, 1).
    async readTexture(name, level = 0, layer = -1) {
        const t = this.texture(name);
        const f = lookUp(FORMATS, t.format, `texture ${name}: format`);
        if (!f.type || f.depth) fail(`readTexture ${name}: format ${t.format} is not read back by this runner`);
        if (!t.desc.webgpu.usage.includes("COPY_SRC")) fail(`texture ${name}: layout.json's usage has no COPY_SRC, so it cannot be read back`);
        const width = Math.max(t.width >> level, 1), height = Math.max(t.height >> level, 1);
        const bytesPerRow = Math.ceil((width * f.bytes) / 256) * 256;
        const buffer = this.device.createBuffer({size: bytesPerRow * height, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ});
        const encoder = this.device.createCommandEncoder();
        encoder.copyTextureToBuffer({texture: t.texture, mipLevel: level, origin: [0, 0, Math.max(layer, 0)]}, {buffer, bytesPerRow}, [width, height, 1]);
        this.device.queue.submit([encoder.finish()]);
        await buffer.mapAsync(GPUMapMode.READ);
        const bytes = new Uint8Array(buffer.getMappedRange().slice(0));
        buffer.unmap();
        buffer.destroy();
        const out = new Float32Array(4 * width * height);
        const view = new DataView(bytes.buffer);
        const half = (h) => {
            const e = (h >> 10) & 31, m = h & 1023, sign = h & 32768 ? -1 : 1;
            if (e === 0) return sign * m * 2 ** -24;
            if (e === 31) return m ? NaN : sign * Infinity;
            return sign * (1 + m / 1024) * 2 ** (e - 15);
        };
        const size = f.bytes / f.channels;
        for (let y = 0; y < height; ++y)
            for (let x = 0; x < width; ++x)
                for (let c = 0; c < 4; ++c) {
                    let v = c === 3 ? 1 : 0;
                    if (c < f.channels) {
                        const at = y * bytesPerRow + x * f.bytes + c * size;
                        v = f.type === "float32" ? view.getFloat32(at, true) : f.type === "uint32" ? view.getUint32(at, true)
                            : f.type === "float16" ? half(view.getUint16(at, true)) : bytes[at] / 255;
                    }
                    out[4 * (y * width + x) + c] = v;
                }
        return out;
    }

    // The layout's result texture (visibility, 0 shadowed to 1 lit) as floats, one a pixel.
    async readResult() {
        const rgba = await this.readTexture(this.layout.result);
        const out = new Float32Array(rgba.length / 4);
        for (let i = 0; i < out.length; ++i) out[i] = rgba[4 * i];
        return out;
    }

    // Every WebGPU object this runner made that can be released.
    dispose() {
        for (const t of Object.values(this.textures)) t.texture.destroy();
        for (const b of this.uniformBuffers.values()) b.destroy();
        if (this.white) this.white.destroy();
        this.textures = {};
        this.uniformBuffers.clear();
    }
}
