// emitter_test.mjs — the WebAssembly emitter against penumbra-gen, byte for byte (label "browser";
// node only, through web/three/penumbra_emitter.js, as the page loads it; the module must import nothing).
//
//   node wasm/emitter_test.mjs --gen build/generator/penumbra-gen --wasm build/wasm/penumbra_emitter.wasm
//
// For every configuration of a seeded sample over the matrix (every technique, target, filter,
// packing, light, fusion, slice count and flag, each technique's parameters; valid and invalid
// values, wrong types, unknown keys, malformed JSON, a whole layout.json) it writes the JSON to
// config.json, runs `penumbra-gen --config config.json --out out` and emits the same text in the
// module. Valid: the module's files are exactly the files penumbra-gen wrote (same names, same
// bytes). Invalid: penumbra-gen exits 2 and writes nothing, the module returns ok = false, and its
// error line is penumbra-gen's stderr, byte for byte. Exit 0 pass, 1 fail, 2 bad arguments.
import {spawnSync} from "node:child_process";
import fs from "node:fs";
import os from "node:os";
import path from "node:path";
import {fileURLToPath, pathToFileURL} from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const {loadEmitter} = await import(pathToFileURL(path.join(here, "../web/three/penumbra_emitter.js")));
const {panelFields} = await import(pathToFileURL(path.join(here, "../web/config_panel.js")));

function parseArguments(argv) {
    const out = {gen: null, wasm: null, seed: 19};
    for (let i = 0; i < argv.length; ++i) {
        const flag = argv[i];
        if (!["--gen", "--wasm", "--seed"].includes(flag) || i + 1 >= argv.length) {
            console.error(`error: '${flag}': usage: node emitter_test.mjs --gen PENUMBRA_GEN --wasm MODULE [--seed N]`);
            process.exit(2);
        }
        out[flag.slice(2)] = argv[++i];
    }
    if (!out.gen || !out.wasm) {
        console.error("error: --gen and --wasm are required");
        process.exit(2);
    }
    return out;
}

// A small seeded generator (mulberry32), so that a failure names a reproducible case.
function random(seed) {
    let a = seed >>> 0;
    return () => {
        a = (a + 0x6d2b79f5) >>> 0;
        let t = a;
        t = Math.imul(t ^ (t >>> 15), t | 1);
        t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
        return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
    };
}

// Values per key: allowed ones, then after BAD out of range or of the wrong type. Allowed values
// can still combine into an invalid configuration (essl300 with 24 slices, volume with sat, ...).
const BAD = Symbol("refused values follow");
const OCCLUSION = {
    slices: [1, 2, 3, 4, 8, 12, 16, 24, 32, 64, 128, BAD, 0, 40, 256, "16"],
    resolution: [32, 64, 128, 256, 512, 1024, 2048, 4096, BAD, 100, 8192, 2.5],
    filter: ["mipmap", "nbuffer", "sat", "gaussian", BAD, "box"],
    fusion: ["probabilistic", "additive", "maximum", "average", "chained", "correlated", "extent", "clustered", BAD, "product"],
    packing: ["atlas", "array", "volume", BAD, "tiles"],
    light: ["rect", "sun", BAD, "point"],
    target: ["glsl330", "glsl450", "essl300", "vulkan", "essl300", "essl300", "hlsl", BAD, "metal"],
    leak_fix: [true, false, BAD, 1],
    self_shadow_fade: [true, false],
    tangent_clip: [true, false, BAD, "yes"],
    slice_placement: ["uniform", "adaptive", BAD, "random"],
};
const TECHNIQUE = {
    shadow_map: {resolution: [32, 256, 1024, 8192, BAD, 100, 16384], constant_bias: [0, 0.02, 1.5, 10, BAD, -1, 11], slope_bias: [0, 1.5, 16, BAD, 17]},
    pcf: {pattern: ["grid", "poisson", BAD, "hex"], grid_size: [1, 4, 16, BAD, 0, 17], poisson_taps: [1, 16, 64, BAD, 65], radius: [0.01, 0.1, 1000, BAD, 0, 1001],
          rotate: [true, false]},
    pcss: {blocker_samples: [1, 8, 16, 64, BAD, 0, 65], filter_samples: [1, 16, 128, BAD, 129], max_filter_texels: [1, 16, 64, 512, BAD, 0, 100000],
           rotate: [true, false]},
    oim: {resolution: [32, 256, 4096, BAD, 8192, 48], intervals: [4, 8, 12, 16, BAD, 5], samples: [256, 512, 1024, 2048, BAD, 300]},
    erosion: {max_search_radius: [1, 16, 256, BAD, 0, 257], edge_threshold: [0.01, 0.5, 4, BAD, 0, 5], search_taps: [1, 32, 64, BAD, 65],
              blur_taps: [1, 16, 64, BAD, 0]},
};
const SECTIONS = {shadowmap: ["shadow_map"], pcf: ["shadow_map", "pcf"], pcss: ["shadow_map", "pcss"], oim: ["oim"],
                  erosion: ["shadow_map", "erosion"]};

