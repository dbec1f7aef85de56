"""Gold-YOLO's gather-and-distribute neck (Wang et al., NeurIPS 2023; seed 000 §2.1) on YOLOv8.

Low-GD gathers B2..B5 at B4's size (Low-FAM: average pooling / bilinear upsampling), fuses them
(Low-IFM: 1x1 conv, C2f, 1x1 conv to the two injection widths) and injects the global feature into
the top-down levels P4 and P3; each level's local feature comes from a LAF (three neighbouring
maps aligned to its size, 1x1 convs, concat, 1x1 fuse). High-GD gathers P3, P4, B5 at B5's size
(High-FAM, at stride 64 as Gold-YOLO's c2t_stride 2), fuses them with attention (High-IFM: transformer blocks, 1x1 conv) and injects into
the bottom-up levels N4 and N5 (local feature: the level below pooled and concatenated with the
reduced top-down map). Gold-YOLO's RepVGG blocks are YOLOv8's C2f here. With 'tfe' (ASF on) the
LAFs of P4 and P3 fuse as ASF-YOLO's triple feature encoding (max + average pooling of the larger
scale, nearest upsampling of the smaller).
"""

from __future__ import annotations

import torch
from torch import nn

from .blocks import BN_EPS, BN_MOMENTUM, C2f, Conv
from .channel_groups import ChannelGroup, DepthwiseSlot, InSlot, OutSlot, conv_out, link, shift
from .config import ModelConfig
from .fusion_ops import avg_pool_to, hard_sigmoid, max_pool_to, relu6, spatial, upsample_to

Slot = InSlot | OutSlot


class LocalFusion(nn.Module):
    """LAF of the top-down levels (Gold-YOLO's SimFusion_3in): the larger scale pooled down and the
    level's own map, each by a 1x1 conv to c_out, and the smaller scale (already c_out wide: the
    reduce conv's output, so no conv, as Gold-YOLO's identity branch) upsampled; concatenated and
    fused by a 1x1 conv."""

    def __init__(self, c_large: int, c_mid: int, c_out: int, tfe: bool):
        super().__init__()
        self.large = Conv(c_large, c_out, 1)
        self.mid = Conv(c_mid, c_out, 1)
        self.fuse = Conv(3 * c_out, c_out, 1)
        self.tfe = tfe

    def forward(self, large: torch.Tensor, mid: torch.Tensor, small: torch.Tensor) -> torch.Tensor:
        size = spatial(mid)
        if self.tfe:  # ASF-YOLO's TFE: convolve, then max + average pool; nearest upsampling
            large = self.large(large)
            large = max_pool_to(large, size) + avg_pool_to(large, size)
            small = upsample_to(small, size, "nearest")
        else:  # Gold-YOLO: average pool, then convolve; bilinear upsampling
            large = self.large(avg_pool_to(large, size))
            small = upsample_to(small, size, "bilinear")
        return self.fuse(torch.cat((large, self.mid(mid), small), 1))

    def small_slots(self) -> list[InSlot]:
        return [InSlot(self.fuse.conv, self.large.out_channels + self.mid.out_channels)]

    def groups(self, name: str) -> list[ChannelGroup]:
        return [
            link(f"{name}.large", self.large.out_slots(), self.large.out_channels, [InSlot(self.fuse.conv, 0)]),
            link(f"{name}.mid", self.mid.out_slots(), self.mid.out_channels, [InSlot(self.fuse.conv, self.large.out_channels)]),
        ]


class Inject(nn.Module):
    """Gold-YOLO's information injection: local_embedding(local) * h_sigmoid(global_act(global)) +
    global_embedding(global), the global maps resized to the local size (bilinear up / average pool)."""

    def __init__(self, c_local: int, c_global: int, c_out: int):
        super().__init__()
        self.local_embedding = Conv(c_local, c_out, 1, act=nn.Identity())
        self.global_embedding = Conv(c_global, c_out, 1, act=nn.Identity())
        self.global_act = Conv(c_global, c_out, 1, act=nn.Identity())

    def _resize(self, g: torch.Tensor, size: tuple[int, int]) -> torch.Tensor:
        if spatial(g)[0] >= size[0]:
            return avg_pool_to(g, size)
        return upsample_to(g, size, "bilinear")

    def forward(self, local: torch.Tensor, global_feature: torch.Tensor) -> torch.Tensor:
        size = spatial(local)
        gate = self._resize(hard_sigmoid(self.global_act(global_feature)), size)
        embedding = self._resize(self.global_embedding(global_feature), size)
        return self.local_embedding(local) * gate + embedding

    @property
    def global_channels(self) -> int:
        return int(self.global_embedding.conv.weight.shape[1])

    def global_slots(self) -> list[InSlot]:
        return [InSlot(self.global_embedding.conv, 0), InSlot(self.global_act.conv, 0)]

    def out_slots(self) -> list[OutSlot]:
        return self.local_embedding.out_slots() + self.global_embedding.out_slots() + self.global_act.out_slots()


