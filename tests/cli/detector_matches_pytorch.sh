#!/usr/bin/env bash
# The C++ detector (OpenCV DNN on the exported ONNX) gives the boxes PyTorch gives on the same
# images: models/detector.onnx against tests/data/detector_reference/boxes.json, written by
#   cd train && /usr/bin/python3 -m semchain_train.reference_boxes --model ../models/detector.onnx --torch-scale n \
#     --images ../tests/data/detector_reference --out ../tests/data/detector_reference/boxes.json \
#     --conf 0.02
# (the export's own weights, half precision included, run in PyTorch; models/README.md).
#   detector_matches_pytorch.sh SEMCHAIN SOURCE_DIR WORK
set -euo pipefail
semchain="$1"
source_dir="$2"
work="$3"
rm -rf "$work"
reference="$source_dir/tests/data/detector_reference"
"$semchain" detect --model "$source_dir/models/detector.onnx" --images "$reference" \
  --conf 0.02 --out "$work" >/dev/null 2>&1
/usr/bin/python3 - "$reference/boxes.json" "$work/detections.jsonl" <<'PY'
import json, sys

def iou(a, b):
    w = max(0.0, min(a[2], b[2]) - max(a[0], b[0]))
    h = max(0.0, min(a[3], b[3]) - max(a[1], b[1]))
    inter = w * h
    union = (a[2] - a[0]) * (a[3] - a[1]) + (b[2] - b[0]) * (b[3] - b[1]) - inter
    return inter / union if union > 0 else 0.0

reference = json.load(open(sys.argv[1]))
cpp = {}
for line in open(sys.argv[2]):
    record = json.loads(line)
    cpp[record["frame"]] = record["detections"]
compared = 0
for image in reference["images"]:
    name = image["image"].rsplit(".", 1)[0]
    theirs = sorted(image["detections"], key=lambda d: -d["score"])
    ours = sorted(cpp.get(name, []), key=lambda d: -d["score"])
    assert len(ours) == len(theirs), f"{name}: C++ {len(ours)} boxes, PyTorch {len(theirs)}"
    for a, b in zip(ours, theirs):
        assert a["class"] == b["class"], f"{name}: class {a['class']} vs {b['class']}"
        assert abs(a["score"] - b["score"]) < 1e-3, f"{name}: score {a['score']} vs {b['score']}"
        assert iou(a["box"], b["box"]) > 0.99, f"{name}: box {a['box']} vs {b['box']}"
        compared += 1
assert compared >= 5, f"only {compared} boxes compared: the reference set is too easy"
print(f"ok: {compared} boxes on {len(reference['images'])} images")
PY
