"""Export a checkpoint's detector to the raw-head ONNX that semchain's C++ runtime runs.

Output: one tensor 1 x (64 + nc) x N, N = anchors of strides 8, 16, 32 in row-major order per
stride (src/detection/yolo_head.h): 16 DFL logits per side (l, t, r, b), then the class logits
before the sigmoid. ONNX opset 12, static input 1 x 3 x H x W (RGB in 0..1; the C++ runtime
letterboxes and scales by 1/255), loadable by OpenCV 4.6. Beside it: M.names, one class per line.
"""

from __future__ import annotations

import argparse
import io
import os
import warnings
from pathlib import Path

import torch
from torch import nn

OPSET = 12
DEFAULT_INPUT = (320, 256)  # width, height


class RawHeadExport(nn.Module):
    """The detector's three maps flattened and concatenated along the anchors: 1 x (64 + nc) x N."""

    def __init__(self, detector: nn.Module):
        super().__init__()
        self.detector = detector

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        maps = self.detector(x)
        # Static reshape sizes (Python ints) keep Shape/Gather arithmetic out of the graph.
        flat = [m.reshape(int(m.shape[0]), int(m.shape[1]), int(m.shape[2]) * int(m.shape[3])) for m in maps]
        return torch.cat(flat, 2)


def parse_size(text: str) -> tuple[int, int]:
    """'WIDTHxHEIGHT' -> (width, height), both positive multiples of 32."""
    parts = text.lower().split("x")
    if len(parts) != 2 or not all(p.isdigit() for p in parts):
        raise ValueError(f"--input {text}: expected WIDTHxHEIGHT, e.g. 320x256")
    width, height = int(parts[0]), int(parts[1])
    if width <= 0 or height <= 0 or width % 32 or height % 32:
        raise ValueError(f"--input {text}: width and height must be positive multiples of 32")
    return width, height


def size_argument(text: str) -> tuple[int, int]:
    """parse_size for argparse's type=: a bad size is a one-line usage error."""
    try:
        return parse_size(text)
    except ValueError as error:
        raise argparse.ArgumentTypeError(str(error)) from None


def _inline_identity_initializers(model) -> None:
    """torch's exporter shares equal initializers through Identity nodes, which OpenCV 4.6 cannot
    import; give each consumer its own copy instead."""
    import onnx

    initializers = {init.name: init for init in model.graph.initializer}
    kept = []
    for node in model.graph.node:
        if node.op_type == "Identity" and node.input[0] in initializers:
            copy = onnx.TensorProto()
            copy.CopyFrom(initializers[node.input[0]])
            copy.name = node.output[0]
            model.graph.initializer.append(copy)
        else:
            kept.append(node)
    del model.graph.node[:]
    model.graph.node.extend(kept)


def _store_weights_as_half(model) -> None:
    """Conv weights and biases stored as FLOAT16, each read through a Cast to FLOAT: half the file
    (the default model must stay small in the repository) at a rounding of 2^-11 of each weight.
    OpenCV 4.6 cannot read FLOAT16 tensors; semchain's loader (src/detection) casts them back."""
    import onnx
    from onnx import helper, numpy_helper

    initializers = {init.name: init for init in model.graph.initializer}
    consumers = {name for node in model.graph.node if node.op_type == "Conv" for name in node.input[1:]}
    casts = []
    for name in sorted(consumers):
        init = initializers.get(name)
        if init is None or init.data_type != onnx.TensorProto.FLOAT:
            continue
        half_name = name + "_fp16"
        init.CopyFrom(numpy_helper.from_array(numpy_helper.to_array(init).astype("float16"), half_name))
        casts.append(helper.make_node("Cast", [half_name], [name], to=onnx.TensorProto.FLOAT, name=name + "_cast"))
    nodes = casts + list(model.graph.node)
    del model.graph.node[:]
    model.graph.node.extend(nodes)


def export_onnx(
    model: nn.Module, path: Path, input_size: tuple[int, int] = DEFAULT_INPUT, half: bool = False
) -> None:
    """Writes 'model' (a Detector, any pruning) as raw-head ONNX to 'path' atomically; with 'half'
    the convolution weights are stored as FLOAT16."""
    import onnx

    width, height = input_size
    wrapper = RawHeadExport(model).eval()
    buffer = io.BytesIO()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # TracerWarnings: the static shapes are intended
        with torch.no_grad():
            torch.onnx.export(
                wrapper,
                torch.zeros(1, 3, height, width),
                buffer,
                opset_version=OPSET,
                input_names=["images"],
                output_names=["output0"],
                do_constant_folding=True,
            )
    graph = onnx.load_from_string(buffer.getvalue())
    _inline_identity_initializers(graph)
    if half:
        _store_weights_as_half(graph)
    onnx.checker.check_model(graph)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".tmp")
    onnx.save(graph, str(tmp))
    os.replace(tmp, path)


