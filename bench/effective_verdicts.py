#!/usr/bin/env python3
"""Bandwidth as GPUs pay it, from compare reports (issue 44's verdicts; docs/bandwidth.md): per
scene and layout, nominal against effective bytes per pixel and 1080p60 traffic per GPU class and
the tile families it fits; the best layout per budget under each class's bytes and which change
against the nominal ranking (report.json's effective_bandwidth and bandwidth_as_paid); then across
the scenes: the layouts each tile budget holds, and a dithered layout against its copy without the
dither (--pair A,B: per target, the effective bytes of A over B's).

usage: bench/effective_verdicts.py [--pair DITHERED,PLAIN] REPORT.json [REPORT.json ...]
       (a scene's report.json, or a suite's: each of its scenes is read)
"""
import json
import sys

CLASSES = ("desktop-dcc", "mali-afbc", "tile-subpass")


def scene_reports(path):
    """(scene name, report) for a scene's report.json, or for each scene of a suite's."""
    j = json.load(open(path))
    if j.get("schema") == "gbufferlab-scene-suite":
        for s in j["scenes"]:
            if s.get("status") == "ok" and "report" in s:
                yield s["name"], s["report"]
    else:
        yield j["run"].get("scene", path), j


def measured_runs(report):
    """The runs of the first IBL mode that carry effective_bandwidth, by layout."""
    mode = report["run"]["ibl_modes"][0]
    return {r["layout"]: r for r in report["runs"] if r.get("effective_bandwidth") and r["ibl_mode"] == mode}


