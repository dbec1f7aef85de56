"""ASF-YOLO's attentional scale-sequence fusion (Kang et al. 2024; seed 000 §2.1):
SSFF (scale sequence feature fusion), TFE (triple feature encoding) and CPAM (channel and position
attention), written with static-shape operations that OpenCV 4.6's DNN runs.
"""

from __future__ import annotations

import math

import torch
import torch.nn.functional as F
from torch import nn

from .blocks import BN_EPS, BN_MOMENTUM, C2f, Conv
from .channel_groups import ChannelGroup, InSlot, link
from .fusion_ops import avg_pool_to, max_pool_to, spatial, upsample_to


class TripleFeatureEncoding(nn.Module):
    """TFE: the larger scale (1x1 conv, then max + average pooled) and the smaller scale (1x1 conv,
    nearest upsampled) brought to the medium scale (c_out wide) and concatenated with it: [large, medium,
    small]."""

    def __init__(self, c_large: int, c_small: int, c_out: int):
        super().__init__()
        self.large = Conv(c_large, c_out, 1)
        self.small = Conv(c_small, c_out, 1)

    def forward(self, large: torch.Tensor, medium: torch.Tensor, small: torch.Tensor) -> torch.Tensor:
        size = spatial(medium)
        large = self.large(large)
        large = max_pool_to(large, size) + avg_pool_to(large, size)
        small = upsample_to(self.small(small), size, "nearest")
        return torch.cat((large, medium, small), 1)

    def large_slots(self) -> list[InSlot]:
        return self.large.in_slots()

    def small_slots(self) -> list[InSlot]:
        return self.small.in_slots()

    def medium_slots(self, consumer: C2f) -> list[InSlot]:
        return [InSlot(consumer.cv1.conv, self.large.out_channels)]

    def groups(self, name: str, consumer: C2f) -> list[ChannelGroup]:
        total = int(consumer.cv1.conv.weight.shape[1])
        small_offset = total - self.small.out_channels
        return [
            link(f"{name}.large", self.large.out_slots(), self.large.out_channels, [InSlot(consumer.cv1.conv, 0)]),
            link(f"{name}.small", self.small.out_slots(), self.small.out_channels, [InSlot(consumer.cv1.conv, small_offset)]),
        ]


