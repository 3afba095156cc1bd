#!/usr/bin/env bash
# scripts/emission_snapshot.sh DIR — every configuration of the glslang matrix tests, emitted by
# penumbra-gen into DIR: one folder of shader files and layout.json per valid configuration, and
# one NAME.rejected file (exit status and error message) per configuration penumbra-gen refuses.
#
# Run it before and after a change that must not alter the emitted text, then compare:
#   scripts/emission_snapshot.sh /tmp/before   # on the old tree
#   scripts/emission_snapshot.sh /tmp/after    # on the new tree
#   diff -r /tmp/before /tmp/after && find /tmp/before -type f | wc -l
#
# The matrix is that of tests/matrix_test.cpp's rows and tests/matrix_snippet_test.cpp (keep them in step):
#   occlusion/   filter x fusion x packing x target x light x slices {1,4,5,8,16,32}
#                x resolution {32,256,2048}, and the same with --no-fade (the generic program's row;
#                penumbra-gen does not emit the generic program itself)
#   tangent_clip/, slices_64_128/, adaptive/   the other occlusion rows
#   shadow_map/, erosion/, evsm/, smrt/, oim/    the rows of those techniques (all but oim for wgsl too)
#   alpha_test/  the cut-out casters' row (every technique with --alpha-test)
#   snippet/     matrix_snippet_test.cpp
# Not covered: the generic reference program (penumbra::emit_generic), which penumbra-gen cannot
# write. --no-rotation turns off both pcf.rotate and pcss.rotate (the tests turn off only the
# technique's own), so layout.json's config differs there from the test's Config; the shaders do not.
#
# Environment: GEN (default build/generator/penumbra-gen), JOBS (parallel runs, default nproc).
set -euo pipefail

