#!/usr/bin/python3
"""Writes a YOLOv8-shaped model with random weights as ultralytics exports it, and its raw head.

    /usr/bin/python3 tools/make_ultralytics_export.py [OUT_DIR] [--scale tiny|n] [--size WxH]
        (needs Debian's python3-torch, python3-onnx and python3-numpy; default OUT_DIR
        src/detection/testdata, scale tiny, size 160x128: the committed test models)

Three models with the same random weights (seed 0) and COCO's 80 class names:

  ultralytics_raw.onnx (+ .names)  the raw head, 1 x (64 + 80) x N, exported the way semchain's
                                   README asks (opset 12, split() in C2f, no box decoding)
  ultralytics_decoded.onnx         the model as `yolo export format=onnx` writes it: opset 17,
                                   the decoding tail of ultralytics 8.x's Detect after the raw
                                   head, 1 x (4 + 80) x N (cx, cy, w, h in input pixels, class
                                   scores), and ultralytics' metadata_props (names, stride,
                                   imgsz, task, ...); no .names file
  ultralytics_decoded_fp16.onnx    the decoded model as a `half=True` export: FLOAT16 weights,
                                   constants, input and output

The decoding tail follows ultralytics 8.x (nn/modules/head.py Detect.forward, block.py DFL,
utils/tal.py make_anchors and dist2bbox): the levels' cat(box, cls) maps are viewed as
(1, 64 + nc, -1) and concatenated, split into 64 box and nc class rows; DFL views the box rows
as (1, 4, 16, N), transposes to (1, 16, 4, N), takes the softmax over the 16 bins and applies a
1x1 convolution with the weights 0..15; dist2bbox turns the distances (left, top, right, bottom)
around the anchor centres into cx, cy, w, h; the result is multiplied by the strides and
concatenated with the sigmoid of the class logits. As ultralytics' exporter does, C2f uses
split() (forward_split) and Detect's anchors and strides are constants of the static shape.

--scale n writes YOLOv8n's widths (3.2 M parameters); tiny (the committed models, 23 k parameters)
narrows the same graph: widths 4-16, one bottleneck per C2f, 8-wide head branches.
The class logits' bias is set so that a few dozen anchors pass a 0.25 threshold on any image.
The weights are random: the boxes mean nothing, but the decoded and the raw export give the same
ones.
"""

import argparse
import os
import sys

import numpy as np
import onnx
import torch
from onnx import TensorProto, numpy_helper
from torch import nn

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_yolov8n_random import REG_MAX, RawDetect, YoloV8n, init_weights  # noqa: E402

COCO_NAMES = [
    "person", "bicycle", "car", "motorcycle", "airplane", "bus", "train", "truck", "boat",
    "traffic light", "fire hydrant", "stop sign", "parking meter", "bench", "bird", "cat", "dog",
    "horse", "sheep", "cow", "elephant", "bear", "zebra", "giraffe", "backpack", "umbrella",
    "handbag", "tie", "suitcase", "frisbee", "skis", "snowboard", "sports ball", "kite",
    "baseball bat", "baseball glove", "skateboard", "surfboard", "tennis racket", "bottle",
    "wine glass", "cup", "fork", "knife", "spoon", "bowl", "banana", "apple", "sandwich", "orange",
    "broccoli", "carrot", "hot dog", "pizza", "donut", "cake", "chair", "couch", "potted plant",
    "bed", "dining table", "toilet", "tv", "laptop", "mouse", "remote", "keyboard", "cell phone",
    "microwave", "oven", "toaster", "sink", "refrigerator", "book", "clock", "vase", "scissors",
    "teddy bear", "hair drier", "toothbrush"]

SCALES = {
    "n": dict(widths=(16, 32, 64, 128, 256), repeats=(1, 2, 2, 1), head_hidden=None),
    "tiny": dict(widths=(4, 4, 8, 8, 16), repeats=(1, 1, 1, 1), head_hidden=(8, 8)),
}
STRIDES = (8, 16, 32)
CLASS_BIAS = -5.0  # the tiny model's mean class logit bias
OUTPUT_STD = 12.0  # the features reaching them are small (about 0.04): logits vary by about 1.4


