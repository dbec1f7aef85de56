"""A detector that 'sees' the synthetic data sets' coloured rectangles and writes them into a raw head
exactly (two-bin DFL logits whose expectation is the distance), to test decoding and evaluation."""

from __future__ import annotations

import math

import numpy as np
import torch
from torch import nn

from synthetic_data import CLASS_COLOURS, class_pixel_box


def _dfl_logits(distance: float, reg_max: int = 16) -> torch.Tensor:
    logits = torch.full((reg_max,), -60.0)
    low = min(int(math.floor(distance)), reg_max - 2)
    weight_high = distance - low
    logits[low] = math.log(max(1 - weight_high, 1e-20))
    logits[low + 1] = math.log(max(weight_high, 1e-20))
    return logits


class OracleDetector(nn.Module):
    strides = (8, 16, 32)
    reg_max = 16

    def __init__(self, classes: int = len(CLASS_COLOURS), height_factor: float = 1.0) -> None:
        super().__init__()
        self.classes = classes
        self.height_factor = height_factor  # < 1: boxes shortened from the bottom, a known IoU

    def forward(self, x: torch.Tensor) -> list[torch.Tensor]:
        batch, _, height, width = x.shape
        channels = 4 * self.reg_max + self.classes
        maps = [torch.full((batch, channels, height // s, width // s), -20.0) for s in self.strides]
        for b in range(batch):
            image = (x[b].permute(1, 2, 0).numpy() * 255).round().astype(np.uint8)
            for class_id in range(self.classes):
                box = class_pixel_box(image, class_id)
                if box is None:
                    continue
                x1, y1, x2, y2 = box
                y2 = y1 + (y2 - y1) * self.height_factor
                stride = 8
                i, j = int((x1 + x2) / 2 // stride), int((y1 + y2) / 2 // stride)
                cx, cy = (i + 0.5) * stride, (j + 0.5) * stride
                for side, distance in enumerate((cx - x1, cy - y1, x2 - cx, y2 - cy)):
                    maps[0][b, side * self.reg_max : (side + 1) * self.reg_max, j, i] = _dfl_logits(distance / stride)
                maps[0][b, 4 * self.reg_max + class_id, j, i] = 10.0
        return maps
