#!/usr/bin/env bash
# Installs the Debian packages gbufferlab needs (only the missing ones: quiet and fast when all
# are present), then configures and builds it in Release.
# Usage: scripts/setup.sh [build-dir [extra cmake args...]]
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  cmake g++ make pkg-config zlib1g-dev
  mesa-vulkan-drivers libvulkan-dev vulkan-validationlayers
  glslang-dev glslang-tools spirv-tools libglm-dev libtinygltf-dev libopenexr-dev
  libbenchmark-dev libgtest-dev
  libtomlplusplus-dev libstb-dev nlohmann-json3-dev
  assimp-testmodels blender-data
  chromium
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" = 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build_dir="${1:-build}"
shift || true
if [ ! -f "$build_dir/CMakeCache.txt" ]; then
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
fi
cmake --build "$build_dir" -j"$(nproc)" >"$build_dir/build.log" 2>&1 || { cat "$build_dir/build.log"; exit 1; }
