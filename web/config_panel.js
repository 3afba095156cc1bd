// config_panel.js — a panel with every field of the `penumbra-gen --config` schema, built from the
// emitter's own table of configuration fields (penumbra/config_fields.hpp, through the WebAssembly
// module): the same names (the JSON keys; the flag in the tooltip), choices and help as
// `penumbra-gen --help`, so they cannot drift from the C++ code. Nothing is checked here: every value
// goes to the emitter as typed, and the emitter's own message is shown beside the field it names.
//
//   const panel = new ConfigPanel(container, emitter, {id: "left", onChange: (config) => ...});
//   panel.config();               // {technique, slices, ..., shadow_map: {...}, pcf: {...}, ...}
//   panel.showResult(emission);   // the diagnostics next to their fields, the error line on top

// What the page adds beside a field's help (it runs the essl300 emission).
const NOTES = {target: "the page runs essl300 on WebGL2, wgsl on WebGPU (the renderer switch); hlsl (Direct3D 12) to view and download; msl (Metal) is SPIRV-Cross's translation, written by penumbra-gen, not here", level_format: "essl300 (the page) stores rgba8"};

// The panel's fields: the table of configuration fields (penumbra/config_fields.hpp) as the
// WebAssembly module gives it (emitter.fields()): key (the JSON path), flag, kind ("integer", "real",
// "boolean", "choice" with its names), help (word for word what penumbra-gen --help says),
// techniques (where the field is read; absent: every technique), profile_sets (whether a profile sets
// it), plus the page's `note`.
export function panelFields(emitter) {
    return emitter.fields().map((f) => ({...f, note: NOTES[f.key], techniques: f.techniques.length ? f.techniques : undefined}));
}

const get = (object, key) => key.split(".").reduce((o, k) => (o === undefined ? undefined : o[k]), object);
function set(object, key, value) {
    const path = key.split(".");
    let o = object;
    for (const k of path.slice(0, -1)) o = o[k] ??= {};
    o[path[path.length - 1]] = value;
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
        this.fields = panelFields(emitter);
        for (const field of this.fields) {
            const row = document.createElement("label");
            row.className = "field";
            row.title = `${field.flag}: ${field.help}`;
            const name = Object.assign(document.createElement("span"), {className: "name", textContent: field.key});
            let input;
            // layout.json leaves out a field added later while it has its default (alpha_test): the table's
            const value = get(initial, field.key) ?? get(defaults, field.key) ?? field.default;
            if (field.kind === "choice") {
                input = document.createElement("select");
                for (const option of field.names)
                    input.append(Object.assign(document.createElement("option"), {value: option, textContent: option}));
                input.value = value;
            } else if (field.kind === "boolean") {
                input = Object.assign(document.createElement("input"), {type: "checkbox", checked: !!value});
            } else {
                input = Object.assign(document.createElement("input"), {type: "text", value: String(value), size: 7});
                input.inputMode = "decimal";
            }
            input.dataset.key = field.key;
            this.emitter = emitter;
            input.addEventListener("change", () => field.key === "profile" ? this.applyProfile() : this.changed());
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
            set(out, key, field.kind === "boolean" ? input.checked : field.kind === "choice" ? input.value : typed(input.value));
        }
        return out;
    }

    // Sets fields from a (partial) configuration object, without an event per field; one change.
    set(values) {
        for (const field of this.fields) {
            const value = get(values, field.key);
            if (value === undefined) continue;
            const input = this.inputs[field.key];
            if (field.kind === "boolean") input.checked = !!value;
            else input.value = String(value);
        }
        this.changed();
    }

    // A profile is a preset of fields (penumbra/profiles.hpp): the panel shows the values it sets, as the
    // emitter resolves them for this light, and the user may change them after.
    applyProfile() {
        const current = this.config();
        const emission = this.emitter.emit({profile: current.profile, light: current.light, tangent_clip: current.tangent_clip,
                                            target: current.target});
        if (!emission.ok || !emission.layout) return this.changed();
        // the fields a profile sets (the table's profile_sets); layout.json leaves out one added later
        // while it has its default, so that default is the preset's
        const preset = {};
        for (const field of this.fields)
            if (field.profile_sets) set(preset, field.key, get(emission.layout.config, field.key) ?? field.default);
        this.set(preset);
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
