"""flops.py on cases whose cost is known in closed form."""

from __future__ import annotations

import pytest
from torch import nn

from semchain_train.flops import measure


class _Single(nn.Module):
    def __init__(self, layer: nn.Module):
        super().__init__()
        self.layer = layer

    def forward(self, x):
        return self.layer(x)


def test_single_convolution():
    # 3 -> 8 channels, 3x3, stride 2, padding 1 at 64x32 (W x H): output 8 x 16 x 32;
    # every output costs 3 x 3 x 3 multiply-adds.
    model = _Single(nn.Conv2d(3, 8, 3, 2, 1, bias=True))
    cost = measure(model, (64, 32))
    macs = 8 * 16 * 32 * 3 * 3 * 3
    assert cost.macs == macs
    assert cost.gflops == pytest.approx(2 * macs / 1e9)
    assert cost.parameters == 8 * 3 * 9 + 8


def test_depthwise_convolution_and_batch():
    model = _Single(nn.Conv2d(3, 3, 5, 1, 2, groups=3, bias=False))
    cost = measure(model, (32, 32), batch=2)
    assert cost.macs == 2 * 3 * 32 * 32 * 25


def test_linear_layer():
    model = nn.Sequential(nn.Flatten(), nn.Linear(3 * 4 * 4, 5))
    assert measure(model, (4, 4)).macs == 48 * 5


def test_measure_restores_training_mode():
    model = _Single(nn.Conv2d(3, 4, 1))
    model.train()
    measure(model, (32, 32))
    assert model.training
