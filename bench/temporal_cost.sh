#!/usr/bin/env bash
# The cost of compare --temporal N against --temporal 1, side by side in one run of this script:
# the same layouts, size and views; wall time and peak memory (GNU time), and time by stage
# (timings.json): the N frames' renders (G-buffer, lighting, read-back) against N x one frame's,
# the metrics (computed twice at N > 1: on the resolve and on frame 0, plus the accumulation)
# against one frame's. The goal (issue 30): --temporal 8 at most about 8.5x the renders of
# --temporal 1 plus the same metrics once; peak memory the same for every N > 1.
#
# usage: bench/temporal_cost.sh [BUILD_DIR]   (default build)
# environment: GBL_BENCH_LAYOUTS (default all), GBL_BENCH_SIZE (default 960x540), GBL_BENCH_VIEWS
#              (default 1), GBL_BENCH_FRAMES (default "2 8": the N > 1 to run), GBL_BENCH_OUT
#              (default out/bench-temporal; replaced)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
bin="$build/gbufferlab"
layouts=${GBL_BENCH_LAYOUTS:-all}
size=${GBL_BENCH_SIZE:-960x540}
views=${GBL_BENCH_VIEWS:-1}
frames=${GBL_BENCH_FRAMES:-2 8}
out=${GBL_BENCH_OUT:-out/bench-temporal}
rm -rf "$out"
mkdir -p "$out"
echo "temporal_cost: $(date -u +%FT%TZ), $(git rev-parse --short HEAD), layouts $layouts, $size, $views views, $(nproc) cores"
for n in 1 $frames; do
    /usr/bin/time -f "%e %M" -o "$out/t$n.time" "$bin" compare --temporal "$n" --layouts "$layouts" --size "$size" \
        --views "$views" --out "$out/t$n" >"$out/t$n.log" 2>&1
done
python3 - "$out" 1 $frames <<'PY'
import json, sys
out, ns = sys.argv[1], [int(n) for n in sys.argv[2:]]
rows = {}
for n in ns:
    wall, kb = open(f"{out}/t{n}.time").read().split()
    t = json.load(open(f"{out}/t{n}/timings.json"))
    s = t["stages_ms"]
    render = (s["rendering"] + s["read-back"]) / 1000
    metrics = s["metrics"] / 1000
    rows[n] = (float(wall), int(kb) // 1024, render, metrics, t["gpu_pass_ms"] / 1000)
    print(f"--temporal {n:<3} wall {float(wall):8.1f} s  peak {int(kb) // 1024:6d} MB  renders+read-back {render:8.1f} s  "
          f"metrics {metrics:7.1f} s  passes {t['gpu_pass_ms'] / 1000:8.1f} s")
w1, m1, r1, x1, p1 = rows[1]
for n in ns[1:]:
    w, m, r, x, p = rows[n]
    budget = 8.5 / 8 * n * r1 + x1 + (w1 - r1 - x1)  # ~1.06 N x the renders, the metrics once, the rest as at N = 1
    print(f"N = {n}: wall {w / w1:.2f}x, renders {r / r1:.2f}x ({n} frames), passes {p / p1:.2f}x, metrics {x / x1:.2f}x, "
          f"peak memory {m / m1:.2f}x; wall against {n * 8.5 / 8:.2f}x the renders + the metrics once: {w / budget:.2f}")
PY
