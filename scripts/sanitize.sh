#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer run of everything that runs: builds with
# -DPENUMBRA_SANITIZE=ON into build-asan (Debug, so the runtime's KHR_debug path is on as well)
# and runs the generator, the headless playground and the window under the sanitizers. Any
# invalid access, undefined behaviour or leak in our code fails the script.
#   scripts/sanitize.sh            the whole set: hostile-input regressions and fuzz (both tools),
#                                  the GL tests, one headless render with --reference, the
#                                  scripted window session under xvfb-run
#   scripts/sanitize.sh --quick    the small set scripts/test.sh runs in CI: penumbra-gen alone
#                                  built sanitized (build-asan-gen), the hostile regressions and a
#                                  tenth of the penumbra-gen fuzz cases through it
#
# One suppression, for a third-party report only (scripts/sanitize.supp: Debian's ImGui 1.86
# loader). Halting stays on for everything else. The vptr check is off (CMakeLists.txt): Debian's
# glslang has no RTTI.
#
# Mesa's EGL dlopens the llvmpipe driver (swrast_dri.so) and dlcloses it at eglTerminate. A draw
# call makes the driver calloc two 56-byte blocks that it keeps in its own globals; once the driver
# is unmapped LeakSanitizer no longer sees those globals and reports the blocks as "indirect leak …
# (<unknown module>)". Preloading the driver keeps it mapped until exit, so its globals stay
# visible and nothing of ours is hidden.
set -euo pipefail
cd "$(dirname "$0")/.."

quick=0
if [ "${1:-}" = "--quick" ]; then
    quick=1
    shift
fi

scripts/setup.sh >/dev/null
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
start=$(date +%s)
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:check_initialization_order=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:suppressions=$PWD/scripts/sanitize.supp"
preload="$(g++ -print-file-name=libasan.so) $(g++ -print-file-name=libubsan.so)"
driver=/usr/lib/x86_64-linux-gnu/dri/swrast_dri.so
if [ -e "$driver" ]; then preload="$preload $driver"; fi
# Only sanitized processes get the preload (the sanitizer runtimes must come first in it): the
# test drivers and the tools they start. Xvfb, started for the window, must not get it.
sanitized() { LD_PRELOAD="$preload" "$@"; }

if [ $quick = 1 ]; then
    # The small set: only penumbra-gen is built sanitized (the generator alone, no playground or
    # tests), and the hostile-input driver of the regular build (scripts/test.sh builds it) runs
    # its regressions and a tenth of its penumbra-gen fuzz cases against it.
    driver_binary=build/tests/hostile/penumbra-tests-hostile
    [ -x "$driver_binary" ] || { echo "sanitize --quick: build $driver_binary first (scripts/test.sh)"; exit 1; }
    cmake -S . -B build-asan-gen -DCMAKE_BUILD_TYPE=Debug -DPENUMBRA_SANITIZE=ON -DPENUMBRA_BUILD_PLAYGROUND=OFF \
        -DPENUMBRA_BUILD_TESTS=OFF "${launcher[@]}" >/dev/null
    cmake --build build-asan-gen --target penumbra-gen --parallel "$(nproc)"
    echo "sanitize --quick: built in $(( $(date +%s) - start )) s"
    export PENUMBRA_TEST_GEN="$PWD/build-asan-gen/generator/penumbra-gen"
    sanitized "$driver_binary" --test-case='hostile:*'
    PENUMBRA_FUZZ_SCALE=0.1 sanitized "$driver_binary" --test-case='fuzz: penumbra-gen*'
    echo "sanitize --quick: clean ($(( $(date +%s) - start )) s in all)"
    exit 0
fi

cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DPENUMBRA_SANITIZE=ON "${launcher[@]}" >/dev/null
cmake --build build-asan --target penumbra-gen penumbra-playground penumbra-tests-hostile penumbra-tests-gl \
    --parallel "$(nproc)"
echo "sanitize: built in $(( $(date +%s) - start )) s"

echo "sanitize: hostile-input regressions (penumbra-gen, penumbra-playground)"
sanitized build-asan/tests/hostile/penumbra-tests-hostile --test-case='hostile:*'
echo "sanitize: fuzz"
sanitized build-asan/tests/hostile/penumbra-tests-hostile --test-case='fuzz:*'
echo "sanitize: GL tests"
sanitized build-asan/tests/runtime/penumbra-tests-gl "$@"
echo "sanitize: window (a scripted session under xvfb-run: configuration, a broken edit, its fix)"
if command -v xvfb-run >/dev/null; then
    session=build-asan/sanitize_window
    rm -rf "$session" && mkdir -p "$session"
    printf '%s\n' 'set filter sat' 'wait 2' 'edit penumbra_deferred.frag append this is not glsl' \
        'wait_reload 20' 'restore penumbra_deferred.frag' 'wait_reload 20' 'set split on' 'wait 2' \
        'screenshot window.png' > "$session/session.txt"
    # The playground's own exit status, not xvfb-run's: xvfb-run has exited 5 after a command that
    # succeeded ("problem while cleaning up temporary directory"), so the session writes its status.
    (cd "$session" && xvfb-run -a sh -c 'env LD_PRELOAD="$1" ../playground/penumbra-playground --scene boxes \
        --size 160x120 --slices 4 --resolution 64 --script session.txt --watch shaders; echo $? > status.txt' \
        sh "$preload") || true
    if [ "$(cat "$session/status.txt" 2>/dev/null)" != 0 ]; then
        echo "sanitize: the window session failed (exit status: $(cat "$session/status.txt" 2>/dev/null || echo none))" >&2
        exit 1
    fi
else
    echo "sanitize: skipped the window: no xvfb-run"
fi

echo "sanitize: one headless playground render"
sanitized build-asan/playground/penumbra-playground --headless --scene boxes --size 64x64 --slices 4 \
    --resolution 64 --out build-asan/sanitize_boxes.png --reference --samples 2 \
    --metrics build-asan/sanitize_boxes.json
echo "sanitize: clean ($(( $(date +%s) - start )) s in all)"
