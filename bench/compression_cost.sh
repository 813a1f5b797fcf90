#!/usr/bin/env bash
# The cost of the framebuffer-compression model (docs/bandwidth.md) in a 1080p compare (the built-in scene) of every
# layout: the previous binary (OLD, without the model), this one (NEW) and this one with
# --no-compression (the model off, everything else the same), alternated ROUNDS times in one run
# of this script; wall and CPU time (GNU time), and NEW's host scope "read-back: G-buffer words to
# the compression model" (GBL_HOST_PROFILE=1: the model's own time, the words' download included).
# The goal (issue 44): NEW under 1.10x OLD.
#
# usage: bench/compression_cost.sh OLD_BINARY NEW_BINARY
# environment: GBL_BENCH_LAYOUTS (default all), GBL_BENCH_SIZE (default 1920x1080), GBL_BENCH_VIEWS
#              (default 3), GBL_BENCH_ROUNDS (default 2), GBL_BENCH_OUT (default out/bench-compression; replaced)
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1
new=$2
layouts=${GBL_BENCH_LAYOUTS:-all}
size=${GBL_BENCH_SIZE:-1920x1080}
views=${GBL_BENCH_VIEWS:-3}
rounds=${GBL_BENCH_ROUNDS:-2}
out=${GBL_BENCH_OUT:-out/bench-compression}
rm -rf "$out"
mkdir -p "$out"
echo "compression_cost: $(date -u +%FT%TZ), $(git rev-parse --short HEAD), layouts $layouts, $size, $views views, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq 1 "$rounds"); do
    for kind in old new off; do
        bin=$new
        extra=()
        [ "$kind" = old ] && bin=$old
        [ "$kind" = off ] && extra=(--no-compression)
        GBL_HOST_PROFILE=1 /usr/bin/time -f "%e %U %S %M" -o "$out/$kind$r.time" "$bin" compare --scene builtin --layouts "$layouts" \
            --size "$size" --views "$views" --out "$out/$kind$r" "${extra[@]}" >"$out/$kind$r.log" 2>&1
        echo "$kind round $r: $(cat "$out/$kind$r.time") (wall s, user s, sys s, peak KiB); load $(cut -d' ' -f1-3 /proc/loadavg)"
    done
done
python3 - "$out" "$rounds" <<'PY'
import re, sys
out, rounds = sys.argv[1], int(sys.argv[2])
def read(kind, r):
    wall, user, sys_, kb = open(f"{out}/{kind}{r}.time").read().split()
    log = open(f"{out}/{kind}{r}.log").read()
    m = re.search(r"read-back: G-buffer words to the compression model\s+(\d+)\s+([0-9.]+)", log)
    return float(wall), float(user) + float(sys_), float(m.group(2)) / 1000 if m else 0.0
for r in range(1, rounds + 1):
    o, n, f = read("old", r), read("new", r), read("off", r)
    print(f"round {r}: wall new/old {n[0] / o[0]:.3f}, new/off {n[0] / f[0]:.3f}; CPU new/old {n[1] / o[1]:.3f}, "
          f"new/off {n[1] / f[1]:.3f}; the model's host scope {n[2]:.2f} s = {n[2] / o[0]:.3f} of old's wall")
PY
