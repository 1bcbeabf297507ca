#!/usr/bin/env bash
# Installs every Debian 12 package Bounce needs, idempotently: only missing packages are
# fetched, so a second run costs one dpkg query. Both README commands call this first.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake ninja-build pkg-config ccache git
  # Vulkan: loader + headers, lavapipe (software device), validation layers, shader compiler
  libvulkan-dev vulkan-validationlayers mesa-vulkan-drivers vulkan-tools glslang-tools spirv-tools
  # windowing, math, UI
  libglfw3-dev libglm-dev libimgui-dev xvfb xauth
  # content: glTF, Draco, OpenSubdiv, meshoptimizer, images
  libtinygltf-dev libdraco-dev libosd-dev libmeshoptimizer-dev libstb-dev nlohmann-json3-dev
  # ray casting, threads
  libembree-dev libtbb-dev
  # tests, fuzzing, plots
  libgtest-dev libgmock-dev clang libclang-rt-14-dev python3-matplotlib python3-numpy python3-pil
)

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi
echo "deps: installing ${#missing[@]} missing packages: ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "deps: done"
