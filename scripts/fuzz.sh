#!/usr/bin/env bash
# Fuzzes the layout parser and the glTF loader with libFuzzer (Debian's clang 14; ASan + UBSan).
# Installs what it needs (only the missing Debian packages), builds the two targets in
# build-fuzz/ straight from the sources they use (no full clang build of the project), seeds the
# corpora from layouts/ and the glTF test models, then runs each target.
# Usage: scripts/fuzz.sh [seconds per target (default 600)] [extra libFuzzer flags...]
#        scripts/fuzz.sh ci   # the short deterministic slice (CI): the seeds plus a fixed number of
#                             # fixed-seed runs per target, about a minute after a 1-2 minute build
# Exits non-zero when a target finds a crash, a hang, a leak or a sanitizer report (its input is
# written to build-fuzz/findings-TARGET/).
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/packages.sh

packages=(clang libclang-rt-14-dev libtinygltf-dev libtomlplusplus-dev nlohmann-json3-dev libglm-dev libstb-dev
          assimp-testmodels)
install_missing "${packages[@]}"

mode="${1:-600}"
shift || true
extra=("$@")
out=build-fuzz
mkdir -p "$out"
flags=(-std=c++20 -O1 -g1 -fsanitize=fuzzer,address,undefined -fno-sanitize=vptr -ffp-contract=off
       -Ishaders -DGLM_FORCE_DEPTH_ZERO_TO_ONE -DGLM_FORCE_RADIANS
       -DGBL_SOURCE_SHADER_DIR="\"$PWD/shaders\"" -DGBL_SOURCE_LAYOUT_DIR="\"$PWD/layouts\"" $(pkg-config --cflags OpenEXR))
