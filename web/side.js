// side.js — one side of the view (the split view has two): its panel, its emission, and the runner
// of the emission its renderer runs, rebuilt on every change of the panel.
//
//   const side = new Side(app, 0, "configuration", {resolution: 256});
//   side.update();  // re-emit, rebuild the runner, re-render

import {LayoutRunner} from "./three/penumbra_runner.js";
import {WebGPULayoutRunner} from "./three/penumbra_webgpu_runner.js";
import {ConfigPanel} from "./config_panel.js";
import {cannotRun} from "./bundle.js";
import {showFiles} from "./emitted_files.js";

const $ = (id) => document.getElementById(id);

// The page's renderers: the emission each one runs.
export const BACKENDS = {
    webgl2: {name: "WebGL2", target: "essl300", language: "ES 3.00"},
    webgpu: {name: "WebGPU", target: "wgsl", language: "WGSL"},
};

// One side of the view: its panel, its emission (as asked), the essl300 emission it runs, its runner.
export class Side {
    constructor(app, index, title, initial) {
        this.app = app;
        this.index = index;
        this.emissions = 0;
        this.runner = null;
        this.reason = "";
        this.generation = 0;        // WebGPU runners are built asynchronously: only the latest one is kept
        this.lastVisibility = null; // WebGPU: the last result read back
        this.panel = new ConfigPanel($("panels"), app.emitter, {
            id: index ? "right" : "left", title, defaults: app.defaults, initial, onChange: () => this.update(),
        });
    }

    // Re-emits from the panel, rebuilds the runner, re-renders.
    update(render = true) {
        const config = this.panel.config();
        const emission = this.app.emitter.emit(config);
        ++this.emissions;
        this.emission = emission;
        this.reason = "";
        let note = emission.ok ? `emitted ${Object.keys(emission.files).length} files in ${emission.ms.toFixed(1)} ms` : "";
        let runnable = emission;
        const backend = BACKENDS[this.app.backend];
        if (emission.ok && emission.layout.config.target !== backend.target) {
            runnable = this.app.emitter.emit({...config, target: backend.target});
            note += runnable.ok ? `; the page runs the ${backend.target} emission of the same configuration (${backend.name} runs ${backend.language})`
                                : `; ${backend.name} runs only ${backend.target}, where this configuration is refused: ${runnable.error}`;
        }
        this.panel.showResult(emission, note);
        if (this.runner) this.runner.dispose();
        this.runner = null;
        this.lastVisibility = null;
        const generation = ++this.generation;
        if (!emission.ok) this.reason = "invalid configuration: " + emission.error;
        else if (!runnable.ok) this.reason = `cannot run on ${backend.name}: ` + runnable.error;
        else {
            this.reason = cannotRun(runnable.layout, this.app.bundle, this.app.state.camera);
            if (!this.reason && this.app.backend === "webgpu") {
                this.reason = "building the WebGPU pipelines…";
                this.app.track(WebGPULayoutRunner.fromEmission(this.app.gpu.device, runnable).then((runner) => {
                    if (generation !== this.generation) return runner.dispose();
                    this.runner = runner;
                    this.reason = "";
                    this.app.render();
                }, (e) => {
                    if (generation !== this.generation) return;
                    this.reason = "cannot run on WebGPU: " + e.message;
                    this.app.render();
                }));
            } else if (!this.reason) {
                try {
                    this.runner = LayoutRunner.fromEmission(this.app.gl, runnable);
                    this.runner.enableTiming();
                    // Baked textures (oim) from the bundle, once per runner.
                    for (const t of runnable.layout.textures)
                        if (t.source === "bake") this.runner.uploadTexture(t.name, 0, -1, this.app.bundle.bake[t.name]);
                } catch (e) {
                    this.reason = "cannot run on WebGL2: " + e.message;
                }
            }
        }
        showFiles(this.app);
        if (render) this.app.render();
    }
}
