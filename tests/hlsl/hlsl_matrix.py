#!/usr/bin/env python3
"""hlsl_matrix.py — the `hlsl_matrix` test, the HLSL counterpart of wgsl_matrix: runs
`penumbra-gen --target hlsl` over a configuration matrix into OUT (one folder a configuration) and
compiles every HLSL file it wrote with glslang's HLSL front end (`glslangValidator -D -V -e main -S
<stage>`, the stage from layout.json; a text several configurations wrote is compiled once, its
SPIR-V kept beside the first of them as NAME.spv).

  hlsl_matrix.py --gen PENUMBRA_GEN --out DIR [--glslang PATH] [--spirv-cross PATH] [--jobs N] [--only REGEX]

Each configuration of the matrix must be accepted, list only .hlsl files in layout.json's programs
(each present, with one `main`), give every cbuffer value and texture its `registers`, and compile
with zero errors; penumbra_visibility.hlsl compiles too, #included by a pixel shader that calls it.
Each one of REFUSED must be refused as a user error (exit 2, one `error: ...` line naming hlsl), so
that a crash cannot pass as a refusal. With --spirv-cross (Debian's spirv-cross), every SPIR-V module
is also translated to Metal Shading Language 2.1 (NAME.metal), and a failed translation fails the test:
no Metal compiler exists here, so the MSL is checked no further. Compiles run on --jobs threads
(default: the CPU count).
(Debian 12's vkd3d-compiler, 1.2, reads no HLSL: only dxbc-tpf; so no second compiler runs here.)
Exit 0 pass, 1 fail, 2 bad arguments, 77 skip (no glslangValidator).
"""
import argparse
import concurrent.futures
import hashlib
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

# ---- The matrix: tests/technique_variants.json's configurations (technique_variants.py, shared with
# the MSL matrix; wgsl_matrix.mjs reads the same JSON).
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent))
from technique_variants import configurations  # noqa: E402
# What the hlsl target refuses (move a line up into the JSON's variants when it lands).
REFUSED = {
    "oim": "--technique oim",
}
# ----

STAGE_FLAG = {"vertex": "vert", "fragment": "frag", "compute": "comp"}


def run(argv):
    r = subprocess.run(argv, capture_output=True, text=True)
    return r.returncode, (r.stdout + r.stderr).strip()


# The snippet #included by a pixel shader that calls it (the deferred pass's use, written by an engine).
SNIPPET_CALLER = """#include "penumbra_visibility.hlsl"
float4 main(float4 position : SV_Position, float3 worldPos : TEXCOORD0, float3 worldNormal : TEXCOORD1) : SV_Target0
{
    return float4(penumbraVisibility(worldPos%s), 0.0, 0.0, 1.0);
}
"""


def check_emission(name, argv, args, failures):
    """Emits one configuration; returns its compile jobs [(file path, stage)]."""
    folder = os.path.join(args.out, name)
    status, message = run([args.gen, "--target", "hlsl", *argv, "--out", folder])
    if status != 0:
        failures.append(f"{name}: penumbra-gen --target hlsl {' '.join(argv)} exited {status}: {message}")
        return []
    with open(os.path.join(folder, "layout.json"), encoding="utf-8") as f:
        layout = json.load(f)
    if layout.get("config", {}).get("target") != "hlsl":
        failures.append(f"{name}: layout.json config.target is {layout.get('config', {}).get('target')!r}")
    jobs = []
    for program in layout.get("programs", []):
        for file, stage in zip(program["files"], program["stages"]):
            path = os.path.join(folder, file)
            if not file.endswith(".hlsl") or not os.path.exists(path):
                failures.append(f"{name}: program {program['name']}: '{file}' is not a written .hlsl file")
                continue
            with open(path, encoding="utf-8") as f:
                if not re.search(r"^\w+ main\(", f.read(), re.M):
                    failures.append(f"{name}: {file}: no entry point main")
            jobs.append((path, stage))
        texts = [open(os.path.join(folder, f), encoding="utf-8").read() for f in program["files"] if os.path.exists(os.path.join(folder, f))]
        for p in program.get("parameters", []):
            if ("block" in p or "binding" in p) and "registers" not in p:
                failures.append(f"{name}: program {program['name']}: parameter {p['name']} has no registers")
                continue
            # layout.json and the text agree: the registers, and each cbuffer value where std140 puts it
            expected = []
            if "block" in p:
                offset = p["offset"]
                expected.append(f"cbuffer {p['block']} : register({p['registers']['cbuffer']}, space{p['registers']['space']})")
                expected.append(f" {p['name']} : packoffset(c{offset // 16}.{'xyzw'[offset % 16 // 4]});")
            elif "binding" in p and p.get("source") != "draw":
                regs = p["registers"]
                expected.append(f"{p['texture_type']} {p['name']} : register({regs['texture']}, space{regs['space']});")
                if "sampler" in regs:
                    expected.append(f"{regs['sampler_type']} {p['name']}_sampler : register({regs['sampler']}, space{regs['space']});")
            for e in expected:
                if not any(e in t for t in texts):
                    failures.append(f"{name}: program {program['name']}: no '{e.strip()}' in its files (layout.json's registers)")
    for file in sorted(os.listdir(folder)):
        if file != "layout.json" and not file.endswith(".hlsl"):
            failures.append(f"{name}: wrote '{file}', neither HLSL nor layout.json")
    snippet = os.path.join(folder, "penumbra_visibility.hlsl")
    if os.path.exists(snippet):
        with open(snippet, encoding="utf-8") as f:
            with_normal = "float penumbraVisibility(float3 worldPos, float3 worldNormal)" in f.read()
        caller = os.path.join(folder, "snippet_caller.frag.hlsl")
        with open(caller, "w", encoding="utf-8") as f:
            f.write(SNIPPET_CALLER % (", worldNormal" if with_normal else ""))
        jobs.append((caller, "fragment"))
    return jobs


