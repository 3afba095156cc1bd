"""technique_variants.py — the configurations of tests/technique_variants.json as (name, penumbra-gen
flags): every variant × light × alpha test, and for the techniques with a normal offset × normal offset.
Read by the HLSL and MSL matrices (tests/hlsl/hlsl_matrix.py, tests/msl/msl_matrix.py); the WGSL matrix
(targets/web/wgsl_matrix.mjs) reads the same JSON."""
import json
import pathlib

MATRIX = json.loads((pathlib.Path(__file__).resolve().parent / "technique_variants.json").read_text())


def configurations():
    out = []
    for variant, flags in MATRIX["variants"].items():
        offsets = MATRIX["normal_offsets"] if flags.split()[1] in MATRIX["normal_offset_techniques"] else [None]
        for light in MATRIX["variant_lights"].get(variant, MATRIX["lights"]):
            for offset in offsets:
                for alpha in MATRIX["alpha_test"]:
                    name = f"{variant}-{light}" + ("" if offset is None else f"-n{offset}") + ("-alpha" if alpha else "")
                    argv = flags.split() + ["--light", light]
                    argv += [] if offset is None else ["--shadow-normal-offset", offset]
                    argv += ["--alpha-test"] if alpha else []
                    out.append((name, argv))
    return out
