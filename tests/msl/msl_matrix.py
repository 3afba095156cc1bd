#!/usr/bin/env python3
"""msl_matrix.py — the `msl_matrix` test: runs `penumbra-gen --target msl` (the vulkan target's
programs through glslang and SPIRV-Cross, penumbra/msl.hpp) over the configurations of
tests/technique_variants.json, one folder a configuration under OUT, and checks what can be checked
without a Metal compiler (there is none on Linux):

  - the configuration is accepted (or, for what the vulkan target refuses, refused naming msl), and
    layout.json says target msl;
  - every program file is a written .metal file that defines the function layout.json's
    msl_functions names for it, as a function of its stage (vertex, fragment, kernel);
  - every parameter with a buffer or texture has "msl" indices, and the text binds them there: the
    parameter's uniform block at [[buffer(i)]], its texture at [[texture(i)]] and its sampler at
    [[sampler(i)]] in at least one stage of its program, and no index beyond Metal's guaranteed
    31 buffers, 31 textures, 16 samplers;
  - "first_free_buffer" (where an engine binds vertex buffers) is above every buffer index;
  - only .metal files and layout.json are written (no snippet), and layout.json lists them.

  msl_matrix.py --gen PENUMBRA_GEN --out DIR [--jobs N] [--only REGEX]

Exit 0 pass, 1 fail, 2 bad arguments.
"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent.parent))
from technique_variants import configurations  # noqa: E402

# What msl refuses, as the vulkan target it is translated from does: more colour targets a pass than
# Vulkan guarantees (32 slices as channels need 8).
def refused(argv):
    return "--slices" in argv and argv[argv.index("--slices") + 1] == "32"


STAGE_KEYWORD = {"vertex": "vertex", "fragment": "fragment", "compute": "kernel"}
MAX_INDEX = {"buffer": 31, "texture": 31, "sampler": 16}


def check(name, argv, args):
    """Emits one configuration; returns its failures and the number of .metal files checked."""
    failures = []
    folder = os.path.join(args.out, name)
    r = subprocess.run([args.gen, "--target", "msl", *argv, "--out", folder], capture_output=True, text=True)
    message = (r.stdout + r.stderr).strip()
    if refused(argv):
        if r.returncode != 2 or not message.startswith("error: ") or "'msl'" not in message:
            return [f"{name}: expected a refusal naming msl (exit 2), got exit {r.returncode}: {message}"], 0
        print(f"refused {name}: {message.splitlines()[0]}")
        return [], 0
    if r.returncode != 0:
        return [f"{name}: penumbra-gen --target msl {' '.join(argv)} exited {r.returncode}: {(r.stdout + r.stderr).strip()}"], 0
    with open(os.path.join(folder, "layout.json"), encoding="utf-8") as f:
        layout = json.load(f)
    if layout.get("config", {}).get("target") != "msl":
        failures.append(f"{name}: layout.json config.target is {layout.get('config', {}).get('target')!r}")
    first_free = layout.get("msl", {}).get("first_free_buffer")
    if not isinstance(first_free, int):
        failures.append(f"{name}: layout.json has no msl.first_free_buffer")
        first_free = 0
    checked = set()
    for program in layout.get("programs", []):
        texts = []
        functions = program.get("msl_functions", [])
        if len(functions) != len(program["files"]):
            failures.append(f"{name}: program {program['name']}: {len(functions)} msl_functions for {len(program['files'])} files")
            continue
        for file, stage, function in zip(program["files"], program["stages"], functions):
            path = os.path.join(folder, file)
            if not file.endswith(".metal") or not os.path.exists(path):
                failures.append(f"{name}: program {program['name']}: '{file}' is not a written .metal file")
                continue
            with open(path, encoding="utf-8") as f:
                text = f.read()
            texts.append(text)
            checked.add(file)
            if "#include <metal_stdlib>" not in text:
                failures.append(f"{name}: {file}: does not include <metal_stdlib>")
            if not re.search(rf"^{STAGE_KEYWORD[stage]} \S+ {re.escape(function)}\(", text, re.M):
                failures.append(f"{name}: {file}: no {STAGE_KEYWORD[stage]} function {function}")
        for p in program.get("parameters", []):
            if "block" not in p and "binding" not in p:
                continue
            msl = p.get("msl")
            if not msl:
                failures.append(f"{name}: program {program['name']}: parameter {p['name']} has no msl indices")
                continue
            for kind, index in msl.items():
                if not 0 <= index < MAX_INDEX[kind]:
                    failures.append(f"{name}: program {program['name']}: {p['name']} {kind} index {index} beyond Metal's {MAX_INDEX[kind]}")
            if "block" in p:
                pattern = rf"constant {re.escape(p['block'])}& \w+ \[\[buffer\({msl['buffer']}\)\]\]"
                if msl["buffer"] >= first_free:
                    failures.append(f"{name}: {p['name']}: buffer {msl['buffer']} at or above first_free_buffer {first_free}")
            else:
                pattern = rf"\b{re.escape(p['name'])} \[\[texture\({msl['texture']}\)\]\]"
                if "sampler" in msl:
                    pattern += rf"[\s\S]*\b{re.escape(p['name'])}Smplr \[\[sampler\({msl['sampler']}\)\]\]"
            # a resource no stage reads is dropped from the SPIR-V: only one some stage names must be bound
            named = p["block"] if "block" in p else p["name"]
            if not any(re.search(pattern, t) for t in texts) and any(re.search(rf"\b{re.escape(named)}\b", t) for t in texts):
                failures.append(f"{name}: program {program['name']}: {p['name']} not bound at {msl} in its files")
    for file in sorted(os.listdir(folder)):
        if file != "layout.json" and not file.endswith(".metal"):
            failures.append(f"{name}: wrote '{file}', neither MSL nor layout.json")
    listed = set(layout.get("files", [])) - {"layout.json"}
    if listed != checked:
        failures.append(f"{name}: layout.json files {sorted(listed)} are not the programs' files {sorted(checked)}")
    return failures, len(checked)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--gen", required=True)
    parser.add_argument("--out", required=True)
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    parser.add_argument("--only", default=None)
    args = parser.parse_args()
    if not os.path.isfile(args.gen):
        print(f"error: --gen: no file {args.gen}", file=sys.stderr)
        return 2
    only = re.compile(args.only) if args.only else None
    started = time.monotonic()
    shutil.rmtree(args.out, ignore_errors=True)
    os.makedirs(args.out)
    chosen = [(n, a) for n, a in configurations() if not only or only.search(n)]
    failures, files = [], 0
    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as pool:
        for found, count in pool.map(lambda c: check(c[0], c[1], args), chosen):
            failures += found
            files += count
    if not files:
        failures.append("no MSL file was written: nothing checked")
    for failure in failures:
        print(f"FAIL {failure}")
    print(f"msl_matrix: {len(chosen)} configurations, {files} MSL files translated by SPIRV-Cross and checked "
          f"against layout.json (not compiled: no Metal compiler here), {len(failures)} failures, "
          f"{time.monotonic() - started:.1f} s on {args.jobs} threads")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