if [[ $# -ne 1 ]]; then
    echo "usage: $0 DIR   (DIR must not exist yet)" >&2
    exit 2
fi
DIR=$1
GEN=${GEN:-build/generator/penumbra-gen}
JOBS=${JOBS:-$(nproc)}
[[ -x "$GEN" ]] || { echo "error: $GEN not found; build it first (cmake --build build)" >&2; exit 2; }
[[ ! -e "$DIR" ]] || { echo "error: $DIR exists; give a new directory" >&2; exit 2; }
GEN=$(realpath "$GEN")
mkdir -p "$DIR"
DIR=$(realpath "$DIR")

filters=(mipmap nbuffer sat gaussian)
fusions=(probabilistic additive maximum average chained correlated extent clustered)
packings=(atlas array volume)
targets=(glsl330 glsl450 essl300 vulkan)
lights=(rect sun)

# One line per configuration: its name (a path under DIR), then its penumbra-gen flags.
list_configurations() {
    local f u p t l s r n k bf fade switches leak clip b cut i=0
    for f in "${filters[@]}"; do for u in "${fusions[@]}"; do for p in "${packings[@]}"; do
        for t in "${targets[@]}"; do for l in "${lights[@]}"; do for fade in on off; do
            for s in 1 4 5 8 16 32; do for r in 32 256 2048; do
                echo "occlusion/$f-$u-$p-$t-$l-fade_$fade-S$s-R$r --slices $s --resolution $r --filter $f" \
                     "--fusion $u --packing $p --target $t --light $l $([[ $fade == off ]] && echo --no-fade)"
            done; done
        done; done; done
    done; done; done
    for f in "${filters[@]}"; do for p in "${packings[@]}"; do for t in "${targets[@]}"; do for l in "${lights[@]}"; do
        for s in 5 6 7 16; do # as in matrix_test.cpp: 5 correlated, 6 extent, 7 clustered, 16 chained
            u=chained; if ((s == 5)); then u=correlated; fi; if ((s == 6)); then u=extent; fi; if ((s == 7)); then u=clustered; fi
            echo "tangent_clip/$f-$p-$t-$l-S$s --slices $s --resolution 256 --filter $f --fusion $u" \
                 "--packing $p --target $t --light $l --tangent-clip"
        done
        for s in 64 128; do # the fusion, leak fix and tangent clip rotate as in matrix_test.cpp
            leak=""; clip=--no-tangent-clip
            if ((i % 3 == 0)); then leak=--no-leak-fix; fi
            if ((i % 2 == 0)); then clip=--tangent-clip; fi
            echo "slices_64_128/$f-$p-$t-$l-S$s --slices $s --resolution 32 --filter $f" \
                 "--fusion ${fusions[$((i % ${#fusions[@]}))]} --packing $p --target $t --light $l $leak $clip"
            i=$((i + 1))
        done
        for switches in 0 1; do
            if ((switches)); then b="--slices 16 --fusion chained --no-fade --tangent-clip"
            else b="--slices 1 --fusion probabilistic --no-tangent-clip"; fi
            echo "adaptive/$f-$p-$t-$l-switches_$switches --resolution 256 --filter $f --packing $p" \
                 "--target $t --light $l --slice-placement adaptive $b"
        done
    done; done; done; done
    for t in "${targets[@]}" wgsl; do for l in "${lights[@]}"; do # the techniques that write WGSL too
        local base="--target $t --light $l"
        echo "shadow_map/$t-$l-shadowmap --technique shadowmap $base"
        echo "shadow_map/$t-$l-shadowmap_unbiased --technique shadowmap $base --shadow-resolution 32" \
             "--shadow-bias 0 --shadow-slope-bias 0"
        for n in 1 4 16; do
            echo "shadow_map/$t-$l-pcf_grid$n --technique pcf $base --pcf-pattern grid --pcf-grid $n" \
                 "$([[ $n != 4 ]] && echo --no-rotation)"
        done
        for k in 1 16 64; do
            echo "shadow_map/$t-$l-pcf_poisson$k --technique pcf $base --pcf-pattern poisson --pcf-taps $k" \
                 "$([[ $k == 1 ]] && echo --no-rotation)"
        done
        for bf in 8:8 16:16 17:34 32:32 32:64 1:1 64:128; do
            echo "shadow_map/$t-$l-pcss${bf/:/_} --technique pcss $base --pcss-blockers ${bf%:*}" \
                 "--pcss-filter ${bf#*:} $([[ ${bf%:*} == 1 ]] && echo --no-rotation)"
        done
        echo "erosion/$t-$l-default --technique erosion $base"
        echo "erosion/$t-$l-smallest --technique erosion $base --erosion-radius 1 --erosion-search-taps 1" \
             "--erosion-blur-taps 1"
        echo "erosion/$t-$l-largest --technique erosion $base --erosion-radius 256 --erosion-edge-threshold 4" \
             "--erosion-search-taps 64 --erosion-blur-taps 64"
        echo "evsm/$t-$l-default --technique evsm $base"
        echo "evsm/$t-$l-smallest --technique evsm $base --shadow-resolution 32 --evsm-bleeding 0" \
             "--evsm-variance-bias 0 --evsm-blur-taps 1 --evsm-max-blur 1"
        echo "evsm/$t-$l-largest --technique evsm $base --evsm-positive-exponent 42 --evsm-negative-exponent 42" \
             "--evsm-bleeding 0.9 --evsm-variance-bias 0.01 --evsm-blur-fraction 1 --evsm-blur-taps 64 --evsm-max-blur 64"
        echo "smrt/$t-$l-default --technique smrt $base"
        echo "smrt/$t-$l-smallest --technique smrt $base --shadow-resolution 32 --smrt-rays 1 --smrt-samples 2" \
             "--smrt-extrapolate-slope 0 --smrt-max-slope-bias 0 --smrt-texel-dither 0"
        echo "smrt/$t-$l-largest --technique smrt $base --smrt-rays 16 --smrt-samples 32 --smrt-extrapolate-slope 50" \
             "--smrt-max-slope-bias 1000 --smrt-texel-dither 8 --smrt-frame 1023"
    done; done
    for t in "${targets[@]}"; do for n in 4 8 12 16; do for r in 32 256 2048; do
        echo "oim/$t-I$n-R$r --technique oim --target $t --oim-intervals $n --oim-resolution $r"
    done; done; done
    for t in "${targets[@]}"; do for l in "${lights[@]}"; do # matrix_test.cpp's alpha_test_row
        local cut="--alpha-test --target $t --light $l"
        echo "alpha_test/$t-$l-R256 --resolution 256 $cut"
        f=sat; [[ $t == essl300 ]] && f=mipmap
        echo "alpha_test/$t-$l-${f}_array --slices 5 --resolution 64 --filter $f --packing array $cut"
        echo "alpha_test/$t-$l-adaptive --slices 16 --resolution 256 --slice-placement adaptive $cut"
        [[ $t != essl300 ]] && echo "alpha_test/$t-$l-S64 --slices 64 --resolution 32 $cut"
        for k in shadowmap pcf pcss erosion evsm smrt oim; do echo "alpha_test/$t-$l-$k --technique $k $cut"; done
    done; done
    for f in "${filters[@]}"; do for p in "${packings[@]}"; do for l in "${lights[@]}"; do
        echo "snippet/$f-$p-$l --slices 6 --resolution 64 --filter $f --packing $p --light $l --target essl300"
    done; done; done
    for l in "${lights[@]}"; do
        echo "snippet/evsm-$l --technique evsm --light $l --target essl300 --shadow-resolution 256"
    done
}

# Emits configuration NAME (flags after it) into DIR/NAME, or writes DIR/NAME.rejected.
emit_one() {
    local name=$1; shift
    local args=("$@")
    mkdir -p "$(dirname "$DIR/$name")"
    local status=0
    "$GEN" "${args[@]}" --out "$DIR/$name" >/dev/null 2>"$DIR/$name.stderr" || status=$?
    if ((status == 0)); then
        rm -f "$DIR/$name.stderr"
    elif ((status == 2)); then # refused: keep the message, so that validation is compared too
        { echo "exit $status"; cat "$DIR/$name.stderr"; } >"$DIR/$name.rejected"
        rm -f "$DIR/$name.stderr"
    else
        echo "error: penumbra-gen exited $status for $name: $(cat "$DIR/$name.stderr")" >&2
        return 255 # stops xargs
    fi
}
export -f emit_one
export GEN DIR

list=$(mktemp)
trap 'rm -f "$list"' EXIT
# No trailing blanks: xargs -L would join such a line with the next one.
list_configurations | sed 's/[[:space:]]*$//' >"$list"
count=$(wc -l <"$list")
xargs -P "$JOBS" -L 1 bash -c 'emit_one "$@"' _ <"$list"
valid=$(find "$DIR" -name layout.json | wc -l)
rejected=$(find "$DIR" -name '*.rejected' | wc -l)
files=$(find "$DIR" -type f | wc -l)
echo "emission snapshot in $DIR: $count configurations, $valid emitted, $rejected rejected, $files files"
if ((valid + rejected != count)); then
    echo "error: $((count - valid - rejected)) configurations left no result" >&2
    exit 1
fi
