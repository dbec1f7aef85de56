#!/usr/bin/env bash
# localize_png.sh SEMCHAIN MAP RUN OUT.png: `localize --png` must write a PNG whose drawing has
# the map's aspect. The layout is that of apps/reloc_drawing.cc: a 30 px margin around the map
# (2 × 30 + 1 px in all) and a 380 px legend panel on the right.
set -euo pipefail
semchain="$1"
map="$2"
run="$3"
png="$4"
mkdir -p "$(dirname "$png")"
rm -f "$png"
"$semchain" localize --map "$map" --run "$run" --method amcl --png "$png" >/dev/null
[ -s "$png" ] || { echo "FAIL: $png was not written"; exit 1; }
# PNG: 8-byte signature, IHDR length and type, then width and height (big-endian).
read -r -a b < <(od -An -tu1 -j16 -N8 "$png")
width=$(((b[0] << 24) + (b[1] << 16) + (b[2] << 8) + b[3]))
height=$(((b[4] << 24) + (b[5] << 16) + (b[6] << 8) + b[7]))
# PGM: "P5", width, height (no comments in our maps).
read -r map_width map_height < <(sed -n 2p "$map/$(sed -n 's/^image: *//p' "$map/map.yaml")")
drawn_width=$((width - 380 - 61))
drawn_height=$((height - 61))
# Cells are square: drawn_width / drawn_height = map_width / map_height, to a pixel.
difference=$((drawn_width * map_height - drawn_height * map_width))
if [ "${difference#-}" -gt $((map_width + map_height)) ]; then
  echo "FAIL: ${width}x${height} PNG draws ${drawn_width}x${drawn_height} px for a ${map_width}x${map_height} map"
  exit 1
fi
echo "ok: ${width}x${height} PNG, map drawn ${drawn_width}x${drawn_height} px (${map_width}x${map_height} cells)"
