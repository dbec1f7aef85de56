"""Detectors with random batch-norm statistics and affine terms (seeded), so that comparisons of
outputs exercise every channel (fresh BNs are identities on zero-mean data)."""

from __future__ import annotations

import torch
from torch import nn

from semchain_train.model.config import ModelConfig
from semchain_train.model.detector import Detector, build_detector

# These tests time nothing; one thread avoids OpenMP spinning on a shared 2-core machine.
torch.set_num_threads(1)

COMBINATIONS = [(False, False), (True, False), (False, True), (True, True)]
COMBINATION_IDS = ["plain", "gd", "asf", "gd+asf"]


def randomize_batch_norms(model: nn.Module, seed: int) -> None:
    generator = torch.Generator().manual_seed(seed)
    with torch.no_grad():
        for module in model.modules():
            if isinstance(module, (nn.BatchNorm2d, nn.BatchNorm3d)):
                n = module.num_features
                module.running_mean.copy_(torch.rand(n, generator=generator) - 0.5)
                module.running_var.copy_(torch.rand(n, generator=generator) + 0.5)
                module.weight.copy_(torch.rand(n, generator=generator) + 0.5)
                module.bias.copy_(0.4 * torch.rand(n, generator=generator) - 0.2)


def random_detector(gd: bool, asf: bool, scale: str = "n", classes: int = 10, seed: int = 0) -> Detector:
    torch.manual_seed(seed)
    model = build_detector(ModelConfig(scale=scale, classes=classes, gd_neck=gd, asf=asf))
    randomize_batch_norms(model, seed)
    return model.eval()
