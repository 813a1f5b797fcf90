#!/usr/bin/env bash
# Builds the benchmarks in Release and runs them, writing Google Benchmark JSON to
# bench/results/<name>.json (gitignored), then prints the summary (bench/summarize.py), also
# written to bench/results/summary.txt.
#
# usage: bench/run.sh [codec] [gpu] [compare] [png] [e2e]    (default: codec gpu compare)
#   codec    codec_bench: CPU mirror encode/decode vs memcpy of the same bytes
#   gpu      gpu_pass_bench: G-buffer and lighting pass per layout (GBL_BENCH_4K=1 adds 3840x2160)
#   compare  compare_bench: computeRunMetrics and FLIP at 1080p
#   png      png_bench: one 4K RGB PNG by the old stb encoder and by encodePng on 1 and several cores
#   e2e      `gbufferlab compare --scene builtin` of all layouts at 1080p, run twice per --eval gpu / cpu (the second,
#            warm, is timed by stage: its timings.json), then at 3840x2160 with the layouts
#            GBL_BENCH_4K_LAYOUTS (default ue4,ryse,crysis3-thin) as mem4k does, and
#            `gbufferlab render` at 3840x2160 whole and with --band-rows 256 and 64 (peak memory;
#            the EXRs compared byte for byte)
#   gpu4k    issue 14's GPU goal: `gbufferlab compare` of the four seed layouts at 3840x2160 (3 views)
#            on GBL_BENCH_DEVICE (default gpu) on fresh caches, then three warm runs: wall, CPU
#            and peak memory per run in results/gpu4k_*.txt, the device and driver in
#            results/gpu4k_device.txt, each run's timings.json; prints the median warm wall time
#            against the goal (< 2 s)
#   mem4k    `gbufferlab compare` at 3840x2160 with GBL_BENCH_4K_LAYOUTS, one view: in bands (the
#            default there on lavapipe) and on whole frames with --eval gpu and cpu: peak RSS and
#            wall time in results/compare_4k_rss_<mode>.txt; the banded numbers checked against
#            the whole-frame --eval gpu ones (bench/report_numbers.py)
#   search   `gbufferlab search --budget 16` at 480x270, 3 views, 600 candidates, confirmed by full
#            renders: candidates per minute, CPU seconds per candidate and the goals in
#            results/search-16/search.json and search-report.md (GBL_BENCH_SEARCH_THREADS, default 2)
#   coldwarm[:WxH] `gbufferlab compare --scene builtin` at WxH (default GBL_BENCH_COLD_SIZE, else 480x270) on fresh
#            caches (an empty GBL_CACHE_DIR: SPIR-V, pipeline and IBL caches), then again (warm).
#            Mesa's own disk shader cache (the only cache of llvmpipe's JIT-compiled code) per
#            GBL_BENCH_COLD_MESA: "off" (default: MESA_SHADER_CACHE_DISABLE=true in both runs, so it
#            hides no driver cost) or "fresh" (an empty MESA_SHADER_CACHE_DIR that the first run
#            fills: what a user's first and second run see). GBL_BENCH_COLD_ARGS: more compare
#            flags (e.g. "--layouts ue4,crysis2-slim --views 1"). Wall times and both timings.json
#            in results/coldwarm_<WxH>_<mesa>_*; e.g. bench/run.sh coldwarm:480x270 coldwarm:1920x1080
#   ratio    issue 14's lavapipe goal (warm 1080p compare <= 1.5x its GPU passes): the built-in
#            scene's comparison (`compare --scene builtin`, the default before the bundled suite:
#            every layout, 1920x1080, 3 views) after a warm-up run, GBL_BENCH_REPETITIONS times alternating the files'
#            encoders at nice 0 (the default) and at nice 19 (GBL_WRITER_NICE), where they take the
#            time the passes leave and no longer stretch the passes' timestamps (lavapipe renders on
#            the same cores); wall, CPU and peak memory per run in results/ratio_nice<N>_<i>.txt,
#            and both ratios printed
# environment:
#   GBL_BENCH_REPETITIONS (default 3; medians are reported), GBL_BENCH_BUILD_DIR (default build-bench),
#   GBL_BENCH_FILTER (a --benchmark_filter regex), GBL_BENCH_4K, GBL_BENCH_LAYOUTS, GBL_BENCH_DEVICE,
#   GBL_BENCH_NO_BUILD=1 (use the binaries already in GBL_BENCH_BUILD_DIR: a machine without the
#   build's packages, e.g. a lent GPU machine given a build made elsewhere)
set -euo pipefail
cd "$(dirname "$0")/.."

