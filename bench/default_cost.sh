#!/usr/bin/env bash
# The default comparison's wall time, one binary against another, alternated in one run of this
# script so that a loaded machine weighs on both alike: `A compare --out DIR` and `B compare --out
# DIR`, each with its own defaults (no other flag), ROUNDS times (default 2), after one untimed
# run of each that fills the caches (SPIR-V, pipelines, IBL maps, texture mips), as the warm
# figures elsewhere in bench/RESULTS.md. Prints each run's wall time and peak memory, the medians
# and B / A; state the machine's load beside them (`uptime` is printed before and after).
# GBL_BENCH_COLD=1: every run on fresh caches instead (what a fresh clone's first run sees): an
# empty GBL_CACHE_DIR (SPIR-V, pipeline, IBL and texture-mip caches) and Mesa's disk cache off
# (MESA_SHADER_CACHE_DISABLE=true); no untimed run.
#
# usage: bench/default_cost.sh A_BINARY B_BINARY [ROUNDS]
#   e.g. the default before and after a change: a binary built at the old commit, then build/gbufferlab
# environment: GBL_BENCH_OUT (default out/bench-default; replaced), GBL_BENCH_WARM=0 (no untimed run),
#              GBL_BENCH_COLD=1 (fresh caches, above), GBL_BENCH_A_ARGS / GBL_BENCH_B_ARGS (more compare
#              flags for A / B, e.g. "--size 320x180" to try another default before changing it)
set -euo pipefail
cd "$(dirname "$0")/.."
a=${1:?usage: bench/default_cost.sh A_BINARY B_BINARY [ROUNDS]}
b=${2:?usage: bench/default_cost.sh A_BINARY B_BINARY [ROUNDS]}
rounds=${3:-2}
out=${GBL_BENCH_OUT:-out/bench-default}
rm -rf "$out"
mkdir -p "$out"
cold=${GBL_BENCH_COLD:-0}
run() {  # name, binary, round
    local name=$1 bin=$2 round=$3
    local extra=()
    [ "$name" = A ] && read -r -a extra <<<"${GBL_BENCH_A_ARGS:-}"
    [ "$name" = B ] && read -r -a extra <<<"${GBL_BENCH_B_ARGS:-}"
    local env=()
    if [ "$cold" = 1 ]; then
        rm -rf "$out/cache"
        mkdir -p "$out/cache"
        env=(GBL_CACHE_DIR="$out/cache" MESA_SHADER_CACHE_DISABLE=true)
    fi
    env "${env[@]}" /usr/bin/time -f "%e %M" -o "$out/$name-$round.time" "$bin" compare "${extra[@]}" --out "$out/$name-$round" \
        >"$out/$name-$round.log" 2>&1
    read -r wall kb <"$out/$name-$round.time"
    printf "%-2s round %s: wall %7.1f s  peak %5d MB  (%s)\n" "$name" "$round" "$wall" "$((kb / 1024))" \
        "$(grep -m1 -o '"command_line": "[^"]*"' "$out/$name-$round/report.json" | cut -d'"' -f4)"
    echo "$wall" >>"$out/$name.walls"
    rm -rf "${out:?}/$name-$round"  # the images: hundreds of MB at 1080p
}
echo "default_cost: $(date -u +%FT%TZ), $(git rev-parse --short HEAD), $(nproc) cores, caches $([ "$cold" = 1 ] && echo fresh || echo warm); load: $(uptime | sed 's/.*average: //')"
echo "A: $a"
echo "B: $b"
if [ "${GBL_BENCH_WARM:-1}" != 0 ] && [ "$cold" != 1 ]; then
    read -r -a a_args <<<"${GBL_BENCH_A_ARGS:-}"
    read -r -a b_args <<<"${GBL_BENCH_B_ARGS:-}"
    "$a" compare "${a_args[@]}" --out "$out/warm-a" >/dev/null 2>&1 || true
    "$b" compare "${b_args[@]}" --out "$out/warm-b" >/dev/null 2>&1 || true
    rm -rf "$out/warm-a" "$out/warm-b"
fi
for ((r = 1; r <= rounds; ++r)); do
    if ((r % 2)); then run A "$a" "$r"; run B "$b" "$r"; else run B "$b" "$r"; run A "$a" "$r"; fi
done
echo "load after: $(uptime | sed 's/.*average: //')"
python3 - "$out" <<'PY'
import statistics, sys
out = sys.argv[1]
med = {n: statistics.median(float(x) for x in open(f"{out}/{n}.walls")) for n in "AB"}
print(f"median wall A {med['A']:.1f} s, B {med['B']:.1f} s; B / A = {med['B'] / med['A']:.3f}")
PY
