#!/usr/bin/env bash
# Installs Penumbra's build and test dependencies from Debian (the platform notes say what each
# is for). Idempotent: does nothing when every package is already installed.
set -euo pipefail

packages=(
    cmake g++ make pkg-config
    libglm-dev glslang-dev glslang-tools spirv-tools doctest-dev nlohmann-json3-dev
    libglfw3-dev libepoxy-dev libgl1-mesa-dri libegl1-mesa-dev mesa-utils xvfb xauth
    libimgui-dev libstb-dev libtinyobjloader-dev libembree-dev
    python3-matplotlib
)

missing=()
for package in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ ${#missing[@]} -eq 0 ]; then
    echo "setup: all ${#packages[@]} packages installed"
    exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "setup: installing ${missing[*]}"
$sudo apt-get update -q
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
