"""YOLOv8's PAN neck (yolov8.yaml layers 10-21); with 'tfe' the top-down fusions are ASF-YOLO's
triple feature encoding (larger scale max+avg pooled, smaller scale upsampled, concatenated with
the medium scale after 1x1 convolutions to its channel count), as in ASF-YOLO's neck.
"""

from __future__ import annotations

import torch
from torch import nn

from .asf import TripleFeatureEncoding
from .blocks import C2f, Conv
from .channel_groups import ChannelGroup, InSlot, link, shift
from .config import ModelConfig
from .fusion_ops import spatial, upsample_to


class PanNeck(nn.Module):
    def __init__(self, config: ModelConfig, b_channels: tuple[int, int, int, int], tfe: bool = False):
        super().__init__()
        ch, n = config.channels, config.depth(3)
        c2, c3, c4, c5 = b_channels
        c_p3, c_p4, c_n4, c_n5 = ch(256), ch(512), ch(512), ch(1024)
        self.tfe = tfe
        if tfe:
            self.tfe4 = TripleFeatureEncoding(c3, c5, c4)
            self.td4 = C2f(3 * c4, c_p4, n)
            self.tfe3 = TripleFeatureEncoding(c2, c_p4, c3)
            self.td3 = C2f(3 * c3, c_p3, n)
        else:
            self.td4 = C2f(c5 + c4, c_p4, n)
            self.td3 = C2f(c_p4 + c3, c_p3, n)
        self.down3 = Conv(c_p3, c_p3, 3, 2)
        self.bu4 = C2f(c_p3 + c_p4, c_n4, n)
        self.down4 = Conv(c_n4, c_n4, 3, 2)
        self.bu5 = C2f(c_n4 + c5, c_n5, n)
        self.out_channels = (c_p3, c_n4, c_n5)

    def forward(self, b2: torch.Tensor, b3: torch.Tensor, b4: torch.Tensor, b5: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        if self.tfe:
            p4 = self.td4(self.tfe4(b3, b4, b5))
            p3 = self.td3(self.tfe3(b2, b3, p4))
        else:
            p4 = self.td4(torch.cat((upsample_to(b5, spatial(b4)), b4), 1))
            p3 = self.td3(torch.cat((upsample_to(p4, spatial(b3)), b3), 1))
        n4 = self.bu4(torch.cat((self.down3(p3), p4), 1))
        n5 = self.bu5(torch.cat((self.down4(n4), b5), 1))
        return p3, n4, n5

    def input_slots(self) -> list[list[InSlot]]:
        """Consumers of B2, B3, B4, B5 inside the neck."""
        bu5_b5 = shift(self.bu5.in_slots(), self.down4.out_channels)
        if self.tfe:
            return [
                self.tfe3.large_slots(),
                self.tfe4.large_slots() + self.tfe3.medium_slots(self.td3),
                self.tfe4.medium_slots(self.td4),
                self.tfe4.small_slots() + bu5_b5,
            ]
        c5 = self.bu5.cv1.conv.weight.shape[1] - self.down4.out_channels
        return [[], shift(self.td3.in_slots(), self.td4.out_channels), shift(self.td4.in_slots(), c5), self.td4.in_slots() + bu5_b5]

    def groups(self, outside: list[list[InSlot] | None]) -> list[ChannelGroup]:
        """Internal groups and those of P3, N4, N5 given their consumers outside (None: keep them whole)."""
        groups: list[ChannelGroup] = []
        for name in ("td4", "td3", "bu4", "bu5"):
            groups += getattr(self, name).groups(f"neck.{name}")
        if self.tfe:
            groups += self.tfe4.groups("neck.tfe4", self.td4)
            groups += self.tfe3.groups("neck.tfe3", self.td3)
            p4_ins = self.tfe3.small_slots()
        else:
            p4_ins = self.td3.in_slots()
        p4_ins = p4_ins + shift(self.bu4.in_slots(), self.down3.out_channels)
        groups.append(link("neck.P4", self.td4.out_slots(), self.td4.out_channels, p4_ins))
        groups.append(link("neck.down3", self.down3.out_slots(), self.down3.out_channels, self.bu4.in_slots()))
        groups.append(link("neck.down4", self.down4.out_slots(), self.down4.out_channels, self.bu5.in_slots()))
        outputs = [(self.td3, self.down3.in_slots()), (self.bu4, self.down4.in_slots()), (self.bu5, [])]
        for level, ((module, inner), extra) in enumerate(zip(outputs, outside)):
            if extra is not None:
                groups.append(link(f"neck.out{level}", module.out_slots(), module.out_channels, inner + extra))
        return groups
