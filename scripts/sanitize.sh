#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run of the GL code: builds with
# -DPENUMBRA_SANITIZE=ON into build-asan (Debug, so the runtime's KHR_debug path is on as well),
# then runs the GL tests and one headless playground render. Any invalid access, undefined
# behaviour or leak in our code fails the script.
#   scripts/sanitize.sh [doctest arguments for penumbra-tests-gl, e.g. -tc="reconfigure*"]
#
# No suppression file. One thing needs care: Mesa's EGL dlopens the llvmpipe driver
# (swrast_dri.so) and dlcloses it at eglTerminate. A draw call makes the driver calloc two 56-byte
# blocks that it keeps in its own globals; once the driver is unmapped LeakSanitizer no longer sees
# those globals and reports the blocks as "indirect leak … (<unknown module>)" (valgrind, with
# --keep-debuginfo=yes, shows the calloc inside swrast_dri.so under glDrawElements). Preloading
# the driver keeps it mapped until exit, so its globals stay visible and nothing of ours is hidden.
set -euo pipefail
cd "$(dirname "$0")/.."

scripts/setup.sh
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DPENUMBRA_SANITIZE=ON
cmake --build build-asan --target penumbra-tests-gl penumbra-playground --parallel "$(nproc)"

export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
driver=/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so
if [ -e "$driver" ]; then
    # The sanitizer runtimes must come first in the preload list.
    export LD_PRELOAD="$(g++ -print-file-name=libasan.so) $(g++ -print-file-name=libubsan.so) $driver"
fi

echo "sanitize: GL tests"
build-asan/tests/runtime/penumbra-tests-gl "$@"

echo "sanitize: one headless playground render"
build-asan/playground/penumbra-playground --headless --scene boxes --size 128x128 \
    --out build-asan/sanitize_boxes.png --reference --samples 4
echo "sanitize: clean"
