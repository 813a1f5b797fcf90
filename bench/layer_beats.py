#!/usr/bin/env python3
"""Does layout A beat layout B on every metric over scenes with material layers (issue 40)?
Reads a compare report over several scenes (report.json, schema gbufferlab-scene-suite: e.g. a
search's compare/ confirmation) and sets A beside B on every metric compare reports: FLIP and
tone-mapped PSNR (mean over the scenes), the attribute errors and the layer attributes' errors
(means over the scenes' pixels: pooled by count), and FLIP on each layer class's pixels (pooled
by pixel count). Prints each metric, which is better, per scene too, and the verdict: A beats B
when it is no worse on any metric, better on one, with no more bytes per pixel.

usage: bench/layer_beats.py SUITE/report.json A B"""
import json
import sys

ATTRS = ["normal", "base_color", "diffuse_color", "specular_color", "roughness", "metallic", "occlusion", "depth",
         "coat", "coat_roughness", "coat_normal", "sheen_color", "sheen_roughness", "anisotropy_strength",
         "anisotropy_direction"]
CLASSES = ["coated", "sheen", "anisotropic", "plain"]


def metrics(scenes, layout):
    per_scene, flip, psnr, attr, cls, nbytes = {}, [], [], {}, {}, None
    for s in scenes:
        rep = s["report"]
        mode = rep["run"]["ibl_modes"][0]
        run = next((r for r in rep["runs"] if r["layout"] == layout and r["ibl_mode"] == mode and r["status"] == "ok"), None)
        if run is None:
            sys.exit(f"{layout}: no run in scene {s['name']}")
        nbytes = run["bytes_per_pixel"]["total"]
        ie = run["image_errors"]
        m = {"FLIP": ie["flip_mean"], "PSNR dB": ie["psnr_tonemapped_db"]}
        flip.append(ie["flip_mean"])
        psnr.append(ie["psnr_tonemapped_db"])
        for a in ATTRS:
            e = run["attribute_errors"].get(a)
            if e and "all" in e:
                m[a] = e["all"]["mean"]
                attr.setdefault(a, []).append((e["all"]["count"], e["all"]["mean"]))
        for c in CLASSES:
            bc = ie.get("by_class", {}).get(c)
            if bc:
                m[f"FLIP {c}"] = bc["flip_mean"]
                cls.setdefault(c, []).append((bc["pixels"], bc["flip_mean"]))
        per_scene[s["name"]] = m
    pooled = lambda ps: sum(w * v for w, v in ps) / sum(w for w, _ in ps) if sum(w for w, _ in ps) else 0.0
    total = {"FLIP": sum(flip) / len(flip), "PSNR dB": sum(psnr) / len(psnr)}
    total.update({a: pooled(v) for a, v in attr.items()})
    total.update({f"FLIP {c}": pooled(v) for c, v in cls.items()})
    return nbytes, total, per_scene


def main():
    top = json.load(open(sys.argv[1]))
    a, b = sys.argv[2], sys.argv[3]
    scenes = [s for s in top["scenes"] if s["status"] == "ok"]
    ba, ta, sa = metrics(scenes, a)
    bb, tb, sb = metrics(scenes, b)
    print(f"{a} ({ba} B/px) against {b} ({bb} B/px) over {', '.join(s['name'] for s in scenes)}")
    print(f"| metric | {a} | {b} | better | scenes where {a} is worse |")
    print("|---|---|---|---|---|")
    worse = []
    for k in ta:
        if k not in tb:
            continue
        higher_better = k == "PSNR dB"
        va, vb = ta[k], tb[k]
        if va == vb:
            better = "equal"
        elif (va > vb) == higher_better:
            better = a
        else:
            better = b
            worse.append(k)
        lost = [n for n in sa if k in sa[n] and k in sb[n] and sa[n][k] != sb[n][k]
                and ((sa[n][k] < sb[n][k]) if higher_better else (sa[n][k] > sb[n][k]))]
        print(f"| {k} | {va:.5g} | {vb:.5g} | {better} | {', '.join(lost) or '-'} |")
    if ba <= bb and not worse:
        verdict = "beats" if any(ta[k] != tb[k] for k in ta if k in tb) else "equal"
    else:
        verdict = "does not beat"
    print(f"\nverdict (means over the scenes): {a} {verdict} {b}"
          + (f" (worse on: {', '.join(worse)})" if worse else "") + (f"; more bytes ({ba} > {bb})" if ba > bb else ""))


if __name__ == "__main__":
    main()