class DFL(nn.Module):
    """Distribution focal loss decoding: the expectation of the 16 bins as a fixed 1x1 conv."""

    def __init__(self):
        super().__init__()
        self.conv = nn.Conv2d(REG_MAX, 1, 1, bias=False).requires_grad_(False)
        self.conv.weight.data[:] = torch.arange(REG_MAX, dtype=torch.float).view(1, REG_MAX, 1, 1)

    def forward(self, x):
        b, _, a = x.shape
        return self.conv(x.view(b, 4, REG_MAX, a).transpose(2, 1).softmax(1)).view(b, 4, a)


def make_anchors(feats, strides, offset=0.5):
    """Anchor centres (in grid cells) and strides of all levels, row-major per level."""
    points, stride_tensor = [], []
    for feat, stride in zip(feats, strides):
        _, _, h, w = feat.shape
        sx = torch.arange(end=w, dtype=feat.dtype) + offset
        sy = torch.arange(end=h, dtype=feat.dtype) + offset
        sy, sx = torch.meshgrid(sy, sx, indexing="ij")
        points.append(torch.stack((sx, sy), -1).view(-1, 2))
        stride_tensor.append(torch.full((h * w, 1), stride, dtype=feat.dtype))
    return torch.cat(points), torch.cat(stride_tensor)


def dist2bbox(distance, anchor_points, dim):
    """Distances (left, top, right, bottom) around the anchors to cx, cy, w, h."""
    lt, rb = distance.chunk(2, dim)
    x1y1 = anchor_points - lt
    x2y2 = anchor_points + rb
    return torch.cat(((x1y1 + x2y2) / 2, x2y2 - x1y1), dim)


class DecodedDetect(RawDetect):
    """RawDetect's layers with ultralytics 8.x's export-mode forward (decoded boxes)."""

    def __init__(self, nc, channels, hidden=None):
        super().__init__(nc, channels, hidden)
        self.dfl = DFL()

    def forward(self, levels):
        x = [torch.cat((self.cv2[i](xi), self.cv3[i](xi)), 1) for i, xi in enumerate(levels)]
        anchors, strides = (t.transpose(0, 1) for t in make_anchors(x, STRIDES, 0.5))
        x_cat = torch.cat([xi.view(x[0].shape[0], self.no, -1) for xi in x], 2)
        box, cls = x_cat.split((4 * REG_MAX, self.nc), 1)
        dbox = dist2bbox(self.dfl(box), anchors.unsqueeze(0), dim=1) * strides
        return torch.cat((dbox, cls.sigmoid()), 1)


def spread_head(head):
    """Output weights that make the tiny model's boxes and scores vary from anchor to anchor
    (init_weights' small ones give every anchor nearly the same), with a few dozen anchors
    scoring at least 0.25."""
    for box, cls in zip(head.cv2, head.cv3):
        nn.init.normal_(box[-1].weight, std=OUTPUT_STD)
        nn.init.normal_(cls[-1].weight, std=OUTPUT_STD)
        nn.init.normal_(cls[-1].bias, mean=CLASS_BIAS, std=0.5)


def metadata(scale, width, height):
    """The metadata_props ultralytics' exporter writes (str() of each value)."""
    return {
        "description": f"Ultralytics YOLOv8{scale} model with random weights (semchain test)",
        "author": "Ultralytics",
        "date": "2024-01-01T00:00:00",
        "version": "8.0.230",
        "license": "AGPL-3.0 License (https://ultralytics.com/license)",
        "docs": "https://docs.ultralytics.com",
        "stride": str(max(STRIDES)),
        "task": "detect",
        "batch": "1",
        "imgsz": str([height, width]),
        "names": str(dict(enumerate(COCO_NAMES))),
    }


def export(model, image, path, opset, meta=None):
    with torch.no_grad():
        torch.onnx.export(model, image, path, opset_version=opset, input_names=["images"],
                          output_names=["output0"], do_constant_folding=True)
    proto = onnx.load(path)
    for key, value in (meta or {}).items():
        entry = proto.metadata_props.add()
        entry.key, entry.value = key, value
    onnx.checker.check_model(proto)
    onnx.save(proto, path)
    return proto


