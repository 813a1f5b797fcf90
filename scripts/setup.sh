#!/usr/bin/env bash
# Installs the Debian packages gbufferlab needs (only the missing ones: quiet and fast when all
# are present), then configures and builds it.
# Usage: scripts/setup.sh [--tests | --sanitize] [--target T]... [build-dir [extra cmake args...]]
#   default:    what building and running `gbufferlab` needs; Release; only the gbufferlab target;
#   --tests:    also what the tests and benchmarks need (GoogleTest, Google Benchmark, Vulkan's
#               validation layers, test models, Chromium for the report's browser test, Node and
#               the pinned glTF Sample Viewer for tools/gltf-viewer); all targets;
#   --sanitize: the sanitizer build (default folder build-asan): clang at -O1 with line tables,
#               ASan + UBSan, the unit tests only, and the libFuzzer targets (tests/fuzz/fuzz.cmake);
#   --target T: build T (repeatable) instead of the mode's default targets.
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/packages.sh

mode=run
case "${1:-}" in
  --tests) mode=tests; shift ;;
  --sanitize) mode=sanitize; shift ;;
esac
targets=()
while [ "${1:-}" = --target ]; do targets+=(--target "$2"); shift 2; done

packages=(
  cmake g++ make pkg-config zlib1g-dev
  mesa-vulkan-drivers libvulkan-dev
  glslang-dev glslang-tools spirv-tools libglm-dev libtinygltf-dev libopenexr-dev
  libtomlplusplus-dev libstb-dev nlohmann-json3-dev
)
if [ "$mode" != run ]; then
  packages+=(
    vulkan-validationlayers libbenchmark-dev libgtest-dev
    assimp-testmodels blender-data
    chromium
  )
fi
# Node and npm for tools/gltf-viewer (the Khronos glTF Sample Viewer, the cross-check's independent
# renderer): Debian's nodejs and npm; npm only when no npm command exists, since NodeSource's nodejs
# package bundles its own npm and Debian's npm package would clash with its files.
if [ "$mode" = tests ]; then
  packages+=(nodejs)
  command -v npm >/dev/null || packages+=(npm)
fi
[ "$mode" = sanitize ] && packages+=(clang libclang-rt-14-dev)
install_missing "${packages[@]}"
# The Sample Viewer's npm package at the version package-lock.json pins (integrity hash included),
# installed only when absent or of another version: quiet and fast when present.
if [ "$mode" = tests ]; then
  viewer_dir=tools/gltf-viewer
  want_viewer=$(node -p "require('./$viewer_dir/package.json').dependencies['@khronosgroup/gltf-viewer']")
  have_viewer=$(node -p "require('./$viewer_dir/node_modules/@khronosgroup/gltf-viewer/package.json').version" 2>/dev/null || true)
  if [ "$have_viewer" != "$want_viewer" ]; then
    echo "${0##*/}: installing @khronosgroup/gltf-viewer $want_viewer into $viewer_dir"
    npm ci --prefix "$viewer_dir" --no-audit --no-fund --loglevel=error >/dev/null
  fi
fi

default_dir=build
[ "$mode" = sanitize ] && default_dir=build-asan
build_dir="${1:-$default_dir}"
shift || true
config=(-DCMAKE_BUILD_TYPE=Release)
case "$mode" in
  run) config+=(-DGBL_BUILD_TESTS=OFF -DGBL_BUILD_BENCH=OFF) ;;
  tests) config+=(-DGBL_BUILD_TESTS=ON -DGBL_BUILD_BENCH=ON) ;;
  # The Sanitize build type is -O1 -g1 (CMakeLists.txt): the reports still name file:line, and it
  # compiles in a fraction of RelWithDebInfo's time.
  sanitize) config=(-DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++
                    -DGBL_SANITIZE=ON -DGBL_BUILD_TESTS=ON -DGBL_BUILD_BENCH=OFF -DGBL_TEST_LABELS=unit) ;;
esac
# scripts/run.sh and scripts/test.sh share the folder build: each states the options it needs, so
# a folder configured by one is reconfigured (seconds, no rebuild of what exists) by the other.
want="GBL_BUILD_TESTS:BOOL=$([ "$mode" = run ] && echo OFF || echo ON)"
if [ ! -f "$build_dir/CMakeCache.txt" ] || ! grep -qx "$want" "$build_dir/CMakeCache.txt" || (($#)) ||
   [ "$mode" = sanitize ]; then
  cmake -S . -B "$build_dir" "${config[@]}" "$@" >/dev/null
fi
if ((${#targets[@]} == 0)) && [ "$mode" = run ]; then targets=(--target gbufferlab); fi
mkdir -p "$build_dir"
cmake --build "$build_dir" -j"$(nproc)" "${targets[@]}" >"$build_dir/build.log" 2>&1 || { cat "$build_dir/build.log"; exit 1; }
