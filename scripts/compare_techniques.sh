#!/usr/bin/env bash
# Compares the techniques on equal terms: same scene, light, G-buffer and Embree truth, one run.
#   scripts/compare_techniques.sh [BUILD_DIR] [SCENES] [SIZE] [SAMPLES]
# defaults: build "boxes tree" 256x256 32. Prints, per scene and technique, the penumbra MAE and
# p95 against the ground truth (the headline reference of metrics.json: oriented), the warm GPU time of the shading pass and of all passes relative
# to the default occlusion-texture configuration, and the texture memory. On llvmpipe only the
# ratios mean anything.
set -euo pipefail
build=${1:-build}
scenes=${2:-boxes tree}
size=${3:-256x256}
samples=${4:-32}
playground="$build/playground/penumbra-playground"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for scene in $scenes; do
    for technique in occlusion shadowmap pcf pcss erosion; do
        "$playground" --headless --scene "$scene" --size "$size" --technique "$technique" --reference \
            --samples "$samples" --out "$out/$scene-$technique.png" --metrics "$out/$scene-$technique.json" >/dev/null
    done
done
python3 - "$out" $scenes <<'PY'
import json, sys
out, scenes = sys.argv[1], sys.argv[2:]
print(f"{'scene':8} {'technique':10} {'pen. MAE':>9} {'pen. p95':>9} {'shading ms':>11} {'x occl.':>8} "
      f"{'all passes ms':>14} {'x occl.':>8} {'textures MiB':>13}")
for scene in scenes:
    base = None
    for technique in ["occlusion", "shadowmap", "pcf", "pcss", "erosion"]:
        m = json.load(open(f"{out}/{scene}-{technique}.json"))
        # erosion: its screen passes, timed together ("erosion_hard+...+erosion_blur")
        shading = sum(p["ms"] for p in m["passes"] if p["name"] == "shading" or p["name"].startswith("erosion_"))
        total = sum(p["ms"] for p in m["passes"])
        if base is None:
            base = (shading, total)
        pen = m["reference"]["penumbra"]
        print(f"{scene:8} {technique:10} {pen['mae']:9.4f} {pen['p95']:9.4f} {shading:11.2f} {shading / base[0]:8.2f} "
              f"{total:14.2f} {total / base[1]:8.2f} {m['texture_bytes'] / 2**20:13.2f}")
print(f"({m['renderer']}, {m['width']}x{m['height']}, {m['reference']['samples_per_axis']}^2 rays per pixel, "
      f"{m['timing']})")
PY
