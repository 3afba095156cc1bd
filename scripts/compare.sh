#!/usr/bin/env bash
# The comparison benchmark: every technique against the ray-traced truth, at equal time, as the
# light grows. Builds penumbra-bench-compare, runs it (results.json, images) and builds the report
# (report.md, figures/) with Debian's matplotlib.
#   scripts/compare.sh [--quick | --full] [penumbra-bench-compare flags] [--out DIR]   (default out/compare)
#   scripts/compare.sh --lights rect,sun ...         the ladder under each scene's rectangle and its sun
#                                                    (occlusion interval maps: the sun only, baked once)
#   scripts/compare.sh --report-only [--out DIR]     rebuild report.md and figures from DIR/results.json
#   scripts/compare.sh --corpus [DIR] ...            also the corpus of real meshes: fetched first into DIR
#                                                    (scripts/get_corpus.sh; default ~/.cache/penumbra/corpus)
#   (either form) [--metric oriented|irradiance|visibility] [--mae-thresholds 0.1,0.15,0.2]: report options
#   (the conclusions use the fair `oriented` reference unless --metric says otherwise)
#   scripts/compare.sh ... --check                   then check report, figures and finite numbers (CI)
# The default set takes about 30 minutes on 2 llvmpipe cores; --quick a few seconds.
# PENUMBRA_BENCH_COMPARE=path/to/penumbra-bench-compare skips setup and build (the ctest test sets it);
# PENUMBRA_CORPUS_READY=1 skips fetching the corpus (the test makes a small one of its own).
set -euo pipefail
cd "$(dirname "$0")/.."

out=out/compare
report_only=0
check=0
corpus=""
bench_args=()
report_args=()
while [ $# -gt 0 ]; do
    case "$1" in
        --report-only) report_only=1 ;;
        --check) check=1 ;;
        --out)
            [ $# -ge 2 ] || { echo "error: --out: missing value (a folder)" >&2; exit 2; }
            out="$2"; bench_args+=(--out "$2"); shift ;;
        --out=*) out="${1#--out=}"; bench_args+=("$1") ;;
        --corpus) # an optional folder: the next argument unless it is a flag or a mesh file
            corpus="${XDG_CACHE_HOME:-$HOME/.cache}/penumbra/corpus"
            if [ $# -ge 2 ] && [[ "$2" != -* ]] && [[ ! "${2,,}" =~ \.(obj|gltf|glb)$ ]]; then corpus="$2"; shift; fi
            bench_args+=(--corpus "$corpus") ;;
        --metric|--mae-thresholds)
            [ $# -ge 2 ] || { echo "error: $1: missing value (see scripts/compare_report.py --help)" >&2; exit 2; }
            report_args+=("$1" "$2"); shift ;;
        *) bench_args+=("$1") ;;
    esac
    shift
done
python=/usr/bin/python3 # Debian's, with python3-matplotlib (a pyenv or venv python may lack it)

if [ "$report_only" -eq 0 ]; then
    bench="${PENUMBRA_BENCH_COMPARE:-}"
    if [ -z "$bench" ]; then
        scripts/setup.sh
        cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
        cmake --build build --parallel "$(nproc)" --target penumbra-bench-compare
        bench=build/penumbra-bench-compare
    fi
    if [ -n "$corpus" ] && [ -z "${PENUMBRA_CORPUS_READY:-}" ]; then scripts/get_corpus.sh "$corpus"; fi
    start=$(date +%s)
    "$bench" "${bench_args[@]}"
    echo "compare: penumbra-bench-compare took $(( $(date +%s) - start )) s"
fi
"$python" scripts/compare_report.py "$out" "${report_args[@]}"
if [ "$check" -eq 1 ]; then "$python" scripts/compare_report.py --check "$out"; fi
echo "report: $out/report.md"
