// status.js — the lines under the canvas: the scene, the frame's time, each side's GPU pass times,
// the mean error against the bundle's desktop run or its truth, and what the renderers reported.

const $ = (id) => document.getElementById(id);

export function showStatus(app) {
    const sides = app.state.split && app.sides[1] ? app.sides : [app.sides[0]];
    const lines = app.backend === "webgpu"
        ? [`${app.sceneName}: ${app.geometry.count / 3} triangles; WebGPU (adapter ${app.gpu.adapter.vendor} ${app.gpu.adapter.architecture}, ` +
           `the wgsl emission); frame ${app.state.frameMs.toFixed(1)} ms (CPU, with the read-back)`]
        : [`${app.sceneName}: ${app.geometry.count / 3} triangles; ` +
           `frame ${app.state.frameMs.toFixed(1)} ms (CPU, with gl.finish)` +
           (app.timer ? "" : "; no EXT_disjoint_timer_query_webgl2 in this browser, so no GPU pass times")];
    if (app.backendNote) lines.push(app.backendNote);
    sides.forEach((side, i) => {
        if (!side.runner || !side.runner.passTimes) return;
        const times = side.runner.passTimes();
        if (!times || !Object.keys(times).length) return;
        const total = Object.values(times).reduce((a, b) => a + b, 0);
        const byName = new Map(); // passes of one name (nbuffer_level, erosion_reduce, ...) summed
        for (const [key, ms] of Object.entries(times)) {
            const name = key.split(" ")[1], entry = byName.get(name) || {ms: 0, count: 0};
            byName.set(name, {ms: entry.ms + ms, count: entry.count + 1});
        }
        lines.push(`${sides.length > 1 ? (i ? "right" : "left") + " " : ""}GPU ${total.toFixed(2)} ms (timer queries): ` +
                   [...byName].map(([name, e]) => `${name}${e.count > 1 ? " ×" + e.count : ""} ${e.ms.toFixed(2)}`).join(", "));
    });
    const against = {difference: app.bundle.gl, error: app.bundle.truth}[app.state.view];
    if (app.state.view === "error" && !app.bundle.truth)
        lines.push("this bundle carries no ray-traced truth (penumbra-export-bundle --reference N writes one)");
    const shown = app.backend === "webgpu" ? app.sides[0].lastVisibility : app.sides[0].runner && app.sides[0].runner.readResult();
    if (against && app.state.camera === "bundle" && app.sides[0].runner && shown) {
        const v = shown, geometry = app.bundle.callerTextures.penumbra_worldPositions;
        let sum = 0, n = 0;
        for (let i = 0; i < v.length; ++i)
            if (geometry[4 * i + 3] > 0.5 && Number.isFinite(against[i])) { sum += Math.abs(v[i] - against[i]); ++n; }
        lines.push(app.state.view === "error"
            ? `MAE against the truth (${app.bundle.info.truth.kind}, ${app.bundle.info.truth.samples}² rays) ${(sum / Math.max(n, 1)).toFixed(4)} over ${n} pixels`
            : `mean |browser − desktop| ${(sum / Math.max(n, 1)).toFixed(4)} over ${n} pixels (the desktop ran the bundle's configuration: ` +
              `${describe(app.bundle.info.config)})`);
    }
    for (const m of app.messages || []) lines.push(m);
    $("status").textContent = lines.join("\n");
}

function describe(c) {
    if (c.technique !== "occlusion") return c.technique;
    return `${c.slices} slices, ${c.resolution}², ${c.filter}, ${c.fusion}, ${c.packing}, ${c.light}${c.tangent_clip ? ", tangent clip" : ""}`;
}
