// penumbra_runner.js — runs an emission on raw WebGL2 by following its layout.json alone: the
// textures of `textures`, the programs of `programs`, and the passes of `passes` in order with
// their render state, input bindings, attachments and integer uniforms. It reads nothing of
// Penumbra's C++ source; it is a second, independent consumer of layout.json (the first is the
// desktop runtime, include/penumbra/gl/runtime.hpp).
//
//   const runner = await LayoutRunner.load(gl, "emission/");           // layout.json + its files
//   const runner = LayoutRunner.fromEmission(gl, emitter.emit(config));  // or an emission in memory
//   runner.setUniforms({penumbra_lightFromWorld: [...16], ...});        // by GLSL name
//   runner.runPhase("shadow", (program) => drawTriangles());            // slicing + prefilter
//   runner.fillTexture("penumbra_worldPositions", w, h, positions);     // a "caller" texture
//   runner.runPhase("screen", null, {width: w, height: h});             // deferred visibility
//   const visibility = runner.readResult();                             // Float32Array, bottom row first

const LAYOUT_VERSION = 3;

// Sized internal formats: upload format and type, whether rendering to it needs
// EXT_color_buffer_float, whether LINEAR filtering needs OES_texture_float_linear.
const FORMATS = {
    RGBA8: {format: "RGBA", type: "UNSIGNED_BYTE", float: false},
    R8: {format: "RED", type: "UNSIGNED_BYTE", float: false},
    RGBA16F: {format: "RGBA", type: "HALF_FLOAT", float: true, filterable: true},
    R16F: {format: "RED", type: "HALF_FLOAT", float: true, filterable: true},
    RG16F: {format: "RG", type: "HALF_FLOAT", float: true, filterable: true},
    RGBA32F: {format: "RGBA", type: "FLOAT", float: true, filterable: false},
    R32F: {format: "RED", type: "FLOAT", float: true, filterable: false},
    RG32F: {format: "RG", type: "FLOAT", float: true, filterable: false},
    RGBA32UI: {format: "RGBA_INTEGER", type: "UNSIGNED_INT", float: false, integer: true}, // evsm moments on ES (float bits)
    R32UI: {format: "RED_INTEGER", type: "UNSIGNED_INT", float: false, integer: true}, // adaptive slice boundaries
    DEPTH_COMPONENT24: {format: "DEPTH_COMPONENT", type: "UNSIGNED_INT", float: false, depth: true},
    DEPTH_COMPONENT32F: {format: "DEPTH_COMPONENT", type: "FLOAT", float: false, depth: true},
};

const TARGETS = {"2D": "TEXTURE_2D", "2D_ARRAY": "TEXTURE_2D_ARRAY", "3D": "TEXTURE_3D"};

export class LayoutError extends Error {}

function fail(message) {
    throw new LayoutError(message);
}

// gl[NAME] for a layout string, or a clear error naming the field and the value.
function glEnum(gl, what, name) {
    const value = gl[name];
    if (typeof value !== "number") fail(`${what}: '${name}' is not a WebGL2 enum`);
    return value;
}

export class LayoutRunner {
    // Fetches `${base}layout.json` and every program file it names.
    static async load(gl, base) {
        const fetchText = async (name) => {
            const response = await fetch(base + name);
            if (!response.ok) fail(`${base}${name}: HTTP ${response.status}`);
            return response.text();
        };
        const layout = JSON.parse(await fetchText("layout.json"));
        const sources = {};
        for (const program of layout.programs || [])
            for (const file of program.files) if (!(file in sources)) sources[file] = await fetchText(file);
        return new LayoutRunner(gl, layout, sources);
    }

    // From an emission in memory: {files: {"<name>": text, ...}, layout} as penumbra_emitter.js's
    // emit() returns it (layout: layout.json parsed; taken from files["layout.json"] when absent).
    static fromEmission(gl, {files, layout}) {
        if (!files) fail("fromEmission: no files (an emission that failed? see its diagnostics)");
        const parsed = layout ?? (files["layout.json"] !== undefined ? JSON.parse(files["layout.json"]) : null);
        if (!parsed) fail("fromEmission: no layout and no layout.json among the files");
        for (const program of parsed.programs || [])
            for (const file of program.files) if (typeof files[file] !== "string") fail(`fromEmission: program ${program.name}: no file ${file}`);
        return new LayoutRunner(gl, parsed, files);
    }

