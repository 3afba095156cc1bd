#!/usr/bin/env bash
# The test command: install dependencies, configure into build/, build, run every test.
#   scripts/test.sh [extra ctest arguments, e.g. -L text]
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)"
ctest --test-dir build --output-on-failure "$@"
