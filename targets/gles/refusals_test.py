#!/usr/bin/env python3
"""penumbra-dialect-test refuses what OpenGL 3.3 / ES 3.0 cannot run, and bad bundles, with one
line naming what is wrong and what is allowed, never a crash (label "dialects").

    refusals_test.py DIALECT_TEST BUNDLE_ROOT WORK_DIR

BUNDLE_ROOT holds the dialect matrix's bundles (essl300-shadowmap, essl300-oim, glsl330-pcss,
essl300-default); each case copies one into WORK_DIR, changes one thing, and expects exit status
1 (2 for bad arguments) and a message that contains the given words. The unchanged copies must
still pass, so that the change alone is what the runner refused.
"""
import json
import os
import shutil
import subprocess
import sys


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    runner, root, work = sys.argv[1:]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    failures = []

    def copy(name, case):
        dst = os.path.join(work, case)
        shutil.copytree(os.path.join(root, name), dst)
        return dst

    def edit_json(path, change):
        with open(path) as f:
            data = json.load(f)
        change(data)
        with open(path, "w") as f:
            json.dump(data, f, indent=1)

    def layout(bundle, change):
        edit_json(os.path.join(bundle, "emission", "layout.json"), change)

    def texture(data, name):
        return next(t for t in data["textures"] if t["name"] == name)

    def check(case, args, status, words):
        run = subprocess.run([runner, *args], capture_output=True, text=True, timeout=60)
        text = (run.stdout + run.stderr).strip()
        ok = run.returncode == status and all(w in text for w in words)
        print(f"{'ok  ' if ok else 'FAIL'} {case}: exit {run.returncode}: {text.splitlines()[-1] if text else '(no output)'}")
        if not ok:
            failures.append(f"{case}: expected exit {status} and {words}; got {run.returncode}:\n{text}")

    # The unchanged bundles run.
    for name in ("essl300-shadowmap", "essl300-oim", "glsl330-pcss"):
        check(f"unchanged {name}", [os.path.join(root, name)], 0, ["ok "])

    # What ES 3.0 cannot do, in a layout that asks for it.
    b = copy("essl300-shadowmap", "es_depth_linear_without_compare")
    layout(b, lambda d: [i["sampling"].update(compare="") for p in d["passes"] if p["name"] == "shading" for i in p["inputs"]
                         if i["texture"] == "penumbra_shadowMap"])
    check("ES 3.0: depth texture filtered without comparison", [b], 1,
          ["without comparison", "OpenGL ES 3.0 cannot", "allowed: NEAREST"])
    b = copy("essl300-shadowmap", "es_border")
    layout(b, lambda d: texture(d, "penumbra_shadowMap").update(wrap="CLAMP_TO_BORDER"))
    check("ES 3.0: CLAMP_TO_BORDER", [b], 1, ["penumbra_shadowMap", "CLAMP_TO_BORDER does not exist in OpenGL ES 3.0"])
    b = copy("essl300-shadowmap", "es_logic_op")
    layout(b, lambda d: next(p for p in d["passes"] if p["name"] == "shadow_depth")["state"].update(logic_op="OR"))
    check("ES 3.0: logic_op OR", [b], 1, ["logic_op OR is not available on OpenGL ES", "allowed: NONE"])

    # Bad layouts and bundles.
    b = copy("glsl330-pcss", "initial_unknown")
    layout(b, lambda d: texture(d, "penumbra_shadowMap").update(initial="undefined"))
    check("initial unknown", [b], 1, ["penumbra_shadowMap", "initial 'undefined' unknown", "allowed: zero, caller, bake"])
    b = copy("glsl330-pcss", "format_unknown")
    layout(b, lambda d: texture(d, "penumbra_shadowMap").update(internal_format="DEPTH_COMPONENT16"))
    check("format unknown", [b], 1, ["penumbra_shadowMap", "DEPTH_COMPONENT16", "unknown"])
    b = copy("essl300-oim", "oim_without_bake")
    edit_json(os.path.join(b, "uniforms.json"), lambda d: d.pop("bake_textures"))
    check("oim without its bake", [b], 1, ["penumbra_rise0", "bake_textures", "--technique oim"])
    b = copy("essl300-oim", "oim_bake_size")
    with open(os.path.join(b, "penumbra_fall1.f32"), "r+b") as f:
        f.truncate(os.path.getsize(f.name) // 4)
    check("oim bake of another size", [b], 1, ["penumbra_fall1", "RGBA texture needs"])
    b = copy("essl300-default", "occlusion_without_oracle")
    os.remove(os.path.join(b, "oracle.f32"))
    check("occlusion without its oracle", [b], 1, ["oracle.f32"])
    check("not a bundle", [work], 1, ["a bundle?"])
    check("unknown flag", ["--epsilon", "1"], 2, ["unknown flag '--epsilon'", "allowed: --help"])
    check("no bundle", [], 2, ["no bundle given", "usage:"])

    for f in failures:
        print(f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
