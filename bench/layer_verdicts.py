#!/usr/bin/env python3
"""The material layers' verdicts (issue 40) from a compare report over scenes with layers
(report.json, schema gbufferlab-scene-suite), optionally against the same layouts' report over
scenes without layers (the default suite).

Per layout: bytes per pixel; mean FLIP over the scenes; the LDR-FLIP of each layer class
(coated, sheen, anisotropic, plain: image_errors.by_class, pooled over the scenes by pixel
count); the layer attributes' mean errors (pooled by count); per scene the tied rank within each
class (significance_by_class). Then the rankings: by FLIP over the layered scenes, and by each
class's FLIP, each against the ranking over the plain scenes, with Kendall's tau-b and the layouts
that move most.

usage: bench/layer_verdicts.py LAYERS/report.json [PLAIN/report.json]"""
import json
import sys

CLASSES = ["coated", "sheen", "anisotropic", "plain"]
LAYER_ATTRS = [("coat", "coat"), ("coat_roughness", "coat r"), ("coat_normal", "coat n deg"),
               ("sheen_color", "sheen dE"), ("sheen_roughness", "sheen r"),
               ("anisotropy_strength", "aniso s"), ("anisotropy_direction", "aniso dir deg")]


def scene_reports(path):
    top = json.load(open(path))
    return top, [s for s in top["scenes"] if s["status"] == "ok"]


def first_mode(report):
    return report["run"]["ibl_modes"][0]


def layout_runs(report):
    mode = first_mode(report)
    return {r["layout"]: r for r in report["runs"] if r["ibl_mode"] == mode and r["status"] == "ok"
            and " vs " not in r["layout"]}


def pooled(pairs):
    """Mean of (weight, value) pairs weighted by weight; None without weight."""
    w = sum(p[0] for p in pairs)
    return sum(p[0] * p[1] for p in pairs) / w if w else None


def kendall_tau_b(a, b):
    """tau-b between two {layout: value} maps over their common layouts (lower value = better)."""
    keys = sorted(set(a) & set(b))
    conc = disc = ta = tb = 0
    for i in range(len(keys)):
        for j in range(i + 1, len(keys)):
            da = a[keys[i]] - a[keys[j]]
            db = b[keys[i]] - b[keys[j]]
            if da == 0 and db == 0:
                continue
            if da == 0:
                ta += 1
            elif db == 0:
                tb += 1
            elif (da > 0) == (db > 0):
                conc += 1
            else:
                disc += 1
    denom = ((conc + disc + ta) * (conc + disc + tb)) ** 0.5
    return (conc - disc) / denom if denom else None, len(keys)


def ranks(values):
    """Plain rank: 1 + layouts of lower value."""
    return {k: 1 + sum(1 for w in values.values() if w < v) for k, v in values.items()}


def fmt(x, digits=4):
    return "-" if x is None else f"{x:.{digits}f}"


