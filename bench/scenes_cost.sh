#!/usr/bin/env bash
# The cost of comparing N scenes in one run against N single-scene runs, side by side in one
# run of this script: the same layouts, size and views; wall time and peak memory of each
# (GNU time), and the summed passes' timestamps (timings.json). The scenes share the device, the
# pipelines (built once) and each environment's IBL pre-computation; the single runs repeat them.
#
# usage: bench/scenes_cost.sh [BUILD_DIR]   (default build)
# environment: GBL_BENCH_LAYOUTS (default all), GBL_BENCH_SIZE (default 480x270), GBL_BENCH_VIEWS (3),
#              GBL_BENCH_OUT (default out/bench-scenes; replaced)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
bin="$build/gbufferlab"
layouts=${GBL_BENCH_LAYOUTS:-all}
size=${GBL_BENCH_SIZE:-480x270}
views=${GBL_BENCH_VIEWS:-3}
out=${GBL_BENCH_OUT:-out/bench-scenes}
assets=../shared/assets
helmet=$assets/models/FlightHelmet/FlightHelmet.gltf
bottle=$assets/models/WaterBottle/WaterBottle.gltf
warehouse=$assets/envmaps/empty_warehouse_01_1k.hdr
rm -rf "$out"
mkdir -p "$out"
suite="$out/suite.toml"
cat > "$suite" <<TOML
[[scene]]
gltf = "builtin"

[[scene]]
gltf = "$(realpath "$helmet")"
environment = "$(realpath "$warehouse")"

[[scene]]
gltf = "$(realpath "$bottle")"
environment = "$(realpath "$warehouse")"
TOML
common=(--layouts "$layouts" --size "$size" --views "$views")
run() {  # name, then the compare arguments
    local name=$1
    shift
    /usr/bin/time -f "%e %M" -o "$out/$name.time" "$bin" compare "$@" "${common[@]}" --out "$out/$name" \
        >"$out/$name.log" 2>&1
    read -r wall kb <"$out/$name.time"
    local gpu
    gpu=$(python3 -c "import json,sys; print(round(json.load(open(sys.argv[1]))['gpu_pass_ms']/1000, 1))" \
        "$out/$name/timings.json")
    printf "%-22s wall %8.1f s  peak %6.0f MB  passes %7.1f s\n" "$name" "$wall" "$((kb / 1024))" "$gpu"
    echo "$wall" >"$out/$name.wall"
}
echo "scenes_cost: $(date -u +%FT%TZ), $(git rev-parse --short HEAD), layouts $layouts, $size, $views views, $(nproc) cores"
run single-builtin --scene builtin
run single-helmet --scene "$helmet" --env "$warehouse"
run single-bottle --scene "$bottle" --env "$warehouse"
run suite --scene "$suite"
python3 - "$out" <<'PY'
import sys
out = sys.argv[1]
w = {n: float(open(f"{out}/{n}.wall").read()) for n in ["single-builtin", "single-helmet", "single-bottle", "suite"]}
singles = w["single-builtin"] + w["single-helmet"] + w["single-bottle"]
print(f"3 single-scene runs: {singles:.1f} s; one run of 3 scenes: {w['suite']:.1f} s ({w['suite'] / singles:.3f}x)")
PY
