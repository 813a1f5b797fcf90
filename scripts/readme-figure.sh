#!/usr/bin/env bash
# Makes the README's figure, docs/images/readme-crops.png, from a real comparison: the built-in
# scene's row of coloured spheres (gold and copper metals, red-tinted dielectrics) at 960x540, one view, as the float
# reference renders it, as crysis3-thin renders it (Crysis 3 stored specular luminance only, so
# coloured highlights turn grey), and crysis3-thin's FLIP map. Needs build/gbufferlab
# (scripts/run.sh builds it).
set -euo pipefail
cd "$(dirname "$0")/.."
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
build/gbufferlab compare --scene builtin --layouts crysis3-thin --size 960x540 --views 1 --out "$out/run" >/dev/null
run="$out/run/runs/crysis3-thin/split-sum"
# flip.png carries a title band above the map: the same crop sits that many rows lower.
title=$(python3 -c 'import struct, sys
h = lambda f: struct.unpack(">I", open(f, "rb").read()[20:24])[0]
print(h(sys.argv[1]) - h(sys.argv[2]))' "$run/flip.png" "$run/render.png")
box="280,290,440,80"
mkdir -p docs/images
python3 scripts/png_strip.py docs/images/readme-crops.png \
  "$out/run/reference-split-sum.png:$box" "$run/render.png:$box" "$run/flip.png:280,$((290 + title)),440,80" \
  --vertical --gap 4
echo "docs/images/readme-crops.png"
