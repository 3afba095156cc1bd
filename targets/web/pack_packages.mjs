// pack_packages.mjs — the `pack-web-packages` test (the bundler tests' fixture): `npm pack` of each
// add-on folder named (web/three, web/babylon), their prepack scripts putting in the WebAssembly
// emitter given by --wasm, into OUT/<package name>.tgz (a name without the version, for ctest).
//
//   node targets/web/pack_packages.mjs --out DIR --wasm FILE PACKAGE_DIR...
import {execFileSync} from "node:child_process";
import fs from "node:fs";
import path from "node:path";

const argv = process.argv.slice(2);
const flag = (name) => {
    const i = argv.indexOf(name);
    if (i < 0 || i + 1 >= argv.length) {
        console.error(`error: ${name} FILE is required\nusage: node pack_packages.mjs --out DIR --wasm FILE PACKAGE_DIR...`);
        process.exit(2);
    }
    return path.resolve(argv.splice(i, 2)[1]);
};
const out = flag("--out"), wasm = flag("--wasm");
if (!argv.length) {
    console.error("error: no package folder\nusage: node pack_packages.mjs --out DIR --wasm FILE PACKAGE_DIR...");
    process.exit(2);
}
fs.mkdirSync(out, {recursive: true});
for (const dir of argv) {
    const started = Date.now();
    let stdout;
    try {
        stdout = execFileSync("npm", ["pack", "--json", "--pack-destination", out, "--loglevel=error"],
                              {cwd: dir, encoding: "utf8", env: {...process.env, PENUMBRA_EMITTER_WASM: wasm}});
    } catch (e) {
        console.log(`FAIL npm pack in ${dir} (exit ${e.status}):\n${e.stdout || ""}${e.stderr || ""}`);
        process.exit(1);
    }
    const [info] = JSON.parse(stdout.slice(stdout.indexOf("[")));
    fs.renameSync(path.join(out, info.filename), path.join(out, `${info.name}.tgz`));
    console.log(`ok   ${info.name}.tgz: ${info.files.length} files, ${(info.size / 1024).toFixed(0)} KiB ` +
                `(${(info.unpackedSize / 1024).toFixed(0)} KiB unpacked) in ${((Date.now() - started) / 1000).toFixed(1)} s`);
}
