#!/usr/bin/env python3
"""Summarises bench/results/*.json (Google Benchmark JSON, medians of the repetitions).

usage: bench/summarize.py [RESULTS_DIR]   (default bench/results)
Prints: codec GB/s as a ratio of memcpy GB/s of the same bytes (goal >= 0.25x; per layout against
the faster of memcpy on 1 thread and on the codec's threads, with the memory-traffic ceilings, and
the verdict on issue 14's goal: >= 0.5x of the DRAM bound in each direction); GPU pass times
per layout and the 4K/1080p ratio; the CPU metrics cost per layout as a ratio of the GPU passes;
`compare` wall time as a ratio of its GPU pass times (goal <= 1.5x); peak RSS (goal < 2 GiB); the
4K PNG encoders' wall time and file size against the old stb encoder's (png_bench).
"""
import json
import os
import re
import sys

CODEC_GOAL = 0.25
# Issue 14: each layout's codec >= 0.5x of its own memory-traffic bound: the DRAM bound below
# (RESULTS.md, "Codec against each layout's own bound", says why not the cache-rate bound).
HALF_BOUND_GOAL = 0.5
COMPARE_GOAL = 1.5
RSS_GOAL_MIB = 2048.0


def base_name(run_name):
    name = re.sub(r"/iterations:\d+", "", run_name)
    for suffix in ("/manual_time", "/real_time"):
        if name.endswith(suffix):
            name = name[: -len(suffix)]
    return name


def medians(path):
    """{base name: median entry}, plus the JSON context."""
    if not os.path.exists(path):
        return None, None
    try:
        with open(path) as f:
            doc = json.load(f)
    except json.JSONDecodeError as e:
        print(f"== {os.path.basename(path)}: unreadable ({e}); still being written?")
        return None, None
    out = {}
    for b in doc.get("benchmarks", []):
        if b.get("error_occurred"):
            out[base_name(b.get("run_name", b["name"]))] = {"error": b.get("error_message", "error")}
            continue
        agg = b.get("aggregate_name")
        if agg not in (None, "median"):
            continue
        key = base_name(b.get("run_name", b["name"]))
        if agg == "median" or key not in out:
            out[key] = b
    return out, doc.get("context", {})


def ms(entry):
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[entry.get("time_unit", "ns")]
    return entry["real_time"] * scale


def codec_primitives(rows):
    """Per-encoding rows: single-threaded CPU time, against memcpy/bytes:<n> (one thread, CPU time)."""
    memcpy = {int(round(v["bytes"])): v["GB_per_s"] for k, v in rows.items()
              if re.fullmatch(r"memcpy/bytes:\d+", k) and "GB_per_s" in v}
    prefixes = ("encode/", "decode/")
    names = sorted({k.split("/", 1)[1] for k in rows if k.startswith(prefixes)})
    if not names:
        return
    print("  per encoding, 1M elements (one thread, CPU time)")
    print(f"    {'name':28s} {'bytes':>10s} {'enc GB/s':>9s} {'x memcpy':>9s} {'dec GB/s':>9s} {'x memcpy':>9s}"
          f" {'Mpix/s enc':>10s} {'Mpix/s dec':>10s}")
    misses = []
    for n in names:
        e, d = rows.get(prefixes[0] + n, {}), rows.get(prefixes[1] + n, {})
        ref = e or d
        if "bytes" not in ref:
            print(f"    {n:28s} {'error: ' + ref.get('error', 'missing')}")
            continue
        nbytes = int(round(ref["bytes"]))
        m = memcpy.get(nbytes)
        cells = []
        for x, prefix in ((e, prefixes[0]), (d, prefixes[1])):
            if "GB_per_s" in x and m:
                r = x["GB_per_s"] / m
                cells.append(f"{x['GB_per_s']:9.3f} {r:8.3f}x")
                if r < CODEC_GOAL:
                    misses.append(f"{prefix}{n} {r:.3f}x")
            else:
                cells.append(f"{'-':>9s} {'-':>9s}")
        pix = [f"{x['pixels_per_s'] / 1e6:10.1f}" if "pixels_per_s" in x else f"{'-':>10s}" for x in (e, d)]
        print(f"    {n:28s} {nbytes:10d} {cells[0]} {cells[1]} {pix[0]} {pix[1]}")
    used = {int(round(rows[p + n]["bytes"])) for n in names for p in prefixes if "bytes" in rows.get(p + n, {})}
    print("    memcpy of those sizes: " + ", ".join(f"{b / 1e6:.1f} MB {g:.1f} GB/s" for b, g in sorted(memcpy.items())
                                                 if b in used))
    print(f"    below goal: {', '.join(misses) if misses else 'none'}")


