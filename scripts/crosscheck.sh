#!/usr/bin/env bash
# The reference against an independent renderer (issue 45; docs/crosscheck.md): each glTF rendered
# through gbufferlab's float reference and through the Khronos glTF Sample Viewer
# (tools/gltf-viewer/render.mjs) with the same camera, punctual lights and exposure, then compared
# where both drew geometry (`gbufferlab crossdiff`).
#
# Usage: scripts/crosscheck.sh [--brdf gltf|ue4] [--base-level | --nearest] [--ibl ENV.hdr] [--size WxH] [--tolerance X] --out DIR MODEL...
#   MODEL       a .gltf/.glb path, or a model name under ../shared/assets/models (WaterBottle, ...)
#   --brdf      gbufferlab's direct-light BRDF (default gltf: the specification's, like for like)
#   --base-level  both renderers sample every texture at its base level, bilinear (the viewer a
#               copy of the model whose samplers say minFilter LINEAR, gbufferlab
#               --texture-base-level): no mip, anisotropy or footprint differences
#   --nearest   the same at the nearest texel (samplers NEAREST, gbufferlab --texture-nearest): no
#               bilinear weights either, whose last bits differ between any two renderers
#   --ibl       also light by this equirectangular environment (default: punctual lights only)
#   --size      frame size (default 320x180)
#   --tolerance crossdiff's per-pixel tolerance (default 1e-3)
# Writes DIR/<model>/{job.json, ref/, viewer.pfm, viewer.mask.pgm, diff/, metrics.json} and
# DIR/summary.json, DIR/summary.csv (one row per model). Exit 0 when every model ran; 2 for bad
# arguments; 3 when a renderer failed (its message names the model).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
gbl="${GBL_BIN:-$root/build/gbufferlab}"
assets="${GBL_SHARED_ASSETS:-$root/../shared/assets}"
brdf=gltf ibl="" size=320x180 tolerance=1e-3 out="" baselevel=0 filter=9729
models=()
die() { echo "crosscheck.sh: $1" >&2; exit "${2:-2}"; }
while [ $# -gt 0 ]; do
  case "$1" in
    --base-level) baselevel=1; shift ;;
    --nearest) baselevel=1 filter=9728; shift ;;
    --brdf) [ $# -ge 2 ] || die "--brdf needs gltf or ue4"; brdf="$2"; shift 2 ;;
    --ibl) [ $# -ge 2 ] || die "--ibl needs an equirectangular .hdr"; ibl="$2"; shift 2 ;;
    --size) [ $# -ge 2 ] || die "--size needs WxH, e.g. 320x180"; size="$2"; shift 2 ;;
    --tolerance) [ $# -ge 2 ] || die "--tolerance needs a number, e.g. 1e-3"; tolerance="$2"; shift 2 ;;
    --out) [ $# -ge 2 ] || die "--out needs a directory"; out="$2"; shift 2 ;;
    -h|--help) sed -n '2,20p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    -*) die "unknown flag $1 (see --help)" ;;
    *) models+=("$1"); shift ;;
  esac
done
[ -n "$out" ] || die "give --out DIR"
[ ${#models[@]} -gt 0 ] || die "give at least one MODEL (a .gltf path or a name such as WaterBottle)"
case "$brdf" in gltf|ue4) ;; *) die "--brdf $brdf: give gltf or ue4" ;; esac
[ -x "$gbl" ] || die "$gbl: not built; run scripts/setup.sh first (or set GBL_BIN)"
[ -z "$ibl" ] || [ -f "$ibl" ] || die "--ibl $ibl: no such file"
command -v node > /dev/null || die "node is not installed; scripts/setup.sh --tests installs it" 3
[ -d "$root/tools/gltf-viewer/node_modules/@khronosgroup/gltf-viewer" ] ||
  die "tools/gltf-viewer/node_modules is missing; run scripts/setup.sh --tests (it runs npm ci there)" 3
