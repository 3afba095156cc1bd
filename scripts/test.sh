#!/usr/bin/env bash
# The test command: install dependencies, configure into build/, build, run every test, then the
# small sanitized set (scripts/sanitize.sh --quick: penumbra-gen under ASan + UBSan through the
# hostile-input regressions and fuzz cases).
#   scripts/test.sh [extra ctest arguments, e.g. -L text]   (with arguments: only those tests)
#
# The tests run as on a machine that never ran them: every cache they could read from an earlier
# run starts empty, in build/cold-caches/ (made anew each time):
#   mesa/   MESA_SHADER_CACHE_DIR: llvmpipe compiles every shader with LLVM; a warm cache hides
#           most of that cost, which a new machine (or CI on one) pays in full
#   xdg/    XDG_CACHE_HOME: the corpus (scripts/get_corpus.sh) and penumbra-playground's bakes
#           (PENUMBRA_CACHE_DIR, which would name another folder for the bakes, is unset)
#   npm/    npm_config_cache: the package tests install offline, from files the setup put in place
# PENUMBRA_WARM_CACHES=1 keeps your own caches instead (faster, and runs the corpus cases).
# After ctest, scripts/test_budget.py prints each test's time against its timeout and fails the
# run when one used more than half of it.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
if [ "${PENUMBRA_WARM_CACHES:-0}" != 1 ]; then
    rm -rf build/cold-caches
    mkdir -p build/cold-caches/mesa build/cold-caches/xdg build/cold-caches/npm
    export MESA_SHADER_CACHE_DIR="$PWD/build/cold-caches/mesa"
    export XDG_CACHE_HOME="$PWD/build/cold-caches/xdg"
    export npm_config_cache="$PWD/build/cold-caches/npm"
    unset PENUMBRA_CACHE_DIR
    echo "test: caches start empty in build/cold-caches (PENUMBRA_WARM_CACHES=1 keeps yours)"
fi
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build --parallel "$(nproc)"

# Tests without a TIMEOUT of their own get this one; test_budget.py reads the same number.
default_timeout=300
junit="build/Testing/last-run.xml"
mkdir -p build/Testing
start=$(date +%s)
status=0
# --test-output-truncation head: ctest keeps the last lines of a passed test's output, where the gl parts
# print what they compiled and linked and doctest its counts.
ctest --test-dir build --output-on-failure --parallel "$(nproc)" --timeout "$default_timeout" \
      --test-output-truncation head --output-junit "$PWD/$junit" "$@" || status=$?
echo "test: ctest took $(( $(date +%s) - start )) s"
python3 scripts/test_budget.py build "$junit" --default-timeout "$default_timeout" || {
    budget=$?
    if [ "$status" -eq 0 ]; then status=$budget; fi
}
if [ "$status" -ne 0 ]; then exit "$status"; fi
if [ $# -eq 0 ]; then scripts/sanitize.sh --quick; fi