function configurations(seed) {
    const next = random(seed);
    // A value's list holds the allowed values first, then after BAD the refused ones, picked 1 time in 8.
    const pick = (list) => {
        const bad = list.indexOf(BAD);
        if (bad < 0) return list[Math.floor(next() * list.length)];
        const refused = next() < 0.125;
        const from = refused ? list.slice(bad + 1) : list.slice(0, bad);
        return from[Math.floor(next() * from.length)];
    };
    const some = (table, p) => {
        const out = {};
        for (const [key, values] of Object.entries(table)) if (next() < p) out[key] = pick(values);
        return out;
    };
    const cases = [];
    // Occlusion textures: a random subset of the keys, each from its list.
    for (let i = 0; i < 64; ++i) cases.push(JSON.stringify(some(OCCLUSION, 0.45)));
    // The other techniques with their parameter objects (and the keys they ignore).
    for (let i = 0; i < 30; ++i) {
        const technique = ["shadowmap", "pcf", "pcss", "oim", "erosion"][i % 5];
        const config = {technique, ...some({light: OCCLUSION.light, target: OCCLUSION.target}, 0.7)};
        if (technique === "oim") config.light = "sun"; // oim needs the sun; invalid values come from its parameters
        for (const section of SECTIONS[technique]) if (next() < 0.8) config[section] = some(TECHNIQUE[section], 0.5);
        if (next() < 0.2) Object.assign(config, some(OCCLUSION, 0.3));
        cases.push(JSON.stringify(config, null, i % 2 ? 2 : 0));
    }
    // What a hand-written file gets wrong.
    cases.push("", "{", "[1, 2]", "null", '{"slices": 8,}', '{"slices": 1e400}', '{"slices": 99999999999}', '{"colour": "red"}',
               '{"pcf": {"taps": 3}}', '{"pcss": 16}', '{"config": 3}', '{"filter": "sat"} trailing', '{"slices": -4}',
               '{"target": "essl300", "slices": 24}', '{"target": "essl300", "slices": 64}', '{"technique": "raytrace"}',
               '{"light": "\\u00e9t\\u00e9"}', '\u00ef\u00bb\u00bf{}');
    return cases;
}

function filesIn(dir) {
    const out = {};
    for (const name of fs.readdirSync(dir).sort()) out[name] = fs.readFileSync(path.join(dir, name));
    return out;
}

