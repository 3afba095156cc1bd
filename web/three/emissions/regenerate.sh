#!/bin/sh
# Regenerates the emissions shipped with the three.js add-on (penumbra_shadows.js's EMISSIONS): essl300
# for WebGLRenderer, and "<name>-wgsl" (the same configuration in WGSL) for WebGPURenderer:
#   web/three/emissions/regenerate.sh [PATH/TO/penumbra-gen]     (default build/generator/penumbra-gen)
# With --check DIR it writes them into DIR instead, for the test that compares them with these.
# "<name>-cut" (and "<name>-cut-wgsl"): the same configuration with --alpha-test, which load() takes
# instead of "<name>" when the scene's casters cut (materials with a map and alphaTest or transparent).
set -eu
here="$(cd "$(dirname "$0")" && pwd)"
out="$here"
if [ "${1:-}" = "--check" ]; then out="$2"; shift 2; fi
gen="${1:-$here/../../../build/generator/penumbra-gen}"
emit() { name="$1"; shift; "$gen" --target essl300 "$@" --out "$out/$name" >/dev/null; }
emit_wgsl() { name="$1-wgsl"; shift; "$gen" --target wgsl "$@" --out "$out/$name" >/dev/null; }
emit rect-nbuffer-16x512 --light rect --filter nbuffer --slices 16 --resolution 512
emit rect-mipmap-16x512  --light rect --filter mipmap  --slices 16 --resolution 512
emit rect-nbuffer-16x256 --light rect --filter nbuffer --slices 16 --resolution 256
emit rect-nbuffer-8x256   --light rect --filter nbuffer --slices 8 --resolution 256
emit sun-nbuffer-16x512  --light sun  --filter nbuffer --slices 16 --resolution 512
emit sun-mipmap-16x512   --light sun  --filter mipmap  --slices 16 --resolution 512
emit rect-nbuffer-16x512-cut --light rect --filter nbuffer --slices 16 --resolution 512 --alpha-test
emit sun-nbuffer-16x512-cut  --light sun  --filter nbuffer --slices 16 --resolution 512 --alpha-test
emit_wgsl rect-nbuffer-16x512 --light rect --filter nbuffer --slices 16 --resolution 512
emit_wgsl rect-mipmap-16x512  --light rect --filter mipmap  --slices 16 --resolution 512
emit_wgsl rect-nbuffer-16x256 --light rect --filter nbuffer --slices 16 --resolution 256
emit_wgsl rect-nbuffer-8x256  --light rect --filter nbuffer --slices 8 --resolution 256
emit_wgsl sun-nbuffer-16x512  --light sun  --filter nbuffer --slices 16 --resolution 512
emit_wgsl sun-mipmap-16x512   --light sun  --filter mipmap  --slices 16 --resolution 512
emit_wgsl rect-nbuffer-16x512-cut --light rect --filter nbuffer --slices 16 --resolution 512 --alpha-test
emit_wgsl sun-nbuffer-16x512-cut  --light sun  --filter nbuffer --slices 16 --resolution 512 --alpha-test
