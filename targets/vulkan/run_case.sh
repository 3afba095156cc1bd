#!/bin/sh
# run_case.sh EXPORT_BUNDLE VULKAN_RUN DIR [penumbra-export-bundle flags]: writes the bundle of one
# configuration into DIR, then runs and checks it on Vulkan (exit 77 when there is no Vulkan device).
set -e
export_bundle=$1 vulkan_run=$2 dir=$3
shift 3
"$export_bundle" --out "$dir" "$@"
exec "$vulkan_run" --bundle "$dir" --min-penumbra 40 --out "$dir/visibility_vulkan.f32"
