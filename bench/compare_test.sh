#!/usr/bin/env bash
# ctest "bench": the quick comparison from an empty folder, its report, then the report rebuilt
# from results.json alone; each time the check that report, figures and finite numbers are there.
# Then --corpus on a corpus made here (one small mesh: a box on a floor, written below, so CI needs
# no network): the run and the report's per-mesh table.
#   bench/compare_test.sh path/to/penumbra-bench-compare OUT_DIR
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
export PENUMBRA_BENCH_COMPARE="$1"
out="$2"
rm -rf "$out"
"$root/scripts/compare.sh" --quick --out "$out" --check
rm -rf "$out/report.md" "$out/figures"
"$root/scripts/compare.sh" --report-only --out "$out" --check

# A corpus of one mesh: a unit box standing on a 6×6 floor, with its manifest as get_corpus.sh writes it.
corpus="$out/corpus"
mkdir -p "$corpus/meshes"
cat >"$corpus/meshes/boxfloor.obj" <<'OBJ'
v -3 0 -3
v 3 0 -3
v 3 0 3
v -3 0 3
v -0.5 0.2 -0.5
v 0.5 0.2 -0.5
v 0.5 0.2 0.5
v -0.5 0.2 0.5
v -0.5 1.2 -0.5
v 0.5 1.2 -0.5
v 0.5 1.2 0.5
v -0.5 1.2 0.5
f 1 4 3 2
f 5 6 7 8
f 9 12 11 10
f 5 9 10 6
f 6 10 11 7
f 7 11 12 8
f 8 12 9 5
OBJ
cat >"$corpus/corpus.json" <<'JSON'
{"meshes": [{"name": "boxfloor", "file": "meshes/boxfloor.obj", "triangles": 14, "source": "bench/compare_test.sh",
             "licence": "made by the test"}]}
JSON
PENUMBRA_CORPUS_READY=1 "$root/scripts/compare.sh" --quick --scenes '' --corpus "$corpus" --light-scales 1 \
    --runs 2 --flicker-frames 2 --out "$out/with-corpus" --check
grep -q '^### Meshes' "$out/with-corpus/report.md" || { echo "error: the report has no per-mesh table" >&2; exit 1; }
# 16: the file's 14 and the floor load_scene puts under every mesh file (--no-ground: none)
grep -q '^| boxfloor | 16 | ' "$out/with-corpus/report.md" || { echo "error: the per-mesh table has no boxfloor row" >&2; exit 1; }
# A missing manifest is one error line and exit 2.
if "$PENUMBRA_BENCH_COMPARE" --quick --corpus "$out" --out "$out/none" 2>"$out/none.err"; then
    echo "error: --corpus without a manifest succeeded" >&2; exit 1
fi
grep -q "^error: --corpus: .*corpus.json not found; fetch the corpus first: scripts/get_corpus.sh" "$out/none.err" ||
    { echo "error: unexpected message for a missing manifest: $(cat "$out/none.err")" >&2; exit 1; }
