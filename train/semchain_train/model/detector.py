"""The detector of seed 000 §2.1: YOLOv8 backbone, PAN or GD neck, optional ASF, DFL head."""

from __future__ import annotations

import torch
from torch import nn

from .asf import ChannelPositionAttention, ScaleSequenceFusion
from .backbone import Backbone
from .channel_groups import ChannelGroup, InSlot, OutSlot
from .config import ModelConfig
from .head import REG_MAX, STRIDES, DetectHead
from .neck_gd import GDNeck
from .neck_pan import PanNeck


class Detector(nn.Module):
    """forward(x [B, 3, H, W] RGB in 0..1, H and W multiples of 32) -> three raw maps
    [B, 64 + nc, H/s, W/s] for s = 8, 16, 32 (16 DFL logits for l, t, r, b; then class logits)."""

    strides = STRIDES
    reg_max = REG_MAX

    def __init__(self, config: ModelConfig):
        super().__init__()
        config.validate()
        self.config = config
        self.classes = config.classes
        self.backbone = Backbone(config)
        b_channels = tuple(m.out_channels for m in self.backbone.output_modules())
        neck_type = GDNeck if config.gd_neck else PanNeck
        self.neck = neck_type(config, b_channels, tfe=config.asf)
        c_p3 = self.neck.out_channels[0]
        self.ssff = ScaleSequenceFusion(b_channels[1], b_channels[2], b_channels[3], c_p3) if config.asf else None
        self.cpam = ChannelPositionAttention(c_p3) if config.asf else None
        self.head = DetectHead(self.neck.out_channels, config.classes)

    def forward(self, x: torch.Tensor) -> list[torch.Tensor]:
        if x.shape[2] % 32 or x.shape[3] % 32:
            raise ValueError(f"input {x.shape[3]}x{x.shape[2]}: width and height must be multiples of 32")
        b2, b3, b4, b5 = self.backbone(x)
        p3, n4, n5 = self.neck(b2, b3, b4, b5)
        if self.ssff is not None and self.cpam is not None:
            p3 = self.cpam(p3, self.ssff(b3, b4, b5))  # N3
        return self.head([p3, n4, n5])

    def channel_groups(self) -> list[ChannelGroup]:
        """Every set of channels that can be pruned (see model/channel_groups.py). With ASF the
        stride-8 output feeds CPAM, whose channel attention mixes neighbouring channels: kept whole."""
        b_consumers: list[list[InSlot | OutSlot]] = [list(s) for s in self.neck.input_slots()]
        if self.ssff is not None:
            for level, slots in enumerate(self.ssff.input_slots()):
                b_consumers[level] += slots
        groups = self.backbone.groups(b_consumers)
        outside: list[list[InSlot] | None] = [self.head.in_slots(level) for level in range(3)]
        if self.cpam is not None:
            outside[0] = None
            groups += self.ssff.groups("ssff")
        groups += self.neck.groups(outside)
        groups += self.head.groups()
        return groups


def build_detector(config: ModelConfig) -> Detector:
    return Detector(config)
