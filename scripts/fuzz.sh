#!/usr/bin/env bash
# Fuzzes the layout parser and the glTF loader with libFuzzer (Debian's clang 14; ASan + UBSan).
# Installs what it needs (only the missing Debian packages), builds the two targets in
# build-fuzz/ straight from the sources they use (no full clang build of the project), seeds the
# corpora from layouts/ and the glTF test models, then runs each target.
# Usage: scripts/fuzz.sh [seconds per target (default 600)] [extra libFuzzer flags...]
#        scripts/fuzz.sh ci   # the short deterministic slice: the seeds plus 2000 fixed-seed runs
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(clang libclang-rt-14-dev libtinygltf-dev libtomlplusplus-dev nlohmann-json3-dev libglm-dev libstb-dev
          assimp-testmodels)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "fuzz: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" = 0 ] || sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

mode="${1:-600}"
shift || true
extra=("$@")
out=build-fuzz
mkdir -p "$out"
flags=(-std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize=vptr -ffp-contract=off
       -Ishaders -DGLM_FORCE_DEPTH_ZERO_TO_ONE -DGLM_FORCE_RADIANS
       -DGBL_SOURCE_SHADER_DIR="\"$PWD/shaders\"" -DGBL_SOURCE_LAYOUT_DIR="\"$PWD/layouts\"")
for folder in base encoding layout scene; do flags+=("-Isrc/$folder"); done
base=(src/base/error.cpp src/base/file_io.cpp src/base/interrupt.cpp)
layout_sources=(src/layout/layout.cpp src/layout/layout_parser.cpp src/layout/layout_parse_fields.cpp
                src/layout/layout_parse_fallbacks.cpp src/layout/layout_validate.cpp src/encoding/encoding_registry.cpp)
scene_sources=(src/scene/scene.cpp src/scene/gltf_loader.cpp src/scene/tangents.cpp src/scene/camera.cpp
               src/scene/scene_normals.cpp src/scene/scene_gltf_accessor.cpp src/scene/scene_gltf_geometry.cpp
               src/scene/scene_gltf_textures.cpp src/scene/scene_gltf_materials.cpp src/scene/scene_gltf_nodes.cpp
               src/scene/scene_gltf_camera_lights.cpp src/scene/scene_shapes.cpp src/scene/scene_gltf_files.cpp
               src/scene/scene_gltf_json_check.cpp)
build() {  # build NAME SOURCES...
  local name=$1
  shift
  [ "$out/$name" -nt "tests/fuzz/$name.cpp" ] && [ -z "$(find src -newer "$out/$name" -name '*.cpp' -o -newer "$out/$name" -name '*.h' | head -1)" ] && return
  echo "fuzz: building $out/$name"
  clang++ "${flags[@]}" "tests/fuzz/$name.cpp" "$@" -o "$out/$name" -ltinygltf -lpthread
}
build fuzz_layout_parser "${base[@]}" "${layout_sources[@]}"
build fuzz_gltf_loader "${base[@]}" "${scene_sources[@]}"

# Seeds: every shipped layout; every .gltf/.glb test model up to 1 MB.
mkdir -p "$out/corpus-layout" "$out/corpus-gltf"
cp layouts/*.toml "$out/corpus-layout/"
find /usr/share/assimp/models/glTF2 ../shared/assets -size -1024k \( -name '*.gltf' -o -name '*.glb' \) 2>/dev/null |
  while read -r f; do cp "$f" "$out/corpus-gltf/$(echo "$f" | md5sum | cut -c1-16).${f##*.}"; done

export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
run() {  # run NAME CORPUS
  local name=$1 corpus=$2
  mkdir -p "$out/findings-$name"
  if [ "$mode" = ci ]; then
    # Deterministic: a fixed seed, a fixed number of runs, the seed corpus only (not written to).
    "$out/$name" -seed=13 -runs=2000 -max_len=65536 -timeout=20 -artifact_prefix="$out/findings-$name/" \
      "$corpus" "${extra[@]}" 2>&1 | tail -3
  else
    nice "$out/$name" -max_total_time="$mode" -max_len=65536 -timeout=20 -print_final_stats=1 \
      -artifact_prefix="$out/findings-$name/" "$corpus" "${extra[@]}" 2>&1 | tail -25
  fi
}
run fuzz_layout_parser "$out/corpus-layout"
run fuzz_gltf_loader "$out/corpus-gltf"
echo "fuzz: findings: $(find "$out"/findings-* -type f | wc -l) (in $out/findings-*)"
