#!/usr/bin/env bash
# The test command: install dependencies, configure into build/, build, run every test, then the
# small sanitized set (scripts/sanitize.sh --quick: penumbra-gen under ASan + UBSan through the
# hostile-input regressions and fuzz cases).
#   scripts/test.sh [extra ctest arguments, e.g. -L text]   (with arguments: only those tests)
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)"
ctest --test-dir build --output-on-failure "$@"
if [ $# -eq 0 ]; then scripts/sanitize.sh --quick; fi
