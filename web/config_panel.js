// config_panel.js — a panel with every field of the `penumbra-gen --config` schema: the same names
// (the JSON keys; the flag in the tooltip) and the same ranges as `penumbra-gen --help`. Nothing
// is checked here: every value goes to the emitter as typed, and the emitter's own message is
// shown beside the field it names. The allowed names of each enumeration are read from the
// emitter's own message for a refused value, so the lists cannot drift from the C++ code.
//
//   const panel = new ConfigPanel(container, emitter, {id: "left", onChange: (config) => ...});
//   panel.config();               // {technique, slices, ..., shadow_map: {...}, pcf: {...}, ...}
//   panel.showResult(emission);   // the diagnostics next to their fields, the error line on top

// key (the JSON path), flag, kind, what --help says (word for word: wasm/emitter_test.mjs checks it
// against penumbra-gen --help, and that every key of layout.json's config has a field here);
// `note`: what the page adds; `techniques`: where the field is read.
const OCCLUSION = ["occlusion"];
const SHADOW_MAP = ["shadowmap", "pcf", "pcss", "erosion"];
export const FIELDS = [
    {key: "technique", flag: "--technique", kind: "enum", help: "shadowing technique"},
    {key: "light", flag: "--light", kind: "enum", help: "area light"},
    {key: "target", flag: "--target", kind: "enum", help: "shading language", note: "the page runs essl300"},
    {key: "slices", flag: "--slices", kind: "int", help: "slices along the light normal: 1 to 32, 64 or 128", techniques: OCCLUSION},
    {key: "resolution", flag: "--resolution", kind: "int", help: "occlusion texture side in texels: a power of two, 32 to 4096", techniques: OCCLUSION},
    {key: "filter", flag: "--filter", kind: "enum", help: "prefilter", techniques: OCCLUSION},
    {key: "fusion", flag: "--fusion", kind: "enum", help: "slice fusion", techniques: OCCLUSION},
    {key: "packing", flag: "--packing", kind: "enum", help: "storage", techniques: OCCLUSION},
    {key: "leak_fix", flag: "--no-leak-fix", kind: "bool", help: "the leak fix", techniques: OCCLUSION},
    {key: "self_shadow_fade", flag: "--no-fade", kind: "bool", help: "the self-shadow fade", techniques: OCCLUSION},
    {key: "tangent_clip", flag: "--[no-]tangent-clip", kind: "bool", help: "kernels cover only the light above the receiver's tangent plane", techniques: OCCLUSION},
    {key: "tangent_clip_offset", flag: "--tangent-clip-offset", kind: "real", help: "slicing texels by which the tangent clip moves a receiver sideways along its normal, off its own texels; 0 to 8", techniques: OCCLUSION},
    {key: "clip_footprint", flag: "--no-clip-footprint", kind: "bool", help: "the tangent clip does not move receivers off their own footprint in the slice above them", techniques: OCCLUSION},
    {key: "fade_ramp", flag: "--fade-ramp", kind: "real", help: "the self-shadow fade ramps over F of a slice's thickness; more than 0 to 4", techniques: OCCLUSION},
    {key: "slice_placement", flag: "--slice-placement", kind: "enum", help: "slice boundaries: uniform (equal slices over the bounds) or adaptive (at the depths the geometry occupies, computed on the GPU; paper §5)", techniques: OCCLUSION},
    {key: "level_format", flag: "--level-format", kind: "enum", help: "storage of the filtered levels", note: "essl300 (the page) stores rgba8", techniques: OCCLUSION},
    {key: "level_bound", flag: "--level-bound", kind: "int", help: "highest filter level built and read", techniques: OCCLUSION},
    {key: "level_reduction", flag: "--level-reduction", kind: "int", help: "the levels above N are stored at half the resolution of the one below", techniques: OCCLUSION},
    {key: "shadow_map.resolution", flag: "--shadow-resolution", kind: "int", help: "shadow map side in texels, a power of two 32 to 8192", techniques: SHADOW_MAP},
    {key: "shadow_map.constant_bias", flag: "--shadow-bias", kind: "real", help: "constant depth bias in scene units along the light axis, 0 to 10", techniques: SHADOW_MAP},
    {key: "shadow_map.slope_bias", flag: "--shadow-slope-bias", kind: "real", help: "slope bias: S times the depth change across one texel, 0 to 16", techniques: SHADOW_MAP},
    {key: "shadow_map.normal_offset", flag: "--shadow-normal-offset", kind: "real", help: "receivers move along their normal by K texels times sin(angle to the light) before the lookup, 0 to 8", techniques: ["shadowmap", "pcf", "pcss"]},
    {key: "shadow_map.receiver_plane_bias", flag: "--no-receiver-plane-bias", kind: "bool", help: "taps compare against the receiver's own depth, not its tangent plane's depth under the tap", techniques: ["pcf", "pcss"]},
    {key: "pcf.pattern", flag: "--pcf-pattern", kind: "enum", help: "tap pattern", techniques: ["pcf"]},
    {key: "pcf.grid_size", flag: "--pcf-grid", kind: "int", help: "N x N grid taps, 1 to 16", techniques: ["pcf"]},
    {key: "pcf.poisson_taps", flag: "--pcf-taps", kind: "int", help: "Poisson taps, 1 to 64", techniques: ["pcf"]},
    {key: "pcf.radius", flag: "--pcf-radius", kind: "real", help: "kernel radius on the receiver in scene units, above 0 to 1000", techniques: ["pcf"]},
    {key: "pcf.rotate", flag: "--no-rotation", kind: "bool", help: "per-pixel rotation of the tap pattern", techniques: ["pcf"]},
    {key: "pcss.blocker_samples", flag: "--pcss-blockers", kind: "int", help: "blocker-search samples, 1 to 64", techniques: ["pcss"]},
    {key: "pcss.filter_samples", flag: "--pcss-filter", kind: "int", help: "filter samples, 1 to 128", techniques: ["pcss"]},
    {key: "pcss.max_filter_texels", flag: "--pcss-max-texels", kind: "int", help: "largest filter half-width in texels, 1 to resolution / 2", techniques: ["pcss"]},
    {key: "pcss.rotate", flag: "--no-rotation", kind: "bool", help: "per-pixel rotation of the tap pattern", techniques: ["pcss"]},
    {key: "oim.resolution", flag: "--oim-resolution", kind: "int", help: "interval-map side in texels, a power of two 32 to 4096", techniques: ["oim"]},
    {key: "oim.intervals", flag: "--oim-intervals", kind: "int", help: "visibility intervals per texel, 4, 8, 12 or 16", techniques: ["oim"]},
    {key: "oim.samples", flag: "--oim-samples", kind: "int", help: "instants the bake traces along the sun's path, 256, 512, 1024 or 2048", techniques: ["oim"]},
    {key: "erosion.max_search_radius", flag: "--erosion-radius", kind: "int", help: "largest penumbra half-width searched, in output pixels, 1 to 256", techniques: ["erosion"]},
    {key: "erosion.edge_threshold", flag: "--erosion-edge-threshold", kind: "real", help: "|Laplacian| of the hard shadow marking an edge, above 0 to 4", techniques: ["erosion"]},
    {key: "erosion.search_taps", flag: "--erosion-search-taps", kind: "int", help: "Poisson taps of the nearest-edge search, 1 to 64", techniques: ["erosion"]},
    {key: "erosion.blur_taps", flag: "--erosion-blur-taps", kind: "int", help: "Poisson taps of the final blur, 1 to 64", techniques: ["erosion"]},
];

