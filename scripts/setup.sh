#!/usr/bin/env bash
# Installs Penumbra's build and test dependencies from Debian (the platform notes say what each
# is for; clang-16 and the wasm32 libraries build the WebAssembly emitter, wasm/) and
# the browser tests' npm packages (into targets/web/node_modules: puppeteer-core, and vite,
# typescript, @types/three and three r180/r187 for the npm package test, the bundlers and Babylon.js). Idempotent:
# does nothing when every package is installed and node_modules matches package-lock.json.
set -euo pipefail

packages=(
    cmake g++ make pkg-config
    libglm-dev glslang-dev glslang-tools spirv-tools spirv-cross libspirv-cross-c-shared-dev doctest-dev nlohmann-json3-dev
    libglfw3-dev libepoxy-dev libgl1-mesa-dri libegl1-mesa-dev mesa-utils xvfb xauth
    libimgui-dev libstb-dev libtinyobjloader-dev libtinygltf-dev libembree-dev
    libdraco-dev libmeshoptimizer-dev gltfpack
    assimp-testmodels
    libvulkan-dev libvulkan-volk-dev mesa-vulkan-drivers vulkan-validationlayers
    python3 python3-jsonschema python3-matplotlib
    chromium
    clang-format clang-tidy
    clang-16 lld-16 libc++-16-dev-wasm32 libc++abi-16-dev-wasm32 libclang-rt-16-dev-wasm32 wasi-libc
)
# The browser test drives chromium from Node (puppeteer-core); Debian's node where none is installed.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then packages+=(nodejs npm); fi

missing=()
for package in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -eq 0 ]; then
    echo "setup: all ${#packages[@]} packages installed"
else
    sudo=""
    if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
    echo "setup: installing ${missing[*]}"
    $sudo apt-get update -q
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# puppeteer-core (never `puppeteer`, which downloads a browser), vite, typescript, @types/three and
# three r180/r187 (three-package installs the add-on's tarball into a fresh project offline beside
# them), esbuild, webpack, rollup with @rollup/plugin-node-resolve, @babylonjs/core, and react,
# react-dom and @react-three/fiber (the bundler-* tests), pinned by package-lock.json.
web="$(cd "$(dirname "$0")/.." && pwd)/targets/web"
if [ ! -f "$web/node_modules/.package-lock.json" ] || [ "$web/package-lock.json" -nt "$web/node_modules/.package-lock.json" ]; then
    echo "setup: npm ci in targets/web"
    npm ci --prefix "$web" --no-audit --no-fund --loglevel=error
fi
# three (the three.js add-on's peer dependency, for its example and tests), pinned by web/three/package-lock.json.
three="$(cd "$(dirname "$0")/.." && pwd)/web/three"
if [ ! -f "$three/node_modules/.package-lock.json" ] || [ "$three/package-lock.json" -nt "$three/node_modules/.package-lock.json" ]; then
    echo "setup: npm ci in web/three"
    npm ci --prefix "$three" --no-audit --no-fund --loglevel=error
fi
# @babylonjs/core (the Babylon.js add-on's peer dependency, for its example), pinned by
# web/babylon/package-lock.json; its "prepare" copies the modules shared with web/three into web/babylon/shared/.
babylon="$(cd "$(dirname "$0")/.." && pwd)/web/babylon"
if [ ! -f "$babylon/node_modules/.package-lock.json" ] || [ "$babylon/package-lock.json" -nt "$babylon/node_modules/.package-lock.json" ]; then
    echo "setup: npm ci in web/babylon"
    npm ci --prefix "$babylon" --no-audit --no-fund --loglevel=error
fi
