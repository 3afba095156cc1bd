#!/usr/bin/env python3
"""conventions_test.py EXPORT_BUNDLE VULKAN_RUN DIR: the Vulkan runner follows layout.json's
conventions, not the shader text's. Writes one PCSS bundle (its blocker search reads the depth map
without comparison, its filter with LEQUAL), then changes one convention at a time in a copy —
the descriptor set of the samplers, the location of the position input, the textures' initial
contents, one binding's sampling — and checks that the runner follows (same image as the GL run)
or refuses with a message naming the change. Exit status: 0 all as expected, 1 otherwise, 77 no Vulkan device."""
import json
import os
import re
import shutil
import subprocess
import sys

export_bundle, vulkan_run, root = sys.argv[1:4]
base = os.path.join(root, "pcss")
subprocess.run([export_bundle, "--scene", "boxes", "--size", "64x64", "--target", "vulkan", "--technique", "pcss",
                "--shadow-resolution", "128", "--no-rotation", "--out", base], check=True, stdout=subprocess.DEVNULL)


def layout_path(bundle):
    return os.path.join(bundle, "emission", "layout.json")


def variant(name, change):
    """A copy of the bundle with `change(layout, emission_dir)` applied."""
    bundle = os.path.join(root, name)
    shutil.rmtree(bundle, ignore_errors=True)
    shutil.copytree(base, bundle)
    with open(layout_path(bundle)) as f:
        layout = json.load(f)
    if layout.get("layout_version", 1) < 3:
        sys.exit(f"{layout_path(bundle)}: layout_version {layout.get('layout_version', 1)}; this test changes version 3's fields")
    change(layout, os.path.join(bundle, "emission"))
    with open(layout_path(bundle), "w") as f:
        json.dump(layout, f, indent=1)
    return bundle


def edit_shaders(emission, program, pattern, replacement):
    for file in program["files"]:
        path = os.path.join(emission, file)
        with open(path) as f:
            text = f.read()
        with open(path, "w") as f:
            f.write(re.sub(pattern, replacement, text))


def samplers_in_set_1(layout, emission):
    for program in layout["programs"]:
        for q in program["parameters"]:
            if "binding" in q:
                q["set"] = 1
        edit_shaders(emission, program, r"layout\(set = 0, binding = (\d+)\) uniform (\w*sampler)",
                     r"layout(set = 1, binding = \1) uniform \2")


def position_at_location_3(layout, emission):
    for program in layout["programs"]:
        for v in program["vertex_inputs"]:
            if v["name"] == "penumbra_position":
                v["location"] = 3
                edit_shaders(emission, program, r"layout\(location = 0\) in vec3 penumbra_position",
                             "layout(location = 3) in vec3 penumbra_position")


def initial_undefined(layout, emission):
    for t in layout["textures"]:
        if t["initial"] == "zero":
            t["initial"] = "undefined"  # every texel the passes read is written first


def comparison_nearest(layout, emission):
    for p in layout["passes"]:
        for i in p["inputs"]:
            if i.get("sampling", {}).get("compare"):
                i["sampling"]["min_filter"] = i["sampling"]["mag_filter"] = "NEAREST"


def comparison_dropped(layout, emission):
    for p in layout["passes"]:
        for i in p["inputs"]:
            if i.get("sampling", {}).get("compare"):
                i["sampling"]["compare"] = ""


def position_renamed(layout, emission):
    for program in layout["programs"]:
        for v in program["vertex_inputs"]:
            if v["name"] == "penumbra_position":
                v["name"] = "penumbra_vertex"


# (name, change, expected exit status, text the output must contain)
cases = [
    ("baseline", lambda layout, emission: None, 0, "0 validation messages"),
    ("samplers_in_set_1", samplers_in_set_1, 0, "0 of 4096 pixels beyond"),
    ("position_at_location_3", position_at_location_3, 0, "0 of 4096 pixels beyond"),
    ("initial_undefined", initial_undefined, 0, "0 of 4096 pixels beyond"),
    ("comparison_nearest", comparison_nearest, 1, "differ from the GL runtime"),
    ("comparison_dropped", comparison_dropped, 1, "has no compare function"),
    ("position_renamed", position_renamed, 1, "allowed: penumbra_position, penumbra_normal"),
]
failures = 0
for name, change, expected, text in cases:
    run = subprocess.run([vulkan_run, "--bundle", variant(name, change)], capture_output=True, text=True)
    output = (run.stdout + run.stderr).strip()
    if run.returncode == 77:
        print(output)
        sys.exit(77)
    ok = run.returncode == expected and text in output
    failures += not ok
    print(f"{'ok  ' if ok else 'FAIL'} {name}: exit {run.returncode} (expected {expected}, with '{text}')\n     "
          + output.replace("\n", "\n     "))
sys.exit(1 if failures else 0)
