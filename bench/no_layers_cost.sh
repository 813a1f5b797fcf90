#!/usr/bin/env bash
# What a scene without material layers costs before and after the layers (issue 40, item 8): the
# same compare by two builds, alternated in one run of this script after a warm-up run of each
# (shader and pipeline caches warm), so that a change of the machine's load falls on both. Wall,
# user CPU and peak RSS of every run (GNU time), the load average beside each, the medians' ratio.
#
# usage: bench/no_layers_cost.sh BEFORE_BIN AFTER_BIN SCENE.gltf [ROUNDS]   (ROUNDS default 3)
# environment: GBL_BENCH_SIZE (960x540), GBL_BENCH_VIEWS (1), GBL_BENCH_LAYOUTS (default: the
#              layouts both builds ship, read from `layouts list`), GBL_BENCH_OUT (out/bench-no-layers; replaced)
# Each binary reads the layouts and shaders of its own source tree.
set -euo pipefail
before=$1
after=$2
scene=$3
rounds=${4:-3}
size=${GBL_BENCH_SIZE:-960x540}
views=${GBL_BENCH_VIEWS:-1}
out=${GBL_BENCH_OUT:-out/bench-no-layers}
rm -rf "$out"
mkdir -p "$out"
names() { "$1" layouts list 2>/dev/null | awk 'NR > 1 && /^  [a-z0-9]/ {print $1}' | grep -v '^reference$' | sort; }
if [ -z "${GBL_BENCH_LAYOUTS:-}" ]; then
    layouts=$(comm -12 <(names "$before") <(names "$after") | paste -sd, -)
else
    layouts=$GBL_BENCH_LAYOUTS
fi
echo "no_layers_cost: $(date -u +%FT%TZ), $size, $views view(s), $rounds rounds, layouts $layouts"
run() {  # label, binary, index
    local dir="$out/$1-$3"
    local load
    load=$(cut -d' ' -f1 /proc/loadavg)
    nice /usr/bin/time -f "%e %U %M" -o "$dir.time" "$2" compare --scene "$scene" --layouts "$layouts" \
        --size "$size" --views "$views" --out "$dir" >"$dir.log" 2>&1 || echo "rc=$?" >>"$dir.time"
    read -r wall user kb <"$dir.time"
    printf "%-7s %-6s wall %7.2f s  user %7.2f s  peak %8d KiB  load before %s after %s\n" "$1" "$3" "$wall" "$user" "$kb" \
        "$load" "$(cut -d' ' -f1 /proc/loadavg)"
    echo "$1 $wall $user $kb" >>"$out/runs.txt"
}
run before "$before" warm
run after "$after" warm
: >"$out/runs.txt"
for i in $(seq 1 "$rounds"); do
    run before "$before" "$i"
    run after "$after" "$i"
done
python3 - "$out/runs.txt" <<'PY'
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
med = {}
for label in ("before", "after"):
    r = [x for x in rows if x[0] == label]
    med[label] = [statistics.median(float(x[i]) for x in r) for i in (1, 2, 3)]
    print(f"{label}: median wall {med[label][0]:.2f} s, user {med[label][1]:.2f} s, peak {med[label][2]:.0f} KiB ({len(r)} runs)")
print("after / before medians: wall %.3f, user %.3f, peak %.3f" % tuple(a / b for a, b in zip(med["after"], med["before"])))
PY