const get = (object, key) => key.split(".").reduce((o, k) => (o === undefined ? undefined : o[k]), object);
function set(object, key, value) {
    const path = key.split(".");
    let o = object;
    for (const k of path.slice(0, -1)) o = o[k] ??= {};
    o[path[path.length - 1]] = value;
}

// The names the emitter allows for an enumeration key, from its message for a refused value
// ("key 'filter': '\x01' is not allowed; allowed: mipmap, nbuffer, sat, gaussian").
export function allowedNames(emitter, key) {
    const probe = {};
    set(probe, key, "\u0001");
    const r = emitter.emit(probe);
    const at = r.error.lastIndexOf("allowed: ");
    if (r.ok || at < 0) throw new Error(`the emitter's message for ${key} names no allowed values: ${r.error}`);
    return r.error.slice(at + "allowed: ".length).split(", ");
}

// A text field's value as the JSON value the user typed: a number when it reads as one, else the
// text itself (the emitter then says what the key allows).
function typed(text) {
    const t = text.trim();
    return t !== "" && /^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/.test(t) ? Number(t) : t;
}

export class ConfigPanel {
    // defaults: a layout.json "config" object (the emitter's defaults); initial: values over them.
    constructor(container, emitter, {id, title, defaults, initial = {}, onChange}) {
        this.id = id;
        this.onChange = onChange;
        this.inputs = {};
        this.rows = {};
        const root = document.createElement("fieldset");
        root.className = "config-panel";
        root.id = id;
        root.append(Object.assign(document.createElement("legend"), {textContent: title}));
        this.errorLine = Object.assign(document.createElement("div"), {className: "error-line"});
        this.errorLine.dataset.role = "error";
        root.append(this.errorLine);
        for (const field of FIELDS) {
            const row = document.createElement("label");
            row.className = "field";
            row.title = `${field.flag}: ${field.help}`;
            const name = Object.assign(document.createElement("span"), {className: "name", textContent: field.key});
            let input;
            const value = get(initial, field.key) ?? get(defaults, field.key);
            if (field.kind === "enum") {
                input = document.createElement("select");
                for (const option of allowedNames(emitter, field.key))
                    input.append(Object.assign(document.createElement("option"), {value: option, textContent: option}));
                input.value = value;
            } else if (field.kind === "bool") {
                input = Object.assign(document.createElement("input"), {type: "checkbox", checked: !!value});
            } else {
                input = Object.assign(document.createElement("input"), {type: "text", value: String(value), size: 7});
                input.inputMode = "decimal";
            }
            input.dataset.key = field.key;
            input.addEventListener("change", () => this.changed());
            const note = Object.assign(document.createElement("span"), {className: "message"});
            const help = Object.assign(document.createElement("span"), {className: "help",
                                                                         textContent: field.help + (field.note ? ` (${field.note})` : "")});
            row.append(name, input, help, note);
            root.append(row);
            this.inputs[field.key] = input;
            this.rows[field.key] = {row, note, field};
        }
        container.append(root);
        this.root = root;
        this.showTechnique();
    }

