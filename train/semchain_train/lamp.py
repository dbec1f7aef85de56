"""LAMP structured pruning (Lee et al., ICLR 2021; seed 000 eq. 1) of output channels to a FLOPs
speed-up ratio.

For each prunable layer (a channel group, model/channel_groups.py: the convolutions producing a
set of channels, with everything that must shrink with them) the channel scores are the squared
weight norms s_u = ||W_u||^2 of the producing convolutions' output rows. Sorted ascending,
LAMP(u) = s_u / sum_{v >= u} s_v (eq. 1), which makes scores comparable across layers. Channels are
removed globally in ascending LAMP score until FLOPs(before) / FLOPs(after) reaches the requested
ratio (a search over the number of channels removed, each candidate measured by flops.py on a
copy), keeping at least max(min_channels, min_fraction x width) channels of every group. The
removal is physical: convolution rows and batch-norm entries of the producers, input columns of
the consumers (at their concat offsets), depthwise convolutions in between.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field

import torch
from torch import nn

from .flops import ModelCost, measure
from .model.channel_groups import ChannelGroup


@dataclass
class PruneOptions:
    """speedup       FLOPs before / FLOPs after to reach (seed 000: 2.0)
    input_size       (width, height) at which FLOPs are counted
    min_channels     every group keeps at least this many channels ...
    min_fraction     ... and at least this fraction of its width
    round_to         kept widths are multiples of this (or the group's whole width): CPU
                     convolutions vectorise over blocks of channels, so odd widths buy less speed"""

    speedup: float = 2.0
    input_size: tuple[int, int] = (320, 256)
    min_channels: int = 8
    min_fraction: float = 0.1
    round_to: int = 1


@dataclass
class PruneResult:
    before: ModelCost
    after: ModelCost
    removed: dict[str, list[int]] = field(default_factory=dict)

    @property
    def speedup(self) -> float:
        return self.before.gflops / self.after.gflops


def lamp_scores(norms: torch.Tensor) -> torch.Tensor:
    """LAMP scores (eq. 1) of one layer's units given their squared norms, in the input order."""
    norms = norms.detach().double().flatten()
    order = torch.argsort(norms, stable=True)
    sorted_norms = norms[order]
    # Suffix sums: sum over v >= u in ascending order, u itself included.
    suffix = torch.flip(torch.cumsum(torch.flip(sorted_norms, [0]), 0), [0])
    scores = torch.zeros_like(norms)
    scores[order] = sorted_norms / suffix.clamp_min(torch.finfo(torch.float64).tiny)
    return scores


def channel_norms(group: ChannelGroup) -> torch.Tensor:
    """||W_u||^2 of each channel u of the group, summed over the convolutions producing it."""
    total = torch.zeros(group.size, dtype=torch.float64)
    for slot in group.outs:
        rows = slot.conv.weight.detach()[slot.offset : slot.offset + group.size]
        total += rows.double().reshape(group.size, -1).pow(2).sum(1)
    return total


def _keep_minimum(group: ChannelGroup, options: PruneOptions) -> int:
    return min(group.size, max(options.min_channels, math.ceil(options.min_fraction * group.size)))


def ranked_channels(groups: list[ChannelGroup], options: PruneOptions) -> list[tuple[float, str, int]]:
    """(LAMP score, group name, channel) of every removable channel, ascending. A group's largest
    channels (its minimum width) are never listed; since LAMP grows with the norm inside a layer,
    the smallest-norm channels of each group are always the ones removed first."""
    ranked = []
    for group in groups:
        norms = channel_norms(group)
        scores = lamp_scores(norms)
        removable = group.size - _keep_minimum(group, options)
        for channel in torch.argsort(norms, stable=True)[:removable].tolist():
            ranked.append((float(scores[channel]), group.name, int(channel)))
    ranked.sort()
    return ranked


def _unique_groups(model: nn.Module) -> list[ChannelGroup]:
    groups = model.channel_groups()
    names = [g.name for g in groups]
    duplicates = {n for n in names if names.count(n) > 1}
    if duplicates:
        raise ValueError(f"channel groups with the same name: {sorted(duplicates)}")
    return groups


def _index_param(param: torch.Tensor, dim: int, keep: torch.Tensor) -> torch.Tensor:
    return param.detach().index_select(dim, keep).clone()


def remove_channels(model: nn.Module, removed: dict[str, list[int]]) -> None:
    """Physically removes the channels 'removed[group name]' from 'model' (in place)."""
    groups = {g.name: g for g in _unique_groups(model)}
    out_masks: dict[nn.Module, torch.Tensor] = {}
    in_masks: dict[nn.Module, torch.Tensor] = {}
    norms: dict[nn.Module, nn.Module] = {}
    depthwise: set[nn.Module] = set()

    def mask(table: dict, conv: nn.Module, size: int) -> torch.Tensor:
        if conv not in table:
            table[conv] = torch.ones(size, dtype=torch.bool)
        return table[conv]

    for name, channels in removed.items():
        if name not in groups:
            raise ValueError(f"no channel group named {name!r} in this model")
        group = groups[name]
        index = torch.as_tensor(sorted(set(channels)), dtype=torch.long)
        if len(index) and (index.min() < 0 or index.max() >= group.size):
            raise ValueError(f"group {name}: channel out of range 0..{group.size - 1}")
        if len(index) >= group.size:
            raise ValueError(f"group {name}: cannot remove all {group.size} channels")
        for slot in group.outs:
            mask(out_masks, slot.conv, slot.conv.weight.shape[0])[slot.offset + index] = False
            if slot.bn is not None:
                norms[slot.conv] = slot.bn
        for slot in group.ins:
            width = slot.conv.weight.shape[1] * getattr(slot.conv, "groups", 1)
            mask(in_masks, slot.conv, width)[slot.offset + index] = False
        for slot in group.depthwise:
            mask(out_masks, slot.conv, slot.conv.weight.shape[0])[slot.offset + index] = False
            depthwise.add(slot.conv)
            if slot.bn is not None:
                norms[slot.conv] = slot.bn

    for conv in set(out_masks) | set(in_masks):
        weight = conv.weight
        if conv in out_masks:
            keep = torch.nonzero(out_masks[conv]).flatten()
            weight = _index_param(weight, 0, keep)
            if conv.bias is not None:
                conv.bias = nn.Parameter(_index_param(conv.bias, 0, keep))
            bn = norms.get(conv)
            if bn is not None:
                bn.weight = nn.Parameter(_index_param(bn.weight, 0, keep))
                bn.bias = nn.Parameter(_index_param(bn.bias, 0, keep))
                bn.running_mean = _index_param(bn.running_mean, 0, keep)
                bn.running_var = _index_param(bn.running_var, 0, keep)
                bn.num_features = len(keep)
            conv.out_channels = len(keep)
            if conv in depthwise:
                conv.groups = len(keep)
                conv.in_channels = len(keep)
        if conv in in_masks and conv not in depthwise:
            keep = torch.nonzero(in_masks[conv]).flatten()
            weight = _index_param(weight, 1, keep)
            conv.in_channels = len(keep)
        conv.weight = nn.Parameter(weight)


def zero_channels(model: nn.Module, removed: dict[str, list[int]]) -> None:
    """Makes the channels 'removed[group name]' exactly zero without removing them (the producers'
    rows, biases and batch-norm scale and shift), for comparing with the physically pruned model."""
    groups = {g.name: g for g in _unique_groups(model)}
    with torch.no_grad():
        for name, channels in removed.items():
            group = groups[name]
            index = torch.as_tensor(sorted(set(channels)), dtype=torch.long)
            for slot in list(group.outs) + list(group.depthwise):
                rows = slot.offset + index
                slot.conv.weight[rows] = 0.0
                if slot.conv.bias is not None:
                    slot.conv.bias[rows] = 0.0
                if slot.bn is not None:
                    slot.bn.weight[rows] = 0.0
                    slot.bn.bias[rows] = 0.0


def _removal_plan(ranked: list[tuple[float, str, int]], count: int, sizes: dict[str, int], round_to: int = 1) -> dict[str, list[int]]:
    """The first 'count' ranked channels, each group's removal then cut back (dropping its
    highest-LAMP removals) until the width it keeps is a multiple of round_to."""
    plan: dict[str, list[int]] = {}
    for _, name, channel in ranked[:count]:
        plan.setdefault(name, []).append(channel)
    if round_to > 1:
        for name in list(plan):
            kept = sizes[name] - len(plan[name])
            excess = (-kept) % round_to
            plan[name] = plan[name][: max(len(plan[name]) - excess, 0)]
            if not plan[name]:
                del plan[name]
    return plan


def plan_pruning(
    model: nn.Module, options: PruneOptions, progress: bool = False
) -> tuple[dict[str, list[int]], ModelCost, ModelCost]:
    """The fewest lowest-LAMP channels whose removal reaches options.speedup (FLOPs measured on a
    copy). Raises ValueError when even the minimum widths do not reach it."""
    from tqdm import tqdm

    if not options.speedup >= 1.0:
        raise ValueError(f"speed-up ratio {options.speedup}: expected at least 1.0")
    if options.round_to < 1:
        raise ValueError(f"round_to {options.round_to}: expected at least 1")
    before = measure(model, options.input_size)
    groups = _unique_groups(model)
    sizes = {g.name: g.size for g in groups}
    ranked = ranked_channels(groups, options)

    def plan_of(count: int) -> dict[str, list[int]]:
        return _removal_plan(ranked, count, sizes, options.round_to)

    def cost_after(count: int) -> ModelCost:
        trial = copy.deepcopy(model)
        remove_channels(trial, plan_of(count))
        return measure(trial, options.input_size)

    target = before.gflops / options.speedup
    steps = math.ceil(math.log2(len(ranked) + 1)) + 1
    with tqdm(total=steps, desc="LAMP search", unit="trial", disable=not progress) as bar:
        most = cost_after(len(ranked))
        bar.update()
        if most.gflops > target * (1 + 1e-9):
            raise ValueError(
                f"speed-up {options.speedup} unreachable: removing every prunable channel down to the minimum widths "
                f"gives {before.gflops / most.gflops:.2f}"
            )
        # FLOPs fall monotonically with the number of channels removed: bisect for the fewest.
        low, high, best = 0, len(ranked), most
        while low < high:
            middle = (low + high) // 2
            cost = cost_after(middle)
            bar.update()
            if cost.gflops <= target * (1 + 1e-9):
                high, best = middle, cost
            else:
                low = middle + 1
    return plan_of(low), before, best


def prune(model: nn.Module, options: PruneOptions | None = None, progress: bool = False) -> PruneResult:
    """Prunes 'model' in place to options.speedup; returns the costs before and after."""
    options = options or PruneOptions()
    plan, before, _ = plan_pruning(model, options, progress)
    remove_channels(model, plan)
    return PruneResult(before=before, after=measure(model, options.input_size), removed=plan)
