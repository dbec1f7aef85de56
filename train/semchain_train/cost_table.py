"""Parameters and GFLOPs of every scale x neck combination (optionally after LAMP pruning of the
freshly initialised model), and optionally the CPU time of one training step.

  /usr/bin/python3 -m semchain_train.cost_table [--input 320x256] [--speedup 2.0] [--time-batch 16 --threads 2]

Pruning an untrained model ranks channels by their initial weights: the pruned costs are what a
trained model pruned at the same ratio costs only in total FLOPs (the target), not in parameters.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time

import torch

from .export import size_argument
from .flops import measure
from .lamp import PruneOptions, prune
from .model.config import ModelConfig
from .model.detector import build_detector

COMBINATIONS = (("plain", False, False), ("gd", True, False), ("asf", False, True), ("gd+asf", True, True))


def train_step_seconds(model: torch.nn.Module, batch: int, input_size: tuple[int, int], repeats: int = 3) -> float:
    """Median seconds of forward + backward of a batch (a stand-in loss: the sum of the outputs)."""
    width, height = input_size
    x = torch.rand(batch, 3, height, width, generator=torch.Generator().manual_seed(0))
    model.train()
    times = []
    for _ in range(repeats + 1):  # the first step warms allocators up and is dropped
        start = time.perf_counter()
        outputs = model(x)
        sum(o.float().mean() for o in outputs).backward()
        times.append(time.perf_counter() - start)
        model.zero_grad(set_to_none=True)
    return statistics.median(times[1:])


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="semchain_train.cost_table", description=__doc__.split("\n\n")[0])
    parser.add_argument("--input", type=size_argument, default=(320, 256), help="WIDTHxHEIGHT (default 320x256)")
    parser.add_argument("--classes", type=int, default=10)
    parser.add_argument("--speedup", type=float, help="also prune each model with LAMP to this FLOPs speed-up")
    parser.add_argument("--time-batch", type=int, help="also time one forward + backward of this batch (scale n)")
    parser.add_argument("--threads", type=int, help="torch CPU threads for the timing")
    args = parser.parse_args(argv)
    if args.threads:
        torch.set_num_threads(args.threads)
    width, height = args.input
    print(f"| scale | neck | parameters (M) | GFLOPs at {width}x{height} |" + (f" after LAMP {args.speedup}: parameters (M) / GFLOPs |" if args.speedup else ""))
    print("|---|---|---|---|" + ("---|" if args.speedup else ""))
    for scale in ("n", "s"):
        for name, gd, asf in COMBINATIONS:
            torch.manual_seed(0)
            model = build_detector(ModelConfig(scale, args.classes, gd, asf))
            cost = measure(model, args.input)
            row = f"| {scale} | {name} | {cost.parameters / 1e6:.3f} | {cost.gflops:.3f} |"
            if args.speedup:
                result = prune(model, PruneOptions(speedup=args.speedup, input_size=args.input))
                row += f" {result.after.parameters / 1e6:.3f} / {result.after.gflops:.3f} ({result.speedup:.2f}x) |"
            print(row, flush=True)
    if args.time_batch:
        print(f"\nforward + backward, batch {args.time_batch} at {width}x{height}, {torch.get_num_threads()} threads:")
        for name, gd, asf in COMBINATIONS:
            torch.manual_seed(0)
            model = build_detector(ModelConfig("n", args.classes, gd, asf))
            print(f"  n {name}: {train_step_seconds(model, args.time_batch, args.input):.2f} s", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
