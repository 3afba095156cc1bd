#!/usr/bin/env bash
# Compile cost of a translation unit that includes the core and calls emit(), at -O2 (docs/getting-started.md,
# "Compile cost"): header-only, then with PENUMBRA_SEPARATE_IMPLEMENTATION (the caller only declares
# emit(); the emitter is compiled once, in the PENUMBRA_IMPLEMENTATION file). Prints wall and CPU
# seconds and peak memory of each compile, and the load average (numbers on a busy machine grow).
#   scripts/compile_cost.sh [-O0|-O2|...]      (CXX: the compiler, default c++; no ccache)
set -euo pipefail
cd "$(dirname "$0")/.."
opt="${1:--O2}"
cxx="${CXX:-c++}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
measure() { # label, then the compiler arguments
    local label="$1"; shift
    /usr/bin/time -f "%e %U %S %M" -o "$out/time" "$cxx" -std=c++20 "$opt" -Iinclude -c "$@" -o "$out/o.o"
    awk -v label="$label" '{ printf "%-50s %6.2f s wall %6.2f s cpu %5d MB\n", label, $1, $2 + $3, $4 / 1024 }' "$out/time"
}
echo "$($cxx --version | head -1), $opt, load average $(cut -d' ' -f1-3 /proc/loadavg)"
measure "emit() caller, header-only" tests/consumer/main.cpp
measure "emit() caller, PENUMBRA_SEPARATE_IMPLEMENTATION" -DPENUMBRA_SEPARATE_IMPLEMENTATION tests/consumer/main.cpp
measure "the PENUMBRA_IMPLEMENTATION file (once)" -DPENUMBRA_SEPARATE_IMPLEMENTATION tests/consumer/implementation.cpp