    constructor(gl, layout, sources) {
        if (layout.layout_version === undefined) fail(`layout.json: no layout_version (an older layout); this runner reads version ${LAYOUT_VERSION}`);
        if (layout.layout_version !== LAYOUT_VERSION)
            fail(`layout.json: layout_version ${layout.layout_version}; this runner reads version ${LAYOUT_VERSION}`);
        if (layout.config && layout.config.target !== "essl300")
            fail(`layout.json: target '${layout.config.target}'; WebGL2 runs the essl300 emission`);
        for (const pass of layout.passes || [])
            if (pass.action === "dispatch")
                fail(`pass ${pass.name}: action 'dispatch' runs a compute shader (prefilter_stage compute), which WebGL2 does not have; emit with prefilter_stage fragment`);
        this.gl = gl;
        this.layout = layout;
        this.uniformValues = {};
        this.outputSize = null;
        this.extensions = this.enableExtensions();
        this.textures = {};
        for (const t of layout.textures) if (t.size !== "output") this.textures[t.name] = this.allocate(t, t.width, t.height);
        this.programs = {};
        for (const p of layout.programs) this.programs[p.name] = this.link(p, sources);
        this.framebuffer = gl.createFramebuffer();
        this.readFramebuffer = gl.createFramebuffer();
        this.emptyVertexArray = gl.createVertexArray();
    }

    texture(name) {
        const t = this.textures[name];
        if (!t) fail(`no texture '${name}' in layout.json (or its size is "output" and no screen pass ran yet)`);
        return t;
    }

    description(name) {
        const t = this.layout.textures.find((d) => d.name === name);
        if (!t) fail(`no texture '${name}' in layout.json`);
        return t;
    }

    // EXT_color_buffer_float only where a pass renders to a float texture; OES_texture_float_linear
    // only where a 32-bit float texture is filtered linearly.
    enableExtensions() {
        const gl = this.gl;
        const rendered = new Set();
        for (const pass of this.layout.passes) for (const out of pass.outputs) rendered.add(out.texture);
        const enabled = [];
        const need = (name, why) => {
            if (enabled.includes(name)) return;
            if (!gl.getExtension(name)) fail(`${why} needs ${name}, which this browser lacks`);
            enabled.push(name);
        };
        for (const t of this.layout.textures) {
            const f = FORMATS[t.internal_format];
            if (!f) fail(`texture ${t.name}: internal_format '${t.internal_format}' unknown; allowed: ${Object.keys(FORMATS).join(", ")}`);
            if (f.float && rendered.has(t.name)) need("EXT_color_buffer_float", `rendering to ${t.name} (${t.internal_format})`);
            if (f.float && !f.filterable && (t.min_filter.startsWith("LINEAR") || t.mag_filter === "LINEAR"))
                need("OES_texture_float_linear", `LINEAR filtering of ${t.name} (${t.internal_format})`);
        }
        return enabled;
    }

