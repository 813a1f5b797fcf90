#!/usr/bin/env bash
# Builds the benchmarks in Release and runs them, writing Google Benchmark JSON to
# bench/results/<name>.json (gitignored), then prints the summary (bench/summarize.py), also
# written to bench/results/summary.txt.
#
# usage: bench/run.sh [codec] [gpu] [compare] [e2e]    (default: codec gpu compare)
#   codec    codec_bench: CPU mirror encode/decode vs memcpy of the same bytes
#   gpu      gpu_pass_bench: G-buffer and lighting pass per layout (GBL_BENCH_4K=1 adds 3840x2160)
#   compare  compare_bench: computeRunMetrics and FLIP at 1080p
#   e2e      `gbufferlab compare` of all layouts at 1080p, run twice per --eval gpu / cpu (the second,
#            warm, is timed by stage: its timings.json), then at 3840x2160 with the layouts
#            GBL_BENCH_4K_LAYOUTS (default ue4,ryse,crysis3-thin) per --eval for peak memory
#   coldwarm `gbufferlab compare` of all layouts at GBL_BENCH_COLD_SIZE (default 480x270) on fresh
#            caches (an empty GBL_CACHE_DIR: SPIR-V, pipeline and IBL caches), then again (warm),
#            both with MESA_SHADER_CACHE_DISABLE=true so Mesa's own disk cache hides no driver cost;
#            wall times and both timings.json in results/coldwarm_*
# environment:
#   GBL_BENCH_REPETITIONS (default 3; medians are reported), GBL_BENCH_BUILD_DIR (default build-bench),
#   GBL_BENCH_FILTER (a --benchmark_filter regex), GBL_BENCH_4K, GBL_BENCH_LAYOUTS, GBL_BENCH_DEVICE
set -euo pipefail
cd "$(dirname "$0")/.."

build=${GBL_BENCH_BUILD_DIR:-build-bench}
reps=${GBL_BENCH_REPETITIONS:-3}
results=bench/results
what=("$@")
[ ${#what[@]} -eq 0 ] && what=(codec gpu compare)

targets=(codec_bench gpu_pass_bench compare_bench)
for w in "${what[@]}"; do [ "$w" = e2e ] || [ "$w" = coldwarm ] && targets+=(gbufferlab); done

cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGBL_BUILD_BENCH=ON >/dev/null
cmake --build "$build" --target "${targets[@]}" -j2
mkdir -p "$results"

run_bench() {  # name
    local args=(--benchmark_repetitions="$reps" --benchmark_report_aggregates_only=true
                --benchmark_out="$results/$1.json" --benchmark_out_format=json)
    [ -n "${GBL_BENCH_FILTER:-}" ] && args+=(--benchmark_filter="$GBL_BENCH_FILTER")
    echo "== $1 -> $results/$1.json"
    "$build/$1" "${args[@]}"
}

for w in "${what[@]}"; do
    case "$w" in
        codec) run_bench codec_bench ;;
        gpu) run_bench gpu_pass_bench ;;
        compare) run_bench compare_bench ;;
        e2e)
            for ev in gpu cpu; do
                out="$results/compare-e2e-$ev"
                echo "== gbufferlab compare --eval $ev (warm-up run)"
                "$build/gbufferlab" compare --device "${GBL_BENCH_DEVICE:-cpu}" --eval "$ev" --out "$out" --force >/dev/null
                echo "== gbufferlab compare --eval $ev (timed run)"
                "$build/gbufferlab" compare --device "${GBL_BENCH_DEVICE:-cpu}" --eval "$ev" --out "$out" --force >/dev/null
                cp "$out/timings.json" "$results/compare_e2e_$ev.json"
            done
            for ev in gpu cpu; do
                echo "== gbufferlab compare --eval $ev at 3840x2160, ${GBL_BENCH_4K_LAYOUTS:-ue4,ryse,crysis3-thin} (peak memory)"
                /usr/bin/time -f '%M' -o "$results/compare_4k_rss_kib_$ev.txt" "$build/gbufferlab" compare \
                    --device "${GBL_BENCH_DEVICE:-cpu}" --eval "$ev" --size 3840x2160 \
                    --layouts "${GBL_BENCH_4K_LAYOUTS:-ue4,ryse,crysis3-thin}" --out "$results/compare-4k-$ev" --force >/dev/null
            done
            ;;
        coldwarm)
            cache=$(mktemp -d)
            for run in cold warm; do
                echo "== gbufferlab compare ($run caches, ${GBL_BENCH_COLD_SIZE:-480x270}, MESA_SHADER_CACHE_DISABLE=true)"
                GBL_CACHE_DIR="$cache" MESA_SHADER_CACHE_DISABLE=true /usr/bin/time -f '%e' -o "$results/coldwarm_${run}_wall_s.txt" \
                    "$build/gbufferlab" compare --device "${GBL_BENCH_DEVICE:-cpu}" --size "${GBL_BENCH_COLD_SIZE:-480x270}" \
                    --out "$results/compare-$run" --force >/dev/null
                cp "$results/compare-$run/timings.json" "$results/coldwarm_${run}.json"
            done
            rm -rf "$cache"
            echo "first run / warm run (wall): $(python3 -c "print(round($(cat "$results/coldwarm_cold_wall_s.txt") / $(cat "$results/coldwarm_warm_wall_s.txt"), 3))")x"
            ;;
        *) echo "bench/run.sh: unknown part '$w' (codec, gpu, compare, e2e, coldwarm)" >&2; exit 2 ;;
    esac
done

python3 bench/summarize.py "$results" | tee "$results/summary.txt"