def main():
    top, scenes = scene_reports(sys.argv[1])
    names = [s["name"] for s in scenes]
    per_layout = {}
    for s in scenes:
        rep = s["report"]
        for name, run in layout_runs(rep).items():
            d = per_layout.setdefault(name, {"bytes": run["bytes_per_pixel"]["total"], "flip": [],
                                             "cls": {c: [] for c in CLASSES},
                                             "attr": {a: [] for a, _ in LAYER_ATTRS}, "tied": {}})
            d["flip"].append(run["image_errors"]["flip_mean"])
            by_class = run["image_errors"].get("by_class", {})
            for c in CLASSES:
                if c in by_class:
                    d["cls"][c].append((by_class[c]["pixels"], by_class[c]["flip_mean"]))
            for a, _ in LAYER_ATTRS:
                e = run["attribute_errors"].get(a)
                if e and "all" in e:
                    d["attr"][a].append((e["all"]["count"], e["all"]["mean"]))
        for c, sig in rep.get("significance_by_class", {}).items():
            for r in sig["ranks"]:
                if r["ibl_mode"] == first_mode(rep) and r["layout"] in per_layout:
                    per_layout[r["layout"]]["tied"][(s["name"], c)] = r["tied_rank"]
    complete = {k: v for k, v in per_layout.items() if len(v["flip"]) == len(scenes)}
    mean_flip = {k: sum(v["flip"]) / len(v["flip"]) for k, v in complete.items()}
    cls_flip = {c: {k: pooled(v["cls"][c]) for k, v in complete.items() if pooled(v["cls"][c]) is not None}
                for c in CLASSES}
    pixels = {c: {s["name"]: 0 for s in scenes} for c in CLASSES}
    for s in scenes:
        runs = layout_runs(s["report"])
        if runs:
            bc = next(iter(runs.values()))["image_errors"].get("by_class", {})
            for c in CLASSES:
                pixels[c][s["name"]] = bc.get(c, {}).get("pixels", 0)
    print(f"scenes: {', '.join(names)}; IBL mode {first_mode(scenes[0]['report'])}")
    for s in scenes:
        notes = [n for n in s["report"]["run"]["notes"] if "forward" in n]
        print(f"  {s['name']}: class pixels " + ", ".join(f"{c} {pixels[c][s['name']]}" for c in CLASSES)
              + (f"; {notes[0]}" if notes else ""))
    print("\n| layout | B/px | FLIP (mean of scenes) | coated | sheen | anisotropic | plain | "
          + " | ".join(label for _, label in LAYER_ATTRS) + " |")
    print("|---" * (7 + len(LAYER_ATTRS)) + "|")
    for k in sorted(complete, key=lambda k: (complete[k]["bytes"], mean_flip[k])):
        v = complete[k]
        print(f"| {k} | {v['bytes']} | {fmt(mean_flip[k])} | "
              + " | ".join(fmt(cls_flip[c].get(k)) for c in CLASSES) + " | "
              + " | ".join(fmt(pooled(v["attr"][a]), 3) for a, _ in LAYER_ATTRS) + " |")
    print("\nTied ranks within each class, per scene (significance_by_class; scene: coated/sheen/anisotropic/plain):")
    for k in sorted(complete, key=lambda k: mean_flip[k]):
        cells = []
        for s in names:
            cells.append(s + " " + "/".join(complete[k]["tied"].get((s, c), "-") for c in CLASSES))
        print(f"  {k}: " + "; ".join(cells))
    for c in CLASSES:
        order = sorted(cls_flip[c], key=cls_flip[c].get)
        print(f"\n{c} (pooled FLIP): " + "; ".join(f"{i + 1} {k} {cls_flip[c][k]:.4f} ({complete[k]['bytes']} B)"
                                                 for i, k in enumerate(order)))
    order = sorted(mean_flip, key=mean_flip.get)
    print("\nlayered scenes (mean FLIP): " + "; ".join(f"{i + 1} {k} {mean_flip[k]:.4f}" for i, k in enumerate(order)))
    ra = top.get("rank_agreement", {})
    if ra.get("in_words"):
        print(f"\nwithin the layered suite: mean tau {ra['in_words']['mean_kendall_tau']:.3f}; {ra['in_words']['sentence']}")
    for p in ra.get("pairs", []):
        print(f"  tau {p['scene_a']}/{p['scene_b']}: {p['kendall_tau']:.3f} ({len(p['swapped_pairs'])} of {p['layout_pairs']} pairs swap)")
    if len(sys.argv) > 2:
        ptop, pscenes = scene_reports(sys.argv[2])
        prow = {r["layout"]: r["mean_error"] for r in ptop["summary"]["layouts"]
                if r["mean_error"] is not None and r["scenes_measured"] == len(pscenes)
                and r["ibl_mode"] == first_mode(pscenes[0]["report"])}
        print(f"\nplain scenes ({', '.join(s['name'] for s in pscenes)}), mean FLIP: "
              + "; ".join(f"{i + 1} {k} {prow[k]:.4f}" for i, k in enumerate(sorted(prow, key=prow.get))))
        for label, vals in [("layered scenes, all pixels", mean_flip)] + [(f"layered, {c} pixels", cls_flip[c]) for c in CLASSES]:
            common = {k: v for k, v in vals.items() if k in prow}
            if len(common) < 2:
                continue
            tau, n = kendall_tau_b(common, prow)
            ra_, rp = ranks(common), ranks({k: prow[k] for k in common})
            moves = sorted(common, key=lambda k: -abs(ra_[k] - rp[k]))[:6]
            print(f"\n{label} vs plain scenes: Kendall tau-b {fmt(tau, 3)} over {n} layouts; largest moves: "
                  + ", ".join(f"{k} {rp[k]} -> {ra_[k]}" for k in moves))
        only = sorted(set(mean_flip) - set(prow))
        if only:
            print("layouts only in the layered report: " + ", ".join(only))


if __name__ == "__main__":
    main()
