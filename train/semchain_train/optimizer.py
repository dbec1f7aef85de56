"""Optimizers with YOLOv8's parameter groups: weight decay on convolution/linear weights only,
none on normalization weights and biases."""

from __future__ import annotations

import torch
from torch import nn

OPTIMIZERS = ("adamw", "sgd")
GROUP_KINDS = ("weights", "norm", "bias")


def parameter_groups(model: nn.Module) -> dict[str, list[nn.Parameter]]:
    groups: dict[str, list[nn.Parameter]] = {kind: [] for kind in GROUP_KINDS}
    norm_types = (nn.modules.batchnorm._NormBase, nn.GroupNorm, nn.LayerNorm)
    for module in model.modules():
        for name, parameter in module.named_parameters(recurse=False):
            if not parameter.requires_grad:
                continue
            if name == "bias":
                groups["bias"].append(parameter)
            elif isinstance(module, norm_types):
                groups["norm"].append(parameter)
            else:
                groups["weights"].append(parameter)
    return groups


def build_optimizer(
    model: nn.Module, kind: str = "adamw", lr: float = 0.001, momentum: float = 0.937, weight_decay: float = 5e-4
) -> torch.optim.Optimizer:
    """AdamW (betas (momentum, 0.999), decoupled decay) or SGD (Nesterov). Each group has a 'kind' key."""
    if kind not in OPTIMIZERS:
        raise ValueError(f"optimizer '{kind}': expected one of {', '.join(OPTIMIZERS)}")
    groups = parameter_groups(model)
    param_groups = [
        {"params": groups["weights"], "weight_decay": weight_decay, "kind": "weights"},
        {"params": groups["norm"], "weight_decay": 0.0, "kind": "norm"},
        {"params": groups["bias"], "weight_decay": 0.0, "kind": "bias"},
    ]
    param_groups = [group for group in param_groups if group["params"]]
    if kind == "adamw":
        return torch.optim.AdamW(param_groups, lr=lr, betas=(momentum, 0.999))
    return torch.optim.SGD(param_groups, lr=lr, momentum=momentum, nesterov=True)
