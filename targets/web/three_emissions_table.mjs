// three_emissions_table.mjs — writes or checks web/three/emissions.js, the table of the emissions
// shipped in web/three/emissions/ (one folder per configuration, emissions/regenerate.sh) with
// every file as a literal `new URL("./emissions/<key>/<file>", import.meta.url)`: the form Vite,
// webpack and Parcel recognise and copy into a build (a URL computed at run time they cannot see).
//
//   node targets/web/three_emissions_table.mjs --write     # after emissions/regenerate.sh
//   node targets/web/three_emissions_table.mjs --check     # exit 1 when emissions.js is out of date
import fs from "node:fs";
import path from "node:path";
import {fileURLToPath} from "node:url";

const three = path.join(path.dirname(fileURLToPath(import.meta.url)), "../../web/three");

// The text emissions.js must have for the folders in `dir` (web/three/emissions).
export function emissionsTable(dir = path.join(three, "emissions")) {
    const keys = fs.readdirSync(dir).filter((k) => fs.statSync(path.join(dir, k)).isDirectory()).sort();
    const lines = [
        "// emissions.js — the emissions shipped in emissions/ (penumbra-gen output, one folder per configuration:",
        "// essl300, and \"<key>-wgsl\" in WGSL; emissions/regenerate.sh), each file a literal `new URL(\"./…\", import.meta.url)`",
        "// so that bundlers (Vite, webpack, Parcel) copy it into the build. Written by",
        "// targets/web/three_emissions_table.mjs --write; do not edit.",
        "export const EMISSIONS = {",
    ];
    for (const key of keys) {
        const files = fs.readdirSync(path.join(dir, key)).filter((f) => fs.statSync(path.join(dir, key, f)).isFile()).sort();
        if (!files.includes("layout.json")) throw new Error(`${path.join(dir, key)}: no layout.json`);
        lines.push(`    "${key}": {`);
        for (const file of files) lines.push(`        "${file}": new URL("./emissions/${key}/${file}", import.meta.url),`);
        lines.push("    },");
    }
    lines.push("};", "");
    return lines.join("\n");
}

if (process.argv[1] && path.resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
    const mode = process.argv[2];
    const file = path.join(three, "emissions.js");
    if (mode === "--write") {
        fs.writeFileSync(file, emissionsTable());
        console.log(`wrote ${file}`);
    } else if (mode === "--check") {
        const current = fs.existsSync(file) ? fs.readFileSync(file, "utf8") : "";
        if (current !== emissionsTable()) {
            console.log(`error: ${file} does not list the files of web/three/emissions/; run node targets/web/three_emissions_table.mjs --write`);
            process.exit(1);
        }
        console.log("ok   web/three/emissions.js lists every file of web/three/emissions/");
    } else {
        console.error("error: give --write or --check\nusage: node targets/web/three_emissions_table.mjs --write|--check");
        process.exit(2);
    }
}
