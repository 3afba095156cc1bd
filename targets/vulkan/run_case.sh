#!/bin/sh
# run_case.sh EXPORT_BUNDLE VULKAN_RUN DIR [penumbra-export-bundle flags] [-- penumbra-vulkan-run flags]:
# writes the bundle of one configuration into DIR, then runs and checks it on Vulkan (exit 77 when
# there is no Vulkan device).
set -e
export_bundle=$1 vulkan_run=$2 dir=$3
shift 3
# The export flags end at "--"; what follows goes to the runner.
count=0
for arg in "$@"; do
    [ "$arg" = "--" ] && break
    count=$((count + 1))
done
export_args=""
i=0
for arg in "$@"; do
    [ $i -ge $count ] && break
    export_args="$export_args '$(printf '%s' "$arg" | sed "s/'/'\\\\''/g")'"
    i=$((i + 1))
done
shift $count
[ $# -gt 0 ] && shift # the "--"
eval "\"\$export_bundle\" --out \"\$dir\" $export_args"
exec "$vulkan_run" --bundle "$dir" --min-penumbra 40 --out "$dir/visibility_vulkan.f32" "$@"
