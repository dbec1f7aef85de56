"""YOLOv8's CSPDarknet backbone (yolov8.yaml layers 0-9), returning B2 (stride 4) to B5 (stride 32)."""

from __future__ import annotations

import torch
from torch import nn

from .blocks import C2f, SPPF, Conv
from .channel_groups import ChannelGroup, InSlot, OutSlot
from .config import ModelConfig


class Backbone(nn.Module):
    def __init__(self, config: ModelConfig):
        super().__init__()
        ch, depth = config.channels, config.depth
        self.stem = Conv(3, ch(64), 3, 2)  # P1/2
        self.down2 = Conv(ch(64), ch(128), 3, 2)  # P2/4
        self.c2f2 = C2f(ch(128), ch(128), depth(3), shortcut=True)  # B2
        self.down3 = Conv(ch(128), ch(256), 3, 2)  # P3/8
        self.c2f3 = C2f(ch(256), ch(256), depth(6), shortcut=True)  # B3
        self.down4 = Conv(ch(256), ch(512), 3, 2)  # P4/16
        self.c2f4 = C2f(ch(512), ch(512), depth(6), shortcut=True)  # B4
        self.down5 = Conv(ch(512), ch(1024), 3, 2)  # P5/32
        self.c2f5 = C2f(ch(1024), ch(1024), depth(3), shortcut=True)
        self.sppf = SPPF(ch(1024), ch(1024), 5)  # B5

    def forward(self, x: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor, torch.Tensor]:
        b2 = self.c2f2(self.down2(self.stem(x)))
        b3 = self.c2f3(self.down3(b2))
        b4 = self.c2f4(self.down4(b3))
        b5 = self.sppf(self.c2f5(self.down5(b4)))
        return b2, b3, b4, b5

    def output_modules(self) -> tuple[nn.Module, nn.Module, nn.Module, nn.Module]:
        """The modules producing B2..B5 (each has out_slots() and out_channels)."""
        return self.c2f2, self.c2f3, self.c2f4, self.sppf

    def groups(self, b_consumers: list[list[InSlot | OutSlot]]) -> list[ChannelGroup]:
        """Internal groups, plus one group per B2..B5 whose consumers outside the backbone the caller
        lists (OutSlots among them are residual writers into the same channels, e.g. High-IFM's)."""
        groups: list[ChannelGroup] = []
        chain = [
            (self.stem, self.down2),
            (self.down2, self.c2f2),
            (self.down3, self.c2f3),
            (self.down4, self.c2f4),
            (self.down5, self.c2f5),
            (self.c2f5, self.sppf),
        ]
        for producer, consumer in chain:
            groups.append(
                ChannelGroup(f"backbone.{_name(self, producer)}", producer.out_channels, producer.out_slots(), consumer.in_slots())
            )
        for c2f in (self.c2f2, self.c2f3, self.c2f4, self.c2f5):
            groups += c2f.groups(f"backbone.{_name(self, c2f)}")
        groups += self.sppf.groups("backbone.sppf")
        # B2..B4 also feed the next downsampling conv inside the backbone.
        inner: list[list[InSlot]] = [self.down3.in_slots(), self.down4.in_slots(), self.down5.in_slots(), []]
        for level, (module, outside) in enumerate(zip(self.output_modules(), b_consumers)):
            ins = inner[level] + [s for s in outside if isinstance(s, InSlot)]
            outs = module.out_slots() + [s for s in outside if isinstance(s, OutSlot)]
            if ins:
                groups.append(ChannelGroup(f"backbone.B{level + 2}", module.out_channels, outs, ins))
        return groups


def _name(parent: nn.Module, child: nn.Module) -> str:
    for name, module in parent.named_children():
        if module is child:
            return name
    return "?"


__all__ = ["Backbone"]
