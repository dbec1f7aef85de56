"""Load a raw-head ONNX export back into a trainable Detector, so that training goes on from the
committed model (models/detector.onnx) on a machine that has no run folder.

The export folds every batch norm into the convolution before it (torch.onnx in eval mode), so
the ONNX holds, per Conv block, W' = W * gamma / sigma and b' = beta - mean * gamma / sigma. Any
(W, BN) with W = W', gamma = sqrt(var + eps) and beta = mean + b' gives the same eval-mode function
for every choice of (mean, var); we pick the mean and variance of W' x over calibration images, so
that in train mode, where the batch statistics replace the running ones, the network still computes
(nearly) what the export computes. With mean 0 and var 1 instead, train mode would renormalise
every layer and fine-tuning would start from a different function.

Convolutions are matched to the graph's Conv nodes in execution order and checked by shape; the
loaded model is then compared with the export (OpenCV DNN, as the C++ runtime runs it), so a
model the mapping does not fit (another scale, a pruned model) is refused rather than mis-loaded.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import torch
from torch import nn

from .model.blocks import Conv
from .model.config import ModelConfig
from .model.detector import Detector, build_detector


class OnnxImportError(ValueError):
    pass


def float32_model(model):
    """A copy of an ONNX ModelProto with FLOAT16 initializers stored as FLOAT, and the Cast nodes
    that turned them into float32 removed (their consumers read the converted initializer)."""
    import onnx
    from onnx import numpy_helper

    converted = onnx.ModelProto()
    converted.CopyFrom(model)
    graph = converted.graph
    half = set()
    for init in graph.initializer:
        if init.data_type == onnx.TensorProto.FLOAT16:
            array = numpy_helper.to_array(init).astype(np.float32)
            init.CopyFrom(numpy_helper.from_array(array, init.name))
            half.add(init.name)
    renamed: dict[str, str] = {}
    kept = []
    for node in graph.node:
        if node.op_type == "Cast" and node.input[0] in half:
            renamed[node.output[0]] = node.input[0]
        else:
            kept.append(node)
    for node in kept:
        for i, name in enumerate(node.input):
            if name in renamed:
                node.input[i] = renamed[name]
    del graph.node[:]
    graph.node.extend(kept)
    return converted


def _conv_weights(path: Path) -> tuple[list[tuple[np.ndarray, np.ndarray | None]], tuple[int, int]]:
    """(weight, bias) of every Conv node in graph order, and the export's input (width, height)."""
    import onnx
    from onnx import numpy_helper

    try:
        model = float32_model(onnx.load(str(path)))
    except Exception as error:  # onnx raises DecodeError and others; one line for the user
        raise OnnxImportError(f"{path}: not an ONNX model ({error})") from None
    initializers = {init.name: numpy_helper.to_array(init) for init in model.graph.initializer}
    convs = []
    for node in model.graph.node:
        if node.op_type != "Conv":
            continue
        if node.input[1] not in initializers:
            raise OnnxImportError(f"{path}: Conv node {node.name} has no constant weight")
        bias = initializers.get(node.input[2]) if len(node.input) > 2 else None
        convs.append((initializers[node.input[1]], bias))
    dims = model.graph.input[0].type.tensor_type.shape.dim
    if len(dims) != 4 or not all(d.dim_value > 0 for d in dims[2:]):
        raise OnnxImportError(f"{path}: expected a static 1x3xHxW input")
    return convs, (int(dims[3].dim_value), int(dims[2].dim_value))


def _execution_order(model: Detector, input_size: tuple[int, int]) -> list[nn.Conv2d]:
    order: list[nn.Conv2d] = []
    hooks = [m.register_forward_hook(lambda m, i, o: order.append(m)) for m in model.modules() if isinstance(m, nn.Conv2d)]
    try:
        with torch.no_grad():
            model.eval()(torch.zeros(1, 3, input_size[1], input_size[0]))
    finally:
        for hook in hooks:
            hook.remove()
    return order


def _batch_norm_of(model: nn.Module) -> dict[nn.Conv2d, nn.BatchNorm2d]:
    return {m.conv: m.bn for m in model.modules() if isinstance(m, Conv)}


