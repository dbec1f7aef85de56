#!/usr/bin/env bash
# The end-to-end demo on a bundled world: simulate a mapping run, build the map, fuse the depth
# camera into it and put the detected objects on it, linked into semantic chains, in one SLAM
# pass; score the trajectory against the simulator's truth, plan a route S -> P1 -> P2 on the fused map,
# relocalize from a few random starts with every method (a table), draw world, run, map (with
# objects and chains) and route as PNG, and one relocalization's particles converging.
#   scripts/demo.sh [OUTPUT_DIR [WORLD.yaml]]   (defaults: demo/, worlds/two_similar_rooms.yaml)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:-$root/demo}"
semchain="$root/build/apps/semchain"
world="${2:-$root/worlds/two_similar_rooms.yaml}"
mkdir -p "$out"

step() { printf '\n== %s\n' "$*"; }

step "simulate: $world -> $out/run"
"$semchain" simulate --world "$world" --out "$out/run" --seed 1
step "render the world and the run"
"$semchain" render "$world" --out "$out/world.png"
"$semchain" render "$out/run" --out "$out/run.png"
step "slam + depth fusion + semantic map, one pass: $out/run -> $out/map (map, trajectory, semantic.json, keyframes.json, semantic.png, semantic_growth.json)"
"$semchain" slam --log "$out/run/log.clf" --out "$out/map" --seed 1 --depth "$out/run" --semantic "$out/run"
step "eval ate: SLAM trajectory against the simulator's truth"
"$semchain" eval ate --poses "$out/map/trajectory.txt" --truth "$out/run/truth.txt" | tee "$out/ate.json"
step "vocab: the world's default bag-of-words vocabulary from the run's frames -> $out/map/vocab.bin"
"$semchain" vocab train --run "$out/run" --out "$out/map/vocab.bin" --seed 1
step "render the map (with its semantic objects and chains)"
"$semchain" render "$out/map" --out "$out/map.png"
# S, P1 and P2: where the robot was at the start, a third and two thirds of the mapping run
# (free space on every bundled world).
points=($(awk '$1 !~ /^#/ && NF == 4 { p[n++] = $2 "," $3 } END { print p[0], p[int(n / 3)], p[int(2 * n / 3)] }' \
  "$out/map/trajectory.txt"))
step "plan: ${points[0]} -> ${points[1]} -> ${points[2]} on the fused map"
"$semchain" plan --map "$out/map" --from "${points[0]}" --to "${points[1]};${points[2]}" \
  --out "$out/route.json" --png "$out/route.png"
step "bench reloc: 3 relocalization trials in $world, every method (table in $out/reloc/results.md)"
"$semchain" bench reloc --world "$world" --trials 3 --seed 1 \
  --methods amcl,semantic-amcl,semantic-scanmatch,scanmatch-global --out "$out/reloc"
# One trial drawn: the robot put down where the mapping run was a third of the way along (free
# space on every bundled world), turning in place and driving off; its particles converging.
start=$(awk '$1 !~ /^#/ && NF == 4 { p[n++] = $2 "," $3 "," $4 } END { print p[int(n / 3)] }' \
  "$out/run/truth.txt")
step "simulate a trial from $start, then localize it with semantic-amcl and amcl (PNGs)"
"$semchain" simulate --world "$world" --out "$out/trial" --seed 2 --route trial --start "$start"
for method in semantic-amcl amcl; do
  "$semchain" localize --map "$out/map" --run "$out/trial" --method "$method" \
    --out "$out/reloc_${method//-/_}.json" --png "$out/reloc_${method//-/_}.png"
done
step "done: pictures in $out"
ls -1 "$out"/*.png