def to_float16(proto):
    """The model as a half-precision export: every FLOAT tensor, type and Cast becomes FLOAT16."""
    half = onnx.ModelProto()
    half.CopyFrom(proto)
    graph = half.graph
    for index, tensor in enumerate(graph.initializer):
        if tensor.data_type == TensorProto.FLOAT:
            array = numpy_helper.to_array(tensor).astype(np.float16)
            graph.initializer[index].CopyFrom(numpy_helper.from_array(array, tensor.name))
    for node in graph.node:
        for attribute in node.attribute:
            if node.op_type == "Constant" and attribute.name == "value" and \
                    attribute.t.data_type == TensorProto.FLOAT:
                array = numpy_helper.to_array(attribute.t).astype(np.float16)
                attribute.t.CopyFrom(numpy_helper.from_array(array, attribute.t.name))
            if node.op_type == "Cast" and attribute.name == "to" and attribute.i == TensorProto.FLOAT:
                attribute.i = TensorProto.FLOAT16
    for value in list(graph.input) + list(graph.output) + list(graph.value_info):
        if value.type.tensor_type.elem_type == TensorProto.FLOAT:
            value.type.tensor_type.elem_type = TensorProto.FLOAT16
    onnx.checker.check_model(half)
    return half


def check_same_boxes(head, decoded, width, height):
    """Decodes the raw head the way semchain does (yolo_head.h) and checks that it gives the
    decoded export's output: the two exports are the same model."""
    head, decoded = head[0].numpy().astype(np.float64), decoded[0].numpy().astype(np.float64)
    centres, strides = [], []
    for s in STRIDES:
        ys, xs = np.meshgrid(np.arange(height // s), np.arange(width // s), indexing="ij")
        centres.append(np.stack(((xs.ravel() + 0.5) * s, (ys.ravel() + 0.5) * s)))
        strides.append(np.full(xs.size, s))
    centres, strides = np.concatenate(centres, 1), np.concatenate(strides)
    logits = head[:4 * REG_MAX].reshape(4, REG_MAX, -1)
    weights = np.exp(logits - logits.max(1, keepdims=True))
    distances = (weights * np.arange(REG_MAX)[None, :, None]).sum(1) / weights.sum(1) * strides
    x1y1, x2y2 = centres - distances[:2], centres + distances[2:]
    boxes = np.concatenate(((x1y1 + x2y2) / 2, x2y2 - x1y1))
    box_error = np.abs(boxes - decoded[:4]).max()
    score_error = np.abs(1 / (1 + np.exp(-head[4 * REG_MAX:])) - decoded[4:]).max()
    assert box_error < 1e-3 and score_error < 1e-6, (box_error, score_error)
    print(f"decoded export = raw head decoded by semchain's rule: largest differences "
          f"{box_error:.1e} px, {score_error:.1e} in score")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out_dir", nargs="?", default="src/detection/testdata")
    parser.add_argument("--scale", choices=sorted(SCALES), default="tiny")
    parser.add_argument("--size", default="160x128", help="static input WIDTHxHEIGHT")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))
    torch.set_num_threads(1)
    config = SCALES[args.scale]
    raw = YoloV8n(len(COCO_NAMES), head=RawDetect, **config).eval()
    init_weights(raw)
    if args.scale == "tiny":
        spread_head(raw.detect)
    decoded = YoloV8n(len(COCO_NAMES), head=DecodedDetect, **config).eval()
    decoded.load_state_dict(raw.state_dict(), strict=False)  # DFL's fixed weights stay
    print(f"parameters: {sum(p.numel() for p in raw.parameters()) / 1e3:.1f} k")
    os.makedirs(args.out_dir, exist_ok=True)
    image = torch.rand(1, 3, height, width, generator=torch.Generator().manual_seed(1))
    out = lambda name: os.path.join(args.out_dir, name)  # noqa: E731
    export(raw, image, out("ultralytics_raw.onnx"), opset=12)
    with open(out("ultralytics_raw.names"), "w") as names:
        names.write("".join(name + "\n" for name in COCO_NAMES))
    proto = export(decoded, image, out("ultralytics_decoded.onnx"), opset=17,
                   meta=metadata(args.scale, width, height))
    onnx.save(to_float16(proto), out("ultralytics_decoded_fp16.onnx"))
    with torch.no_grad():
        output = decoded(image)
        check_same_boxes(raw(image), output, width, height)
    scores = output[0, 4:].max(0).values
    print(f"anchors scoring at least 0.25 on a random image: {int((scores >= 0.25).sum())} "
          f"of {scores.numel()}")
    print(f"wrote ultralytics_raw.onnx (+ .names), ultralytics_decoded.onnx and "
          f"ultralytics_decoded_fp16.onnx in {args.out_dir}")


if __name__ == "__main__":
    main()