def load_detector_from_onnx(path: Path, config: ModelConfig, calibration: torch.Tensor) -> Detector:
    """A Detector of 'config' computing what the raw-head export at 'path' computes; batch-norm
    statistics from 'calibration' (N x 3 x H x W RGB in 0..1 at the export's input size)."""
    convs, input_size = _conv_weights(path)
    model = build_detector(config)
    order = _execution_order(model, input_size)
    if len(order) != len(convs):
        raise OnnxImportError(
            f"{path}: {len(convs)} convolutions in the graph, {len(order)} in a YOLOv8{config.scale} "
            f"(gd {config.gd_neck}, asf {config.asf}) with {config.classes} classes: another architecture"
        )
    batch_norms = _batch_norm_of(model)
    folded_bias: dict[nn.Conv2d, torch.Tensor] = {}
    with torch.no_grad():
        for index, (module, (weight, bias)) in enumerate(zip(order, convs)):
            if tuple(module.weight.shape) != weight.shape:
                raise OnnxImportError(
                    f"{path}: convolution {index} has weights {weight.shape}, the model expects "
                    f"{tuple(module.weight.shape)}: another architecture"
                )
            module.weight.copy_(torch.from_numpy(weight.copy()))
            b = torch.zeros(weight.shape[0]) if bias is None else torch.from_numpy(bias.astype(np.float32))
            bn = batch_norms.get(module)
            if bn is None:
                if module.bias is None:
                    raise OnnxImportError(f"{path}: convolution {index} has a bias the model cannot hold")
                module.bias.copy_(b)
                continue
            # Identity batch norm plus the folded bias: the export's function, for calibration.
            bn.running_mean.zero_()
            bn.running_var.fill_(1.0)
            bn.weight.fill_(float(np.sqrt(1.0 + bn.eps)))
            bn.bias.copy_(b)
            folded_bias[module] = b
    _calibrate(model, folded_bias, batch_norms, calibration)
    return model.train()


def _calibrate(
    model: Detector,
    folded_bias: dict[nn.Conv2d, torch.Tensor],
    batch_norms: dict[nn.Conv2d, nn.BatchNorm2d],
    calibration: torch.Tensor,
) -> None:
    sums: dict[nn.Conv2d, torch.Tensor] = {}
    squares: dict[nn.Conv2d, torch.Tensor] = {}
    counts: dict[nn.Conv2d, int] = {}

    def record(module: nn.Conv2d, _inputs, output: torch.Tensor) -> None:
        values = output.detach().double().transpose(0, 1).reshape(output.shape[1], -1)
        sums[module] = sums.get(module, 0) + values.sum(1)
        squares[module] = squares.get(module, 0) + (values * values).sum(1)
        counts[module] = counts.get(module, 0) + values.shape[1]

    hooks = [m.register_forward_hook(record) for m in folded_bias]
    try:
        with torch.no_grad():
            model.eval()
            for start in range(0, calibration.shape[0], 8):
                model(calibration[start : start + 8])
    finally:
        for hook in hooks:
            hook.remove()
    with torch.no_grad():
        for module, bias in folded_bias.items():
            mean = sums[module] / counts[module]
            var = (squares[module] / counts[module] - mean * mean).clamp(min=0.0)
            bn = batch_norms[module]
            bn.running_mean.copy_(mean.float())
            bn.running_var.copy_(var.float())
            bn.weight.copy_(torch.sqrt(var + bn.eps).float())
            bn.bias.copy_((mean + bias.double()).float())


def calibration_images(paths: list[Path], input_size: tuple[int, int]) -> torch.Tensor:
    """Letterboxed RGB images in 0..1 (N x 3 x H x W), as the runtime feeds the network."""
    from .data.augment import apply_letterbox, fit_letterbox
    from .data.dataset import read_rgb

    if not paths:
        raise OnnxImportError("no calibration images (the data set's train split is empty)")
    images = []
    for path in paths:
        rgb = read_rgb(path)
        boxed = apply_letterbox(rgb, fit_letterbox((rgb.shape[1], rgb.shape[0]), input_size))
        images.append(torch.from_numpy(boxed).permute(2, 0, 1).float() / 255.0)
    return torch.stack(images)


def export_input_size(path: Path) -> tuple[int, int]:
    return _conv_weights(path)[1]
