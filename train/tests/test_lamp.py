"""LAMP pruning: eq. 1 on hand-made tensors, outputs unchanged where the pruned channels were
zero, the requested FLOPs speed-up reached."""

from __future__ import annotations

import copy
import math

import pytest
import torch
from torch import nn

from randomized_model import COMBINATION_IDS, COMBINATIONS, random_detector
from semchain_train.flops import measure
from semchain_train.lamp import (
    PruneOptions,
    channel_norms,
    lamp_scores,
    plan_pruning,
    ranked_channels,
    remove_channels,
    zero_channels,
)
from semchain_train.model.channel_groups import ChannelGroup, InSlot, OutSlot

SIZE = (64, 64)


def test_lamp_scores_equal_eq_1_by_hand():
    # Squared norms 4, 1, 9, 2 -> ascending 1, 2, 4, 9 with suffix sums 16, 15, 13, 9.
    scores = lamp_scores(torch.tensor([4.0, 1.0, 9.0, 2.0]))
    assert torch.allclose(scores, torch.tensor([4 / 13, 1 / 16, 9 / 9, 2 / 15], dtype=torch.float64))


def test_channel_norms_sum_the_producers_rows():
    a, b = nn.Conv2d(2, 3, 1, bias=False), nn.Conv2d(1, 5, 1, bias=False)
    with torch.no_grad():
        a.weight.copy_(torch.tensor([1.0, 2.0, 0.0, 1.0, 3.0, 0.0]).reshape(3, 2, 1, 1))
        b.weight.copy_(torch.arange(5.0).reshape(5, 1, 1, 1))
    # Group of 3 channels: a's rows 0..2 and b's rows 2..4 (an offset slot).
    group = ChannelGroup("g", 3, [OutSlot(a, None, 0), OutSlot(b, None, 2)], [])
    assert channel_norms(group).tolist() == [5.0 + 4.0, 1.0 + 9.0, 9.0 + 16.0]


def test_ranked_channels_keep_each_groups_minimum_width():
    conv = nn.Conv2d(1, 20, 1)
    group = ChannelGroup("g", 20, [OutSlot(conv, None, 0)], [InSlot(nn.Conv2d(20, 1, 1), 0)])
    ranked = ranked_channels([group], PruneOptions(min_channels=8, min_fraction=0.1))
    assert len(ranked) == 12
    norms = conv.weight.detach().flatten() ** 2
    assert {c for _, _, c in ranked} == set(torch.argsort(norms)[:12].tolist())


@pytest.mark.parametrize("gd,asf", COMBINATIONS, ids=COMBINATION_IDS)
def test_pruned_model_equals_masked_model_and_reaches_speedup(gd, asf):
    model = random_detector(gd, asf, seed=3)
    options = PruneOptions(speedup=2.0, input_size=SIZE)
    plan, before, _ = plan_pruning(model, options)
    masked = copy.deepcopy(model)
    zero_channels(masked, plan)
    pruned = copy.deepcopy(model)
    remove_channels(pruned, plan)
    x = torch.rand(2, 3, *SIZE[::-1], generator=torch.Generator().manual_seed(0))
    with torch.no_grad():
        expected, got, original = masked(x), pruned(x), model(x)
    for e, g, o in zip(expected, got, original):
        assert g.shape == e.shape
        assert torch.allclose(g, e, atol=1e-4)
    # The comparison has teeth: the removed channels mattered.
    assert max(float((e - o).abs().max()) for e, o in zip(expected, original)) > 1e-2
    after = measure(pruned, SIZE)
    assert before.gflops / after.gflops >= 2.0
    assert after.parameters < before.parameters
    # Every group keeps max(8, 10 %) of its channels; nothing else changed width.
    widths = {g.name: g.size for g in model.channel_groups()}
    for group in pruned.channel_groups():
        original = widths.pop(group.name)
        assert group.size == original - len(plan.get(group.name, []))
        assert group.size >= min(original, max(8, math.ceil(0.1 * original)))
    assert not widths


def test_unreachable_speedup_is_a_clear_error():
    model = random_detector(False, False, seed=5)
    with pytest.raises(ValueError, match="unreachable"):
        plan_pruning(model, PruneOptions(speedup=50.0, input_size=SIZE))
    with pytest.raises(ValueError, match="at least 1"):
        plan_pruning(model, PruneOptions(speedup=0.5, input_size=SIZE))