def write_names(path: Path, names: list[str]) -> None:
    for name in names:
        if not name or "\n" in name:
            raise ValueError(f"class name {name!r}: expected a non-empty single-line name")
    tmp = path.with_name(path.name + ".tmp")
    tmp.write_text("".join(f"{name}\n" for name in names))
    os.replace(tmp, path)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--weights", type=Path, required=True, help="checkpoint (.pt) to export")
    parser.add_argument("--out", type=Path, required=True, help="ONNX file to write; M.names is written beside it")
    parser.add_argument("--input", type=size_argument, default=DEFAULT_INPUT, help="static network input WIDTHxHEIGHT (default 320x256)")
    parser.add_argument("--no-check", action="store_true", help="skip running the export through OpenCV DNN")
    parser.add_argument("--half", action="store_true", help="store the convolution weights as FLOAT16 (half the file size)")


def load_model_and_names(weights: Path) -> tuple[nn.Module, list[str]]:
    """The checkpoint's model (EMA weights when present) and class names."""
    from .checkpoint import load_checkpoint

    checkpoint = load_checkpoint(weights)
    model = checkpoint.model.float().eval()
    names = list(checkpoint.names)
    classes = getattr(model, "classes", len(names))
    if classes != len(names):
        raise ValueError(f"{weights}: the model has {classes} classes but the checkpoint names {len(names)}")
    return model, names


def check_with_opencv(model: nn.Module, path: Path, input_size: tuple[int, int], seed: int = 0) -> float:
    """Max |OpenCV DNN - PyTorch| on a random input, relative to the largest output magnitude (at
    least 1): trained logits reach ~10-15, and OpenCV's float32 attention and pooling round
    differently from PyTorch's by a few 1e-4 of that. Raises when OpenCV cannot load or run it."""
    import cv2
    import numpy as np

    width, height = input_size
    generator = torch.Generator().manual_seed(seed)
    x = torch.rand(1, 3, height, width, generator=generator)
    with torch.no_grad():
        expected = RawHeadExport(model).eval()(x).numpy()
    import onnx

    from .onnx_import import float32_model

    # OpenCV 4.6 reads no FLOAT16 tensor: check a half export as the C++ loader runs it (cast back).
    buffer = np.frombuffer(float32_model(onnx.load(str(path))).SerializeToString(), dtype=np.uint8)
    net = cv2.dnn.readNetFromONNX(buffer)
    net.setPreferableBackend(cv2.dnn.DNN_BACKEND_OPENCV)
    net.setPreferableTarget(cv2.dnn.DNN_TARGET_CPU)
    net.setInput(x.numpy())
    got = net.forward()
    if got.shape != expected.shape:
        raise ValueError(f"{path}: OpenCV DNN output {got.shape}, PyTorch {expected.shape}")
    return float(np.abs(got - expected).max() / max(1.0, float(np.abs(expected).max())))


def run(args: argparse.Namespace) -> int:
    input_size = args.input
    model, names = load_model_and_names(args.weights)
    # Checked before it replaces anything: a model OpenCV runs differently never lands at --out.
    staged = args.out.with_name(args.out.name + ".staged.onnx")
    try:
        export_onnx(model, staged, input_size, half=args.half)
        if not args.no_check:
            diff = check_with_opencv(model, staged, input_size)
            print(f"OpenCV DNN runs it: max |OpenCV - PyTorch| = {diff:.2e} of the largest output")
            # Half-precision weights move the outputs by about 1e-3 of their range by themselves.
            limit = 1e-2 if args.half else 1e-3
            if diff > limit:
                raise ValueError(
                    f"{args.out}: OpenCV DNN output differs from PyTorch by {diff:.3g} of the largest output (> {limit:g})"
                )
        os.replace(staged, args.out)
    finally:
        staged.unlink(missing_ok=True)
    write_names(args.out.with_suffix(".names"), names)
    print(f"wrote {args.out} (1x{4 * 16 + len(names)}xN raw head, input {input_size[0]}x{input_size[1]}) and {args.out.with_suffix('.names')}")
    return 0
