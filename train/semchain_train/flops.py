"""GFLOPs and parameter counts of a model at an input size, as ultralytics reports them:
2 x multiply-accumulates of the convolutions and linear layers (via forward hooks), plus the
matrix products of attention (modules that do them through torch.matmul report them with a
functional_macs(inputs, output) method). Batch norms, activations, pooling and resizing are not
counted (they are folded or negligible, as in thop, which ultralytics uses).
"""

from __future__ import annotations

from dataclasses import dataclass

import torch
from torch import nn


@dataclass
class ModelCost:
    gflops: float
    parameters: int
    macs: int


def _conv_macs(module: nn.Module, output: torch.Tensor) -> int:
    weight = module.weight
    # Each output element costs (in_channels / groups) x kernel volume multiply-accumulates.
    per_output = int(weight[0].numel())
    return int(output.numel()) * per_output


def _linear_macs(module: nn.Linear, output: torch.Tensor) -> int:
    return int(output.numel()) * int(module.in_features)


def count_parameters(model: nn.Module) -> int:
    return sum(int(p.numel()) for p in model.parameters())


def measure(model: nn.Module, input_size: tuple[int, int] = (320, 256), batch: int = 1) -> ModelCost:
    """Cost of one forward pass of 'batch' images of input_size = (width, height), in eval mode."""
    width, height = input_size
    macs = [0]
    handles = []

    def conv_hook(module: nn.Module, inputs: tuple, output: torch.Tensor) -> None:
        macs[0] += _conv_macs(module, output)

    def linear_hook(module: nn.Module, inputs: tuple, output: torch.Tensor) -> None:
        macs[0] += _linear_macs(module, output)

    def functional_hook(module: nn.Module, inputs: tuple, output: torch.Tensor) -> None:
        macs[0] += int(module.functional_macs(inputs, output))

    for module in model.modules():
        if isinstance(module, (nn.Conv1d, nn.Conv2d, nn.Conv3d)):
            handles.append(module.register_forward_hook(conv_hook))
        elif isinstance(module, nn.Linear):
            handles.append(module.register_forward_hook(linear_hook))
        if hasattr(module, "functional_macs"):
            handles.append(module.register_forward_hook(functional_hook))
    was_training = model.training
    model.eval()
    try:
        parameter = next(model.parameters(), None)
        device = parameter.device if parameter is not None else torch.device("cpu")
        with torch.no_grad():
            model(torch.zeros(batch, 3, height, width, device=device))
    finally:
        for handle in handles:
            handle.remove()
        model.train(was_training)
    return ModelCost(gflops=2.0 * macs[0] / 1e9, parameters=count_parameters(model), macs=macs[0])
