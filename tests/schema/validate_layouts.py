#!/usr/bin/env python3
"""Validates every layout.json penumbra-gen writes for a configuration matrix against
docs/layout.schema.json (python3-jsonschema), plus what a schema cannot say: every texture and
program a pass names exists, and the result texture is written by a screen pass. Also checks that
broken layouts are rejected, so the test can fail.

usage: validate_layouts.py PENUMBRA_GEN SCHEMA WORK_DIR
"""
import concurrent.futures
import copy
import itertools
import json
import pathlib
import shutil
import subprocess
import sys

import jsonschema


def references_errors(layout):
    """What the schema cannot check: names that must exist elsewhere in the document."""
    errors = []
    textures = {t["name"] for t in layout["textures"]}
    programs = {p["name"] for p in layout["programs"]}
    if layout["result"] not in textures:
        errors.append(f"result {layout['result']} is not a texture")
    writes_result = False
    for i, p in enumerate(layout["passes"]):
        if p["program"] and p["program"] not in programs:
            errors.append(f"pass {i} ({p['name']}): no program {p['program']}")
        for b in p["inputs"]:
            if b["texture"] not in textures:
                errors.append(f"pass {i} ({p['name']}): input texture {b['texture']} does not exist")
        for image in p.get("image_outputs", []):
            if image["texture"] not in textures:
                errors.append(f"pass {i} ({p['name']}): image texture {image['texture']} does not exist")
        for a in p["outputs"]:
            if a["texture"] not in textures:
                errors.append(f"pass {i} ({p['name']}): output texture {a['texture']} does not exist")
            writes_result |= p["phase"] == "screen" and a["texture"] == layout["result"]
    if not writes_result:
        errors.append("no screen pass writes the result texture")
    extension_stage = {".vert": "vertex", ".frag": "fragment", ".comp": "compute"}
    for program in layout["programs"]:
        for f in program["files"]:
            if f not in layout["files"]:
                errors.append(f"program {program['name']}: file {f} not in files")
        # stages[i] is the stage of files[i]: as many, and the one the file's extension says
        if len(program["stages"]) != len(program["files"]):
            errors.append(f"program {program['name']}: {len(program['stages'])} stages for "
                          f"{len(program['files'])} files")
        for f, stage in zip(program["files"], program["stages"]):
            # WGSL, HLSL and MSL: the GLSL name and .wgsl, .hlsl or .metal (penumbra_deferred.frag.wgsl)
            expected = extension_stage.get(pathlib.PurePath(f.removesuffix(".wgsl").removesuffix(".hlsl").removesuffix(".metal")).suffix)
            if stage != expected:
                errors.append(f"program {program['name']}: file {f} has stage {stage}, its extension says {expected}")
    return errors


def all_errors(validator, layout):
    errors = [f"{'/'.join(map(str, e.absolute_path))}: {e.message}" for e in validator.iter_errors(layout)]
    return errors + (references_errors(layout) if not errors else [])


