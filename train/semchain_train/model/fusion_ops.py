"""Resizing by whole factors read from static shapes, so ONNX export gets constant pool kernels and
resize scales that OpenCV 4.6's DNN runs (no adaptive pooling, no shape arithmetic in the graph).
"""

from __future__ import annotations

import torch
import torch.nn.functional as F


def _factor(big: int, small: int) -> int:
    big, small = int(big), int(small)
    if small <= 0 or big % small != 0:
        raise ValueError(f"feature map sizes {big} and {small} are not whole multiples (input sides must be multiples of 32)")
    return big // small


def avg_pool_to(x: torch.Tensor, size: tuple[int, int]) -> torch.Tensor:
    """Average pooling of x down to 'size' with kernel = stride = the whole size ratio."""
    fy, fx = _factor(x.shape[2], size[0]), _factor(x.shape[3], size[1])
    if fy == 1 and fx == 1:
        return x
    return F.avg_pool2d(x, (fy, fx), (fy, fx))


def max_pool_to(x: torch.Tensor, size: tuple[int, int]) -> torch.Tensor:
    fy, fx = _factor(x.shape[2], size[0]), _factor(x.shape[3], size[1])
    if fy == 1 and fx == 1:
        return x
    return F.max_pool2d(x, (fy, fx), (fy, fx))


def upsample_to(x: torch.Tensor, size: tuple[int, int], mode: str = "nearest") -> torch.Tensor:
    """x resized up to 'size' by whole factors ('nearest' or 'bilinear' with half-pixel centres)."""
    fy, fx = _factor(size[0], x.shape[2]), _factor(size[1], x.shape[3])
    if fy == 1 and fx == 1:
        return x
    if mode == "nearest":
        return F.interpolate(x, scale_factor=(float(fy), float(fx)), mode="nearest")
    return F.interpolate(x, scale_factor=(float(fy), float(fx)), mode=mode, align_corners=False)


def spatial(x: torch.Tensor) -> tuple[int, int]:
    return int(x.shape[2]), int(x.shape[3])


def relu6(x: torch.Tensor) -> torch.Tensor:
    """min(max(x, 0), 6) as two ReLUs: ONNX opset 12 writes F.relu6 as a 3-input Clip, which
    OpenCV 4.6 cannot import."""
    return F.relu(x) - F.relu(x - 6.0)


def hard_sigmoid(x: torch.Tensor) -> torch.Tensor:
    """relu6(x + 3) / 6 (Gold-YOLO's h_sigmoid gate)."""
    return relu6(x + 3.0) / 6.0
