#!/usr/bin/env bash
# The main job: set up, build, emit and validate the default configuration's shaders into
# out/shaders, then open the playground window where a display exists; without one, render the
# default scene headless, compare it with the ray-traced ground truth and print the metrics.
#   scripts/run.sh [extra penumbra-playground arguments, e.g. --scene tree --filter sat]
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)"

rm -rf out/shaders
mkdir -p out/shaders
build/generator/penumbra-gen --validate --out out/shaders
echo "emitted and validated $(find out/shaders -type f | wc -l) files into out/shaders"

playground=build/playground/penumbra-playground
if [ -n "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ]; then
    echo "opening the playground window (shaders hot-reload from ./playground-shaders)"
    if "$playground" "$@"; then exit 0; fi
    echo "the window could not open; rendering headless instead"
fi

echo "no display: rendering the default scene headless"
"$playground" --headless --scene boxes --size 512x512 --out out/boxes.png --reference --samples 16 \
    --metrics out/metrics.json "$@"
echo
echo "wrote out/boxes.png, the truths (out/boxes.reference.pfm, .reference.oriented.pfm, .reference.irradiance.pfm), out/boxes.error.png and out/metrics.json"
echo "for the interactive window on a machine without a display: xvfb-run -a $playground"
