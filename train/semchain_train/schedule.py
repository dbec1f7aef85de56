"""Learning rate and momentum per iteration: YOLOv8's warm-up, then linear or cosine decay to lr0 * lrf.

Everything is a function of the global iteration, so a resumed run needs no scheduler state.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

SCHEDULES = ("linear", "cosine")


@dataclass
class ScheduleOptions:
    lr0: float = 0.001  # initial learning rate (the paper's)
    lrf: float = 0.01  # final learning rate as a fraction of lr0
    schedule: str = "linear"  # linear | cosine decay over the epochs
    warmup_epochs: float = 3.0
    min_warmup_iterations: int = 100  # YOLOv8 warms up for at least this many iterations
    warmup_momentum: float = 0.8
    warmup_bias_lr: float = 0.1  # biases start high and fall to their lr during warm-up
    momentum: float = 0.937  # SGD momentum or AdamW's beta1


def epoch_factor(options: ScheduleOptions, epoch: int, epochs: int) -> float:
    """lr / lr0 for an epoch: 1 at epoch 0, lrf at epoch `epochs`."""
    x = epoch / max(epochs, 1)
    if options.schedule == "cosine":
        return ((1 - math.cos(x * math.pi)) / 2) * (options.lrf - 1) + 1
    if options.schedule == "linear":
        return (1 - x) * (1.0 - options.lrf) + options.lrf
    raise ValueError(f"schedule '{options.schedule}': expected one of {', '.join(SCHEDULES)}")


def warmup_iterations(options: ScheduleOptions, iterations_per_epoch: int) -> int:
    if options.warmup_epochs <= 0:
        return 0
    return max(round(options.warmup_epochs * iterations_per_epoch), options.min_warmup_iterations)


def learning_rates(
    options: ScheduleOptions, epoch: int, epochs: int, iteration: int, iterations_per_epoch: int
) -> tuple[dict[str, float], float]:
    """(lr per group kind {'weights', 'norm', 'bias'}, momentum) at a global iteration of an epoch."""
    target = options.lr0 * epoch_factor(options, epoch, epochs)
    warmup = warmup_iterations(options, iterations_per_epoch)
    if iteration >= warmup:
        return {"weights": target, "norm": target, "bias": target}, options.momentum
    points = [0, warmup]
    weights_lr = float(np.interp(iteration, points, [0.0, target]))
    bias_lr = float(np.interp(iteration, points, [options.warmup_bias_lr, target]))
    momentum = float(np.interp(iteration, points, [options.warmup_momentum, options.momentum]))
    return {"weights": weights_lr, "norm": weights_lr, "bias": bias_lr}, momentum


def apply_rates(optimizer, rates: dict[str, float], momentum: float) -> None:
    for group in optimizer.param_groups:
        group["lr"] = rates[group.get("kind", "weights")]
        if "betas" in group:
            group["betas"] = (momentum, group["betas"][1])
        elif "momentum" in group:
            group["momentum"] = momentum
