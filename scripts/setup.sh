#!/usr/bin/env bash
# Installs the Debian packages gbufferlab needs (only the missing ones: quiet and fast when all
# are present), then configures and builds it in Release.
# Usage: scripts/setup.sh [--tests] [build-dir [extra cmake args...]]
#   default: what building and running `gbufferlab` needs, and only the gbufferlab target;
#   --tests: also what the tests and benchmarks need (GoogleTest, Google Benchmark, Vulkan's
#            validation layers, test models, Chromium for the report's browser test), and all targets.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/packages.sh

with_tests=0
if [ "${1:-}" = "--tests" ]; then with_tests=1; shift; fi

packages=(
  cmake g++ make pkg-config zlib1g-dev
  mesa-vulkan-drivers libvulkan-dev
  glslang-dev glslang-tools spirv-tools libglm-dev libtinygltf-dev libopenexr-dev
  libtomlplusplus-dev libstb-dev nlohmann-json3-dev
)
if ((with_tests)); then
  packages+=(
    vulkan-validationlayers libbenchmark-dev libgtest-dev
    assimp-testmodels blender-data
    chromium
  )
fi

install_missing "${packages[@]}"

build_dir="${1:-build}"
shift || true
# Both scripts share one build folder: each states the options it needs, so a folder configured by
# one is reconfigured (seconds, no rebuild of what exists) by the other.
onoff=$( ((with_tests)) && echo ON || echo OFF )
want="GBL_BUILD_TESTS:BOOL=$onoff"
if [ ! -f "$build_dir/CMakeCache.txt" ] || ! grep -qx "$want" "$build_dir/CMakeCache.txt" || (($#)); then
  cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DGBL_BUILD_TESTS="$onoff" -DGBL_BUILD_BENCH="$onoff" "$@" >/dev/null
fi
targets=()
((with_tests)) || targets=(--target gbufferlab)
mkdir -p "$build_dir"
cmake --build "$build_dir" -j"$(nproc)" "${targets[@]}" >"$build_dir/build.log" 2>&1 || { cat "$build_dir/build.log"; exit 1; }
