#!/usr/bin/env python3
"""The verdicts of a compare report over several scenes (report.json, schema gbufferlab-scene-suite):
each scene's ranking with tied ranks, the ranking across the scenes, Kendall's tau between scenes,
and which statements hold on every scene.  usage: bench/suite_verdicts.py OUT/report.json"""
import json
import sys

top = json.load(open(sys.argv[1]))
scenes = [s for s in top["scenes"] if s["status"] == "ok"]
rows = top["summary"]["layouts"]
names = [s["name"] for s in top["scenes"]]
print("scenes:", ", ".join(f"{s['name']} (exposure {s['report']['run']['view_exposures'] or s['report']['run']['exposure']}, "
                           f"coverage {[round(c, 2) for c in s['report']['run']['view_coverage']]})" for s in scenes))
for i, name in enumerate(names):
    order = sorted((r for r in rows if r["per_scene"][i]["error"] is not None), key=lambda r: r["per_scene"][i]["error"])
    print(f"\n{name}: " + "; ".join(f"{r['per_scene'][i]['tied_rank']} {r['layout']} {r['per_scene'][i]['error']:.4f}"
                                     for r in order))
order = sorted((r for r in rows if r["mean_error"] is not None), key=lambda r: r["mean_error"])
print("\nacross: " + "; ".join(f"{r['tied_rank_across_scenes']} {r['layout']} {r['mean_error']:.4f} "
                              f"(mean rank {r['mean_rank']:.1f}, worst {r['worst_rank']})" for r in order))
for p in top["rank_agreement"]["pairs"]:
    print(f"\ntau {p['scene_a']}/{p['scene_b']}: {p['kendall_tau']:.3f}, {len(p['swapped_pairs'])} of {p['layout_pairs']} pairs swap")
# Which layouts store metallic (the atlas of any scene's report).
atlas = {a["layout"]: a for a in scenes[0]["report"]["atlas"]}
metallic = [l for l, a in atlas.items() if any(x["name"] == "metallic" for x in a["attributes"])]
for i, name in enumerate(names):
    errs = {r["layout"]: r["per_scene"][i]["error"] for r in rows if r["per_scene"][i]["error"] is not None}
    m = sorted((errs[l], l) for l in metallic if l in errs)
    best = min(errs, key=errs.get)
    worst = max(errs, key=errs.get)
    print(f"{name}: best {best}, worst {worst}; of those storing metallic the worst: {m[-1][1] if m else '-'}")
sig = top["significance_across_scenes"]["pairs"]
print(f"\nacross scenes: {sum(p['significant'] for p in sig)} of {len(sig)} pairs significant")