for folder in base encoding image layout scene codec; do flags+=("-Isrc/$folder"); done
# The whole base, layout, encoding and codec libraries (a list by hand missed a file added later
# and broke this build twice): the layout target also runs `layouts export` on what check accepts.
base=(src/base/*.cpp)
layout_sources=(src/layout/*.cpp src/encoding/*.cpp src/codec/*.cpp)
# The glTF loader needs the whole scene library and the image library (it probes every texture's
# dimensions before it decodes one).
scene_sources=(src/image/*.cpp src/scene/*.cpp)
# Each source is compiled once into $out/obj (in parallel; again when it or any header changed) and
# shared by both targets.
object() { local src=${1//\//_}; echo "$out/obj/${src%.cpp}.o"; }
compile() {  # compile SOURCE, in the background
  local src=$1 obj
  obj=$(object "$1")
  if [ "$obj" -nt "$src" ] && [ -z "$(find src shaders tests/fuzz -name '*.h' -newer "$obj" | head -1)" ]; then return; fi
  while (($(jobs -rp | wc -l) >= $(nproc))); do wait -n || failed=1; done
  echo "fuzz: compiling $src"
  clang++ "${flags[@]}" -c "$src" -o "$obj" &
}
link() {  # link NAME SOURCES...
  local name=$1 src objs=() newer=0
  shift
  for src in "$@"; do objs+=("$(object "$src")"); done
  for src in "${objs[@]}"; do [ "$src" -nt "$out/$name" ] && newer=1; done
  ((newer)) || [ ! -e "$out/$name" ] || return 0
  echo "fuzz: linking $out/$name"
  clang++ "${flags[@]}" "${objs[@]}" -o "$out/$name" -ltinygltf $(pkg-config --libs OpenEXR zlib) -lpthread
}
mkdir -p "$out/obj"
failed=0
for src in tests/fuzz/fuzz_layout_parser.cpp tests/fuzz/fuzz_gltf_loader.cpp "${base[@]}" "${layout_sources[@]}" \
           "${scene_sources[@]}"; do
  compile "$src"
done
while (($(jobs -rp | wc -l))); do wait -n || failed=1; done
((failed == 0)) || { echo "fuzz: the build failed" >&2; exit 1; }
link fuzz_layout_parser tests/fuzz/fuzz_layout_parser.cpp "${base[@]}" "${layout_sources[@]}"
link fuzz_gltf_loader tests/fuzz/fuzz_gltf_loader.cpp "${base[@]}" "${scene_sources[@]}"

# Seeds: every shipped layout; every .gltf/.glb test model up to 1 MB. The long runs grow
# corpus-*; the ci slice starts from a fresh copy of the seeds alone each time (libFuzzer adds
# what it finds to its first corpus folder).
seed() {  # seed LAYOUT-DIR GLTF-DIR
  mkdir -p "$1" "$2"
  cp layouts/*.toml "$1/"
  local dirs=() d
  for d in /usr/share/assimp/models/glTF2 ../shared/assets; do [ -d "$d" ] && dirs+=("$d"); done
  ((${#dirs[@]})) || return 0
  find "${dirs[@]}" -size -1024k \( -name '*.gltf' -o -name '*.glb' \) |
    while read -r f; do cp "$f" "$2/$(echo "$f" | md5sum | cut -c1-16).${f##*.}"; done
}
if [ "$mode" = ci ]; then
  rm -rf "$out/ci-corpus-layout" "$out/ci-corpus-gltf"
  seed "$out/ci-corpus-layout" "$out/ci-corpus-gltf"
else
  seed "$out/corpus-layout" "$out/corpus-gltf"
fi

# The glTF target writes its scratch scene under TMPDIR: keep that in build-fuzz, removed after.
export TMPDIR="$PWD/$out/tmp"
mkdir -p "$TMPDIR"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
status=0
stamp="$out/.run-started"
touch "$stamp"
run() {  # run NAME CORPUS CI-RUNS: libFuzzer's exit status is non-zero when it found anything
  local name=$1 corpus=$2 runs=${3:-0} rc=0
  mkdir -p "$out/findings-$name"
  echo "fuzz: $name on $corpus ($(find "$corpus" -type f | wc -l) inputs)"
  if [ "$mode" = ci ]; then
    # Deterministic: a fixed seed, a fixed number of runs, a fresh copy of the seeds.
    "$out/$name" -seed=13 -runs="$runs" -max_len=65536 -timeout=20 -print_final_stats=1 \
      -artifact_prefix="$out/findings-$name/" "$corpus" "${extra[@]}" >"$out/$name.log" 2>&1 || rc=$?
    tail -8 "$out/$name.log"
  else
    nice "$out/$name" -max_total_time="$mode" -max_len=65536 -timeout=20 -print_final_stats=1 \
      -artifact_prefix="$out/findings-$name/" "$corpus" "${extra[@]}" >"$out/$name.log" 2>&1 || rc=$?
    tail -25 "$out/$name.log"
  fi
  echo "fuzz: $name exit status $rc; corpus now $(find "$corpus" -type f | wc -l) inputs; log $out/$name.log"
  ((rc == 0)) || status=1
}
targets=" ${FUZZ_TARGETS:-fuzz_layout_parser fuzz_gltf_loader} "  # FUZZ_TARGETS=fuzz_gltf_loader: that one only
if [ "$mode" = ci ]; then
  [[ "$targets" != *" fuzz_layout_parser "* ]] || run fuzz_layout_parser "$out/ci-corpus-layout" 20000  # ~20 s
  [[ "$targets" != *" fuzz_gltf_loader "* ]] || run fuzz_gltf_loader "$out/ci-corpus-gltf" 5000         # ~20 s
else
  [[ "$targets" != *" fuzz_layout_parser "* ]] || run fuzz_layout_parser "$out/corpus-layout"
  [[ "$targets" != *" fuzz_gltf_loader "* ]] || run fuzz_gltf_loader "$out/corpus-gltf"
fi
rm -rf "$TMPDIR"
new=$(find "$out"/findings-* -type f -newer "$stamp" | wc -l)
echo "fuzz: findings this run: $new (in $out/findings-*)"
((status == 0 && new == 0)) || { echo "fuzz: FAILED: a target found a crash, a hang, a leak or a sanitizer report" >&2; exit 1; }
