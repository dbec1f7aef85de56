"""Boxes of a detector on a folder of images, decoded in PyTorch exactly as the C++ runtime does
(src/detection/yolo_detector.cc): letterbox (bilinear, grey 114, scaled size rounded, padding
split evenly), RGB / 255, raw head, best class by sigmoid score >= 0.25, DFL expectation boxes,
class-wise NMS at IoU 0.45 (suppress when IoU > 0.45), at most 300, mapped back to the image,
clamped, empty boxes dropped. For comparing the C++ detector's boxes with PyTorch's.

  /usr/bin/python3 -m semchain_train.reference_boxes --model M.pt|M.onnx --images DIR --out boxes.json

With a checkpoint (.pt) the network runs in PyTorch; with an ONNX file it runs in OpenCV's DNN
(the C++ runtime's engine) and only the decoding is PyTorch's.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import torch

from .boxes import decode_outputs
from .data.augment import apply_letterbox, fit_letterbox
from .data.dataset import read_rgb
from .val import EvalOptions, postprocess

IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".bmp")


@dataclass
class ReferenceOptions:
    """The C++ YoloOptions defaults (src/detection/yolo_detector.h)."""

    input_size: tuple[int, int] = (320, 256)  # (width, height); an ONNX model's own static size
    conf: float = 0.25
    iou: float = 0.45
    max_det: int = 300


def split_flat_output(flat: torch.Tensor, input_size: tuple[int, int], strides=(8, 16, 32)) -> list[torch.Tensor]:
    """1 x rows x N (the exported raw head) -> the three maps [1, rows, H/s, W/s]."""
    width, height = input_size
    maps, start = [], 0
    for stride in strides:
        h, w = height // stride, width // stride
        maps.append(flat[:, :, start : start + h * w].reshape(flat.shape[0], flat.shape[1], h, w))
        start += h * w
    if start != flat.shape[2]:
        raise ValueError(f"the model's output has {flat.shape[2]} anchors, {width}x{height} gives {start}")
    return maps


class _Network:
    """forward(RGB uint8 letterboxed image) -> raw maps, from a checkpoint or an ONNX file."""

    def __init__(self, path: Path, input_size: tuple[int, int], torch_scale: str | None = None):
        self.path = path
        if path.suffix == ".onnx" and torch_scale is not None:
            # The export's own weights (half-precision ones included) run in PyTorch: what OpenCV
            # computes from the file is compared with PyTorch on the very same numbers.
            from .model.config import ModelConfig
            from .onnx_import import export_input_size, load_detector_from_onnx

            names_path = path.with_suffix(".names")
            if not names_path.is_file():
                raise FileNotFoundError(f"{names_path}: no class-names file beside the model")
            self.names = [line.strip() for line in names_path.read_text().splitlines() if line.strip()]
            self.input_size = export_input_size(path)
            # Eval mode computes the export's function whatever the batch-norm statistics.
            calibration = torch.zeros(1, 3, self.input_size[1], self.input_size[0])
            config = ModelConfig(scale=torch_scale, classes=len(self.names))
            self.model = load_detector_from_onnx(path, config, calibration).eval()
        elif path.suffix == ".onnx":
            import cv2
            import onnx

            graph = onnx.load(str(path))
            dims = [d.dim_value for d in graph.graph.input[0].type.tensor_type.shape.dim]
            if len(dims) != 4 or dims[2] <= 0 or dims[3] <= 0:
                raise ValueError(f"{path}: expected a static 1x3xHxW input, found {dims}")
            self.input_size = (dims[3], dims[2])
            from .onnx_import import float32_model

            # FLOAT16 weights (export --half) cast back as semchain's loader does; OpenCV reads no FLOAT16.
            buffer = np.frombuffer(float32_model(graph).SerializeToString(), dtype=np.uint8)
            self.net = cv2.dnn.readNetFromONNX(buffer)
            names_path = path.with_suffix(".names")
            if not names_path.is_file():
                raise FileNotFoundError(f"{names_path}: no class-names file beside the model")
            self.names = [line.strip() for line in names_path.read_text().splitlines() if line.strip()]
            self.model = None
        else:
            from .checkpoint import load_checkpoint

            checkpoint = load_checkpoint(path)
            self.model = checkpoint.model.float().eval()
            self.names = list(checkpoint.names)
            self.input_size = input_size

    def __call__(self, image: np.ndarray) -> list[torch.Tensor]:
        x = torch.from_numpy(np.ascontiguousarray(image.transpose(2, 0, 1))).float().div(255.0)[None]
        if self.model is not None:
            with torch.no_grad():
                return self.model(x)
        self.net.setInput(x.numpy())
        flat = torch.from_numpy(np.array(self.net.forward()))
        return split_flat_output(flat, self.input_size)


def detect_image(network: _Network, rgb: np.ndarray, options: ReferenceOptions) -> list[dict[str, Any]]:
    letterbox = fit_letterbox((rgb.shape[1], rgb.shape[0]), network.input_size)
    maps = network(apply_letterbox(rgb, letterbox))
    if maps[0].shape[1] != 64 + len(network.names):
        raise ValueError(f"{network.path}: {maps[0].shape[1]} output rows do not fit {len(network.names)} class names")
    boxes, scores = decode_outputs(maps)
    nms = EvalOptions()
    nms.input_size, nms.conf, nms.iou, nms.max_det = network.input_size, options.conf, options.iou, options.max_det
    found = postprocess(boxes[0], scores[0], letterbox, nms)
    return [
        {"class": network.names[int(c)], "class_id": int(c), "score": float(s), "box": [float(v) for v in box]}
        for *box, s, c in found.tolist()
    ]


def reference_boxes(
    model: Path, images: list[Path], options: ReferenceOptions, torch_scale: str | None = None
) -> dict[str, Any]:
    network = _Network(model, options.input_size, torch_scale)
    results = []
    for path in images:
        results.append({"image": path.name, "detections": detect_image(network, read_rgb(path), options)})
    width, height = network.input_size
    return {
        "model": str(model),
        "input": f"{width}x{height}",
        "conf": options.conf,
        "iou": options.iou,
        "max_det": options.max_det,
        "images": results,
    }


def list_images(folder: Path) -> list[Path]:
    if folder.is_file():
        return [folder]
    if not folder.is_dir():
        raise FileNotFoundError(f"{folder}: no such image or folder")
    images = sorted(p for p in folder.iterdir() if p.suffix.lower() in IMAGE_SUFFIXES)
    if not images:
        raise ValueError(f"{folder}: no images ({', '.join(IMAGE_SUFFIXES)})")
    return images


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="semchain_train.reference_boxes", description=__doc__.split("\n\n")[0])
    parser.add_argument("--model", type=Path, required=True, help="checkpoint (.pt) or raw-head ONNX (.onnx + .names)")
    parser.add_argument("--images", type=Path, required=True, help="an image or a folder of images")
    parser.add_argument("--out", type=Path, required=True, help="JSON file to write")
    parser.add_argument("--input", default="320x256", help="network input WIDTHxHEIGHT for a checkpoint (default 320x256)")
    parser.add_argument("--conf", type=float, default=ReferenceOptions.conf, help="confidence threshold (default 0.25)")
    parser.add_argument("--iou", type=float, default=ReferenceOptions.iou, help="NMS IoU threshold (default 0.45)")
    parser.add_argument("--torch-scale", choices=("n", "s"),
                        help="run an .onnx export's weights in PyTorch (a YOLOv8 of this scale) instead of OpenCV")
    args = parser.parse_args(argv)
    try:
        from .export import parse_size

        options = ReferenceOptions(input_size=parse_size(args.input), conf=args.conf, iou=args.iou)
        if not (0 < options.conf <= 1 and 0 < options.iou <= 1):
            raise ValueError("--conf and --iou must lie in (0, 1]")
        result = reference_boxes(args.model, list_images(args.images), options, args.torch_scale)
        args.out.parent.mkdir(parents=True, exist_ok=True)
        tmp = args.out.with_name(args.out.name + ".tmp")
        tmp.write_text(json.dumps(result, indent=1) + "\n")
        os.replace(tmp, args.out)
    except (ValueError, FileNotFoundError, OSError) as error:
        sys.stderr.write(f"semchain_train: error: {str(error).splitlines()[0]}\n")
        return 1
    count = sum(len(r["detections"]) for r in result["images"])
    print(f"wrote {args.out}: {count} detections on {len(result['images'])} images")
    return 0


if __name__ == "__main__":
    sys.exit(main())
