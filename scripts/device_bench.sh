#!/usr/bin/env bash
# GPU timings in one go: builds the comparison and quality benchmarks, runs the comparison (the default,
# the compute prefilter, the irradiance window and PCSS 16/16 on boxes and tree at light x1, x8, x32,
# 1024x1024) and the quality bench on the GPU through EGL's device platform, and writes one report.
#   scripts/device_bench.sh [--out DIR] [--small] [--surfaceless] [--tests]
#     --out DIR      where results and the report go (default out/device_bench): DIR/report.md,
#                    DIR/compare/ (results.json, report.md, figures), DIR/quality.txt, DIR/build.log
#     --small        a smoke-sized run (quick comparison at 32², quality bench on one scene at 64²),
#                    for checking the script on a machine without a GPU
#     --surfaceless  keep Mesa's surfaceless platform (llvmpipe) instead of asking for the GPU
#     --tests        also build and run penumbra-tests-gl there (DIR/tests_gl.txt): the GPU against the
#                    oracle and the checks that GL allows latitude in (docs/model.md §4, On a GPU)
# On an NVIDIA machine (EGL_EXT_platform_device, libnvidia-egl) the default run takes a few minutes
# after the build. The renderer each bench ran on is the first line of its output and of the report:
# check that it names the GPU. Nothing in CI depends on this script.
set -euo pipefail
cd "$(dirname "$0")/.."

out=out/device_bench
small=0
tests=0
platform=device
while [ $# -gt 0 ]; do
    case "$1" in
        --out)
            [ $# -ge 2 ] || { echo "error: --out: missing value (a folder)" >&2; exit 2; }
            out="$2"; shift ;;
        --out=*) out="${1#--out=}" ;;
        --small) small=1 ;;
        --surfaceless) platform=surfaceless ;;
        --tests) tests=1 ;;
        -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "error: unknown argument '$1'; allowed: --out DIR, --small, --surfaceless, --tests, --help" >&2; exit 2 ;;
    esac
    shift
done
[ -n "$out" ] || { echo "error: --out: empty; allowed: a folder" >&2; exit 2; }
mkdir -p "$out"
start=$(date +%s)

jobs=$(nproc 2>/dev/null || echo 2)
build=${PENUMBRA_BUILD_DIR:-build}
targets=(penumbra-bench-compare penumbra-bench-quality)
[ "$tests" -eq 1 ] && targets+=(penumbra-tests-gl penumbra-playground)
echo "building ${targets[*]} in $build (-j$jobs) ..."
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
if ! { cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" &&
       cmake --build "$build" --target "${targets[@]}" -j"$jobs"; } >"$out/build.log" 2>&1; then
    tail -20 "$out/build.log" >&2
    echo "error: the build failed (whole log: $out/build.log)" >&2
    exit 1
fi
built=$(date +%s)

export PENUMBRA_EGL_PLATFORM=$platform
if [ "$small" -eq 1 ]; then
    compare_args=(--quick --size 32 --samples 4 --runs 2 --flicker-frames 2)
    quality_args=(--scenes boxes --filters nbuffer --configs 16x512 --size 64x64 --samples 4 --repeat 2)
else
    compare_args=(--scenes boxes,tree --settings "OT nbuffer 16/512,OT nbuffer 16/512 compute,OT nbuffer 16/512 area,PCSS 16/16"
                  --light-scales 1,8,32 --size 1024 --samples 8 --runs 7 --flicker-frames 4)
    quality_args=(--filters mipmap,nbuffer,sat --configs 16x512,4x128 --size 256x256 --samples 16 --repeat 3)
fi

echo "comparison: $build/penumbra-bench-compare ${compare_args[*]} --out $out/compare"
"$build/penumbra-bench-compare" "${compare_args[@]}" --out "$out/compare" >"$out/compare.txt" 2>&1 ||
    { tail -20 "$out/compare.txt" >&2; echo "error: penumbra-bench-compare failed ($out/compare.txt)" >&2; exit 1; }
/usr/bin/python3 scripts/compare_report.py "$out/compare" >"$out/compare_report.txt" 2>&1 ||
    { cat "$out/compare_report.txt" >&2; echo "error: compare_report.py failed" >&2; exit 1; }
compared=$(date +%s)

echo "quality: $build/penumbra-bench-quality ${quality_args[*]}"
"$build/penumbra-bench-quality" "${quality_args[@]}" >"$out/quality.txt" 2>&1 ||
    { tail -20 "$out/quality.txt" >&2; echo "error: penumbra-bench-quality failed ($out/quality.txt)" >&2; exit 1; }
tests_line="not run (--tests)"
if [ "$tests" -eq 1 ]; then
    tests_gl="$(cd "$build" && pwd)/tests/runtime/penumbra-tests-gl"
    echo "tests: $tests_gl"
    # the failures are the finding: the run goes on to the report either way
    (cd "$out" && "$tests_gl") >"$out/tests_gl.txt" 2>&1 || true
    tests_line=$(grep -E '^\[doctest\] test cases:' "$out/tests_gl.txt" | tail -1 | sed 's/^\[doctest\] //')
    [ -n "$tests_line" ] || tests_line="no summary: the run ended early ($out/tests_gl.txt)"
fi
done_at=$(date +%s)

renderer=$(/usr/bin/python3 -c 'import json,sys; m=json.load(open(sys.argv[1]))["meta"]; print(m["renderer"], "|", m["gl_version"], "| EGL", m["egl_platform"])' "$out/compare/results.json")
{
    echo "# Device bench"
    echo
    echo "- renderer: $renderer"
    echo "- date: $(date -u +%Y-%m-%dT%H:%M:%SZ), commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
    echo "- build $((built - start)) s, comparison $((compared - built)) s, quality and tests $((done_at - compared)) s"
    echo "- comparison: \`$build/penumbra-bench-compare ${compare_args[*]} --out $out/compare\`"
    echo "- quality: \`$build/penumbra-bench-quality ${quality_args[*]}\`"
    echo "- penumbra-tests-gl: $tests_line"
    echo
    echo "## Comparison (per setting: GPU time of every pass, texture memory, fair penumbra MAE)"
    echo
    echo '```'
    grep -v '^\[' "$out/compare.txt" || true
    echo '```'
    echo
    echo "The full comparison report: compare/report.md."
    echo
    echo "## Quality bench"
    echo
    echo '```'
    cat "$out/quality.txt"
    echo '```'
} >"$out/report.md"
echo "wrote $out/report.md ($renderer) in $((done_at - start)) s"