    allocate(t, width, height) {
        const gl = this.gl;
        const target = glEnum(gl, `texture ${t.name}: target`, TARGETS[t.target] || t.target);
        const format = glEnum(gl, `texture ${t.name}: internal_format`, t.internal_format);
        if (t.wrap === "CLAMP_TO_BORDER") fail(`texture ${t.name}: wrap CLAMP_TO_BORDER does not exist in WebGL2`);
        const id = gl.createTexture();
        gl.bindTexture(target, id);
        if (target === gl.TEXTURE_2D) gl.texStorage2D(target, t.mip_levels, format, width, height);
        else gl.texStorage3D(target, t.mip_levels, format, width, height, t.depth);
        gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, glEnum(gl, `texture ${t.name}: min_filter`, t.min_filter));
        gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, glEnum(gl, `texture ${t.name}: mag_filter`, t.mag_filter));
        const wrap = glEnum(gl, `texture ${t.name}: wrap`, t.wrap);
        for (const axis of [gl.TEXTURE_WRAP_S, gl.TEXTURE_WRAP_T, gl.TEXTURE_WRAP_R]) gl.texParameteri(target, axis, wrap);
        gl.texParameteri(target, gl.TEXTURE_MAX_LEVEL, t.mip_levels - 1);
        gl.bindTexture(target, null);
        // WebGL2 zero-initialises texture storage, as the layout's textures expect.
        return {id, target, desc: t, width, height};
    }

    // Textures whose size is "output": (re)allocated at the output size of the screen phase.
    allocateOutputSized(width, height) {
        const gl = this.gl;
        if (this.outputSize && this.outputSize.width === width && this.outputSize.height === height) return;
        for (const t of this.layout.textures) {
            if (t.size !== "output") continue;
            if (this.textures[t.name]) gl.deleteTexture(this.textures[t.name].id);
            this.textures[t.name] = this.allocate(t, width, height);
        }
        this.outputSize = {width, height};
    }

    // A texture whose source is "caller", filled with `data` (a typed array matching its format).
    fillTexture(name, width, height, data) {
        const gl = this.gl;
        const desc = this.description(name);
        if (desc.source !== "caller") fail(`texture ${name}: source '${desc.source}', not one the caller fills`);
        if (desc.size === "output") this.allocateOutputSized(width, height);
        const t = this.texture(name);
        const f = FORMATS[desc.internal_format];
        gl.bindTexture(t.target, t.id);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
        gl.texSubImage2D(t.target, 0, 0, 0, width, height, gl[f.format], gl[f.type], data);
        gl.bindTexture(t.target, null);
    }

    link(p, sources) {
        const gl = this.gl;
        if (p.files.length !== 2) fail(`program ${p.name}: ${p.files.length} files; WebGL2 runs vertex + fragment`);
        const stages = [gl.VERTEX_SHADER, gl.FRAGMENT_SHADER];
        const program = gl.createProgram();
        const shaders = p.files.map((file, i) => {
            const shader = gl.createShader(stages[i]);
            gl.shaderSource(shader, sources[file]);
            gl.compileShader(shader);
            if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS))
                fail(`${file}: ${(gl.getShaderInfoLog(shader) || "compile failed").trim()}`);
            gl.attachShader(program, shader);
            return shader;
        });
        gl.linkProgram(program);
        for (const s of shaders) gl.deleteShader(s);
        if (!gl.getProgramParameter(program, gl.LINK_STATUS))
            fail(`program ${p.name}: ${(gl.getProgramInfoLog(program) || "link failed").trim()}`);
        // ES 3.00 has no layout(binding): every sampler gets its texture unit from the layout.
        gl.useProgram(program);
        const locations = {};
        for (const param of p.parameters) {
            locations[param.name] = gl.getUniformLocation(program, param.name);
            if (param.binding !== undefined && param.binding >= 0 && locations[param.name])
                gl.uniform1i(locations[param.name], param.binding);
        }
        gl.useProgram(null);
        return {id: program, desc: p, locations};
    }

    // Values of plain uniforms by GLSL name: numbers, or arrays (matrices column-major).
    setUniforms(values) {
        Object.assign(this.uniformValues, values);
    }

    // Sets every plain uniform of the program that has a value; the type comes from layout.json.
    applyUniforms(program) {
        const gl = this.gl;
        for (const param of program.desc.parameters) {
            if (param.binding !== undefined && param.binding >= 0) continue;
            const value = this.uniformValues[param.name];
            const location = program.locations[param.name];
            if (value === undefined || !location) continue;
            const v = typeof value === "number" ? [value] : value;
            switch (param.type) {
            case "float": gl.uniform1f(location, v[0]); break;
            case "vec2": gl.uniform2fv(location, v); break;
            case "vec3": gl.uniform3fv(location, v); break;
            case "vec4": gl.uniform4fv(location, v); break;
            case "mat4": gl.uniformMatrix4fv(location, false, v); break;
            case "int": gl.uniform1i(location, v[0]); break;
            default: fail(`program ${program.desc.name}: uniform ${param.name} of type '${param.type}' unknown`);
            }
        }
    }

    // Parameters whose value the caller must give (source "light" or "camera"), over every program.
    parameters() {
        const out = {};
        for (const p of this.layout.programs)
            for (const param of p.parameters)
                if (!(param.binding >= 0) && param.source !== "pass") out[param.name] = param;
        return out;
    }

    applyState(state) {
        const gl = this.gl;
        const on = (cap, enabled) => (enabled ? gl.enable(cap) : gl.disable(cap));
        on(gl.BLEND, state.blend);
        if (state.blend) {
            gl.blendEquation(glEnum(gl, "state.blend_equation", state.blend_equation));
            gl.blendFunc(glEnum(gl, "state.blend_src", state.blend_src), glEnum(gl, "state.blend_dst", state.blend_dst));
        }
        on(gl.DEPTH_TEST, state.depth_test);
        if (state.depth_test) gl.depthFunc(glEnum(gl, "state.depth_func", state.depth_func));
        gl.depthMask(!!state.depth_write);
        gl.colorMask(...state.color_mask);
        on(gl.CULL_FACE, state.cull !== "NONE");
        if (state.cull !== "NONE") gl.cullFace(glEnum(gl, "state.cull", state.cull));
        const offset = state.polygon_offset_factor !== 0 || state.polygon_offset_units !== 0;
        on(gl.POLYGON_OFFSET_FILL, offset);
        if (offset) gl.polygonOffset(state.polygon_offset_factor, state.polygon_offset_units);
        let mask = 0;
        if (state.clear_color && (this.integerOutputs || []).some((x) => x)) {
            // an integer target clears with clearBufferuiv (gl.clear would be an error)
            this.integerOutputs.forEach((integer, i) => {
                if (integer) gl.clearBufferuiv(gl.COLOR, i, Uint32Array.from(state.clear_color));
                else gl.clearBufferfv(gl.COLOR, i, state.clear_color);
            });
        } else if (state.clear_color) {
            gl.clearColor(...state.clear_color);
            mask |= gl.COLOR_BUFFER_BIT;
        }
        if (state.clear_depth !== null && state.clear_depth !== undefined) {
            gl.clearDepth(state.clear_depth);
            gl.depthMask(true); // a clear writes depth only through the mask
            mask |= gl.DEPTH_BUFFER_BIT;
        }
        if (mask) gl.clear(mask);
        gl.depthMask(!!state.depth_write);
    }

    attach(target, attachment, out) {
        const gl = this.gl;
        const t = this.texture(out.texture);
        if (out.layer >= 0) gl.framebufferTextureLayer(target, attachment, t.id, out.level, out.layer);
        else gl.framebufferTexture2D(target, attachment, gl.TEXTURE_2D, t.id, out.level);
    }

    // Binds the pass's outputs to our framebuffer, or the default one when it has none.
    bindOutputs(pass) {
        const gl = this.gl;
        this.integerOutputs = pass.outputs.filter((o) => o.kind !== "depth").map((o) => !!FORMATS[this.texture(o.texture).desc.internal_format].integer);
        if (pass.outputs.length === 0) {
            gl.bindFramebuffer(gl.FRAMEBUFFER, null);
            return;
        }
        gl.bindFramebuffer(gl.FRAMEBUFFER, this.framebuffer);
        for (let i = 0; i < 8; ++i) gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, gl.TEXTURE_2D, null, 0);
        gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.TEXTURE_2D, null, 0);
        const buffers = [];
        for (const out of pass.outputs) {
            if (out.kind === "depth") {
                this.attach(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, out);
                continue;
            }
            const attachment = gl.COLOR_ATTACHMENT0 + buffers.length;
            this.attach(gl.FRAMEBUFFER, attachment, out);
            buffers.push(attachment);
        }
        gl.drawBuffers(buffers.length ? buffers : [gl.NONE]);
        const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
        if (status !== gl.FRAMEBUFFER_COMPLETE) fail(`pass ${pass.name}: framebuffer incomplete (0x${status.toString(16)})`);
    }

    // The sampler object of a binding's "sampling" (filters, wrap, comparison), made once: bindings
    // read through samplers, so one texture can be read two ways (PCSS's shadow map).
    sampler(sampling, where) {
        const gl = this.gl;
        const key = JSON.stringify(sampling);
        this.samplers = this.samplers || {};
        if (this.samplers[key]) return this.samplers[key];
        if (sampling.wrap === "CLAMP_TO_BORDER") fail(`${where}: wrap CLAMP_TO_BORDER does not exist in WebGL2`);
        const id = gl.createSampler();
        gl.samplerParameteri(id, gl.TEXTURE_MIN_FILTER, glEnum(gl, `${where}: min_filter`, sampling.min_filter));
        gl.samplerParameteri(id, gl.TEXTURE_MAG_FILTER, glEnum(gl, `${where}: mag_filter`, sampling.mag_filter));
        const wrap = glEnum(gl, `${where}: wrap`, sampling.wrap);
        for (const axis of [gl.TEXTURE_WRAP_S, gl.TEXTURE_WRAP_T, gl.TEXTURE_WRAP_R]) gl.samplerParameteri(id, axis, wrap);
        if (sampling.compare) {
            gl.samplerParameteri(id, gl.TEXTURE_COMPARE_MODE, gl.COMPARE_REF_TO_TEXTURE);
            gl.samplerParameteri(id, gl.TEXTURE_COMPARE_FUNC, glEnum(gl, `${where}: compare`, sampling.compare));
        }
        this.samplers[key] = id;
        return id;
    }

    // Binds each input's texture and sampler to its unit; an input with a level reads only that level.
    bindInputs(pass) {
        const gl = this.gl;
        const restore = [];
        for (const input of pass.inputs) {
            const t = this.texture(input.texture);
            gl.activeTexture(gl.TEXTURE0 + input.binding);
            gl.bindTexture(t.target, t.id);
            gl.bindSampler(input.binding, input.sampling ? this.sampler(input.sampling, `pass ${pass.name} input ${input.texture}`) : null);
            if (input.level !== undefined && input.level >= 0) {
                gl.texParameteri(t.target, gl.TEXTURE_BASE_LEVEL, input.level);
                gl.texParameteri(t.target, gl.TEXTURE_MAX_LEVEL, input.level);
                restore.push(t);
            }
        }
        gl.activeTexture(gl.TEXTURE0);
        return () => {
            for (const t of restore) {
                gl.bindTexture(t.target, t.id);
                gl.texParameteri(t.target, gl.TEXTURE_BASE_LEVEL, 0);
                gl.texParameteri(t.target, gl.TEXTURE_MAX_LEVEL, t.desc.mip_levels - 1);
            }
            for (const input of pass.inputs) {
                gl.activeTexture(gl.TEXTURE0 + input.binding);
                gl.bindTexture(this.texture(input.texture).target, null);
                gl.bindSampler(input.binding, null);
            }
            gl.activeTexture(gl.TEXTURE0);
        };
    }

    // The location layout.json's programs give vertex input `name` (penumbra_position, …); -1 if none.
    vertexLocation(name) {
        for (const p of this.layout.programs)
            for (const v of p.vertex_inputs || []) if (v.name === name) return v.location;
        return -1;
    }

    // Runs one pass. `drawScene(programId)` draws the caller's triangles (world positions at
    // vertexLocation("penumbra_position")); `size` is the output size, for passes whose viewport is 0 × 0.
    runPass(pass, drawScene, size) {
        const gl = this.gl;
        if (pass.action === "generate_mipmap") { // 2x2 box levels ("mipmap": downsample box)
            if (!pass.mipmap || pass.mipmap.downsample !== "box") fail(`pass ${pass.name}: generate_mipmap needs "mipmap" with downsample "box"`);
            const t = this.texture(pass.outputs[0].texture);
            gl.bindTexture(t.target, t.id);
            gl.generateMipmap(t.target);
            gl.bindTexture(t.target, null);
            return;
        }
        if (pass.action === "copy" && !pass.copy) fail(`pass ${pass.name}: a copy pass needs "copy" (levels, layers, size)`);
        if (pass.action === "copy" && FORMATS[this.texture(pass.inputs[0].texture).desc.internal_format].depth) {
            // A depth texture: WebGL2 cannot copyTexSubImage depth, but blits it between two
            // framebuffers of the same depth format (NEAREST, same size).
            const source = pass.inputs[0], c = pass.copy;
            const out = {texture: pass.outputs[0].texture, level: c.target_level, layer: c.target_layer};
            const [w, h] = [c.width, c.height];
            gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.readFramebuffer);
            // only the depth attachments: a colour texture left from a read-back would make the
            // framebuffer incomplete (attachments of different sizes)
            gl.framebufferTexture2D(gl.READ_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, null, 0);
            this.attach(gl.READ_FRAMEBUFFER, gl.DEPTH_ATTACHMENT, {texture: source.texture, level: c.source_level, layer: c.source_layer});
            gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, this.framebuffer);
            for (let i = 0; i < 8; ++i) gl.framebufferTexture2D(gl.DRAW_FRAMEBUFFER, gl.COLOR_ATTACHMENT0 + i, gl.TEXTURE_2D, null, 0);
            this.attach(gl.DRAW_FRAMEBUFFER, gl.DEPTH_ATTACHMENT, out);
            gl.blitFramebuffer(0, 0, w, h, 0, 0, w, h, gl.DEPTH_BUFFER_BIT, gl.NEAREST);
            gl.framebufferTexture2D(gl.READ_FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.TEXTURE_2D, null, 0);
            gl.framebufferTexture2D(gl.DRAW_FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.TEXTURE_2D, null, 0);
            gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
            gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
            return;
        }
        if (pass.action === "copy") {
            // the region "copy" names, texel for texel, through a read framebuffer
            const source = pass.inputs[0], c = pass.copy;
            const t = this.texture(pass.outputs[0].texture);
            gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.readFramebuffer);
            this.attach(gl.READ_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, {texture: source.texture, level: c.source_level, layer: c.source_layer});
            gl.readBuffer(gl.COLOR_ATTACHMENT0);
            gl.bindTexture(t.target, t.id);
            if (t.target === gl.TEXTURE_2D) gl.copyTexSubImage2D(t.target, c.target_level, 0, 0, 0, 0, c.width, c.height);
            else gl.copyTexSubImage3D(t.target, c.target_level, 0, 0, Math.max(c.target_layer, 0), 0, 0, c.width, c.height);
            gl.bindTexture(t.target, null);
            gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
            return;
        }
        if (pass.action !== "fullscreen" && pass.action !== "draw_scene")
            fail(`pass ${pass.name}: action '${pass.action}' unknown; allowed: draw_scene, fullscreen, generate_mipmap, copy`);
        const program = this.programs[pass.program];
        if (!program) fail(`pass ${pass.name}: no program '${pass.program}' in layout.json`);
        this.bindOutputs(pass);
        const [vw, vh] = pass.viewport;
        if (vw > 0) gl.viewport(0, 0, vw, vh);
        else gl.viewport(0, 0, size.width, size.height);
        gl.useProgram(program.id);
        this.applyUniforms(program);
        for (const [name, value] of Object.entries(pass.int_uniforms)) {
            const location = program.locations[name] || gl.getUniformLocation(program.id, name);
            if (location) gl.uniform1i(location, value);
        }
        const unbind = this.bindInputs(pass);
        this.applyState(pass.state);
        if (pass.action === "draw_scene") {
            drawScene(program.id);
        } else {
            gl.bindVertexArray(this.emptyVertexArray);
            gl.drawArrays(gl.TRIANGLES, 0, 3);
            gl.bindVertexArray(null);
        }
        unbind();
        this.applyState({blend: false, depth_test: false, depth_write: true, color_mask: [true, true, true, true], cull: "NONE",
                         polygon_offset_factor: 0, polygon_offset_units: 0});
        gl.useProgram(null);
        gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    }

    // Runs every pass of `phase` in layout order ("shadow": when the scene or light changes;
    // "screen": every frame at the output size; "example": the caller's own framebuffer).
    // `replace[passName](pass)`, where given, fills that pass's outputs instead of running it.
    runPhase(phase, drawScene, size, replace = {}) {
        if (phase === "screen") this.allocateOutputSized(size.width, size.height);
        let count = 0;
        this.layout.passes.forEach((pass, index) => {
            if (pass.phase !== phase) return;
            const query = this.beginTiming(index);
            if (replace[pass.name]) replace[pass.name](pass);
            else this.runPass(pass, drawScene, size);
            if (query) this.gl.endQuery(this.timer.TIME_ELAPSED_EXT);
            ++count;
        });
        const error = this.gl.getError();
        if (error !== this.gl.NO_ERROR) fail(`phase ${phase}: WebGL error 0x${error.toString(16)}`);
        return count;
    }

    // GPU time of every pass, where the browser has EXT_disjoint_timer_query_webgl2 (false
    // otherwise). Results arrive a few frames late: passTimes() collects them.
    enableTiming() {
        this.timer = this.gl.getExtension("EXT_disjoint_timer_query_webgl2");
        this.pendingQueries = [];
        this.times = {};
        return !!this.timer;
    }

    beginTiming(index) {
        if (!this.timer) return null;
        const query = this.gl.createQuery();
        this.gl.beginQuery(this.timer.TIME_ELAPSED_EXT, query);
        this.pendingQueries.push({query, index});
        return query;
    }

    // {"<index> <pass name>": milliseconds} of the latest results (null without the extension);
    // a disjoint event (the GPU was interrupted) drops the pending ones.
    passTimes() {
        if (!this.timer) return null;
        const gl = this.gl;
        if (gl.getParameter(this.timer.GPU_DISJOINT_EXT)) {
            for (const q of this.pendingQueries) gl.deleteQuery(q.query);
            this.pendingQueries = [];
            return this.times;
        }
        while (this.pendingQueries.length && gl.getQueryParameter(this.pendingQueries[0].query, gl.QUERY_RESULT_AVAILABLE)) {
            const {query, index} = this.pendingQueries.shift();
            this.times[`${index} ${this.layout.passes[index].name}`] = gl.getQueryParameter(query, gl.QUERY_RESULT) / 1e6;
            gl.deleteQuery(query);
        }
        return this.times;
    }

    // The alpha test's per-draw inputs of `program` (one of this.programs) for the caller's caster draws
    // (penumbra-gen --alpha-test: parameters whose source is "draw", the material's alpha texture and
    // cutoff, and the vertex input penumbra_uv); null for a program without them. bind(draw) before each
    // draw: draw.cut ({cutoff}), draw.texture (a GL texture) and draw.uv (a buffer of the draw's texture
    // coordinates), or a draw without all three, which is solid (a 1x1 opaque texture, cutoff 0);
    // end() after the last draw.
    alphaTestInputs(program) {
        const gl = this.gl;
        const texture = program.desc.parameters.find((p) => p.source === "draw" && p.type.startsWith("sampler"));
        if (!texture) return null;
        const cutoff = program.desc.parameters.find((p) => p.source === "draw" && p.type === "float");
        const cutoffLocation = cutoff ? program.locations[cutoff.name] || gl.getUniformLocation(program.id, cutoff.name) : null;
        const uvLocation = (program.desc.vertex_inputs || []).find((v) => v.name === "penumbra_uv")?.location ?? -1;
        return {
            bind: (draw) => {
                const cut = draw.cut && draw.texture && draw.uv ? draw : null; // (no texture or coordinates yet: solid)
                gl.activeTexture(gl.TEXTURE0 + texture.binding);
                gl.bindTexture(gl.TEXTURE_2D, cut ? cut.texture : this.opaqueTexture());
                gl.bindSampler(texture.binding, null); // the material texture's own filtering and wrapping
                if (cutoffLocation) gl.uniform1f(cutoffLocation, cut ? cut.cut.cutoff : 0);
                if (uvLocation < 0) return;
                if (cut) {
                    gl.bindBuffer(gl.ARRAY_BUFFER, cut.uv);
                    gl.enableVertexAttribArray(uvLocation);
                    gl.vertexAttribPointer(uvLocation, 2, gl.FLOAT, false, 0, 0);
                } else {
                    gl.disableVertexAttribArray(uvLocation);
                }
            },
            end: () => {
                gl.activeTexture(gl.TEXTURE0 + texture.binding);
                gl.bindTexture(gl.TEXTURE_2D, null);
                gl.activeTexture(gl.TEXTURE0);
            },
        };
    }

    // The 1x1 opaque white texture a solid caster draw binds for the alpha test (made once).
    opaqueTexture() {
        if (!this.opaque) {
            const gl = this.gl;
            this.opaque = gl.createTexture();
            gl.bindTexture(gl.TEXTURE_2D, this.opaque);
            gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
            gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, 1, 1, 0, gl.RGBA, gl.UNSIGNED_BYTE, new Uint8Array([255, 255, 255, 255]));
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
            gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
        }
        return this.opaque;
    }

    // A "caller" texture at the output size, for the caller to render into (a G-buffer pass):
    // {id, target}; null when the layout has no such texture.
    callerTarget(name, width, height) {
        const desc = this.layout.textures.find((d) => d.name === name);
        if (!desc || desc.source !== "caller") return null;
        if (desc.size === "output") this.allocateOutputSized(width, height);
        return this.texture(name);
    }

    // Every GL object this runner made (before dropping it for a new emission).
    dispose() {
        const gl = this.gl;
        for (const t of Object.values(this.textures)) gl.deleteTexture(t.id);
        if (this.opaque) gl.deleteTexture(this.opaque);
        this.opaque = null;
        for (const id of Object.values(this.samplers || {})) gl.deleteSampler(id);
        this.samplers = {};
        for (const p of Object.values(this.programs)) gl.deleteProgram(p.id);
        gl.deleteFramebuffer(this.framebuffer);
        gl.deleteFramebuffer(this.readFramebuffer);
        gl.deleteVertexArray(this.emptyVertexArray);
        for (const q of this.pendingQueries || []) gl.deleteQuery(q.query);
        this.textures = {};
        this.programs = {};
    }

    // Writes RGBA floats (bottom row first) into one level and layer of a colour texture.
    uploadTexture(name, level, layer, rgba) {
        const gl = this.gl;
        const t = this.texture(name);
        const f = FORMATS[t.desc.internal_format];
        const width = Math.max(t.width >> level, 1), height = Math.max(t.height >> level, 1);
        if (f.format !== "RGBA" || rgba.length !== 4 * width * height) fail(`uploadTexture ${name}: expected ${4 * width * height} RGBA values`);
        const data = f.float ? Float32Array.from(rgba) : Uint8Array.from(rgba, (v) => Math.round(Math.min(Math.max(v, 0), 1) * 255));
        gl.bindTexture(t.target, t.id);
        gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
        if (t.target === gl.TEXTURE_2D) gl.texSubImage2D(t.target, level, 0, 0, width, height, gl.RGBA, f.float ? gl.FLOAT : gl.UNSIGNED_BYTE, data);
        else gl.texSubImage3D(t.target, level, 0, 0, Math.max(layer, 0), width, height, 1, gl.RGBA, f.float ? gl.FLOAT : gl.UNSIGNED_BYTE, data);
        gl.bindTexture(t.target, null);
    }

    // The layout's result texture (visibility, 0 shadowed to 1 lit) as floats, bottom row first.
    readResult() {
        const rgba = this.readTexture(this.layout.result);
        const out = new Float32Array(rgba.length / 4);
        for (let i = 0; i < out.length; ++i) out[i] = rgba[4 * i];
        return out;
    }

    // One level (and layer) of a colour texture as RGBA floats, bottom row first.
    readTexture(name, level = 0, layer = -1) {
        const gl = this.gl;
        const t = this.texture(name);
        const f = FORMATS[t.desc.internal_format];
        const width = Math.max(t.width >> level, 1), height = Math.max(t.height >> level, 1);
        gl.bindFramebuffer(gl.READ_FRAMEBUFFER, this.readFramebuffer);
        this.attach(gl.READ_FRAMEBUFFER, gl.COLOR_ATTACHMENT0, {texture: name, level, layer});
        gl.readBuffer(gl.COLOR_ATTACHMENT0);
        const n = 4 * width * height;
        let out;
        // WebGL2 always allows RGBA/UNSIGNED_BYTE from normalised and RGBA/FLOAT from float buffers.
        if (f.float) {
            out = new Float32Array(n);
            gl.readPixels(0, 0, width, height, gl.RGBA, gl.FLOAT, out);
        } else {
            const bytes = new Uint8Array(n);
            gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
            out = Float32Array.from(bytes, (b) => b / 255);
        }
        gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
        return out;
    }
}