mkdir -p "$out"
out="$(cd "$out" && pwd)"
rows=()
for m in "${models[@]}"; do
  if [ -f "$m" ]; then model="$(cd "$(dirname "$m")" && pwd)/$(basename "$m")"
  else model="$(ls "$assets/models/$m/$m.gltf" "$assets/models/$m/glTF/$m.gltf" 2>/dev/null | head -1 || true)"; fi
  [ -n "$model" ] && [ -f "$model" ] || die "$m: no such model (a .gltf path, or a folder of $assets/models)"
  name="$(basename "${model%.*}")"
  dir="$out/$name"
  rm -rf "$dir"
  mkdir -p "$dir"
  envflags=(--no-ibl)
  [ -z "$ibl" ] || envflags=(--env "$ibl")
  scene="$model"
  if [ "$baselevel" = 1 ]; then
    # A copy beside links to the model's files, every texture on one sampler without mips.
    mkdir -p "$dir/model"
    python3 - "$model" "$dir/model" "$filter" <<'PY'
import json, os, sys
src, dst, filt = sys.argv[1], sys.argv[2], int(sys.argv[3])
folder = os.path.dirname(src)
for f in os.listdir(folder):
    if f != os.path.basename(src):
        os.symlink(os.path.join(folder, f), os.path.join(dst, f))
g = json.load(open(src))
if g.get("textures"):
    g["samplers"] = [{"magFilter": filt, "minFilter": filt, "wrapS": 10497, "wrapT": 10497}]
    for t in g["textures"]:
        t["sampler"] = 0
json.dump(g, open(os.path.join(dst, os.path.basename(src)), "w"))
PY
    scene="$dir/model/$(basename "$model")"
    envflags+=(--texture-base-level --allow-outside-scene)
    [ "$filter" = 9729 ] || envflags+=(--texture-nearest)
  fi
  t0=$(date +%s.%N)
  "$gbl" render --scene "$scene" "${envflags[@]}" --size "$size" --brdf "$brdf" --viewer-job "$dir/job.json" \
    --out "$dir/ref" > "$dir/render.log" 2>&1 || { cat "$dir/render.log" >&2; die "$name: gbufferlab render failed" 3; }
  t1=$(date +%s.%N)
  node "$root/tools/gltf-viewer/render.mjs" "$dir/job.json" > "$dir/viewer.log" 2>&1 ||
    { cat "$dir/viewer.log" >&2; die "$name: the Sample Viewer failed (tools/gltf-viewer/render.mjs)" 3; }
  t2=$(date +%s.%N)
  "$gbl" crossdiff "$dir/ref/reference.exr" "$dir/ref/reference.mask.pgm" "$dir/viewer.pfm" "$dir/viewer.mask.pgm" \
    --tolerance "$tolerance" --out "$dir/diff" --json > "$dir/metrics.json"
  rows+=("$name $dir/metrics.json $(awk "BEGIN{print $t1 - $t0}") $(awk "BEGIN{print $t2 - $t1}")")
  echo "$name: $(python3 -c "import json,sys; m=json.load(open(sys.argv[1])); print('relative RMSE %.3e (8x8 means %.3e), max relative %.3e, %d of %d covered pixels beyond %g, HDR-FLIP mean %.5f' % (m['relative_rmse'], m['box_relative_rmse'], m['max_relative'], m['beyond_tolerance_pixels'], m['covered_pixels'], m['tolerance'], m['hdr_flip_mean']))" "$dir/metrics.json")"
done
python3 - "$out" "$brdf" "$size" "${ibl:-none}" "$baselevel" "$filter" "${rows[@]}" <<'PY'
import csv, json, sys
out, brdf, size, ibl, rows = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[7:]
models = []
for r in rows:
    name, path, tr, tv = r.split(" ")
    m = json.load(open(path))
    m.update(model=name, gbufferlab_seconds=float(tr), viewer_seconds=float(tv))
    models.append(m)
json.dump({"brdf": brdf, "size": size, "ibl": ibl, "base_level": sys.argv[5] == "1", "nearest": sys.argv[6] == "9728", "models": models}, open(out + "/summary.json", "w"), indent=2)
keys = ["model", "covered_pixels", "only_reference_pixels", "only_test_pixels", "mean_reference_luminance",
        "mean_test_luminance", "relative_rmse", "box_relative_rmse", "max_relative", "max_abs", "beyond_tolerance_pixels", "tolerance", "hdr_flip_mean",
        "hdr_flip_max", "gbufferlab_seconds", "viewer_seconds"]
with open(out + "/summary.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(keys)
    for m in models:
        w.writerow([m[k] for k in keys])
PY
echo "summary: $out/summary.json, $out/summary.csv"