build=${GBL_BENCH_BUILD_DIR:-build-bench}
reps=${GBL_BENCH_REPETITIONS:-3}
results=bench/results
what=("$@")
[ ${#what[@]} -eq 0 ] && what=(codec gpu compare)

targets=()  # only what the parts asked for need be built
for w in "${what[@]}"; do
    case "${w%%:*}" in
        codec) targets+=(codec_bench) ;;
        gpu) targets+=(gpu_pass_bench) ;;
        compare) targets+=(compare_bench) ;;
        png) targets+=(png_bench) ;;
        e2e | coldwarm | search | mem4k | gpu4k | ratio) targets+=(gbufferlab) ;;
    esac
done

if [ -z "${GBL_BENCH_NO_BUILD:-}" ]; then
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGBL_BUILD_BENCH=ON >/dev/null
    cmake --build "$build" --target "${targets[@]}" -j2
fi
mkdir -p "$results"

# Repetitions in random order (Google Benchmark's random interleaving): each benchmark's
# repetitions are spread over the run instead of back to back, so a disturbance of a few seconds
# (another process, a VM neighbour) touches one repetition of several benchmarks, not every
# repetition of one. The medians, and the ratios of benchmarks measured side by side, then no
# longer swing with it (bench/RESULTS.md: the codec goal's verdict, 2026-11-25).
run_bench() {  # name
    local args=(--benchmark_repetitions="$reps" --benchmark_enable_random_interleaving=true
                --benchmark_report_aggregates_only=true
                --benchmark_out="$results/$1.json" --benchmark_out_format=json)
    [ -n "${GBL_BENCH_FILTER:-}" ] && args+=(--benchmark_filter="$GBL_BENCH_FILTER")
    echo "== $1 -> $results/$1.json"
    "$build/$1" "${args[@]}"
}

# compare at 3840x2160 with GBL_BENCH_4K_LAYOUTS, one view, for peak memory (KiB) and wall time:
# in bands (--band-rows auto: the default there on a CPU device), and on whole frames per --eval;
# the banded report's numbers are checked against the whole-frame --eval gpu one's.
run_mem4k() {
    local layouts=${GBL_BENCH_4K_LAYOUTS:-ue4,ryse,crysis3-thin}
    for mode in bands gpu cpu; do
        local flags=(--band-rows 0 --eval "$mode")
        [ "$mode" = bands ] && flags=(--band-rows auto)
        echo "== gbufferlab compare at 3840x2160, $layouts, one view, ${flags[*]} (peak memory)"
        /usr/bin/time -f '%M KiB %e s' -o "$results/compare_4k_rss_$mode.txt" "$build/gbufferlab" compare --scene builtin \
            --device "${GBL_BENCH_DEVICE:-cpu}" "${flags[@]}" --size 3840x2160 --views 1 --layouts "$layouts" \
            --out "$results/compare-4k-$mode" --force >/dev/null
        cat "$results/compare_4k_rss_$mode.txt"
    done
    python3 bench/report_numbers.py "$results/compare-4k-gpu/report.json" "$results/compare-4k-bands/report.json"
}