def scene_tables(name, report):
    run = report["run"]
    runs = measured_runs(report)
    print(f"## {name} ({run['width']}x{run['height']}, {run.get('views', 1)} views, lighting {run.get('lighting', 'tiled')})")
    print()
    print("| layout | nominal B/px | GB/s | desktop-dcc B/px | GB/s | mali-afbc B/px | GB/s | tile-subpass B/px | GB/s | fits tile memory of | FLIP |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for layout, r in sorted(runs.items(), key=lambda kv: kv[1]["effective_bandwidth"]["nominal_bytes_per_pixel"]):
        e = r["effective_bandwidth"]
        c = {x["class"]: x for x in e["classes"]}
        fits = " ".join(f["family"] for f in e["tile_memory"] if f["fits"]) or "none"
        flip = r.get("image_errors", {}).get("flip_mean")
        cells = " | ".join(f"{c[k]['bytes_per_pixel']:.1f} | {c[k]['gb_per_s_1080p60']:.2f}" for k in CLASSES)
        flip_cell = f"{flip:.4f}" if flip is not None else "-"
        print(f"| {layout} | {e['nominal_bytes_per_pixel']:.0f} | {e['nominal_gb_per_s_1080p60']:.2f} | {cells} | {fits} | {flip_cell} |")
    b = report.get("bandwidth_as_paid")
    if b:
        print()
        print("Best layout (lowest mean FLIP) whose bytes fit the budget, per class:")
        print()
        print("| budget B/px | " + " | ".join(v["class"] for v in b["verdicts"]) + " |")
        print("|---|" + "---|" * len(b["verdicts"]))
        for i in range(len(b["verdicts"][0]["budgets"])):
            budget = b["verdicts"][0]["budgets"][i]["budget_bytes_per_pixel"]
            cells = []
            for v in b["verdicts"]:
                line = v["budgets"][i]
                cells.append(f"{line['best']} ({line['bytes_per_pixel']:.1f})" if line.get("best") else "none fits")
            print(f"| {budget} | " + " | ".join(cells) + " |")
        print()
        for c in b["changes"] or ["no budget's best layout changes under any class"]:
            print(f"- {c}")
    print()
    return runs


def scene_table(per_scene, title, nominal_header, layouts, cell):
    """One row per layout, one column per scene: cell(classes by name, nominal B/px) of its run."""
    names = list(per_scene)
    print(title)
    print()
    print(f"| layout | {nominal_header} | " + " | ".join(names) + " |")
    print("|---|---|" + "---|" * len(names))
    for l in layouts:
        cells, nominal = [], None
        for n in names:
            r = per_scene[n].get(l)
            if not r:
                cells.append("-")
                continue
            e = r["effective_bandwidth"]
            nominal = e["nominal_bytes_per_pixel"]
            cells.append(cell({x["class"]: x for x in e["classes"]}, nominal))
        print(f"| {l} | {nominal:.0f} | " + " | ".join(cells) + " |")
    print()


def bytes_table(per_scene):
    """Nominal against effective bytes per pixel per class, every scene in one table."""
    layouts = sorted({l for runs in per_scene.values() for l in runs},
                     key=lambda l: (next(runs[l]["effective_bandwidth"]["nominal_bytes_per_pixel"]
                                         for runs in per_scene.values() if l in runs), l))
    scene_table(per_scene, "## Nominal against effective B/px (desktop-dcc / mali-afbc / tile-subpass), per scene",
                "nominal", layouts,
                lambda c, nominal: " / ".join(f"{c[k]['bytes_per_pixel']:.1f}" for k in CLASSES))


def tile_budgets(per_scene):
    """Which layouts fit each tile family's colour storage (the same on every scene: it is bytes)."""
    families = {}
    for runs in per_scene.values():
        for layout, r in runs.items():
            for f in r["effective_bandwidth"]["tile_memory"]:
                d = families.setdefault(f["family"], {"limit": f["limit_bytes_per_pixel"], "fit": set(), "not": {}})
                if f["fits"]:
                    d["fit"].add(layout)
                else:
                    d["not"][layout] = f"{f['colour_bytes_per_pixel']} B/px, {f['overflow']}"
    print("## Tile budgets (colour targets + light buffers + the lit output, against each family's limit)")
    print()
    for fam, d in families.items():
        print(f"- **{fam}** ({d['limit']} B/px): fit {len(d['fit'])}: {', '.join(sorted(d['fit'])) or 'none'}; "
              f"do not fit {len(d['not'])}: " + (", ".join(f"{k} ({v})" for k, v in sorted(d["not"].items())) or "none"))
    print()


def ratio_table(per_scene):
    """Effective over nominal G-buffer bytes per class, per layout and scene (depth included)."""
    layouts = sorted({l for runs in per_scene.values() for l in runs})
    scene_table(per_scene, "## Effective over nominal bytes per pixel (desktop-dcc / mali-afbc), per scene",
                "nominal B/px", layouts,
                lambda c, nominal: f"{c['desktop-dcc']['bytes_per_pixel'] / nominal:.2f} / "
                                   f"{c['mali-afbc']['bytes_per_pixel'] / nominal:.2f}")


def pair(per_scene, a, b):
    print(f"## {a} against {b} (per target: nominal B/px; desktop-dcc B/px; mali-afbc write B/px)")
    print()
    for n, runs in per_scene.items():
        if a not in runs or b not in runs:
            print(f"- {n}: {a if a not in runs else b} not measured")
            continue
        ea, eb = runs[a]["effective_bandwidth"], runs[b]["effective_bandwidth"]
        ta = {t["name"]: t for t in ea["targets"]}
        tb = {t["name"]: t for t in eb["targets"]}
        parts = []
        for t in ta:
            if t not in tb:
                continue
            x, y = ta[t], tb[t]
            parts.append(f"{t} {x['bytes_per_pixel']} B/px: dcc {x['desktop_dcc_bytes_per_pixel']:.2f} vs {y['desktop_dcc_bytes_per_pixel']:.2f} "
                         f"({x['desktop_dcc_bytes_per_pixel'] / y['desktop_dcc_bytes_per_pixel']:.2f}x), afbc "
                         f"{x['mali_afbc_write_bytes_per_pixel']:.2f} vs {y['mali_afbc_write_bytes_per_pixel']:.2f} "
                         f"({x['mali_afbc_write_bytes_per_pixel'] / y['mali_afbc_write_bytes_per_pixel']:.2f}x)")
        ca = {x["class"]: x for x in ea["classes"]}
        cb = {x["class"]: x for x in eb["classes"]}
        whole = "; ".join(f"{k} {ca[k]['bytes_per_pixel']:.2f} vs {cb[k]['bytes_per_pixel']:.2f} B/px" for k in CLASSES[:2])
        fa = runs[a].get("image_errors", {}).get("flip_mean")
        fb = runs[b].get("image_errors", {}).get("flip_mean")
        flips = f"; FLIP {fa:.4f} vs {fb:.4f}" if fa is not None and fb is not None else ""
        print(f"- {n}: " + "; ".join(parts) + f"; whole layout {whole}{flips}")
    print()


def main(argv):
    pairs = []
    while argv and argv[0] == "--pair":
        pairs.append(argv[1].split(","))
        argv = argv[2:]
    if not argv:
        sys.exit(__doc__.strip().splitlines()[-2].strip())
    per_scene = {}
    for path in argv:
        for name, report in scene_reports(path):
            per_scene[name] = scene_tables(name, report)
    bytes_table(per_scene)
    ratio_table(per_scene)
    tile_budgets(per_scene)
    for a, b in pairs:
        pair(per_scene, a, b)


if __name__ == "__main__":
    main(sys.argv[1:])
