#!/usr/bin/env python3
"""Single frame against the resolve of a `compare --temporal N` run: per layout, frame 0's and the
resolved image's FLIP and PSNR and the normal error of frame 0 and of the temporal mean, each
layout's rank by either FLIP, Kendall's tau between the two rankings and the pairs that swap.

usage: bench/temporal_verdicts.py OUT_DIR [MODE]   (the compare --out folder; default its first IBL mode)
"""
import json
import sys


def main():
    report = json.load(open(f"{sys.argv[1]}/report.json"))
    mode = sys.argv[2] if len(sys.argv) > 2 else report["run"]["ibl_modes"][0]
    t = report["run"].get("temporal")
    if not t:
        sys.exit(f"{sys.argv[1]}: not a --temporal N report")
    rows = []
    for r in report["runs"]:
        if r["ibl_mode"] != mode or r["status"] != "ok" or "single_frame" not in r:
            continue
        one, res = r["single_frame"], r
        n1 = one["attribute_errors"].get("normal", {}).get("all", {}).get("mean")
        nr = res["attribute_errors"].get("normal", {}).get("all", {}).get("mean")
        rows.append((r["layout"], r["bytes_per_pixel"]["total"], one["image_errors"]["flip_mean"],
                     res["image_errors"]["flip_mean"], one["image_errors"]["psnr_tonemapped_db"],
                     res["image_errors"]["psnr_tonemapped_db"], n1, nr))
    rank1 = {name: i + 1 for i, name in enumerate(x[0] for x in sorted(rows, key=lambda x: x[2]))}
    rankr = {name: i + 1 for i, name in enumerate(x[0] for x in sorted(rows, key=lambda x: x[3]))}
    print(f"{report['run']['scene']}, {report['run']['width']}x{report['run']['height']}, "
          f"{max(1, len(report['run']['views']))} views, --temporal {t['frames']} ({t['resolve']}), {mode}")
    print(f"{'layout':24} {'B/px':>4} {'FLIP 1f':>8} {'FLIP res':>8} {'res/1f':>6} {'#1f':>3} {'#res':>4} "
          f"{'PSNR 1f':>7} {'PSNR res':>8} {'n° 1f':>6} {'n° mean':>7}")
    fmt = lambda v, f: ("%" + f) % v if isinstance(v, (int, float)) else str(v)
    for x in sorted(rows, key=lambda x: x[3]):
        print(f"{x[0]:24} {x[1]:4d} {x[2]:8.4f} {x[3]:8.4f} {x[3] / x[2] if x[2] else 0:6.3f} {rank1[x[0]]:3d} "
              f"{rankr[x[0]]:4d} {fmt(x[4], '7.2f')} {fmt(x[5], '8.2f')} {fmt(x[6], '6.3f')} {fmt(x[7], '7.3f')}")
    names = [x[0] for x in rows]
    concordant = discordant = 0
    swaps = []
    for i in range(len(names)):
        for j in range(i + 1, len(names)):
            a, b = names[i], names[j]
            s = (rank1[a] - rank1[b]) * (rankr[a] - rankr[b])
            if s > 0:
                concordant += 1
            elif s < 0:
                discordant += 1
                swaps.append((a, b) if rankr[a] < rankr[b] else (b, a))
    pairs = concordant + discordant
    print(f"Kendall's tau (frame 0 vs resolve, by FLIP): {(concordant - discordant) / pairs if pairs else 1:.3f}; "
          f"{discordant} of {pairs} pairs swap")
    moved = sorted(((rank1[n] - rankr[n], n) for n in names), reverse=True)
    print("rank changes (frame 0 -> resolve): " +
          ", ".join(f"{n} {rank1[n]}->{rankr[n]}" for d, n in moved if d != 0))
    for better, worse in swaps:
        print(f"  swap: {better} beats {worse} once resolved")


if __name__ == "__main__":
    main()
