#!/usr/bin/env node
// scripts/corpus_convert.js — the corpus's converter (scripts/get_corpus.sh runs it): meshes that
// are not OBJ or glTF into Wavefront OBJ, and the triangle count of any corpus file.
//
//   corpus_convert.js ply    IN.ply[.gz] OUT.obj   ASCII or binary PLY (vertex x y z, face lists), gzip or not
//   corpus_convert.js module IN.js OUT.obj         a CommonJS module exporting {positions, cells} (npm
//                                                  teapot, snowden): required here, so it is code you trust
//   corpus_convert.js count  FILE                  prints the triangles of an .obj, .glb or .gltf file
//
// Polygons are fan-triangulated; every index is checked against the vertex count and every
// coordinate must be finite. OUT is written to OUT.tmp and renamed, so it is whole or absent.
// Errors: one "error: ..." line on stderr, exit 2. Node's standard library only.
'use strict';
const fs = require('fs');
const path = require('path');
const zlib = require('zlib');

class InputError extends Error {}
const fail = (message) => { throw new InputError(message); };

function readMaybeGzip(file) {
    const data = fs.readFileSync(file);
    return data.length >= 2 && data[0] === 0x1f && data[1] === 0x8b ? zlib.gunzipSync(data) : data;
}

// PLY: {positions: [[x,y,z]...], faces: [[i,j,k,...]...]}.
function parsePly(file) {
    const data = readMaybeGzip(file);
    const headerEnd = data.indexOf('end_header');
    if (data.subarray(0, 3).toString() !== 'ply' || headerEnd < 0) fail(`${file}: not a PLY file (no 'ply' ... 'end_header' header)`);
    const bodyStart = data.indexOf(0x0a, headerEnd) + 1;
    const header = data.subarray(0, bodyStart).toString('latin1').split(/\r?\n/);
    let format = null;
    const elements = [];
    for (const line of header) {
        const w = line.trim().split(/\s+/);
        if (w[0] === 'format') format = w[1];
        else if (w[0] === 'element') elements.push({name: w[1], count: Number(w[2]), props: []});
        else if (w[0] === 'property') {
            if (!elements.length) fail(`${file}: property before any element`);
            elements[elements.length - 1].props.push(w[1] === 'list' ? {list: true, countType: w[2], type: w[3], name: w[4]}
                                                                     : {list: false, type: w[1], name: w[2]});
        }
    }
    if (!['ascii', 'binary_little_endian', 'binary_big_endian'].includes(format)) fail(`${file}: PLY format '${format}' is not ascii or binary`);
    const vertex = elements.find((e) => e.name === 'vertex');
    const face = elements.find((e) => e.name === 'face');
    if (!vertex || !face) fail(`${file}: PLY needs a vertex and a face element`);
    const axes = ['x', 'y', 'z'].map((a) => vertex.props.findIndex((p) => p.name === a && !p.list));
    if (axes.some((i) => i < 0)) fail(`${file}: PLY vertex element lacks x, y or z`);
    const faceList = face.props.findIndex((p) => p.list && (p.name === 'vertex_indices' || p.name === 'vertex_index'));
    if (faceList < 0) fail(`${file}: PLY face element has no vertex_indices list`);

    const positions = [], faces = [];
    if (format === 'ascii') {
        const tokens = data.subarray(bodyStart).toString('latin1').split(/\s+/).filter((t) => t.length);
        let t = 0;
        const next = () => { if (t >= tokens.length) fail(`${file}: PLY body ends early`); return Number(tokens[t++]); };
        for (const e of elements)
            for (let n = 0; n < e.count; ++n) {
                const values = [];
                for (const p of e.props) {
                    if (!p.list) { values.push(next()); continue; }
                    const k = next(), list = [];
                    for (let i = 0; i < k; ++i) list.push(next());
                    values.push(list);
                }
                if (e === vertex) positions.push(axes.map((i) => values[i]));
                else if (e === face) faces.push(values[faceList]);
            }
    } else {
        const little = format === 'binary_little_endian';
        const size = {char: 1, uchar: 1, int8: 1, uint8: 1, short: 2, ushort: 2, int16: 2, uint16: 2, int: 4, uint: 4,
                      int32: 4, uint32: 4, float: 4, float32: 4, double: 8, float64: 8};
        const view = new DataView(data.buffer, data.byteOffset, data.byteLength);
        let o = bodyStart;
        const read = (type) => {
            if (!(type in size)) fail(`${file}: PLY type '${type}' is not known`);
            if (o + size[type] > data.length) fail(`${file}: PLY body ends early`);
            let v;
            switch (type) {
                case 'char': case 'int8': v = view.getInt8(o); break;
                case 'uchar': case 'uint8': v = view.getUint8(o); break;
                case 'short': case 'int16': v = view.getInt16(o, little); break;
                case 'ushort': case 'uint16': v = view.getUint16(o, little); break;
                case 'int': case 'int32': v = view.getInt32(o, little); break;
                case 'uint': case 'uint32': v = view.getUint32(o, little); break;
                case 'float': case 'float32': v = view.getFloat32(o, little); break;
                default: v = view.getFloat64(o, little);
            }
            o += size[type];
            return v;
        };
        for (const e of elements)
            for (let n = 0; n < e.count; ++n) {
                const values = [];
                for (const p of e.props) {
                    if (!p.list) { values.push(read(p.type)); continue; }
                    const k = read(p.countType), list = [];
                    for (let i = 0; i < k; ++i) list.push(read(p.type));
                    values.push(list);
                }
                if (e === vertex) positions.push(axes.map((i) => values[i]));
                else if (e === face) faces.push(values[faceList]);
            }
    }
    return {positions, faces};
}