def codec_layouts(rows):
    """Per-layout rows: CpuCodec on its threads, wall time, against memcpy of the same bytes on 1
    thread and on the codec's threads (same run); the goal ratio uses the faster of the two, i.e.
    the machine's copy bandwidth. Bounds: the memory-traffic ceilings of that ratio, at the
    G-buffer's own copy rate (cache-rate "bound", for information) and at the DRAM copy rate of the
    whole Surface image ("DRAM bnd", the goal's bound)."""
    # memcpy/bytes:<n>/threads:<t> -> {n: {t: GB/s}}
    memcpy = {}
    for k, v in rows.items():
        m = re.fullmatch(r"memcpy/bytes:(\d+)/threads:(\d+)", k)
        if m and "GB_per_s" in v:
            memcpy.setdefault(int(m.group(1)), {})[int(m.group(2))] = v["GB_per_s"]
    prefixes = ("layout_encode/", "layout_decode/")
    names = sorted({k.split("/", 1)[1] for k in rows if k.startswith(prefixes)})
    if not names:
        return
    threads = sorted({int(round(rows[p + n]["threads"])) for n in names for p in prefixes
                      if "threads" in rows.get(p + n, {})})
    t = threads[-1] if threads else 0
    print(f"  per layout, 1920x1080 image (CpuCodec on {t} threads, wall time; x1 / x{t}: / memcpy of the same "
          f"bytes on 1 / {t} threads; x copy: / the faster of the two = the goal ratio; bound: memory-bound "
          "ceiling 2G / (S + G + M))")
    print(f"    {'layout':20s} {'B/px':>4s} {'bound':>6s} | {'enc GB/s':>8s} {'x1':>7s} {'x' + str(t):>7s} "
          f"{'x copy':>7s} | {'dec GB/s':>8s} {'x1':>7s} {'x' + str(t):>7s} {'x copy':>7s} | "
          f"{'Mpix/s enc':>10s} {'dec':>6s} | {'DRAM bnd':>8s} {'enc/DRAM':>8s} {'dec/DRAM':>8s} | "
          f"{'enc/bnd':>7s} {'dec/bnd':>7s}")
    # The copy rate of the whole Surface image (memcpy/bytes:<S * pixels>), always from DRAM: the
    # codec streams its Surfaces at no more than that, whereas memcpy of a small G-buffer runs
    # partly in L3. "DRAM bnd" = bound * (that rate / the G-buffer's memcpy rate): the ceiling of
    # "x copy" when the codec's S + G + M bytes move at the DRAM copy rate. The goal (issue 14):
    # x copy >= 0.5 DRAM bnd in both directions; x copy / bound (the cache rate) is for information.
    misses, half_misses, dram_misses, dram_checked = [], [], [], 0
    for n in names:
        e, d = rows.get(prefixes[0] + n, {}), rows.get(prefixes[1] + n, {})
        ref = e or d
        if "bytes" not in ref:
            print(f"    {n:20s} {'error: ' + ref.get('error', 'missing')}")
            continue
        nbytes = int(round(ref["bytes"]))
        g, s_, m_ = (ref.get(k, 0.0) for k in ("bytes_per_pixel", "surface_bytes_per_pixel", "material_bytes_per_pixel"))
        bound = 2.0 * g / (s_ + g + m_) if s_ + g + m_ > 0 else float("nan")
        copies = memcpy.get(nbytes, {})
        one, many = copies.get(1), copies.get(t)
        best = max([c for c in (one, many) if c], default=None)
        pixels = nbytes / g if g else 0
        surface_copy = max(memcpy.get(int(round(s_ * pixels)), {}).values(), default=None)
        dram = bound * surface_copy / best if surface_copy and best else None
        ratios, dram_ratios = [], []
        cells = []
        for x, prefix in ((e, prefixes[0]), (d, prefixes[1])):
            if "GB_per_s" not in x or not best:
                cells.append(f"{'-':>8s} {'-':>7s} {'-':>7s} {'-':>7s}")
                continue
            gbs = x["GB_per_s"]
            r1 = f"{gbs / one:6.3f}x" if one else f"{'-':>7s}"
            rt = f"{gbs / many:6.3f}x" if many else f"{'-':>7s}"
            rb = gbs / best
            cells.append(f"{gbs:8.3f} {r1} {rt} {rb:6.3f}x")
            ratios.append(f"{rb / bound:6.2f}x")
            if dram:
                dram_checked += 1
                dram_ratios.append(f"{rb / dram:7.2f}x")
                if rb < HALF_BOUND_GOAL * dram:
                    dram_misses.append(f"{prefix}{n} {rb / dram:.2f}x")
            else:
                dram_ratios.append(f"{'-':>8s}")
            if rb < CODEC_GOAL:
                misses.append(f"{prefix}{n} {rb:.3f}x (bound {bound:.2f}x)")
            if rb < HALF_BOUND_GOAL * bound:
                half_misses.append(f"{prefix}{n} {rb / bound:.2f}x")
        ratios += [f"{'-':>7s}"] * (2 - len(ratios))
        dram_ratios += [f"{'-':>8s}"] * (2 - len(dram_ratios))
        pix = [f"{x['pixels_per_s'] / 1e6:10.1f}" if "pixels_per_s" in x else f"{'-':>10s}" for x in (e, d)]
        dram_cell = f"{dram:7.3f}x" if dram else f"{'-':>8s}"
        print(f"    {n:20s} {g:4.0f} {bound:5.2f}x | {cells[0]} | {cells[1]} | {pix[0]} {pix[1].strip():>6s} | "
              f"{dram_cell} {dram_ratios[0]} {dram_ratios[1]} | {ratios[0]} {ratios[1]}")
    print("    memcpy of those sizes (GB/s, 1 / " + str(t) + " threads): " +
          ", ".join(f"{b / 1e6:.1f} MB {c.get(1, float('nan')):.1f} / {c.get(t, float('nan')):.1f}"
                    for b, c in sorted(memcpy.items())))
    print(f"    below goal: {', '.join(misses) if misses else 'none'}")
    print(f"    (information) below {HALF_BOUND_GOAL}x of the cache-rate bound (enc/bnd, dec/bnd): "
          f"{', '.join(half_misses) if half_misses else 'none'}")
    if dram_checked:
        verdict = f"missed by {len(dram_misses)} of {dram_checked}: {', '.join(dram_misses)}" if dram_misses else \
            f"met by all {dram_checked}"
    else:
        verdict = "not measured (no memcpy of the whole Surface image in this run)"
    print(f"    goal >= {HALF_BOUND_GOAL}x of the DRAM bound (enc/DRAM, dec/DRAM): {verdict}")