def main():
    gen, schema_path, work = sys.argv[1], pathlib.Path(sys.argv[2]), pathlib.Path(sys.argv[3])
    schema = json.loads(schema_path.read_text())
    jsonschema.Draft202012Validator.check_schema(schema)
    validator = jsonschema.Draft202012Validator(schema)
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)

    matrix = [(f"{filt}-{packing}-{light}-{target}-S{slices}-R{resolution}",
               ["--filter", filt, "--packing", packing, "--light", light, "--target", target,
                "--slices", str(slices), "--resolution", str(resolution)])
              for filt, packing, light, target, (slices, resolution) in itertools.product(
                  ["mipmap", "nbuffer", "sat", "gaussian"], ["atlas", "array", "volume"], ["rect", "sun"],
                  ["glsl330", "glsl450", "essl300", "vulkan"], [(5, 32), (16, 128)])]
    # Every other technique (its own textures, passes and uniforms), every light and target.
    matrix += [(f"{technique}-{light}-{target}", ["--technique", technique, "--light", light, "--target", target])
               for technique, light, target in itertools.product(
                   ["shadowmap", "pcf", "pcss", "oim", "erosion", "evsm", "smrt"], ["rect", "sun"],
                   ["glsl330", "glsl450", "essl300", "vulkan"])]
    matrix += [(f"occlusion-{fusion}-clip-{target}", ["--fusion", fusion, "--tangent-clip", "--target", target])
               for fusion in ["chained", "correlated", "extent"] for target in ["glsl330", "glsl450", "essl300", "vulkan"]]
    # More than 32 slices: the slicing as bits (logic op OR) and the unpack passes.
    matrix += [(f"bits-{filt}-{packing}-{target}-S{slices}",
                ["--filter", filt, "--packing", packing, "--target", target, "--slices", str(slices),
                 "--resolution", "32"])
               for filt, packing, target, slices in itertools.product(
                   ["mipmap", "nbuffer", "sat"], ["atlas", "array"], ["glsl330", "glsl450", "vulkan"], [64, 128])]
    # Adaptive slice placement (paper §5): the depth-bin and boundary passes and their textures.
    matrix += [(f"occlusion-adaptive-{packing}-{light}-{target}",
                ["--slice-placement", "adaptive", "--packing", packing, "--light", light, "--target", target,
                 "--slices", "5", "--resolution", "64"])
               for packing, light, target in itertools.product(
                   ["atlas", "array"], ["rect", "sun"], ["glsl330", "glsl450", "essl300", "vulkan"])]

    # The compute prefilter: dispatch passes with image outputs (N-buffers, atlas, glsl450 only; the
    # other targets and packings are refused), RGBA8 and RGBA16F levels.
    matrix += [(f"compute-{packing}-{target}-{fmt}",
                ["--prefilter-stage", "compute", "--packing", packing, "--target", target, "--level-format", fmt,
                 "--slices", "5", "--resolution", "128"])
               for packing, target, fmt in itertools.product(
                   ["atlas", "array"], ["glsl330", "glsl450", "essl300", "vulkan"], ["rgba8", "rgba16f"])]

    # Cut-out casters (alpha_test): the caster programs' penumbra_uv and per-draw ("draw") parameters,
    # every technique and target, the adaptive depth bins too.
    matrix += [(f"alpha-test-{technique}-{target}", ["--alpha-test", "--technique", technique, "--target", target])
               for technique, target in itertools.product(
                   ["occlusion", "shadowmap", "pcf", "pcss", "oim", "erosion", "evsm", "smrt"], ["glsl330", "glsl450", "essl300", "vulkan"])]
    # WGSL (WebGPU): bind groups, sampler bindings, texture formats and usages; the techniques it writes.
    matrix += [(f"wgsl-{technique}-{light}{'-alpha' if alpha else ''}",
                ["--technique", technique, "--light", light, "--target", "wgsl", *(["--alpha-test"] if alpha else [])])
               for technique, light, alpha in itertools.product(
                   ["shadowmap", "pcf", "pcss", "erosion", "evsm", "smrt"], ["rect", "sun"], [False, True])]
    # HLSL (Direct3D 12): registers beside the bindings; the techniques it writes, one occlusion variant a
    # filter and packing.
    matrix += [(f"hlsl-{technique}-{light}{'-alpha' if alpha else ''}",
                ["--technique", technique, "--light", light, "--target", "hlsl", *(["--alpha-test"] if alpha else [])])
               for technique, light, alpha in itertools.product(
                   ["occlusion", "shadowmap", "pcf", "pcss", "erosion", "evsm", "smrt"], ["rect", "sun"], [False, True])]
    matrix += [(f"hlsl-{filt}-{packing}", ["--filter", filt, "--packing", packing, "--target", "hlsl", "--slices", "8",
                                          "--resolution", "64"])
               for filt, packing in [("mipmap", "atlas"), ("mipmap", "array"), ("sat", "atlas"), ("sat", "array"),
                                     ("nbuffer", "array"), ("nbuffer", "volume")]]
    # MSL (Metal, SPIRV-Cross from the vulkan target): msl indices, msl_functions, the msl object.
    matrix += [(f"msl-{technique}-{light}{'-alpha' if alpha else ''}",
                ["--technique", technique, "--light", light, "--target", "msl", *(["--alpha-test"] if alpha else [])])
               for technique, light, alpha in itertools.product(
                   ["occlusion", "shadowmap", "pcf", "pcss", "oim", "erosion", "evsm"], ["rect", "sun"], [False, True])]
    matrix += [(f"alpha-test-adaptive-{target}", ["--alpha-test", "--slice-placement", "adaptive", "--target", target,
                                                  "--slices", "5", "--resolution", "64"])
               for target in ["glsl330", "glsl450", "essl300", "vulkan"]]

    def generate(entry):
        """(name, layout or None when penumbra-gen refuses the combination, failure text)"""
        name, flags = entry
        out = work / name
        run = subprocess.run([gen, *flags, "--out", str(out)], capture_output=True, text=True)
        if run.returncode == 2:  # a combination the validator refuses (e.g. gaussian with a rect light)
            return name, None, ""
        if run.returncode != 0:
            return name, None, f"penumbra-gen exited {run.returncode}: {run.stderr.strip()}"
        layout = json.loads((out / "layout.json").read_text())
        shutil.rmtree(out)
        return name, layout, ""

    checked, skipped, failures, sample, compute_sample, cut_sample = 0, 0, [], None, None, None
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        for name, layout, failure in pool.map(generate, matrix):
            if failure:
                failures.append(f"{name}: {failure}")
            elif layout is None:
                skipped += 1
            else:
                failures += [f"{name}: {e}" for e in all_errors(validator, layout)]
                checked += 1
                sample = sample or layout
                if any(p["action"] == "dispatch" for p in layout["passes"]):
                    compute_sample = compute_sample or layout
                if layout["config"].get("alpha_test") and layout["config"]["technique"] == "occlusion":
                    cut_sample = cut_sample or layout

    # The check can fail: each of these breaks one rule of a layout of its kind and must be rejected.
    def check_rejected(kind, base, edits):
        if base is None:
            failures.append(f"no {kind} was generated")
            return
        for label, edit in edits.items():
            doc = copy.deepcopy(base)
            edit(doc)
            if not all_errors(validator, doc):
                failures.append(f"a broken layout ({label}) was accepted")

    def first_border_texture(doc):
        return next(t for t in doc["textures"] if t["wrap"] == "CLAMP_TO_BORDER")

    breakages = {
        "wrong version": lambda d: d.update(layout_version=1),
        "prose state": lambda d: d["passes"][0].update(state="blend MAX"),
        "unknown phase": lambda d: d["passes"][0].update(phase="sometimes"),
        "border colour missing": lambda d: first_border_texture(d).pop("border_color"),
        "output-sized with a width": lambda d: next(t for t in d["textures"] if t["size"] == "output").update(width=64),
        "uniform without compute": lambda d: next(u for p in d["programs"] for u in p["parameters"]
                                                  if "source" in u).pop("compute"),
        "unknown format": lambda d: d["textures"][0].update(internal_format="RGB5"),
        "missing texture": lambda d: d["passes"][-1]["inputs"].append(
            {"sampler": "x", "texture": "penumbra_nothing", "binding": 9, "level": -1}),
        "result not written": lambda d: d.update(result=d["textures"][0]["name"]),
        "extra field": lambda d: d["passes"][0].update(colour="blue"),
        "unknown logic op": lambda d: d["passes"][0]["state"].update(logic_op="XOR"),
        "logic op with blending": lambda d: d["passes"][0]["state"].update(logic_op="OR", blend=True),
        # layout_version 3: the conventions are data
        "binding without sampling": lambda d: next(i for p in d["passes"] for i in p["inputs"]).pop("sampling"),
        "sampling with an unknown compare": lambda d: next(i for p in d["passes"] for i in p["inputs"])["sampling"]
                                                      .update(compare="SOMETIMES"),
        "texture compare (version 2)": lambda d: d["textures"][0].update(compare=""),
        "program without vertex_inputs": lambda d: d["programs"][0].pop("vertex_inputs"),
        "vertex input without a location": lambda d: next(p for p in d["programs"] if p["vertex_inputs"])
                                                     ["vertex_inputs"][0].pop("location"),
        "caller texture starting at zero": lambda d: next(t for t in d["textures"] if t["source"] == "caller")
                                                     .update(initial="zero"),
        "copy details on a draw": lambda d: d["passes"][0].update(copy={"source_level": 0, "source_layer": -1,
                                                                          "target_level": 0, "target_layer": -1,
                                                                          "width": 1, "height": 1}),
        "slice in channel x": lambda d: d["slice_map"][0].update(channel="x"),
        # every program file states its stage
        "program without stages": lambda d: d["programs"][0].pop("stages"),
        "unknown stage": lambda d: d["programs"][0].update(stages=["geometry"] * len(d["programs"][0]["files"])),
        "one stage short": lambda d: d["programs"][0].update(stages=d["programs"][0]["stages"][:-1]),
        "stages swapped": lambda d: d["programs"][0].update(stages=list(reversed(d["programs"][0]["stages"]))),
    }
    def first_dispatch(doc):
        return next(p for p in doc["passes"] if p["action"] == "dispatch")

    compute_breakages = {
        "dispatch without groups": lambda d: first_dispatch(d)["dispatch"].pop("groups"),
        "dispatch without image_outputs": lambda d: first_dispatch(d).pop("image_outputs"),
        "image with an unknown access": lambda d: first_dispatch(d)["image_outputs"][0].update(access="SOMETIMES"),
        "unknown memory barrier": lambda d: first_dispatch(d)["dispatch"].update(memory_barrier=["ALL"]),
        "dispatch details on a draw": lambda d: d["passes"][0].update(dispatch=first_dispatch(d)["dispatch"]),
        "image of a missing texture": lambda d: first_dispatch(d)["image_outputs"][0].update(texture="penumbra_nothing"),
    }
    check_rejected("layout with a dispatch pass", compute_sample, compute_breakages)
    def draw_param(doc, name):
        return next(u for p in doc["programs"] for u in p["parameters"] if u["name"] == name)

    cut_breakages = {
        "draw sampler with a layout texture": lambda d: draw_param(d, "penumbra_alphaTexture").update(
            texture="penumbra_level0"),
        "draw sampler without a binding": lambda d: draw_param(d, "penumbra_alphaTexture").pop("binding"),
        "layout sampler with a draw source": lambda d: next(u for p in d["programs"] for u in p["parameters"]
                                                            if "texture" in u).update(source="draw", compute="x"),
        "alpha_test not a boolean": lambda d: d["config"].update(alpha_test="yes"),
    }
    check_rejected("layout with alpha_test", cut_sample, cut_breakages)
    check_rejected("layout", sample, breakages)

    rejected = len(breakages) + len(compute_breakages) + len(cut_breakages)
    print(f"layout.schema.json: {checked} layouts valid, {skipped} combinations refused by penumbra-gen, "
          f"{rejected} broken layouts rejected")
    for f in failures[:20]:
        print("FAIL:", f)
    return 1 if failures or checked < 140 else 0


if __name__ == "__main__":
    sys.exit(main())
