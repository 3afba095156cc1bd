#!/usr/bin/env bash
# The main job: build, then emit and validate the default configuration's shaders into out/shaders.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)"

rm -rf out/shaders
mkdir -p out/shaders
build/generator/penumbra-gen --validate --out out/shaders

echo
echo "== summary =="
echo "files in out/shaders: $(find out/shaders -type f | wc -l)"
find out/shaders -type f -printf '  %P (%s bytes)\n' | sort
