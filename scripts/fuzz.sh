#!/usr/bin/env bash
# Fuzzes the layout parser and the glTF loader with libFuzzer (Debian's clang 14; ASan + UBSan).
# The two targets are built in the sanitizer build (build-asan, scripts/setup.sh --sanitize), whose
# libraries carry libFuzzer's coverage counters (tests/fuzz/fuzz.cmake): after
# scripts/test-sanitizers.sh only the two targets are left to link. The corpora are seeded from
# layouts/ and the glTF test models, then each target runs; corpora, logs and findings live in
# build-fuzz/.
# Usage: scripts/fuzz.sh [seconds per target (default 600)] [extra libFuzzer flags...]
#        scripts/fuzz.sh ci   # the short deterministic slice (CI): the seeds plus a fixed number of
#                             # fixed-seed runs per target, about a minute
# Exits non-zero when a target finds a crash, a hang, a leak or a sanitizer report (its input is
# written to build-fuzz/findings-TARGET/).
set -euo pipefail
cd "$(dirname "$0")/.."

mode="${1:-600}"
shift || true
extra=("$@")
out=build-fuzz
mkdir -p "$out"
scripts/setup.sh --sanitize --target fuzz_layout_parser --target fuzz_gltf_loader build-asan
bin=build-asan/fuzz

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
    "$bin/$name" -seed=13 -runs="$runs" -max_len=65536 -timeout=20 -print_final_stats=1 \
      -artifact_prefix="$out/findings-$name/" "$corpus" "${extra[@]}" >"$out/$name.log" 2>&1 || rc=$?
    tail -8 "$out/$name.log"
  else
    nice "$bin/$name" -max_total_time="$mode" -max_len=65536 -timeout=20 -print_final_stats=1 \
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
