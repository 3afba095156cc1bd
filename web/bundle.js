// bundle.js — what the page takes from a bundle of penumbra-export-bundle (targets/bundle/README.md):
// its files, its images as textures, its light, and whether a layout can run with what it carries.
//
//   const bundle = await loadBundle("scenes/boxes/");  // {info, width, height, triangles, ...}
//   const reason = cannotRun(layout, bundle, camera);  // "" when it can

export async function fetchOk(url) {
    const response = await fetch(url);
    if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
    return response;
}
export const floats = async (url) => new Float32Array(await (await fetchOk(url)).arrayBuffer());

// Everything of a bundle the page uses (targets/bundle/README.md): triangles, light, G-buffers at
// its camera, the desktop run's visibility; the oracle's value and bound (occlusion textures), the
// ray-traced truth (--reference), the bake (oim) where it has them.
export async function loadBundle(base) {
    const info = await (await fetchOk(base + "uniforms.json")).json();
    const bundle = {base, info, width: info.width, height: info.height, triangles: await floats(base + "mesh.f32"), callerTextures: {},
                    bake: {}, gl: await floats(base + "visibility_gl.f32"), oracle: null, bound: null, truth: null};
    for (const [name, file] of Object.entries(info.caller_textures || {})) bundle.callerTextures[name] = await floats(base + file);
    for (const [name, file] of Object.entries(info.bake_textures || {})) bundle.bake[name] = await floats(base + file);
    if (info.config.technique === "occlusion") {
        bundle.oracle = await floats(base + "oracle.f32");
        bundle.bound = await floats(base + "bound.f32");
    }
    if (info.truth) bundle.truth = await floats(base + info.truth.file);
    return bundle;
}

// An R32F texture of a bundle image (bottom row first), for the difference and error views.
export function imageTexture(gl, width, height, values) {
    const id = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, id);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.R32F, width, height);
    // one level: NEAREST, or the texture is incomplete and texelFetch reads 0
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, width, height, gl.RED, gl.FLOAT, values);
    gl.bindTexture(gl.TEXTURE_2D, null);
    return id;
}

// The light of a bundle, or a default one of the other kind over the bounds.
export function lightFor(kind, bundle, box) {
    const span = Math.max(box.hi[0] - box.lo[0], box.hi[2] - box.lo[2], 1e-3);
    const centre = [0, 2].map((i) => 0.5 * (box.lo[i] + box.hi[i]));
    const given = bundle.info.light;
    if (kind === "sun") {
        if (given.kind === "sun") return {kind: "sun", direction: [...given.direction], angularDiameter: given.angular_diameter_degrees * Math.PI / 180};
        return {kind: "sun", direction: [0.3, -1, 0.2], angularDiameter: 5 * Math.PI / 180};
    }
    if (given.kind === "rect") {
        const m = bundle.info.uniforms.penumbra_lightFromWorld;
        return {kind: "rect", center: [...given.center], u: [m[0], m[4], m[8]], v: [m[1], m[5], m[9]], width: given.width, height: given.height};
    }
    return {kind: "rect", center: [centre[0], box.hi[1] + span, centre[1]], u: [1, 0, 0], v: [0, 0, 1], width: 0.2 * span, height: 0.2 * span};
}

// Why a layout cannot run on this page with this bundle at this camera ("" when it can).
export function cannotRun(layout, bundle, camera) {
    const baked = layout.textures.filter((t) => t.source === "bake");
    if (baked.length) {
        const c = layout.config, b = bundle.info.config;
        const missing = baked.filter((t) => !bundle.bake[t.name]).map((t) => t.name);
        if (missing.length)
            return `cannot run here: ${c.technique} reads textures baked offline (${missing.join(", ")}), which this scene's bundle does not ` +
                   "carry (penumbra-export-bundle --technique oim writes a bundle with its bake)";
        if (b.oim.resolution !== c.oim.resolution || b.oim.intervals !== c.oim.intervals || b.oim.samples !== c.oim.samples)
            return `cannot run here: the bundle's bake is for oim.resolution ${b.oim.resolution}, oim.intervals ${b.oim.intervals}, ` +
                   `oim.samples ${b.oim.samples}`;
    }
    for (const t of layout.textures) {
        if (t.source !== "caller" || ["penumbra_worldPositions", "penumbra_worldNormals"].includes(t.name)) continue;
        if (!bundle.callerTextures[t.name]) return `cannot run here: the layout reads a G-buffer (${t.name}) that this page does not draw`;
        if (camera !== "bundle")
            return `runs only at the bundle's camera here: the layout reads ${t.name}, which the bundle carries for its camera (camera: the bundle's)`;
    }
    return "";
}