async function main() {
    const args = parseArguments(process.argv.slice(2));
    const bytes = fs.readFileSync(args.wasm);
    const imports = WebAssembly.Module.imports(new WebAssembly.Module(bytes));
    if (imports.length) {
        console.log(`FAIL the module imports ${imports.map((i) => `${i.module}.${i.name}`).join(", ")}; it must import nothing`);
        process.exit(1);
    }
    const emitter = await loadEmitter(bytes);
    const cases = configurations(Number(args.seed));
    // A whole layout.json as the configuration (penumbra-gen reads its "config" object).
    const sample = emitter.emit({slices: 8, filter: "mipmap", target: "essl300"});
    if (!sample.ok) throw new Error(`the sample for the layout.json case is invalid: ${sample.error}`);
    cases.push(sample.files["layout.json"]);
    // The profiles (penumbra/profiles.hpp), with keys beside them that win, in JSON's own order.
    cases.push('{"profile": "large"}', '{"profile": "large", "light": "sun", "fusion": "chained"}',
               '{"fusion": "extent", "profile": "large", "target": "essl300"}', '{"profile": "fast", "target": "wgsl"}',
               '{"slices": 16, "profile": "fast"}', '{"profile": "huge"}');
    // The add-ons' profile option (penumbra_emission.js): the configuration it asks the module for.
    const {requestedEmission, PROFILES} = await import(pathToFileURL(path.join(here, "../web/three/penumbra_emission.js")));
    // The add-ons check the option before any module is loaded, against their own list: it must be the
    // table's (penumbra/profiles.hpp), in its order.
    const profileNames = emitter.fields().find((f) => f.key === "profile")?.names ?? [];
    if (JSON.stringify(PROFILES) !== JSON.stringify(profileNames))
        throw new Error(`the add-ons' PROFILES ${JSON.stringify(PROFILES)} are not the emitter's profiles ${JSON.stringify(profileNames)}`);
    for (const kind of ["rect", "sun"]) {
        const large = emitter.emit(requestedEmission({profile: "large"}, kind));
        const c = large.ok ? large.layout.config : {};
        if (c.profile !== "large" || c.fusion !== "extent" || c.irradiance_quadrants !== true || (c.irradiance_window ?? true) !== true)
            throw new Error(`profile large for ${kind}: ${large.ok ? JSON.stringify(c) : large.error}`);
        const fast = emitter.emit(requestedEmission({profile: "fast"}, kind));
        const f = fast.ok ? fast.layout.config : {};
        if (f.profile !== "fast" || f.slices !== 8 || f.resolution !== 128 || f.fusion !== "chained" || f.irradiance_window !== false)
            throw new Error(`profile fast for ${kind}: ${fast.ok ? JSON.stringify(f) : fast.error}`);
    }
    if (requestedEmission({profile: "balanced"}, "rect") !== "rect-nbuffer-16x512")
        throw new Error("profile balanced alone should be the shipped default emission");
    // Metal: penumbra-gen translates it with SPIRV-Cross, which the module does not link; the module
    // refuses it, naming where it is written.
    const metal = emitter.emit({target: "msl"});
    if (metal.ok || !metal.error.includes("penumbra-gen --target msl"))
        throw new Error(`target msl: the module should refuse it naming penumbra-gen: ${metal.ok ? "emitted" : metal.error}`);
    const root = fs.mkdtempSync(path.join(os.tmpdir(), "penumbra-emitter-test-"));
    let valid = 0, invalid = 0;
    const failures = [];
    cases.forEach((text, i) => {
        const dir = path.join(root, String(i));
        fs.mkdirSync(dir);
        fs.writeFileSync(path.join(dir, "config.json"), text);
        const gen = spawnSync(path.resolve(args.gen), ["--config", "config.json", "--out", "out"], {cwd: dir, encoding: "utf8"});
        const r = emitter.emit(text, {source: "config.json"});
        const label = `case ${i} ${text.length > 160 ? text.slice(0, 160) + "…" : text}`;
        const fail = (why) => failures.push(`${label}: ${why}`);
        if (gen.status === 0) {
            ++valid;
            if (!r.ok) return fail(`penumbra-gen wrote the files, the module refused: ${r.error}`);
            const written = filesIn(path.join(dir, "out"));
            const ours = Object.keys(r.files).sort(), theirs = Object.keys(written);
            if (ours.join() !== theirs.join()) return fail(`files differ: module [${ours}] vs penumbra-gen [${theirs}]`);
            for (const name of ours)
                if (!Buffer.from(r.files[name], "utf8").equals(written[name])) return fail(`${name} differs`);
            if (JSON.stringify(r.layout) !== JSON.stringify(JSON.parse(written["layout.json"]))) return fail("layout differs");
        } else if (gen.status === 2) {
            ++invalid;
            if (r.ok) return fail(`penumbra-gen refused (${gen.stderr.trim()}), the module emitted`);
            if (gen.stderr !== r.error + "\n") return fail(`messages differ:\n  penumbra-gen: ${gen.stderr.trim()}\n  module:       ${r.error}`);
            if (!r.diagnostics.length || r.diagnostics.some((d) => d.severity !== "error" || !d.message || !r.error.includes(d.message)))
                return fail(`diagnostics do not make up the error line: ${JSON.stringify(r.diagnostics)}`);
            if (fs.existsSync(path.join(dir, "out"))) return fail("penumbra-gen wrote an output directory for an invalid configuration");
        } else {
            fail(`penumbra-gen exited ${gen.status}: ${gen.error ?? gen.stderr.trim()}`);
        }
    });
    fs.rmSync(root, {recursive: true, force: true});

    // The page's panel (web/config_panel.js, from the module's table of configuration fields): a field
    // for every key of layout.json's config, each with penumbra-gen's flag and its --help text word for
    // word (a field written only when not its default, such as alpha_test, may be absent from the sample).
    const FIELDS = panelFields(emitter);
    const help = spawnSync(path.resolve(args.gen), ["--help"], {encoding: "utf8"}).stdout.replace(/\s+/g, " ");
    const keys = [];
    const walk = (object, prefix) => {
        for (const [k, v] of Object.entries(object))
            if (v && typeof v === "object") walk(v, `${prefix}${k}.`);
            else keys.push(prefix + k);
    };
    walk(sample.layout.config, "");
    for (const key of keys)
        if (!FIELDS.some((f) => f.key === key)) failures.push(`panel: no field for layout.json config key ${key}`);
    for (const f of FIELDS) {
        if (!keys.includes(f.key) && !f.optional) failures.push(`panel: field ${f.key} is no key of layout.json's config`);
        if (!help.includes(f.flag)) failures.push(`panel: ${f.key}: flag ${f.flag} is not in penumbra-gen --help`);
        if (!help.includes(f.help)) failures.push(`panel: ${f.key}: '${f.help}' is not what penumbra-gen --help says`);
    }
    console.log(`panel: ${FIELDS.length} fields for the ${keys.length} keys of layout.json's config, flags and help text as --help`);
    console.log(`${cases.length} configurations: ${valid} valid (files equal byte for byte), ${invalid} invalid (same error line); ` +
                `${failures.length} failures`);
    for (const f of failures) console.log(`FAIL ${f}`);
    // The sample must cover both sides, or it proves less than it says.
    if (valid < 20 || invalid < 20) {
        console.log(`FAIL the sample has ${valid} valid and ${invalid} invalid configurations; at least 20 of each are needed`);
        process.exit(1);
    }
    process.exit(failures.length ? 1 : 0);
}

main();