# Issue 14's GPU goal: every seed layout at 4K, compare end to end, in under 2 s of wall time.
run_gpu4k() {
    local device=${GBL_BENCH_DEVICE:-gpu} cache
    cache=$(mktemp -d)
    "$build/gbufferlab" devices | tee "$results/gpu4k_device.txt"
    for run in cold warm1 warm2 warm3; do
        echo "== gbufferlab compare --device $device, 3840x2160, the seed layouts, 3 views ($run)"
        GBL_CACHE_DIR="$cache" /usr/bin/time -f '%e %U %S %M' -o "$results/gpu4k_${run}_time.txt" \
            "$build/gbufferlab" compare --scene builtin --device "$device" --size 3840x2160 --layouts ue4,ryse,crysis2-slim,crysis3-thin \
            --out "$results/compare-gpu4k-$run" --force >"$results/gpu4k_${run}_console.txt"
        cp "$results/compare-gpu4k-$run/timings.json" "$results/gpu4k_${run}.json"
        grep -E '^time by stage|^total' "$results/gpu4k_${run}_console.txt"
        echo "wall, user, system (s), peak KiB: $(cat "$results/gpu4k_${run}_time.txt")"
    done
    rm -rf "$cache"
    python3 - "$results" <<'PY'
import statistics, sys
walls = [float(open(f"{sys.argv[1]}/gpu4k_warm{i}_time.txt").read().split()[0]) for i in (1, 2, 3)]
cold = float(open(f"{sys.argv[1]}/gpu4k_cold_time.txt").read().split()[0])
m = statistics.median(walls)
print(f"4K seed layouts, warm wall median {m:.2f} s (goal < 2 s: {'met' if m < 2 else 'missed'}); "
      f"first run {cold:.2f} s = {cold / m:.2f}x warm")
PY
}

for w in "${what[@]}"; do
    case "$w" in
        codec) run_bench codec_bench ;;
        gpu) run_bench gpu_pass_bench ;;
        compare) run_bench compare_bench ;;
        png) run_bench png_bench ;;
        e2e)
            for ev in gpu cpu; do
                out="$results/compare-e2e-$ev"
                echo "== gbufferlab compare --eval $ev (warm-up run)"
                "$build/gbufferlab" compare --scene builtin --device "${GBL_BENCH_DEVICE:-cpu}" --eval "$ev" --out "$out" --force >/dev/null
                echo "== gbufferlab compare --eval $ev (timed run)"
                "$build/gbufferlab" compare --scene builtin --device "${GBL_BENCH_DEVICE:-cpu}" --eval "$ev" --out "$out" --force >/dev/null
                cp "$out/timings.json" "$results/compare_e2e_$ev.json"
            done
            run_mem4k
            for rows in 0 256 64; do  # 0: the whole frame
                echo "== gbufferlab render at 3840x2160, --band-rows $rows (peak memory)"
                band=()
                [ "$rows" != 0 ] && band=(--band-rows "$rows")
                /usr/bin/time -f '%M' -o "$results/render_4k_rss_kib_rows$rows.txt" "$build/gbufferlab" render \
                    --device "${GBL_BENCH_DEVICE:-cpu}" --size 3840x2160 "${band[@]}" --out "$results/render-4k-$rows" \
                    --force >/dev/null
                cmp "$results/render-4k-0/reference.exr" "$results/render-4k-$rows/reference.exr"  # bit for bit
            done
            ;;
        ratio)
            out="$results/compare-ratio"
            echo "== gbufferlab compare (warm-up run)"
            "$build/gbufferlab" compare --scene builtin --device "${GBL_BENCH_DEVICE:-cpu}" --out "$out" --force >/dev/null 2>&1
            for ((i = 1; i <= reps; ++i)); do
                for nice in 0 19; do
                    echo "== gbufferlab compare, the files' encoders at nice $nice ($i of $reps)"
                    GBL_WRITER_NICE=$nice /usr/bin/time -f '%e %U %S %M' -o "$results/ratio_nice${nice}_$i.time" \
                        "$build/gbufferlab" compare --scene builtin --device "${GBL_BENCH_DEVICE:-cpu}" --out "$out" --force \
                        >"$results/ratio_nice${nice}_$i.log" 2>&1
                    python3 - "$out/timings.json" "$results/ratio_nice${nice}_$i.time" "$nice" \
                        > "$results/ratio_nice${nice}_$i.txt" <<'PY'