class ConvBN(nn.Module):
    """1x1 convolution + batch norm without activation (Gold-YOLO's Conv2d_BN)."""

    def __init__(self, c_in: int, c_out: int, bn_weight: float = 1.0):
        super().__init__()
        self.conv = nn.Conv2d(c_in, c_out, 1, bias=False)
        self.bn = nn.BatchNorm2d(c_out, eps=BN_EPS, momentum=BN_MOMENTUM)
        nn.init.constant_(self.bn.weight, bn_weight)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.bn(self.conv(x))

    def out_slots(self, offset: int = 0) -> list[OutSlot]:
        return [OutSlot(self.conv, self.bn, offset)]


class Attention(nn.Module):
    """Multi-head self-attention over the pixels with 1x1-conv projections (Gold-YOLO's Attention:
    key_dim 8, 4 heads, values attn_ratio x key_dim wide, ReLU6 before the output projection,
    whose BN starts at zero so each block starts as the identity)."""

    def __init__(self, dim: int, key_dim: int = 8, heads: int = 4, attn_ratio: int = 2):
        super().__init__()
        self.key_dim, self.heads, self.value_dim = key_dim, heads, attn_ratio * key_dim
        self.scale = key_dim**-0.5
        self.q = ConvBN(dim, key_dim * heads)
        self.k = ConvBN(dim, key_dim * heads)
        self.v = ConvBN(dim, self.value_dim * heads)
        self.proj = ConvBN(self.value_dim * heads, dim, bn_weight=0.0)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        b, h, w = int(x.shape[0]), int(x.shape[2]), int(x.shape[3])
        q = self.q(x).reshape(b * self.heads, self.key_dim, h * w).permute(0, 2, 1)
        k = self.k(x).reshape(b * self.heads, self.key_dim, h * w)
        v = self.v(x).reshape(b * self.heads, self.value_dim, h * w).permute(0, 2, 1)
        attention = torch.softmax(torch.matmul(q, k) * self.scale, dim=-1)
        y = torch.matmul(attention, v).permute(0, 2, 1).reshape(b, self.heads * self.value_dim, h, w)
        return self.proj(relu6(y))

    def functional_macs(self, inputs: tuple, output: torch.Tensor) -> int:
        x = inputs[0]
        pixels = int(x.shape[2]) * int(x.shape[3])
        return int(x.shape[0]) * self.heads * pixels * pixels * (self.key_dim + self.value_dim)


class Mlp(nn.Module):
    """Gold-YOLO's MLP: 1x1 conv+BN, 3x3 depthwise conv, ReLU6, 1x1 conv+BN."""

    def __init__(self, dim: int, hidden: int):
        super().__init__()
        self.fc1 = ConvBN(dim, hidden)
        self.dw = nn.Conv2d(hidden, hidden, 3, 1, 1, groups=hidden, bias=True)
        self.fc2 = ConvBN(hidden, dim)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.fc2(relu6(self.dw(self.fc1(x))))


class TransformerBlock(nn.Module):
    def __init__(self, dim: int, mlp_ratio: float = 1.0):
        super().__init__()
        self.attention = Attention(dim)
        self.mlp = Mlp(dim, int(dim * mlp_ratio))

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        x = x + self.attention(x)
        return x + self.mlp(x)


class HighIFM(nn.Module):
    """High-GD's information fusion: transformer blocks on the gathered map, 1x1 conv to the
    injection widths of N4 and N5."""

    def __init__(self, dim: int, c_out: int, depth: int = 2):
        super().__init__()
        self.blocks = nn.ModuleList(TransformerBlock(dim) for _ in range(depth))
        self.out = Conv(dim, c_out, 1)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        for block in self.blocks:
            x = block(x)
        return self.out(x)

    def stream_slots(self, offset: int) -> list[Slot]:
        """Where channels of the gathered map live: read by q, k, v, fc1 and the output conv,
        written (residual adds) by each block's output projection and fc2."""
        slots: list[Slot] = []
        for block in self.blocks:
            a, m = block.attention, block.mlp
            slots += [InSlot(a.q.conv, offset), InSlot(a.k.conv, offset), InSlot(a.v.conv, offset), InSlot(m.fc1.conv, offset)]
            slots += a.proj.out_slots(offset) + m.fc2.out_slots(offset)
        slots.append(InSlot(self.out.conv, offset))
        return slots

    def groups(self, name: str) -> list[ChannelGroup]:
        groups = []
        for i, block in enumerate(self.blocks):
            m = block.mlp
            group = link(f"{name}.block{i}.mlp", m.fc1.out_slots(), conv_out(m.fc1.conv), [InSlot(m.fc2.conv, 0)])
            group.depthwise.append(DepthwiseSlot(m.dw, None, 0))
            groups.append(group)
        return groups


