#!/usr/bin/env bash
# publish_web.sh — the browser playground as one folder for any static host: web/ (the page, no
# build step), the WebAssembly emitter (build/wasm/penumbra_emitter.wasm, into three/) and the
# built-in scenes as small essl300 bundles (penumbra-export-bundle, 96x96 G-buffers, 128² slicing, an 8x8-ray
# Embree truth for the error view; the desktop run's visibility is kept for the difference view,
# its slicing output is not), plus boxes-oim: boxes with its occlusion interval maps baked, and
# the three.js add-on (three/: the npm package's modules, penumbra_shadows.js, the layout runner,
# the light frame and the emitter, which the page imports from there; its shipped emissions; its
# example at three/example/) with the three modules the example and the README's snippets import
# (three, OrbitControls, lil-gui, the RectAreaLight helpers, GLTFLoader, OBJLoader,
# BufferGeometryUtils; npm ci in web/three).
#
#   scripts/publish_web.sh [--build DIR] [--scenes "planes boxes ..."] OUT_DIR
#   python3 -m http.server --directory OUT_DIR 8000     # then http://localhost:8000/
#
# Needs a build with the targets penumbra-emitter-wasm and penumbra-export-bundle (EGL: llvmpipe
# or a GPU). Exit 0 written, 1 a step failed, 2 bad arguments.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build"
scenes="planes boxes tree butterfly terrain crowd box"
out=""
while [ $# -gt 0 ]; do
    case "$1" in
        --build) build="$2"; shift 2 ;;
        --scenes) scenes="$2"; shift 2 ;;
        -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
        -*) echo "error: unknown flag '$1'; allowed: --build DIR, --scenes LIST, OUT_DIR" >&2; exit 2 ;;
        *) out="$1"; shift ;;
    esac
done
if [ -z "$out" ]; then echo "error: OUT_DIR missing; usage: scripts/publish_web.sh [--build DIR] [--scenes LIST] OUT_DIR" >&2; exit 2; fi
wasm="$build/wasm/penumbra_emitter.wasm"
exporter="$build/targets/bundle/penumbra-export-bundle"
for need in "$wasm" "$exporter"; do
    if [ ! -f "$need" ]; then
        echo "error: $need is missing; build it: cmake --build $build --target penumbra-emitter-wasm penumbra-export-bundle" >&2
        exit 1
    fi
done

mkdir -p "$out/scenes"
cp "$root"/web/*.html "$root"/web/*.js "$out/"
# The three.js add-on (the page imports its runner, light frame and emitter from three/), and of
# three only the files the example and the README's snippets load: the example's import map points
# at three/node_modules/three.
three="$root/web/three/node_modules/three"
if [ ! -f "$three/build/three.module.js" ]; then
    echo "error: $three is missing; install it: npm ci --prefix $root/web/three" >&2
    exit 1
fi
mkdir -p "$out/three/node_modules/three/build" "$out/three/node_modules/three/examples/jsm"/{controls,helpers,lights,libs,loaders,utils}
cp -r "$root"/web/three/{penumbra_shadows.js,penumbra_shadows_webgpu.js,penumbra_scene.js,penumbra_runner.js,penumbra_webgpu_runner.js,light_frame.js,gltf_lights_area.js,penumbra_emitter.js,emissions.js} \
      "$root"/web/three/{penumbra_shadows.d.ts,gltf_lights_area.d.ts,penumbra_emitter.d.ts,package.json,README.md} \
      "$root"/web/three/emissions "$root"/web/three/example "$out/three/"
rm -f "$out/three/emissions/regenerate.sh"
# the example's "room (glTF)" scene loads ../../rooms/room.gltf
if [ -f "$root/web/rooms/room.gltf" ]; then mkdir -p "$out/rooms" && cp "$root/web/rooms/room.gltf" "$out/rooms/"; fi
cp "$wasm" "$out/three/penumbra_emitter.wasm"
cp "$three"/LICENSE "$three"/package.json "$out/three/node_modules/three/"
# (three.webgpu.js and three.tsl.js: the example's renderer switch to WebGPURenderer)
cp "$three"/build/three.module.js "$three"/build/three.core.js "$three"/build/three.webgpu.js "$three"/build/three.tsl.js \
   "$out/three/node_modules/three/build/"
addons="controls/OrbitControls.js helpers/RectAreaLightHelper.js lights/RectAreaLightUniformsLib.js
        lights/RectAreaLightTexturesLib.js libs/lil-gui.module.min.js loaders/GLTFLoader.js loaders/OBJLoader.js
        utils/BufferGeometryUtils.js utils/SkeletonUtils.js"
for module in $addons; do
    cp "$three/examples/jsm/$module" "$out/three/node_modules/three/examples/jsm/$module"
done
# every relative import of those modules is there too (GLTFLoader needs BufferGeometryUtils and SkeletonUtils)
for module in $addons; do
    for import in $(grep -o "from '\.[^']*'" "$three/examples/jsm/$module" | sed "s/from '\(.*\)'/\1/"); do
        if [ ! -f "$out/three/node_modules/three/examples/jsm/$(dirname "$module")/$import" ]; then
            echo "error: three/addons/$module imports $import, which publish_web.sh does not copy; add it to the list" >&2
            exit 1
        fi
    done
done
index="{\"scenes\": ["
first=1
for scene in $scenes; do
    dir="$out/scenes/$scene"
    "$exporter" --scene "$scene" --target essl300 --resolution 128 --size 96x96 --reference 8 --out "$dir" >/dev/null
    rm -rf "$dir/slices.f32" "$dir/emission" # the page emits its own
    [ $first -eq 1 ] || index+=", "
    index+="{\"name\": \"$scene\", \"dir\": \"$scene\"}"
    first=0
done
# Occlusion interval maps need a bake: boxes with the default oim parameters (the panel's).
"$exporter" --scene boxes --technique oim --target essl300 --size 96x96 --reference 8 --out "$out/scenes/boxes-oim" >/dev/null
rm -rf "$out/scenes/boxes-oim/emission"
index+=", {\"name\": \"boxes-oim (with its bake)\", \"dir\": \"boxes-oim\"}"
index+="]}"
echo "$index" > "$out/scenes/index.json"
echo "publish_web: wrote $out ($(du -sh "$out" | cut -f1); the page, three/penumbra_emitter.wasm ($(stat -c %s "$wasm") bytes), scenes: $scenes; the three.js example at three/example/)"