import json, sys
t = json.load(open(sys.argv[1]))
wall, user, system, rss = open(sys.argv[2]).read().split()[-4:]
print(f"nice {sys.argv[3]}: total {t['total_ms'] / 1000:.2f} s, GPU passes {t['gpu_pass_ms'] / 1000:.2f} s, "
      f"ratio {t['total_over_gpu_passes']:.2f}x (goal <= 1.5x); wall {wall} s, user {user} s, sys {system} s, "
      f"peak {rss} KiB")
PY
                    cat "$results/ratio_nice${nice}_$i.txt"
                done
            done
            ;;
        mem4k) run_mem4k ;;
        gpu4k) run_gpu4k ;;
        search)
            out="$results/search-16"
            rm -rf "$out"
            echo "== gbufferlab search --budget 16 (480x270, 3 views, 600 candidates)"
            "$build/gbufferlab" search --budget 16 --size 480x270 --views 3 --candidates 600 --seed 1 \
                --threads "${GBL_BENCH_SEARCH_THREADS:-2}" --device "${GBL_BENCH_DEVICE:-cpu}" --out "$out"
            cp "$out/search.json" "$results/search.json"
            ;;
        coldwarm|coldwarm:*)
            size=${w#coldwarm:}
            [ "$size" = coldwarm ] && size=${GBL_BENCH_COLD_SIZE:-480x270}
            mesa=${GBL_BENCH_COLD_MESA:-off}
            tag="coldwarm_${size}_${mesa}"
            cache=$(mktemp -d)
            mesa_env=(MESA_SHADER_CACHE_DISABLE=true)
            [ "$mesa" = fresh ] && mesa_env=(MESA_SHADER_CACHE_DISABLE=false MESA_SHADER_CACHE_DIR="$cache/mesa")
            read -r -a extra <<< "${GBL_BENCH_COLD_ARGS:-}"
            for run in cold warm; do
                echo "== gbufferlab compare ($run caches, $size, Mesa disk cache $mesa) ${extra[*]}"
                # wall, user and system seconds: on a machine shared with other jobs the CPU time
                # (user + system) is the steadier figure
                env GBL_CACHE_DIR="$cache/gbl" "${mesa_env[@]}" /usr/bin/time -f '%e %U %S' -o "$results/${tag}_${run}_time.txt" \
                    "$build/gbufferlab" compare --scene builtin --device "${GBL_BENCH_DEVICE:-cpu}" --size "$size" "${extra[@]}" \
                    --out "$results/compare-$tag-$run" --force >"$results/${tag}_${run}_console.txt"
                cp "$results/compare-$tag-$run/timings.json" "$results/${tag}_${run}.json"
                tail -n 4 "$results/${tag}_${run}_console.txt"
                echo "wall, user, system (s): $(cat "$results/${tag}_${run}_time.txt"); load $(cut -d' ' -f1-3 /proc/loadavg)"
            done
            rm -rf "$cache"
            python3 - "$results/${tag}_cold_time.txt" "$results/${tag}_warm_time.txt" "$size" "$mesa" <<'PY'
import sys
cold, warm = ([float(x) for x in open(f).read().split()] for f in sys.argv[1:3])
print(f"first run / warm run ({sys.argv[3]}, Mesa cache {sys.argv[4]}): wall {cold[0] / warm[0]:.3f}x, "
      f"CPU (user + system) {(cold[1] + cold[2]) / (warm[1] + warm[2]):.3f}x")
PY
            ;;
        *) echo "bench/run.sh: unknown part '$w' (codec, gpu, compare, png, e2e, mem4k, gpu4k, search, coldwarm[:WxH])" >&2; exit 2 ;;
    esac
done

python3 bench/summarize.py "$results" | tee "$results/summary.txt"