    // The configuration as the panel holds it: every field, as typed.
    config() {
        const out = {};
        for (const [key, input] of Object.entries(this.inputs)) {
            const {field} = this.rows[key];
            set(out, key, field.kind === "bool" ? input.checked : field.kind === "enum" ? input.value : typed(input.value));
        }
        return out;
    }

    // Sets fields from a (partial) configuration object, without an event per field; one change.
    set(values) {
        for (const field of FIELDS) {
            const value = get(values, field.key);
            if (value === undefined) continue;
            const input = this.inputs[field.key];
            if (field.kind === "bool") input.checked = !!value;
            else input.value = String(value);
        }
        this.changed();
    }

    changed() {
        this.showTechnique();
        this.onChange(this.config());
    }

    // Only the fields the selected technique reads (plus light and target).
    showTechnique() {
        const technique = this.inputs.technique.value;
        for (const {row, field} of Object.values(this.rows)) row.hidden = !!field.techniques && !field.techniques.includes(technique);
    }

    // The emitter's diagnostics beside the fields they name; its error line (penumbra-gen's) on top.
    showResult(emission, note = "") {
        for (const {row, note: message} of Object.values(this.rows)) {
            message.textContent = "";
            row.classList.remove("invalid");
        }
        for (const d of emission.diagnostics) {
            const slot = this.rows[d.field];
            if (!slot) continue;
            slot.note.textContent = d.message;
            slot.row.classList.add("invalid");
            slot.row.hidden = false;
        }
        this.errorLine.textContent = emission.ok ? note : emission.error;
        this.errorLine.classList.toggle("bad", !emission.ok);
    }
}