// A {positions, cells} module (the stackgl "simplicial complex" convention).
function loadModule(file) {
    let mod;
    try {
        mod = require(path.resolve(file));
    } catch (e) {
        fail(`${file}: cannot load the module: ${String(e.message).split('\n')[0]}`);
    }
    if (!mod || !Array.isArray(mod.positions) || !Array.isArray(mod.cells)) fail(`${file}: the module does not export {positions, cells} arrays`);
    return {positions: mod.positions, faces: mod.cells};
}

// Writes OBJ (1-based, fan-triangulated) atomically; returns the triangle count.
function writeObj(mesh, source, out) {
    const n = mesh.positions.length;
    if (n === 0) fail(`${source}: no vertices`);
    const lines = [`# converted from ${path.basename(source)} by penumbra scripts/corpus_convert.js`,
                   `# ${n} vertices`];
    mesh.positions.forEach((p, i) => {
        if (!Array.isArray(p) || p.length < 3 || !p.slice(0, 3).every(Number.isFinite)) fail(`${source}: vertex ${i} is not three finite numbers`);
        lines.push(`v ${p[0]} ${p[1]} ${p[2]}`);
    });
    let triangles = 0;
    mesh.faces.forEach((f, i) => {
        if (!Array.isArray(f) || f.length < 3) fail(`${source}: face ${i} has fewer than three corners`);
        for (const v of f) if (!Number.isInteger(v) || v < 0 || v >= n) fail(`${source}: face ${i} has index ${v}, allowed 0 to ${n - 1}`);
        for (let k = 1; k + 1 < f.length; ++k) {
            lines.push(`f ${f[0] + 1} ${f[k] + 1} ${f[k + 1] + 1}`);
            ++triangles;
        }
    });
    if (triangles === 0) fail(`${source}: no faces`);
    const tmp = `${out}.tmp`;
    fs.writeFileSync(tmp, lines.join('\n') + '\n');
    fs.renameSync(tmp, out);
    return triangles;
}

// Triangles of an OBJ file: each face of k corners gives k − 2.
function countObj(file) {
    let triangles = 0;
    for (const line of fs.readFileSync(file, 'latin1').split('\n')) {
        if (!line.startsWith('f ') && !line.startsWith('f\t')) continue;
        const corners = line.trim().split(/\s+/).length - 1;
        if (corners >= 3) triangles += corners - 2;
    }
    return triangles;
}

// Triangles of a glTF 2.0 asset's default scene: every node's mesh (instances counted), its
// primitives in mode 4 (TRIANGLES, the default) or 5/6 (strip, fan), from the index or POSITION count.
function countGltf(file) {
    const data = fs.readFileSync(file);
    let json;
    if (data.subarray(0, 4).toString('latin1') === 'glTF') {
        const length = data.readUInt32LE(12);
        if (data.readUInt32LE(16) !== 0x4e4f534a) fail(`${file}: the first GLB chunk is not JSON`);
        json = JSON.parse(data.subarray(20, 20 + length).toString('utf8'));
    } else {
        json = JSON.parse(data.toString('utf8'));
    }
    const accessors = json.accessors || [], meshes = json.meshes || [], nodes = json.nodes || [];
    const meshTriangles = meshes.map((m) => (m.primitives || []).reduce((sum, p) => {
        const mode = p.mode === undefined ? 4 : p.mode;
        const accessor = accessors[p.indices !== undefined ? p.indices : (p.attributes || {}).POSITION];
        const count = accessor ? accessor.count : 0;
        return sum + (mode === 4 ? Math.floor(count / 3) : mode === 5 || mode === 6 ? Math.max(0, count - 2) : 0);
    }, 0));
    const scenes = json.scenes || [];
    const roots = scenes.length ? scenes[json.scene || 0].nodes || [] : nodes.map((_, i) => i);
    let triangles = 0;
    const visit = (i, depth) => {
        if (depth > 64 || !nodes[i]) return;
        if (nodes[i].mesh !== undefined && meshes[nodes[i].mesh]) triangles += meshTriangles[nodes[i].mesh];
        for (const c of nodes[i].children || []) visit(c, depth + 1);
    };
    roots.forEach((r) => visit(r, 0));
    return triangles;
}

function main(argv) {
    const [mode, input, out] = argv;
    const usage = 'usage: corpus_convert.js ply IN.ply[.gz] OUT.obj | module IN.js OUT.obj | count FILE';
    if (mode === 'count' && input) {
        if (!fs.existsSync(input)) fail(`${input}: no such file`);
        const ext = path.extname(input).toLowerCase();
        if (ext === '.obj') console.log(countObj(input));
        else if (ext === '.glb' || ext === '.gltf') console.log(countGltf(input));
        else fail(`${input}: count reads .obj, .glb or .gltf files`);
        return;
    }
    if ((mode !== 'ply' && mode !== 'module') || !input || !out) fail(`${usage}`);
    if (!fs.existsSync(input)) fail(`${input}: no such file`);
    const mesh = mode === 'ply' ? parsePly(input) : loadModule(input);
    console.log(writeObj(mesh, input, out));
}

try {
    main(process.argv.slice(2));
} catch (e) {
    if (!(e instanceof InputError) && !(e instanceof SyntaxError)) throw e;
    console.error(`error: ${e.message}`);
    process.exit(2);
}