class GDNeck(nn.Module):
    def __init__(self, config: ModelConfig, b_channels: tuple[int, int, int, int], tfe: bool = False):
        super().__init__()
        ch, n = config.channels, config.depth(3)
        c2, c3, c4, c5 = b_channels
        c_p3, c_p4, c_n4, c_n5 = ch(256), ch(512), ch(512), ch(1024)
        embed_low = ch(256)  # Gold-YOLO-S: embed_dim_p 128
        # Low-GD
        self.low_ifm_in = Conv(c2 + c3 + c4 + c5, embed_low, 1)
        self.low_ifm_block = C2f(embed_low, embed_low, n)
        self.low_ifm_out = Conv(embed_low, c_p4 + c_p3, 1)
        self.reduce5 = Conv(c5, c_p4, 1)
        self.laf4 = LocalFusion(c3, c4, c_p4, tfe)
        self.inject4 = Inject(c_p4, c_p4, c_p4)
        self.block4 = C2f(c_p4, c_p4, n)
        self.reduce4 = Conv(c_p4, c_p3, 1)
        self.laf3 = LocalFusion(c2, c3, c_p3, tfe)
        self.inject3 = Inject(c_p3, c_p3, c_p3)
        self.block3 = C2f(c_p3, c_p3, n)
        # High-GD
        self.high_ifm = HighIFM(c_p3 + c_p4 + c5, c_n4 + c_n5)
        self.inject_n4 = Inject(c_p3 + c_p3, c_n4, c_n4)
        self.block_n4 = C2f(c_n4, c_n4, n)
        self.inject_n5 = Inject(c_n4 + c_p4, c_n5, c_n5)
        self.block_n5 = C2f(c_n5, c_n5, n)
        self.out_channels = (c_p3, c_n4, c_n5)

    def forward(self, b2: torch.Tensor, b3: torch.Tensor, b4: torch.Tensor, b5: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        size4, size5 = spatial(b4), spatial(b5)
        # Low-FAM: everything to B4's size; Low-IFM; split for the two injections.
        low = torch.cat((avg_pool_to(b2, size4), avg_pool_to(b3, size4), b4, upsample_to(b5, size4, "bilinear")), 1)
        low = self.low_ifm_out(self.low_ifm_block(self.low_ifm_in(low)))
        g4, g3 = low.split([self.inject4.global_channels, self.inject3.global_channels], 1)
        r5 = self.reduce5(b5)
        p4 = self.block4(self.inject4(self.laf4(b3, b4, r5), g4))
        r4 = self.reduce4(p4)
        p3 = self.block3(self.inject3(self.laf3(b2, b3, r4), g3))
        # High-FAM: P3, P4, B5 pooled to half B5's size (Gold-YOLO's c2t_stride 2; B5's own size
        # when a side is odd); High-IFM; split for N4 and N5 (injections resize back).
        high_size = (size5[0] // 2, size5[1] // 2) if size5[0] % 2 == 0 and size5[1] % 2 == 0 else size5
        high = torch.cat((avg_pool_to(p3, high_size), avg_pool_to(p4, high_size), avg_pool_to(b5, high_size)), 1)
        high = self.high_ifm(high)
        g_n4, g_n5 = high.split([self.inject_n4.global_channels, self.inject_n5.global_channels], 1)
        n4 = self.block_n4(self.inject_n4(torch.cat((avg_pool_to(p3, spatial(p4)), r4), 1), g_n4))
        n5 = self.block_n5(self.inject_n5(torch.cat((avg_pool_to(n4, size5), r5), 1), g_n5))
        return p3, n4, n5

    def input_slots(self) -> list[list[Slot]]:
        """Consumers (and residual writers) of B2, B3, B4, B5 inside the neck."""
        # Low-FAM concat offsets: B2, B3, B4, B5 widths are the backbone's, read from the LAF convs.
        c2 = int(self.laf3.large.conv.weight.shape[1])
        c3 = int(self.laf3.mid.conv.weight.shape[1])
        c4 = int(self.laf4.mid.conv.weight.shape[1])
        low = self.low_ifm_in.in_slots()
        p3_width, p4_width = self.block3.out_channels, self.block4.out_channels
        return [
            low + self.laf3.large.in_slots(),
            shift(low, c2) + self.laf4.large.in_slots() + self.laf3.mid.in_slots(),
            shift(low, c2 + c3) + self.laf4.mid.in_slots(),
            shift(low, c2 + c3 + c4) + self.reduce5.in_slots() + self.high_ifm.stream_slots(p3_width + p4_width),
        ]

    def groups(self, outside: list[list[InSlot] | None]) -> list[ChannelGroup]:
        groups: list[ChannelGroup] = []
        for name in ("low_ifm_block", "block4", "block3", "block_n4", "block_n5"):
            groups += getattr(self, name).groups(f"neck.{name}")
        groups += self.laf4.groups("neck.laf4") + self.laf3.groups("neck.laf3") + self.high_ifm.groups("neck.high_ifm")
        groups.append(link("neck.low_ifm_in", self.low_ifm_in.out_slots(), self.low_ifm_in.out_channels, self.low_ifm_block.in_slots()))
        groups.append(link("neck.low_ifm_mid", self.low_ifm_block.out_slots(), self.low_ifm_block.out_channels, self.low_ifm_out.in_slots()))
        # The IFM outputs are split among the injections: one group per slice.
        for name, ifm_out, injects in (("low", self.low_ifm_out, (self.inject4, self.inject3)), ("high", self.high_ifm.out, (self.inject_n4, self.inject_n5))):
            offset = 0
            for i, inject in enumerate(injects):
                outs = [OutSlot(ifm_out.conv, ifm_out.bn, offset)]
                groups.append(link(f"neck.{name}_global{i}", outs, inject.global_channels, inject.global_slots()))
                offset += inject.global_channels
        for name, inject, block in (("inject4", self.inject4, self.block4), ("inject3", self.inject3, self.block3), ("inject_n4", self.inject_n4, self.block_n4), ("inject_n5", self.inject_n5, self.block_n5)):
            groups.append(link(f"neck.{name}", inject.out_slots(), conv_out(inject.local_embedding), block.in_slots()))
        groups.append(link("neck.laf4", self.laf4.fuse.out_slots(), self.laf4.fuse.out_channels, [InSlot(self.inject4.local_embedding.conv, 0)]))
        groups.append(link("neck.laf3", self.laf3.fuse.out_slots(), self.laf3.fuse.out_channels, [InSlot(self.inject3.local_embedding.conv, 0)]))
        p3_width, p4_width, n4_width = self.block3.out_channels, self.block4.out_channels, self.block_n4.out_channels
        r5_ins = self.laf4.small_slots() + [InSlot(self.inject_n5.local_embedding.conv, n4_width)]
        groups.append(link("neck.reduce5", self.reduce5.out_slots(), self.reduce5.out_channels, r5_ins))
        r4_ins = self.laf3.small_slots() + [InSlot(self.inject_n4.local_embedding.conv, p3_width)]
        groups.append(link("neck.reduce4", self.reduce4.out_slots(), self.reduce4.out_channels, r4_ins))
        p4_slots = self.reduce4.in_slots() + self.high_ifm.stream_slots(p3_width)
        groups.append(_group("neck.P4", self.block4.out_slots(), p4_width, p4_slots))
        inner = [
            self.high_ifm.stream_slots(0) + [InSlot(self.inject_n4.local_embedding.conv, 0)],
            [InSlot(self.inject_n5.local_embedding.conv, 0)],
            [],
        ]
        for level, (module, extra) in enumerate(zip((self.block3, self.block_n4, self.block_n5), outside)):
            if extra is not None:
                groups.append(_group(f"neck.out{level}", module.out_slots(), module.out_channels, inner[level] + extra))
        return groups


def _group(name: str, outs: list[OutSlot], size: int, slots: list[Slot]) -> ChannelGroup:
    """A group whose extra slots may include residual writers (OutSlot) as well as readers."""
    return ChannelGroup(
        name=name,
        size=size,
        outs=outs + [s for s in slots if isinstance(s, OutSlot)],
        ins=[s for s in slots if isinstance(s, InSlot)],
    )