class ScaleSequenceConv3d(nn.Module):
    """SSFF's 3D convolution over the scale axis: Conv3d (kernel 1x1x1, as ASF-YOLO), BatchNorm3d,
    LeakyReLU(0.1), then a 3D max pool of depth 3 over the scales.

    OpenCV 4.6's DNN cannot run the 5-D graph (unsqueeze, Conv3d, BatchNorm3d, MaxPool3d), so the
    same computation is written in 2-D: the 1x1x1 kernel is one 1x1 convolution shared by the
    three scale slices, and the depth-3 max pool is the elementwise maximum of the slices. In
    training the slices are stacked along the batch so that the batch statistics are BatchNorm3d's
    (over batch, scales and pixels); in eval each slice runs on its own (the same result) so that the
    ONNX graph stays 4-D. The parameters are the Conv3d's and BatchNorm3d's own.
    """

    def __init__(self, channels: int):
        super().__init__()
        self.conv = nn.Conv3d(channels, channels, kernel_size=(1, 1, 1))
        self.bn = nn.BatchNorm3d(channels, eps=BN_EPS, momentum=BN_MOMENTUM)
        self.act = nn.LeakyReLU(0.1)

    def _conv_bn(self, x: torch.Tensor) -> torch.Tensor:
        y = F.conv2d(x, self.conv.weight[:, :, 0], self.conv.bias)
        bn = self.bn
        if bn.training and bn.num_batches_tracked is not None:
            bn.num_batches_tracked.add_(1)
        return F.batch_norm(y, bn.running_mean, bn.running_var, bn.weight, bn.bias, bn.training, bn.momentum, bn.eps)

    def forward(self, slices: list[torch.Tensor]) -> torch.Tensor:
        if self.training:
            batch = slices[0].shape[0]
            fused = self.act(self._conv_bn(torch.cat(slices, 0))).split(batch, 0)
        else:
            fused = [self.act(self._conv_bn(s)) for s in slices]
        out = fused[0]
        for other in fused[1:]:
            out = torch.max(out, other)
        return out

    def functional_macs(self, inputs: tuple, output: torch.Tensor) -> int:
        # The convolution runs through F.conv2d, so flops.py's Conv3d hook never sees it.
        slices = inputs[0]
        return sum(int(s.numel()) // int(s.shape[1]) for s in slices) * int(self.conv.weight.shape[0]) * int(self.conv.weight.shape[1])


class ScaleSequenceFusion(nn.Module):
    """SSFF: B3, B4, B5 to one channel count (1x1 conv), resized (nearest) to B3's size, stacked as a
    sequence over scales and fused by ScaleSequenceConv3d."""

    def __init__(self, c3: int, c4: int, c5: int, c_out: int):
        super().__init__()
        self.conv3 = Conv(c3, c_out, 1)
        self.conv4 = Conv(c4, c_out, 1)
        self.conv5 = Conv(c5, c_out, 1)
        self.fuse = ScaleSequenceConv3d(c_out)

    def forward(self, b3: torch.Tensor, b4: torch.Tensor, b5: torch.Tensor) -> torch.Tensor:
        size = spatial(b3)
        slices = [self.conv3(b3), upsample_to(self.conv4(b4), size), upsample_to(self.conv5(b5), size)]
        return self.fuse(slices)

    def input_slots(self) -> list[list[InSlot]]:
        return [[], self.conv3.in_slots(), self.conv4.in_slots(), self.conv5.in_slots()]

    def groups(self, name: str) -> list[ChannelGroup]:
        # Channel k of all three slices meets the shared kernel's input k: pruned together.
        outs = self.conv3.out_slots() + self.conv4.out_slots() + self.conv5.out_slots()
        return [link(f"{name}.slices", outs, self.conv3.out_channels, [InSlot(self.fuse.conv, 0)])]


class ChannelAttention(nn.Module):
    """CPAM's channel branch (ECA): global average, a 1-D convolution across neighbouring channels
    (kernel from the channel count, gamma 2, b 1), sigmoid gate. The 1-D convolution is a (k, 1)
    2-D convolution over [B, 1, C, 1] for OpenCV. Its channel neighbourhoods make these channels
    unprunable."""

    def __init__(self, channels: int, gamma: int = 2, b: int = 1):
        super().__init__()
        k = int(abs((math.log2(channels) + b) / gamma))
        k = k if k % 2 else k + 1
        self.conv = nn.Conv2d(1, 1, (k, 1), padding=(k // 2, 0), bias=False)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        y = F.avg_pool2d(x, spatial(x))  # [B, C, 1, 1]
        y = self.conv(y.permute(0, 2, 1, 3)).permute(0, 2, 1, 3)
        return x * torch.sigmoid(y)


class PositionAttention(nn.Module):
    """CPAM's position branch (coordinate attention): averages along W and along H, a shared 1x1
    conv + BN + ReLU on both, then per-axis 1x1 convs and sigmoid gates multiplied onto x."""

    def __init__(self, channels: int, reduction: int = 16):
        super().__init__()
        hidden = max(channels // reduction, 1)
        self.conv = nn.Conv2d(channels, hidden, 1, bias=False)
        self.bn = nn.BatchNorm2d(hidden, eps=BN_EPS, momentum=BN_MOMENTUM)
        self.conv_h = nn.Conv2d(hidden, channels, 1, bias=False)
        self.conv_w = nn.Conv2d(hidden, channels, 1, bias=False)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        h, w = spatial(x)
        x_h = F.avg_pool2d(x, (1, w)).permute(0, 1, 3, 2)  # [B, C, 1, H]
        x_w = F.avg_pool2d(x, (h, 1))  # [B, C, 1, W]
        y = F.relu(self.bn(self.conv(torch.cat((x_h, x_w), 3))))
        y_h, y_w = y.split([h, w], 3)
        gate_h = torch.sigmoid(self.conv_h(y_h.permute(0, 1, 3, 2)))  # [B, C, H, 1]
        gate_w = torch.sigmoid(self.conv_w(y_w))  # [B, C, 1, W]
        return x * gate_h * gate_w


class ChannelPositionAttention(nn.Module):
    """CPAM: N3 = position_attention(channel_attention(P3 branch) + SSFF output)."""

    def __init__(self, channels: int):
        super().__init__()
        self.channel = ChannelAttention(channels)
        self.position = PositionAttention(channels)

    def forward(self, p3: torch.Tensor, ssff: torch.Tensor) -> torch.Tensor:
        return self.position(self.channel(p3) + ssff)


__all__ = ["TripleFeatureEncoding", "ScaleSequenceFusion", "ChannelPositionAttention"]
