#!/usr/bin/env bash
# ctest "bench": the quick comparison from an empty folder, its report, then the report rebuilt
# from results.json alone; each time the check that report, figures and finite numbers are there.
#   bench/compare_test.sh path/to/penumbra-bench-compare OUT_DIR
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
export PENUMBRA_BENCH_COMPARE="$1"
out="$2"
rm -rf "$out"
"$root/scripts/compare.sh" --quick --out "$out" --check
rm -rf "$out/report.md" "$out/figures"
"$root/scripts/compare.sh" --report-only --out "$out" --check
