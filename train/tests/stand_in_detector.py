"""A tiny detector with the Detector output contract, for tests that need a model but not YOLOv8.

Output: three raw maps [B, 4*16 + nc, H/s, W/s] for strides 8, 16, 32 (DFL logits l,t,r,b then class logits).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import torch
from torch import nn


@dataclass
class StandInConfig:
    classes: int = 2
    width: int = 8


def _conv(c_in: int, c_out: int, stride: int) -> nn.Sequential:
    return nn.Sequential(nn.Conv2d(c_in, c_out, 3, stride, 1, bias=False), nn.BatchNorm2d(c_out), nn.SiLU())


class StandInDetector(nn.Module):
    strides = (8, 16, 32)
    reg_max = 16

    def __init__(self, config: StandInConfig | None = None) -> None:
        super().__init__()
        self.config = config or StandInConfig()
        self.classes = self.config.classes
        w = self.config.width
        self.stem = nn.Sequential(_conv(3, w, 2), _conv(w, w, 2), _conv(w, 2 * w, 2))
        self.down4 = _conv(2 * w, 2 * w, 2)
        self.down5 = _conv(2 * w, 2 * w, 2)
        outputs = 4 * self.reg_max + self.classes
        self.heads = nn.ModuleList(
            nn.Sequential(_conv(2 * w, 2 * w, 1), nn.Conv2d(2 * w, outputs, 1)) for _ in self.strides
        )
        for head, stride in zip(self.heads, self.strides):
            bias = head[-1].bias.data
            bias[: 4 * self.reg_max] = 1.0
            # YOLOv8's prior: about 5 objects per 640x640 image spread over the classes.
            bias[4 * self.reg_max :] = math.log(5 / self.classes / (640 / stride) ** 2)

    def forward(self, x: torch.Tensor) -> list[torch.Tensor]:
        p3 = self.stem(x)
        p4 = self.down4(p3)
        p5 = self.down5(p4)
        return [head(p) for head, p in zip(self.heads, (p3, p4, p5))]
