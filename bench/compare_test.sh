#!/usr/bin/env bash
# ctest "bench": the quick comparison from an empty folder, its report, then the report rebuilt
# from results.json alone; each time the check that report, figures and finite numbers are there.
# Then the sun's own run: the rectangle and the sun, occlusion interval maps (baked into the run's
# cache) under the sun only, skipped under the rectangle with its reason, the sun's tables.
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

"$root/scripts/compare.sh" --scenes boxes --settings 'OT nbuffer 8/256,erosion r16,OIM 8/128' --lights rect,sun \
    --size 32 --samples 4 --light-scales 1 --runs 1 --flicker-frames 2 --out "$out/sun" --check >"$out/sun.log"
grep -q '^skip: boxes, rect light, OIM 8/128: occlusion interval maps are baked for the sun' "$out/sun.log" ||
    { echo "error: OIM was not skipped under the rectangle with its reason" >&2; exit 1; }
grep -q '^# Under the sun' "$out/sun/report.md" || { echo "error: the report has no tables for the sun" >&2; exit 1; }
for label in 'OIM 8/128' 'erosion r16' 'OT nbuffer 8/256'; do
    grep -q "^| boxes | x1 | $label | " "$out/sun/report.md" || { echo "error: no measurement of $label" >&2; exit 1; }
done
grep -q '^| boxes | OIM 8/128 | 128² | 8 | 256 | ' "$out/sun/report.md" || { echo "error: the report has no bake row" >&2; exit 1; }
# A second run reads the bake from the cache.
"$PENUMBRA_BENCH_COMPARE" --scenes boxes --settings 'OIM 8/128' --lights sun --size 32 --samples 4 --light-scales 1 \
    --runs 1 --flicker-frames 2 --out "$out/sun" >"$out/sun-again.log"
grep -q '^bake: boxes, sun light, OIM 8/128: .* read ' "$out/sun-again.log" ||
    { echo "error: the second run did not read the bake from the cache" >&2; exit 1; }

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