def codec(results):
    rows, ctx = medians(os.path.join(results, "codec_bench.json"))
    if rows is None:
        return
    print("== codec_bench: CPU mirror GB/s of encoded bytes / memcpy GB/s of the same bytes, same run "
          f"(goal >= {CODEC_GOAL}x; medians; {ctx.get('num_cpus', '?')} CPUs)")
    codec_primitives(rows)
    codec_layouts(rows)


def gpu(results, file_name="gpu_pass_bench.json"):
    rows, ctx = medians(os.path.join(results, file_name))
    if rows is None:
        return None
    print(f"== {file_name} on {ctx.get('vulkan_device', '?')} ({ctx.get('vulkan_driver', '?')}); "
          "medians of timestamp-query pass times")
    layouts = sorted({k.split("/")[1] for k in rows if k.startswith("gbuffer_pass/")})
    sizes = sorted({k.split("/")[2] for k in rows if k.startswith("gbuffer_pass/")},
                   key=lambda s: int(s.split("x")[0]))
    passes = {}
    print(f"    {'layout':20s} {'B/px':>5s} " + " ".join(f"{'gbuf ' + s:>15s} {'light ' + s:>16s}" for s in sizes) +
          ("   4K/1080p gbuf  light" if len(sizes) > 1 else ""))
    peak = 0.0
    for lay in layouts:
        cells, bpp = [], "-"
        for s in sizes:
            g, l = rows.get(f"gbuffer_pass/{lay}/{s}", {}), rows.get(f"lighting_pass/{lay}/{s}", {})
            if "real_time" in g and "real_time" in l:
                passes[(lay, s)] = (ms(g), ms(l))
                bpp = f"{g['bytes_per_pixel']:.0f}"
                peak = max(peak, g.get("peak_rss_MiB", 0), l.get("peak_rss_MiB", 0))
                cells.append(f"{ms(g):12.1f} ms {ms(l):13.1f} ms")
            else:
                cells.append(f"{'error: ' + (g or l).get('error', 'missing'):>32s}")
        line = f"    {lay:20s} {bpp:>5s} " + " ".join(cells)
        if len(sizes) > 1 and (lay, sizes[0]) in passes and (lay, sizes[-1]) in passes:
            a, b = passes[(lay, sizes[0])], passes[(lay, sizes[-1])]
            line += f"   {b[0] / a[0]:8.2f}x {b[1] / a[1]:6.2f}x"
        print(line)
    print(f"    (absolute times: {ctx.get('vulkan_device', '?')} on {ctx.get('num_cpus', '?')} CPUs, context only)")
    print(f"    peak RSS of the process: {peak:.0f} MiB (goal < {RSS_GOAL_MIB:.0f} MiB at 4K; "
          f"4K {'included' if len(sizes) > 1 else 'NOT run: GBL_BENCH_4K=1'})")
    return passes


