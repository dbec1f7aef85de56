import math

import pytest
import torch
from torch import nn

from semchain_train.ema import ModelEMA
from semchain_train.optimizer import build_optimizer, parameter_groups
from semchain_train.schedule import ScheduleOptions, apply_rates, epoch_factor, learning_rates, warmup_iterations


def _net() -> nn.Sequential:
    return nn.Sequential(nn.Conv2d(3, 4, 3, bias=False), nn.BatchNorm2d(4), nn.Conv2d(4, 2, 1), nn.Linear(5, 3))


def test_ema_follows_the_decay_ramp() -> None:
    model = nn.Linear(1, 1, bias=False)
    with torch.no_grad():
        model.weight.fill_(0.0)
    ema = ModelEMA(model, decay=0.9999, tau=2000)
    with torch.no_grad():
        model.weight.fill_(1.0)
    ema.update(model)
    d1 = 0.9999 * (1 - math.exp(-1 / 2000))
    assert abs(ema.module.weight.item() - (1 - d1)) < 1e-7
    ema.update(model)
    d2 = 0.9999 * (1 - math.exp(-2 / 2000))
    assert abs(ema.module.weight.item() - (1 - d1 * d2)) < 1e-6
    assert ema.updates == 2 and not ema.module.weight.requires_grad
    assert abs(ema.decay(10**6) - 0.9999) < 1e-12


def test_ema_averages_batch_norm_statistics_but_not_counters() -> None:
    model = nn.BatchNorm1d(2)
    ema = ModelEMA(model)
    model.train()(torch.randn(8, 2) * 5 + 3)
    ema.update(model)
    assert ema.module.num_batches_tracked.item() == 0
    assert 0 < ema.module.running_mean.abs().sum() < model.running_mean.abs().sum()


def test_no_weight_decay_on_norm_layers_and_biases() -> None:
    model = _net()
    groups = parameter_groups(model)
    assert [p.shape for p in groups["weights"]] == [model[0].weight.shape, model[2].weight.shape, model[3].weight.shape]
    assert [p.shape for p in groups["norm"]] == [model[1].weight.shape]
    assert len(groups["bias"]) == 3  # BN, conv and linear biases
    optimizer = build_optimizer(model, "adamw", lr=0.001, weight_decay=5e-4)
    decay = {g["kind"]: g["weight_decay"] for g in optimizer.param_groups}
    assert decay == {"weights": 5e-4, "norm": 0.0, "bias": 0.0}
    assert isinstance(build_optimizer(model, "sgd"), torch.optim.SGD)
    with pytest.raises(ValueError, match="optimizer 'adam9'"):
        build_optimizer(model, "adam9")


def test_linear_and_cosine_decay_reach_lr0_times_lrf() -> None:
    options = ScheduleOptions(lrf=0.01)
    assert epoch_factor(options, 0, 100) == 1.0
    assert abs(epoch_factor(options, 100, 100) - 0.01) < 1e-12
    assert abs(epoch_factor(options, 50, 100) - 0.505) < 1e-12
    cosine = ScheduleOptions(lrf=0.01, schedule="cosine")
    assert abs(epoch_factor(cosine, 50, 100) - 0.505) < 1e-12
    assert abs(epoch_factor(cosine, 25, 100) - (1 - (1 - math.cos(math.pi / 4)) / 2 * 0.99)) < 1e-12


def test_warm_up_ramps_weights_from_zero_and_biases_down_from_warmup_bias_lr() -> None:
    options = ScheduleOptions(lr0=0.01, warmup_epochs=2, min_warmup_iterations=10, warmup_bias_lr=0.1)
    assert warmup_iterations(options, 20) == 40 and warmup_iterations(options, 2) == 10
    rates, momentum = learning_rates(options, 0, 10, 0, 20)
    assert rates["weights"] == 0.0 and rates["bias"] == 0.1 and momentum == 0.8
    rates, momentum = learning_rates(options, 1, 10, 30, 20)
    target = 0.01 * epoch_factor(options, 1, 10)
    assert abs(rates["weights"] - 0.75 * target) < 1e-12
    assert abs(rates["bias"] - (0.1 + 0.75 * (target - 0.1))) < 1e-12
    assert abs(momentum - (0.8 + 0.75 * (0.937 - 0.8))) < 1e-12
    rates, momentum = learning_rates(options, 2, 10, 40, 20)
    assert rates == {k: 0.01 * epoch_factor(options, 2, 10) for k in rates} and momentum == 0.937


def test_apply_rates_sets_lr_and_momentum_or_beta1() -> None:
    model = _net()
    for kind in ("adamw", "sgd"):
        optimizer = build_optimizer(model, kind)
        apply_rates(optimizer, {"weights": 1.0, "norm": 2.0, "bias": 3.0}, 0.5)
        assert {g["kind"]: g["lr"] for g in optimizer.param_groups} == {"weights": 1.0, "norm": 2.0, "bias": 3.0}
        for group in optimizer.param_groups:
            assert (group["betas"][0] if kind == "adamw" else group["momentum"]) == 0.5
