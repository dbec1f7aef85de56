#!/usr/bin/env bash
# The end-to-end demo on a bundled world: simulate a mapping run, build the map with SLAM,
# score it against the simulator's truth, and draw world, run and map as PNG.
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
step "slam: $out/run/log.clf -> $out/map"
"$semchain" slam --log "$out/run/log.clf" --out "$out/map" --seed 1
step "eval ate: SLAM trajectory against the simulator's truth"
"$semchain" eval ate --poses "$out/map/trajectory.txt" --truth "$out/run/truth.txt" | tee "$out/ate.json"
step "render the map"
"$semchain" render "$out/map" --out "$out/map.png"
step "done: pictures in $out"
ls -1 "$out"/*.png
