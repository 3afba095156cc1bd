// controls.js — the controls under the canvas (scene, view, renderer, camera, split view, the light
// sliders) and dragging on the canvas: orbit, or with shift move the light. They change the app's
// state and re-render; the panels of the configuration are config_panel.js.

import {BACKENDS} from "./side.js";

const $ = (id) => document.getElementById(id);

export function buildControls(app) {
    const controls = $("controls");
    const row = (...items) => {
        const div = document.createElement("div");
        div.className = "row";
        div.append(...items);
        controls.append(div);
        return div;
    };
    const select = (id, options, value, onChange) => {
        const s = Object.assign(document.createElement("select"), {id});
        for (const [v, text] of options) s.append(Object.assign(document.createElement("option"), {value: v, textContent: text}));
        s.value = value;
        s.addEventListener("change", () => onChange(s.value));
        return s;
    };
    row("scene ", select("scene", app.scenes.map((s) => [s.name, s.name]), app.sceneName, async (name) => {
        await app.loadScene(app.scenes.find((s) => s.name === name));
        buildLightControls(app);
        app.sides.forEach((s) => s && s.update(false));
        app.render();
    }));
    row("view ", select("view-mode", [["shaded", "shaded"], ["visibility", "visibility"], ["difference", "difference from the bundle's desktop run"],
                                       ["error", "error against the bundle's ray-traced truth"]],
                        app.state.view, (v) => {
                            app.state.view = v;
                            if (v === "difference" || v === "error") app.setCamera("bundle"); else app.render();
                        }));
    row("renderer ", select("backend", Object.entries(BACKENDS).map(([key, b]) => [key, `${b.name} (the ${b.target} emission)`]), app.backend,
                            (v) => app.setBackend(v)));
    row("camera ", select("camera", [["orbit", "orbit (drag the image)"], ["bundle", "the bundle's camera and G-buffers"]], app.state.camera,
                          (v) => app.setCamera(v)));
    const split = Object.assign(document.createElement("input"), {type: "checkbox", id: "split"});
    split.addEventListener("change", () => app.setSplit(split.checked));
    const label = document.createElement("label");
    label.append(split, " split view: a second configuration on the right half");
    row(label);
    app.lightRow = document.createElement("div");
    controls.append(app.lightRow);
    buildLightControls(app);

    // Orbit by dragging; with shift, the light moves over the scene.
    let drag = null;
    app.canvas.addEventListener("pointerdown", (e) => { drag = {x: e.clientX, y: e.clientY, shift: e.shiftKey}; app.canvas.setPointerCapture(e.pointerId); });
    app.canvas.addEventListener("pointerup", () => { drag = null; });
    app.canvas.addEventListener("pointermove", (e) => {
        if (!drag) return;
        const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
        drag.x = e.clientX;
        drag.y = e.clientY;
        if (drag.shift) {
            const kind = app.sides[0].runner ? app.sides[0].runner.layout.config.light : "rect";
            const light = app.light(kind);
            const span = Math.max(app.geometry.box.hi[0] - app.geometry.box.lo[0], 1e-3);
            if (kind === "rect") { light.center[0] += dx * span / 300; light.center[2] += dy * span / 300; }
            else light.direction = [light.direction[0] + dx / 200, light.direction[1], light.direction[2] + dy / 200];
        } else {
            app.state.yaw -= dx / 150;
            app.state.pitch = Math.min(1.5, Math.max(-0.2, app.state.pitch + dy / 150));
        }
        app.render();
    });
}

// Rebuilt with each scene: the sliders' ranges follow its bounds.
function buildLightControls(app) {
    const panel = app.lightRow;
    panel.replaceChildren();
    const box = app.geometry.box;
    const span = Math.max(box.hi[0] - box.lo[0], box.hi[2] - box.lo[2], 1e-3);
    const slider = (label, id, min, max, value, onInput) => {
        const row = document.createElement("label");
        row.className = "row";
        const input = Object.assign(document.createElement("input"), {type: "range", id, min, max, step: (max - min) / 200, value});
        const shown = Object.assign(document.createElement("span"), {textContent: Number(value).toFixed(2)});
        input.addEventListener("input", () => { shown.textContent = Number(input.value).toFixed(2); onInput(Number(input.value)); app.render(); });
        row.append(label + " ", input, " ", shown);
        panel.append(row);
    };
    const rect = app.light("rect");
    ["x", "y", "z"].forEach((axis, i) => {
        const lo = i === 1 ? box.hi[1] + 0.05 * span : box.lo[i] - 0.5 * span;
        const hi = i === 1 ? box.hi[1] + 2 * span : box.hi[i] + 0.5 * span;
        slider(`rect light ${axis}`, `light-${axis}`, lo, hi, rect.center[i], (v) => { rect.center[i] = v; });
    });
    const aspect = rect.height / rect.width;
    slider("rect light width", "light-width", 0.01 * span, span, rect.width, (v) => { rect.width = v; rect.height = v * aspect; });
    const sun = app.light("sun");
    const d = sun.direction;
    let azimuth = Math.atan2(d[2], d[0]), elevation = Math.asin(Math.min(1, -d[1] / Math.hypot(...d)));
    const set = () => { sun.direction = [Math.cos(elevation) * Math.cos(azimuth), -Math.sin(elevation), Math.cos(elevation) * Math.sin(azimuth)]; };
    slider("sun azimuth", "sun-azimuth", -Math.PI, Math.PI, azimuth, (v) => { azimuth = v; set(); });
    slider("sun elevation", "sun-elevation", 0.2, Math.PI / 2, elevation, (v) => { elevation = v; set(); });
    slider("sun diameter (°)", "sun-diameter", 0.1, 20, sun.angularDiameter * 180 / Math.PI, (v) => { sun.angularDiameter = v * Math.PI / 180; });
    if (app.bundle.info.sun_path) // oim: the sun can only move along the path its bake traced
        slider("oim sun time t (the bake's path)", "sun-time", 0, 1, app.state.sunTime, (v) => app.setSunTime(v));
}