def compile_glslang(glslang, path, stage):
    spv = path[: -len(".hlsl")] + ".spv"
    status, message = run([glslang, "-D", "-V", "-e", "main", "-S", STAGE_FLAG[stage], path, "-o", spv])
    return status, message


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--gen", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--glslang", default=shutil.which("glslangValidator"))
    parser.add_argument("--spirv-cross", default=None)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--only", default=None)
    args = parser.parse_args()
    if not os.path.isfile(args.gen):
        print(f"error: --gen: no file {args.gen}", file=sys.stderr)
        return 2
    if not args.glslang:
        print("skip: no glslangValidator (Debian's glslang-tools)")
        return 77
    only = re.compile(args.only) if args.only else None
    started = time.monotonic()
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(args.out)
    failures = []

    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        # 1. Emit every configuration.
        chosen = [(n, a) for n, a in configurations() if not only or only.search(n)]
        jobs = []
        for found in pool.map(lambda c: check_emission(c[0], c[1], args, failures), chosen):
            jobs += found

        # 2. The refusals: a user error naming hlsl, not a crash.
        refused = 0
        for name, flags in REFUSED.items():
            if only and not only.search(name):
                continue
            status, message = run([args.gen, "--target", "hlsl", *flags.split(), "--out", os.path.join(args.out, f"refused-{name}")])
            if status == 0:
                failures.append(f"{name}: expected a refusal for hlsl, but penumbra-gen {flags} --target hlsl wrote an emission")
            elif status != 2 or not message.startswith("error: ") or "hlsl" not in message or message.startswith("error: --target:"):
                failures.append(f"{name}: not a refusal naming hlsl (exit {status}): {message}")
            else:
                refused += 1
                print(f"refused {name}: {message.splitlines()[0]}")
        if not jobs:
            failures.append("no HLSL file was emitted: nothing compiled")

        # 3. glslang's HLSL front end on every file; a text that another configuration wrote too (the
        # fullscreen vertex stage, the depth passes) is compiled once and its result counted for each.
        unique = {}
        for path, stage in jobs:
            with open(path, "rb") as f:
                key = (hashlib.sha256(f.read()).hexdigest(), stage)
            if os.path.basename(path) == "snippet_caller.frag.hlsl":  # it #includes its folder's snippet
                key = (path, stage)
            unique.setdefault(key, (path, stage))
        results = dict(zip(unique, pool.map(lambda j: compile_glslang(args.glslang, *j), unique.values())))
        errors = 0
        for path, stage in jobs:
            with open(path, "rb") as f:
                key = (hashlib.sha256(f.read()).hexdigest(), stage)
            status, message = results.get(key) or results[(path, stage)]
            if status != 0:
                errors += 1
                lines = [l for l in message.splitlines() if "ERROR" in l][:3] or message.splitlines()[-3:]
                failures.append(f"{os.path.relpath(path, args.out)} ({stage}): glslang: " + " | ".join(lines))

        # 4. SPIRV-Cross: the same SPIR-V as Metal Shading Language.
        translated = 0
        if args.spirv_cross:
            modules = sorted({path[: -len(".hlsl")] + ".spv" for path, _ in unique.values()})
            modules = [m for m in modules if os.path.exists(m)]
            translate = lambda m: run([args.spirv_cross, m, "--msl", "--msl-version", "20100", "--output", m[: -len(".spv")] + ".metal"])
            for module, (status, message) in zip(modules, pool.map(translate, modules)):
                if status != 0:
                    failures.append(f"{os.path.relpath(module, args.out)}: spirv-cross --msl: {message.splitlines()[-1] if message else status}")
                else:
                    translated += 1
            print(f"spirv-cross: {translated} of {len(modules)} SPIR-V modules translated to MSL 2.1 (not compiled: no Metal compiler here)")

    seconds = time.monotonic() - started
    for failure in failures:
        print(f"FAIL {failure}")
    print(f"hlsl_matrix: {len(chosen)} configurations, {len(jobs)} HLSL files ({len(unique)} distinct texts), glslang errors {errors}, "
          f"{refused} refusals as expected, {len(failures)} failures, {seconds:.1f} s on {args.jobs} threads")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
