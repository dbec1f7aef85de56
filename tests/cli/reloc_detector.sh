#!/usr/bin/env bash
# `bench reloc --detector`: the ONNX model's detections on the rendered frames (the mapping
# run's and every trial's) replace the simulator's. The tiny test model recognises the pure
# red, green and blue boxes of tests/data/coloured_boxes.yaml.
#   reloc_detector.sh SEMCHAIN SOURCE_DIR WORK
set -euo pipefail
semchain="$1"
source_dir="$2"
work="$3"
rm -rf "$work"
mkdir -p "$work"
model="$source_dir/src/detection/testdata/tiny_squares_raw.onnx"
"$semchain" bench reloc --world "$source_dir/tests/data/coloured_boxes.yaml" --trials 3 --seed 2 \
  --methods semantic-amcl,semantic-scanmatch --detector "$model" --out "$work/reloc" >/dev/null
/usr/bin/python3 - "$work/reloc/results.json" "$model" <<'PY'
import json, sys
results = json.load(open(sys.argv[1]))
assert results["detections"] == sys.argv[2], results["detections"]
assert results["map_objects"] == 3, f"the model's detections mapped {results['map_objects']} objects, not 3"
for name in ("semantic-amcl", "semantic-scanmatch"):
    method = results["methods"][name]
    # Pre-localization needs the model's detections in the trials.
    assert method["prelocalized"] == 3, f"{name}: pre-localized {method['prelocalized']} of 3 trials"
    assert method["successes"] >= 2, f"{name}: {method['successes']} of 3 trials"
    for run in results["runs"][name]:
        assert run["cpu_ms"] > 0 and run["time_s"] > 0, f"{name}: trial {run['trial']} charged nothing"
print("ok")
PY
grep -q "detections: $model" "$work/reloc/results.md"

# localize --detector: a map made from the model's detections, a trial relocalized from them.
world="$source_dir/tests/data/coloured_boxes.yaml"
"$semchain" simulate --world "$world" --seed 2 --out "$work/run" >/dev/null 2>&1
"$semchain" slam --log "$work/run/log.clf" --semantic "$work/run" --detector "$model" \
  --out "$work/map" >/dev/null 2>&1
"$semchain" simulate --world "$world" --seed 5 --route trial --start 3,2,1.0 \
  --out "$work/trial" >/dev/null 2>&1
# The trial's simulator detections are removed: only the model can supply objects.
rm "$work/trial/detections.jsonl"
"$semchain" localize --map "$work/map" --run "$work/trial" --method semantic-amcl \
  --detector "$model" --out "$work/localize.json" >/dev/null 2>&1
/usr/bin/python3 - "$work/localize.json" <<'PY'
import json, sys
result = json.load(open(sys.argv[1]))
assert result["prelocalizations"] > 0, "no pre-localization from the model's detections"
assert result["localized"] and result["error_m"] < 0.25 and result["error_deg"] < 10, result
print("ok")
PY
