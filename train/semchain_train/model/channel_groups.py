"""Channel groups: which convolution channels must be removed together when pruning (lamp.py).

A group is one set of channel indices 0..size-1 shared by several tensors: the convolutions that
produce those channels (their output rows at an offset, with their batch norm), the depthwise
convolutions that pass them through, and the convolutions that consume them (input columns at an
offset, e.g. a slot of a concatenation). Elementwise operations (activations, residual adds,
pooling, resizing, gating) keep channel identity, so everything that adds into or reads from the
same channel belongs to one group. Offsets refer to the layout at the time the groups are built.
Channels that no group lists are never pruned (e.g. the head's outputs, attention heads, CPAM's
channel-neighbourhood convolution).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from torch import nn

@dataclass
class OutSlot:
    """Output channels offset..offset+size-1 of 'conv' (rows of its weight) and of its batch norm."""

    conv: nn.Module
    bn: nn.Module | None = None
    offset: int = 0


@dataclass
class InSlot:
    """Input channels offset..offset+size-1 of 'conv' (columns of its weight)."""

    conv: nn.Module
    offset: int = 0


@dataclass
class DepthwiseSlot:
    """A depthwise convolution (groups == channels) whose channels pass through: pruned in and out."""

    conv: nn.Module
    bn: nn.Module | None = None
    offset: int = 0


@dataclass
class ChannelGroup:
    name: str
    size: int
    outs: list[OutSlot]
    ins: list[InSlot]
    depthwise: list[DepthwiseSlot] = field(default_factory=list)


def conv_out(module: nn.Module) -> int:
    """Output channel count of a Conv block or a bare convolution, read from its weights."""
    conv = getattr(module, "conv", module)
    return int(conv.weight.shape[0])


def conv_in(module: nn.Module) -> int:
    conv = getattr(module, "conv", module)
    return int(conv.weight.shape[1]) * int(getattr(conv, "groups", 1))


def shift(slots: list[InSlot], offset: int) -> list[InSlot]:
    """The same consumers, 'offset' channels further into their inputs (a later concat slot)."""
    return [InSlot(slot.conv, slot.offset + offset) for slot in slots]


def link(name: str, producer_outs: list[OutSlot], size: int, consumer_ins: list[InSlot]) -> ChannelGroup:
    return ChannelGroup(name=name, size=size, outs=list(producer_outs), ins=list(consumer_ins))
