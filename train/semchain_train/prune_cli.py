"""`prune`: LAMP channel pruning of a checkpoint to a FLOPs speed-up, then fine-tuning (seed 000
§2.1: ratio 2.0). Writes OUT/pruned.pt (before fine-tuning), OUT/prune.json (costs before and
after, channels removed per group) and, with --epochs > 0, the fine-tuning run (OUT/best.pt,
last.pt, results.csv) through semchain_train.train.fit.
"""

from __future__ import annotations

import argparse
import json
import os
from pathlib import Path
from typing import Any

from .export import size_argument
from .lamp import PruneOptions, PruneResult, prune


def add_arguments(parser: argparse.ArgumentParser) -> None:
    d = PruneOptions()
    parser.add_argument("--weights", type=Path, required=True, help="trained checkpoint (.pt); its EMA weights are pruned")
    parser.add_argument("--out", type=Path, required=True, help="run folder (pruned.pt, prune.json, fine-tuning run)")
    parser.add_argument("--speedup", type=float, default=d.speedup, help=f"FLOPs before / after (default {d.speedup})")
    parser.add_argument("--data", type=Path, help="data.yaml for fine-tuning (required with --epochs > 0)")
    parser.add_argument("--epochs", type=int, default=0, help="fine-tuning epochs after pruning (default 0: none)")
    parser.add_argument("--input", type=size_argument, help="WIDTHxHEIGHT for FLOPs and fine-tuning (default: the checkpoint's training size, else 320x256)")
    parser.add_argument("--batch", type=int, help="fine-tuning batch (default: the checkpoint's)")
    parser.add_argument("--lr0", type=float, help="fine-tuning initial learning rate (default: the checkpoint's)")
    parser.add_argument("--min-channels", type=int, default=d.min_channels, help=f"channels every group keeps at least (default {d.min_channels})")
    parser.add_argument("--min-fraction", type=float, default=d.min_fraction, help=f"fraction of its width every group keeps (default {d.min_fraction})")
    parser.add_argument("--round-to", type=int, default=d.round_to, help=f"kept widths are multiples of this (default {d.round_to}: any)")
    parser.add_argument("--seed", type=int, default=0, help="fine-tuning seed (default 0)")
    parser.add_argument("--device", default="cpu", help="cpu | cuda | cuda:N (default cpu)")
    parser.add_argument("--workers", type=int, default=2, help="data loader processes (default 2)")
    parser.add_argument("--threads", type=int, help="torch CPU threads (default: torch's choice)")
    parser.add_argument("--no-progress", action="store_true", help="no progress bars")


def _cost(cost) -> dict[str, Any]:
    return {"gflops": round(cost.gflops, 4), "parameters": cost.parameters}


def _report(result: PruneResult, speedup: float, input_size: tuple[int, int], weights: Path, round_to: int) -> dict[str, Any]:
    return {
        "weights": str(weights),
        "method": "LAMP (seed 000 eq. 1), structured output channels, global ranking",
        "requested_speedup": speedup,
        "achieved_speedup": round(result.speedup, 4),
        "input": f"{input_size[0]}x{input_size[1]}",
        "round_to": round_to,
        "before": _cost(result.before),
        "after": _cost(result.after),
        "removed_channels": {name: len(channels) for name, channels in sorted(result.removed.items())},
    }


def run(args: argparse.Namespace) -> int:
    from .checkpoint import load_checkpoint, save_checkpoint

    if args.epochs < 0:
        raise ValueError(f"--epochs {args.epochs}: must be 0 or more")
    if args.epochs > 0 and args.data is None:
        raise ValueError("--data is required to fine-tune (--epochs > 0)")
    if args.min_channels < 1 or not 0 <= args.min_fraction <= 1:
        raise ValueError("--min-channels must be >= 1 and --min-fraction in [0, 1]")
    if args.threads is not None:
        if args.threads < 1:
            raise ValueError(f"--threads {args.threads}: must be at least 1")
        import torch

        torch.set_num_threads(args.threads)
    checkpoint = load_checkpoint(args.weights)
    model, names = checkpoint.model, checkpoint.names
    if not hasattr(model, "channel_groups"):
        raise ValueError(f"{args.weights}: its model is not a semchain_train Detector (no channel groups to prune)")
    saved = checkpoint.raw.get("train_options") or {}
    input_size = args.input or (tuple(saved["input_size"]) if saved.get("input_size") else (320, 256))
    options = PruneOptions(speedup=args.speedup, input_size=input_size, min_channels=args.min_channels, min_fraction=args.min_fraction, round_to=args.round_to)
    if args.data is not None:
        from .data.dataset import load_data_yaml

        spec = load_data_yaml(args.data)
        if spec.names != names:
            raise ValueError(f"{args.weights}: its classes {names} are not {args.data}'s {spec.names}")

    print(f"pruning {args.weights} to a {args.speedup}x FLOPs speed-up at {input_size[0]}x{input_size[1]} (LAMP)")
    result = prune(model, options, progress=not args.no_progress)
    print(f"before: {result.before.parameters / 1e6:.3f} M parameters, {result.before.gflops:.3f} GFLOPs")
    print(f"after:  {result.after.parameters / 1e6:.3f} M parameters, {result.after.gflops:.3f} GFLOPs ({result.speedup:.3f}x)")
    report = _report(result, args.speedup, input_size, args.weights, args.round_to)
    args.out.mkdir(parents=True, exist_ok=True)
    save_checkpoint(args.out / "pruned.pt", model, names=names, epoch=-1, extra={"prune": report})
    if args.epochs > 0:
        from .train import TrainOptions, fit

        train_options = TrainOptions.from_dict(saved) if saved else TrainOptions()
        train_options.data, train_options.out, train_options.epochs = args.data, args.out, args.epochs
        train_options.input_size, train_options.seed, train_options.device = input_size, args.seed, args.device
        train_options.workers, train_options.progress, train_options.resume = args.workers, not args.no_progress, False
        train_options.threads = args.threads
        if args.batch is not None:
            train_options.batch = args.batch
        if args.lr0 is not None:
            train_options.lr0 = args.lr0
        train_options.validate()
        best = fit(model.train(), train_options, names, extra_checkpoint={"prune": report})
        report["fine_tuned"] = {"epochs": args.epochs, "best": str(best)}
        print(f"fine-tuned {args.epochs} epochs: {best}")
    tmp = args.out / "prune.json.tmp"
    tmp.write_text(json.dumps(report, indent=2) + "\n")
    os.replace(tmp, args.out / "prune.json")
    return 0
