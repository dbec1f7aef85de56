#!/usr/bin/env bash
# `semchain detect` on models as ultralytics exports them (src/detection/testdata, written by
# tools/make_ultralytics_export.py: a narrow YOLOv8 with random weights and COCO's class names):
# the default export (decoded head, names in its metadata, no .names file) runs unchanged and
# writes the detections its raw-head export writes; the half-precision export finds the same;
# with --class-map config/classes/coco.yaml every detection is of a semchain class, and a map of
# the two classes the model finds most to "chair" gives chairs only, merged by the NMS.
#   ultralytics_export.sh SEMCHAIN SOURCE_DIR WORK
set -euo pipefail
semchain="$1"
source_dir="$2"
work="$3"
rm -rf "$work"
models="$source_dir/src/detection/testdata"
images="$source_dir/tests/data/detector_reference"
for model in raw decoded decoded_fp16; do
  "$semchain" detect --model "$models/ultralytics_$model.onnx" --images "$images" --conf 0.1 \
    --out "$work/$model" >/dev/null 2>&1
done
"$semchain" detect --model "$models/ultralytics_decoded.onnx" --images "$images" --conf 0.1 \
  --class-map "$source_dir/config/classes/coco.yaml" --out "$work/coco" >/dev/null 2>&1
/usr/bin/python3 - "$work" <<'PY'
import collections, json
import sys
frames = [json.loads(line) for line in open(f"{sys.argv[1]}/decoded/detections.jsonl")]
counts = collections.Counter(d["class"] for f in frames for d in f["detections"])
with open(f"{sys.argv[1]}/two_to_chair.yaml", "w") as out:
    out.write("".join(f"'{name}': chair\n" for name, _ in counts.most_common(2)))
PY
"$semchain" detect --model "$models/ultralytics_decoded.onnx" --images "$images" --conf 0.1 \
  --class-map "$work/two_to_chair.yaml" --out "$work/mapped" >/dev/null 2>&1
"$semchain" detect --model "$models/ultralytics_decoded.onnx" --images "$images" --conf 0.1 \
  --nms 1 --out "$work/unsuppressed" >/dev/null 2>&1
/usr/bin/python3 - "$work" <<'PY'
import json, sys
import yaml

def read(name):
    frames = [json.loads(line) for line in open(f"{sys.argv[1]}/{name}/detections.jsonl")]
    return [(f["frame"], d) for f in frames for d in f["detections"]]

raw, decoded, half, coco, mapped, unsuppressed = (
    read(n) for n in ("raw", "decoded", "decoded_fp16", "coco", "mapped", "unsuppressed"))
assert len(raw) >= 10, f"only {len(raw)} detections: the comparison would compare little"
assert len(decoded) == len(raw), f"decoded export: {len(decoded)} detections, raw: {len(raw)}"
for (frame_a, a), (frame_b, b) in zip(raw, decoded):
    assert frame_a == frame_b and a["class"] == b["class"], (frame_a, a, b)
    assert max(abs(p - q) for p, q in zip(a["box"], b["box"])) < 1e-3, (frame_a, a, b)
    assert abs(a["score"] - b["score"]) < 1e-5, (frame_a, a, b)
# Half precision: the confident detections are found again, nearly where they were.
for frame, d in decoded:
    if d["score"] < 0.15:
        continue
    assert any(f == frame and e["class"] == d["class"] and
               max(abs(p - q) for p, q in zip(d["box"], e["box"])) < 1.0 for f, e in half), (frame, d)
semchain = {"chair", "sofa", "bed", "table", "computer", "clock"}
assert all(d["class"] in semchain for _, d in coco), [d["class"] for _, d in coco]
two = set(yaml.safe_load(open(f"{sys.argv[1]}/two_to_chair.yaml")))
of_two = [(f, d) for f, d in decoded if d["class"] in two]
assert mapped and all(d["class"] == "chair" for _, d in mapped), [d["class"] for _, d in mapped]
# Each chair is one of the two classes' boxes (before NMS); they are fewer than the two classes
# keep apart: overlapping boxes of the two are merged.
for frame, chair in mapped:
    assert any(f == frame and d["class"] in two and d["box"] == chair["box"]
               for f, d in unsuppressed), (frame, chair)
assert len(mapped) < len(of_two), (len(mapped), len(of_two))
print(f"ok: {len(raw)} detections the same; {len(of_two)} of {sorted(two)} -> {len(mapped)} chairs")
PY
