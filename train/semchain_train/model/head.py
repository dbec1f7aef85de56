"""YOLOv8's decoupled detection head: per stride a box branch (4 x 16 DFL logits) and a class branch."""

from __future__ import annotations

import math

import torch
from torch import nn

from .blocks import Conv
from .channel_groups import ChannelGroup, InSlot, conv_out, link

REG_MAX = 16
STRIDES = (8, 16, 32)


class DetectHead(nn.Module):
    """Raw outputs [B, 4*16 + nc, H/s, W/s] per stride: l, t, r, b DFL logits then class logits."""

    def __init__(self, in_channels: tuple[int, int, int], classes: int):
        super().__init__()
        self.classes = classes
        box_hidden = max(16, in_channels[0] // 4, REG_MAX * 4)
        cls_hidden = max(in_channels[0], min(classes, 100))
        self.box = nn.ModuleList(
            nn.Sequential(Conv(c, box_hidden, 3), Conv(box_hidden, box_hidden, 3), nn.Conv2d(box_hidden, 4 * REG_MAX, 1))
            for c in in_channels
        )
        self.cls = nn.ModuleList(
            nn.Sequential(Conv(c, cls_hidden, 3), Conv(cls_hidden, cls_hidden, 3), nn.Conv2d(cls_hidden, classes, 1))
            for c in in_channels
        )
        self.initialize_biases()

    def initialize_biases(self) -> None:
        # As YOLOv8: box logits start flat (bias 1); class logits start at the prior of about 5
        # objects per 640x640 image spread over the classes, so early training is not swamped by
        # background gradients.
        for box, cls, stride in zip(self.box, self.cls, STRIDES):
            nn.init.constant_(box[-1].bias, 1.0)
            nn.init.constant_(cls[-1].bias, math.log(5 / self.classes / (640 / stride) ** 2))

    def forward(self, features: list[torch.Tensor]) -> list[torch.Tensor]:
        return [torch.cat((box(x), cls(x)), 1) for x, box, cls in zip(features, self.box, self.cls)]

    def in_slots(self, level: int) -> list[InSlot]:
        return [InSlot(self.box[level][0].conv, 0), InSlot(self.cls[level][0].conv, 0)]

    def groups(self) -> list[ChannelGroup]:
        groups = []
        for level in range(len(self.box)):
            for kind, branch in (("box", self.box[level]), ("cls", self.cls[level])):
                for i in range(2):
                    consumer = branch[i + 1]
                    slot = InSlot(getattr(consumer, "conv", consumer), 0)
                    groups.append(link(f"head.{kind}{level}.{i}", branch[i].out_slots(), conv_out(branch[i]), [slot]))
        return groups
