// penumbra_emission.js — what every add-on (penumbra-three here; penumbra-babylon, whose package
// copies this folder's renderer-free modules) does alike whatever the engine: the add-on's error,
// each add-on's own names, the emission's files (shipped in emissions/, a folder, in memory, or
// emitted by the WebAssembly emitter) and the visibility snippet's parameters. It imports no
// engine: only emissions.js, and penumbra_emitter.js on demand.
import {EMISSIONS} from "./emissions.js";

export {EMISSIONS};

export class PenumbraError extends Error {}

export function fail(message) {
    throw new PenumbraError(`PenumbraShadows: ${message}`);
}

// The shadow quality tiers (penumbra/profiles.hpp's Profile, in its order).
export const PROFILES = ["balanced", "large", "fast"];

// What load() emits or fetches: options.emission, or the profile's (penumbra/profiles.hpp) configuration
// for this light, through the WebAssembly emitter; "balanced" alone is the shipped default emission.
export function requestedEmission(options, kind) {
    const shipped = kind === "sun" ? "sun-nbuffer-16x512" : "rect-nbuffer-16x512";
    const profile = options.profile;
    if (profile === undefined) return options.emission ?? shipped;
    if (!PROFILES.includes(profile)) fail(`profile '${profile}' is not allowed; allowed: ${PROFILES.join(", ")}`);
    const emission = options.emission;
    if (emission === undefined) return profile === "balanced" ? shipped : {profile, light: kind};
    if (emission && typeof emission === "object" && !emission.layout) return {...emission, profile};
    fail("profile applies to a configuration (options.emission a configuration object, or none); " +
         "this emission is already emitted");
}

// The emission for `requested` (requestedEmission's) with the alpha test where `alphaTest` says
// (undefined: where cuts(), the engine's own test of whether the scene's casters cut, is true): a shipped
// name's "<name>-cut" twin (penumbra-gen --alpha-test; emissions/regenerate.sh), a configuration with
// alpha_test: true (a forced true wins over the configuration's own alpha_test, a followed one does not).
// A shipped name without a twin, a folder or an emission in memory is taken as it is: if it has no alpha
// test, the add-on warns and draws the casters solid.
export function emissionWithCut(requested, alphaTest, cuts) {
    if (!(alphaTest ?? cuts())) return requested;
    if (typeof requested === "string" && Object.hasOwn(EMISSIONS, requested))
        return Object.hasOwn(EMISSIONS, `${requested}-cut`) ? `${requested}-cut` : requested;
    if (requested && typeof requested === "object" && !requested.layout)
        return alphaTest === true ? {...requested, alpha_test: true} : {alpha_test: true, ...requested};
    return requested;
}

// Every add-on gets its own names: the emission's identifiers penumbra_x / penumbraX become
// penumbra<N>_x / penumbra<N>X (N: the add-on's serial number), so that several add-ons (one per
// light) can put their snippets into one material.
let serial = 0;
export function nextSerial() {
    return ++serial;
}
export function renamer(prefix) {
    return (text) => text.replace(/\bpenumbra(?=[_A-Z])/g, prefix);
}

// The emission's files for a renderer's target ("essl300" on WebGL2, "wgsl" on WebGPU):
// {layout, files}. `emission`: a key of EMISSIONS (the wgsl one of a key is "<key>-wgsl"), a
// folder URL ending in "/", {layout, files}, or a configuration object (the WebAssembly emitter).
export async function loadEmissionFiles(emission, kind, wasm, target) {
    const snippet = target === "wgsl" ? "penumbra_visibility.wgsl" : "penumbra_visibility.glsl";
    const check = (em) => {
        const t = em.layout && em.layout.config && em.layout.config.target;
        if (t && t !== target)
            fail(`the emission's target is '${t}', but this renderer runs '${target}' (penumbra-gen --target ${target}` +
                 `${target === "wgsl" ? " for WebGPU: three's WebGPURenderer, Babylon's WebGPUEngine" :
                                        " for WebGL2: three's WebGLRenderer, Babylon's Engine"})`);
        if (typeof em.files[snippet] !== "string") fail(`the emission has no ${snippet}`);
        return em;
    };
    if (typeof emission === "string") {
        const shipped = target === "wgsl" ? `${emission}-wgsl` : emission;
        if (Object.hasOwn(EMISSIONS, shipped)) {
            const files = {};
            await Promise.all(Object.entries(EMISSIONS[shipped]).map(async ([name, url]) => {
                const response = await fetch(url);
                if (!response.ok) fail(`emission '${emission}': ${url}: HTTP ${response.status}`);
                files[name] = await response.text();
            }));
            return check({layout: JSON.parse(files["layout.json"]), files});
        }
        if (!emission.endsWith("/")) {
            const keys = Object.keys(EMISSIONS).filter((k) => k.endsWith("-wgsl") === (target === "wgsl"))
                .map((k) => k.replace(/-wgsl$/, ""));
            fail(`emission '${emission}': not one of ${keys.join(", ")} (shipped for ${target}) nor a folder URL ending in '/'`);
        }
        const fetchText = async (name) => {
            const response = await fetch(emission + name);
            if (!response.ok) fail(`${emission}${name}: HTTP ${response.status}`);
            return response.text();
        };
        const layout = JSON.parse(await fetchText("layout.json"));
        const files = {};
        // (the snippet is no program of the layout: fetched by name)
        const names = new Set([...(layout.programs || []).flatMap((p) => p.files), snippet]);
        await Promise.all([...names].map(async (name) => (files[name] = await fetchText(name))));
        return check({layout, files});
    }
    if (emission && emission.layout && emission.files) return check(emission);
    if (emission && typeof emission === "object") {
        // A configuration (penumbra-gen --config's schema): emitted here by the WebAssembly emitter.
        const emitter = await loadEmitter(wasm);
        const result = emitter.emit({light: kind, ...emission, target});
        if (!result.ok) fail(`emission: ${result.diagnostics.map((d) => d.message).join("; ") || result.error}`);
        return check({layout: result.layout, files: result.files});
    }
    fail("options.emission: a key of EMISSIONS, a folder URL ending in '/', {layout, files}, or a configuration object");
}

// The WebAssembly emitter (penumbra_emitter.js; its .wasm at `wasm`, default the one beside it),
// loaded once, on demand (bundlers split it and its .wasm off the main chunk).
let emitterPromise = null;
export function loadEmitter(wasm = null) {
    if (!emitterPromise)
        emitterPromise = import("./penumbra_emitter.js")
            .then((m) => (wasm ? m.loadEmitter(wasm) : m.loadEmitter()))
            .catch((e) => {
                emitterPromise = null;
                fail(`a configuration needs the WebAssembly emitter (penumbra_emitter.js and penumbra_emitter.wasm), which did not load: ${e.message}`);
            });
    return emitterPromise;
}

// The uniforms of the visibility snippet, from layout.json: the parameters of the program of the
// screen pass that writes the result (the deferred shading pass, which includes the snippet),
// less the textures the caller fills (its G-buffer).
export function snippetParameters(layout) {
    const pass = (layout.passes || []).find((p) => p.phase === "screen" && p.outputs.some((o) => o.texture === layout.result));
    const program = pass && (layout.programs || []).find((p) => p.name === pass.program);
    if (!program) fail(`layout.json: no screen pass writing '${layout.result}', so the visibility snippet's parameters are unknown`);
    const caller = new Set(layout.textures.filter((t) => t.source === "caller").map((t) => t.name));
    return program.parameters.filter((p) => !caller.has(p.name));
}
