#!/usr/bin/env bash
# vocab_cli_e2e.sh SEMCHAIN WORLD OUT: simulate a trial run, train a vocabulary on its frames,
# and query frame 000010 against a keyframe list of three of its frames.
set -euo pipefail
semchain="$1"
world="$2"
out="$3"
rm -rf "$out"
mkdir -p "$out/map"
"$semchain" simulate --world "$world" --out "$out/run" --seed 3 --route trial >/dev/null
"$semchain" vocab train --run "$out/run" --out "$out/vocab.bin" --k 6 --levels 3 --seed 1
cat >"$out/map/keyframes.json" <<JSON
{"version": 1, "run": "$out/run", "keyframes": [
 {"frame": "frames/000002", "stamp": 1.0, "pose": [0, 0, 0], "objects": []},
 {"frame": "frames/000010", "stamp": 5.0, "pose": [1, 0, 0], "objects": []},
 {"frame": "frames/000018", "stamp": 9.0, "pose": [2, 0, 0], "objects": []}]}
JSON
result="$("$semchain" vocab query --vocab "$out/vocab.bin" --map "$out/map" \
  --image "$out/run/frames/000010.png" --top 1)"
echo "$result"
grep -q "1. frames/000010 score 1.0000" <<<"$result"
