"""YOLOv8's building blocks (Conv, Bottleneck, C2f, SPPF) with their pruning channel groups."""

from __future__ import annotations

import torch
import torch.nn.functional as F
from torch import nn

from .channel_groups import ChannelGroup, InSlot, OutSlot, conv_out, link

# ultralytics' batch-norm settings for YOLOv8.
BN_EPS = 1e-3
BN_MOMENTUM = 0.03


class Conv(nn.Module):
    """Convolution, batch norm, activation (SiLU unless 'act' says otherwise)."""

    def __init__(self, c_in: int, c_out: int, k: int = 1, s: int = 1, groups: int = 1, act: nn.Module | None = None):
        super().__init__()
        self.conv = nn.Conv2d(c_in, c_out, k, s, k // 2, groups=groups, bias=False)
        self.bn = nn.BatchNorm2d(c_out, eps=BN_EPS, momentum=BN_MOMENTUM)
        self.act = nn.SiLU() if act is None else act

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.act(self.bn(self.conv(x)))

    def out_slots(self) -> list[OutSlot]:
        return [OutSlot(self.conv, self.bn, 0)]

    def in_slots(self) -> list[InSlot]:
        return [InSlot(self.conv, 0)]

    @property
    def out_channels(self) -> int:
        return conv_out(self)


class Bottleneck(nn.Module):
    """Two 3x3 convolutions, with a residual add when 'shortcut' (C2f's inner block)."""

    def __init__(self, c_in: int, c_out: int, shortcut: bool):
        super().__init__()
        self.cv1 = Conv(c_in, c_out, 3)
        self.cv2 = Conv(c_out, c_out, 3)
        self.add = shortcut and c_in == c_out

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        y = self.cv2(self.cv1(x))
        return x + y if self.add else y


class _InputCv1OutputCv2:
    """Slots of a block that reads its input with cv1 and writes its output with cv2."""

    cv1: Conv
    cv2: Conv

    def out_slots(self) -> list[OutSlot]:
        return self.cv2.out_slots()

    def in_slots(self) -> list[InSlot]:
        return self.cv1.in_slots()

    @property
    def out_channels(self) -> int:
        return conv_out(self.cv2)


class C2f(_InputCv1OutputCv2, nn.Module):
    """YOLOv8's CSP block: cv1 splits into two parts; the second runs through n bottlenecks whose
    outputs are all concatenated with both parts into cv2.

    Split sizes are read from the weights (first part = cv1's outputs not consumed by the first
    bottleneck), so that the two parts may be pruned to different widths.
    """

    def __init__(self, c_in: int, c_out: int, n: int = 1, shortcut: bool = False):
        super().__init__()
        hidden = c_out // 2
        self.cv1 = Conv(c_in, 2 * hidden, 1)
        self.cv2 = Conv((2 + n) * hidden, c_out, 1)
        self.m = nn.ModuleList(Bottleneck(hidden, hidden, shortcut) for _ in range(n))
        self.shortcut = shortcut

    def split_sizes(self) -> tuple[int, int]:
        second = int(self.m[0].cv1.conv.weight.shape[1])
        return conv_out(self.cv1) - second, second

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        first, second = self.split_sizes()
        y = list(self.cv1(x).split([first, second], 1))
        for block in self.m:
            y.append(block(y[-1]))
        return self.cv2(torch.cat(y, 1))

    def groups(self, name: str) -> list[ChannelGroup]:
        first, second = self.split_sizes()
        groups = [link(f"{name}.part1", [OutSlot(self.cv1.conv, self.cv1.bn, 0)], first, [InSlot(self.cv2.conv, 0)])]
        for i, block in enumerate(self.m):
            hidden = conv_out(block.cv1)
            groups.append(link(f"{name}.m{i}.hidden", block.cv1.out_slots(), hidden, [InSlot(block.cv2.conv, 0)]))
        if self.shortcut:
            # Residual stream: part2 and every bottleneck's cv2 add into the same channels.
            outs = [OutSlot(self.cv1.conv, self.cv1.bn, first)] + [b.cv2.out_slots()[0] for b in self.m]
            ins = [InSlot(b.cv1.conv, 0) for b in self.m]
            ins += [InSlot(self.cv2.conv, first + i * second) for i in range(len(self.m) + 1)]
            groups.append(link(f"{name}.stream", outs, second, ins))
        else:
            # Without residual adds every bottleneck output is its own tensor.
            offset = first
            producer, size = [OutSlot(self.cv1.conv, self.cv1.bn, first)], second
            for i, block in enumerate(self.m):
                groups.append(link(f"{name}.in{i}", producer, size, [InSlot(block.cv1.conv, 0), InSlot(self.cv2.conv, offset)]))
                offset += size
                producer, size = block.cv2.out_slots(), conv_out(block.cv2)
            groups.append(link(f"{name}.out{len(self.m) - 1}", producer, size, [InSlot(self.cv2.conv, offset)]))
        return groups


class SPPF(_InputCv1OutputCv2, nn.Module):
    """Spatial pyramid pooling (fast): three chained 5x5 max pools concatenated with their input."""

    def __init__(self, c_in: int, c_out: int, k: int = 5):
        super().__init__()
        hidden = c_in // 2
        self.cv1 = Conv(c_in, hidden, 1)
        self.cv2 = Conv(hidden * 4, c_out, 1)
        self.k = k

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        y = [self.cv1(x)]
        for _ in range(3):
            y.append(F.max_pool2d(y[-1], self.k, 1, self.k // 2))
        return self.cv2(torch.cat(y, 1))

    def groups(self, name: str) -> list[ChannelGroup]:
        hidden = conv_out(self.cv1)
        return [link(f"{name}.hidden", self.cv1.out_slots(), hidden, [InSlot(self.cv2.conv, i * hidden) for i in range(4)])]
