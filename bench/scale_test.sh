#!/usr/bin/env bash
# ctest "bench": penumbra-bench-scale on a series made here (one sheet over a floor, tessellated
# into 2·16² and 2·32² triangles: sheet-512 and sheet-2k) and the built-in box, tiny sizes; checks
# the table, the growth row of the series and the JSON (every number finite).
#   bench/scale_test.sh path/to/penumbra-bench-scale OUT_DIR
set -euo pipefail
bench="$1"
out="$2"
rm -rf "$out" && mkdir -p "$out"
sheet() { # sheet N FILE: a floor quad and above it an N×N grid of quads
    awk -v n="$1" 'BEGIN {
        print "v -2 0 -2"; print "v 2 0 -2"; print "v 2 0 2"; print "v -2 0 2"; print "f 1 4 3 2"
        for (j = 0; j <= n; ++j) for (i = 0; i <= n; ++i) printf "v %g 1 %g\n", -1 + 2 * i / n, -1 + 2 * j / n
        for (j = 0; j < n; ++j) for (i = 0; i < n; ++i) {
            a = 5 + j * (n + 1) + i; printf "f %d %d %d %d\n", a, a + n + 1, a + n + 2, a + 1
        } }' >"$2"
}
sheet 16 "$out/sheet-512.obj"
sheet 32 "$out/sheet-2k.obj"
"$bench" --scenes box "$out/sheet-512.obj" "$out/sheet-2k.obj" --size 32 --samples 2 --runs 1 --warmup 1 \
    --json "$out/scale.json" | tee "$out/scale.txt"
# +2 triangles each: the floor load_scene puts under every mesh file
grep -q '^| sheet-512 | 516 | ' "$out/scale.txt" || { echo "error: no sheet-512 row" >&2; exit 1; }
grep -q '^| sheet-2k | 2052 | ' "$out/scale.txt" || { echo "error: no sheet-2k row" >&2; exit 1; }
grep -q '^| sheet-512 | sheet-2k | 4.0 | ' "$out/scale.txt" || { echo "error: no growth row for the sheet series" >&2; exit 1; }
/usr/bin/python3 - "$out/scale.json" <<'PY'
import json, math, sys
r = json.load(open(sys.argv[1]))
names = [s["name"] for s in r["scenes"]]
assert names == ["box", "sheet-512", "sheet-2k"], names  # sorted by triangles
def numbers(v):
    if isinstance(v, dict): return [x for k in v.values() for x in numbers(k)]
    if isinstance(v, list): return [x for k in v for x in numbers(k)]
    return [v] if isinstance(v, (int, float)) and not isinstance(v, bool) else []
bad = [x for x in numbers(r) if not math.isfinite(x)]
assert not bad, f"non-finite numbers: {bad[:3]}"
for s in r["scenes"]:
    assert s["techniques"]["OT default"]["scene_draws"] >= 1 and s["techniques"]["PCSS 16/16"]["scene_draws"] == 1, s["name"]
    assert s["truth"]["build_ms"] > 0 and s["truth"]["visibility_rays"] > 0, s["name"]
assert r["growth"] and r["growth"][0]["from"] == "sheet-512" and "OT scene passes" in r["growth"][0]["exponents"]
print("scale_test: 3 scenes, one growth row, every number finite")
PY
# Bad input: one error line, exit 2.
if "$bench" --size 8 2>"$out/err.txt"; then echo "error: --size 8 was accepted" >&2; exit 1; fi
grep -q "^error: --size: '8' is not allowed; allowed: 16 to 1024" "$out/err.txt" || { cat "$out/err.txt" >&2; exit 1; }