def compare(results, passes):
    rows, _ = medians(os.path.join(results, "compare_bench.json"))
    if rows is not None:
        print("== compare_bench (1920x1080, synthetic images, medians)")
        for k in sorted(rows):
            if "real_time" in rows[k]:
                extra = f", {rows[k]['exposures']:.0f} exposures" if "exposures" in rows[k] else ""
                print(f"    {k:28s} {ms(rows[k]):9.1f} ms{extra}")
        hd = [v for (lay, s), v in (passes or {}).items() if s == "1920x1080"]
        full = next((v for k, v in rows.items() if k.startswith("run_metrics/full")), {})
        if hd and "real_time" in full:
            mean_pass = sum(g + l for g, l in hd) / len(hd)
            print(f"    metrics of one layout (run_metrics/full) / its GPU passes (mean over layouts, 1080p): "
                  f"{ms(full) / mean_pass:.2f}x")
    # The timed (warm) run's timings.json per evaluation: --eval gpu and --eval cpu side by side.
    for ev in ("gpu", "cpu", None):
        e2e = os.path.join(results, f"compare_e2e_{ev}.json" if ev else "compare_e2e.json")
        if not os.path.exists(e2e):
            continue
        t = json.load(open(e2e))
        total, gpu_ms = t["total_ms"], t["gpu_pass_ms"]
        label = f", --eval {ev}" if ev else ""
        print(f"== gbufferlab compare end to end (warm, 1080p, all layouts + reference{label}): "
              f"wall {total / 1000:.2f} s = {t['total_over_gpu_passes']:.2f}x the GPU passes' "
              f"{gpu_ms / 1000:.2f} s (goal <= {COMPARE_GOAL}x)")
        for stage, v in t["stages_ms"].items():
            print(f"    {stage:16s} {v / 1000:7.2f} s  {v / gpu_ms if gpu_ms else float('nan'):5.2f}x the GPU passes")
    for ev in ("gpu", "cpu", None):
        rss = os.path.join(results, f"compare_4k_rss_kib_{ev}.txt" if ev else "compare_4k_rss_kib.txt")
        if os.path.exists(rss):
            mib = float(open(rss).read().split()[-1]) / 1024.0
            label = f" --eval {ev}" if ev else ""
            print(f"== gbufferlab compare at 3840x2160{label}: peak RSS {mib:.0f} MiB (goal < {RSS_GOAL_MIB:.0f} MiB)")


def png(results):
    """png_bench: each encoder's wall time and file size beside the old stb encoder's, same run."""
    rows, ctx = medians(os.path.join(results, "png_bench.json"))
    if rows is None:
        return
    old = rows.get("png/old_stb", {})
    if "real_time" not in old:
        print("== png_bench: no png/old_stb result")
        return
    print(f"== png_bench: one 3840x2160 RGB heat map, in memory (medians; {ctx.get('num_cpus', '?')} CPUs, "
          f"load average {ctx.get('load_avg', ['?'])[0]})")
    print(f"    {'encoder':22s} {'chunks':>6s} {'threads':>7s} {'wall ms':>8s} {'x faster':>8s} {'CPU ms':>7s} "
          f"{'bytes':>10s} {'size':>8s}")
    for k in ["png/old_stb"] + sorted((k for k in rows if k.startswith("png/new")),
                                       key=lambda k: int(k.rsplit(":", 1)[-1] or 0)):
        v = rows[k]
        if "real_time" not in v:
            print(f"    {k:22s} error: {v.get('error', 'missing')}")
            continue
        print(f"    {k:22s} {v['chunks']:6.0f} {v['threads']:7.0f} {ms(v):8.1f} {ms(old) / ms(v):7.2f}x "
              f"{v.get('cpu_ms', float('nan')):7.1f} {v['bytes']:10.0f} {100.0 * (v['bytes'] / old['bytes'] - 1.0):+7.2f}%")


def main():
    results = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "results")
    codec(results)
    passes = gpu(results)
    gpu(results, "gpu_pass_bench_4k.json")  # GBL_BENCH_4K=1 run written under this name, if any
    compare(results, passes)
    png(results)


if __name__ == "__main__":
    main()
