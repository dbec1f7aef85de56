"""Exponential moving average of the weights (YOLOv5/v8's ModelEMA).

decay(n) = decay * (1 - exp(-n / tau)): the average follows the model closely during the first
updates (when the weights move fast) and settles to `decay` after a few thousand updates.
"""

from __future__ import annotations

import copy
import math

import torch
from torch import nn


class ModelEMA:
    def __init__(self, model: nn.Module, decay: float = 0.9999, tau: float = 2000.0, updates: int = 0) -> None:
        self.module = copy.deepcopy(model).eval()
        for parameter in self.module.parameters():
            parameter.requires_grad_(False)
        self.decay_max = decay
        self.tau = tau
        self.updates = updates

    def decay(self, updates: int) -> float:
        return self.decay_max * (1 - math.exp(-updates / self.tau))

    @torch.no_grad()
    def update(self, model: nn.Module) -> None:
        self.updates += 1
        d = self.decay(self.updates)
        live = model.state_dict()
        for name, value in self.module.state_dict().items():
            if value.dtype.is_floating_point:  # BN's num_batches_tracked is an integer count
                value.mul_(d).add_(live[name].detach().to(value.dtype), alpha=1 - d)
