"""Command line: python3 -m semchain_train {train,val,prune,export} ... (see train/README.md).

Bad input ends with one line `semchain_train: error: ...` on stderr and exit status 1.
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
from pathlib import Path
from typing import NoReturn, Sequence

PROGRAM = "semchain_train"


class CommandError(Exception):
    """A user error found by the command line itself."""


class OneLineParser(argparse.ArgumentParser):
    """argparse, but a usage error is one line and exit status 1 like every other bad input."""

    def error(self, message: str) -> NoReturn:
        command = self.prog.split()[-1]
        where = "" if command == PROGRAM else f"{command}: "
        sys.stderr.write(f"{PROGRAM}: error: {where}{message}\n")
        sys.exit(1)


def parse_size(text: str) -> tuple[int, int]:
    """'320x256' -> (320, 256): width x height as the C++ CLI writes sizes."""
    parts = text.lower().split("x")
    try:
        width, height = (int(p) for p in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}': expected WIDTHxHEIGHT, e.g. 320x256") from None
    if width <= 0 or height <= 0 or width % 32 or height % 32:
        raise argparse.ArgumentTypeError(f"'{text}': width and height must be positive multiples of 32")
    return width, height


def _add_train_arguments(parser: argparse.ArgumentParser) -> None:
    from semchain_train.train import TrainOptions

    d = TrainOptions()
    parser.add_argument("--data", type=Path, required=True, help="data.yaml with train and val splits")
    parser.add_argument("--out", type=Path, required=True, help="run folder (last.pt, best.pt, results.csv, args.yaml)")
    parser.add_argument("--scale", choices=("n", "s"), default="n", help="YOLOv8 scale (default n)")
    parser.add_argument("--gd", action="store_true", help="Gold-YOLO gather-and-distribute neck")
    parser.add_argument("--asf", action="store_true", help="ASF-YOLO attentional scale-sequence fusion")
    parser.add_argument("--weights", type=Path, help="start from this checkpoint's model (.pt), or from an exported raw-head model (.onnx, with its .names; --scale, --gd, --asf say its architecture)")
    parser.add_argument("--epochs", type=int, default=d.epochs, help=f"default {d.epochs}")
    parser.add_argument("--batch", type=int, default=d.batch, help=f"default {d.batch}")
    parser.add_argument("--input", type=parse_size, default=d.input_size, help="WIDTHxHEIGHT (default 320x256)")
    parser.add_argument("--optimizer", choices=("adamw", "sgd"), default=d.optimizer, help="default adamw")
    parser.add_argument("--lr0", type=float, default=d.lr0, help=f"initial learning rate (default {d.lr0})")
    parser.add_argument("--lrf", type=float, default=d.lrf, help=f"final lr as a fraction of lr0 (default {d.lrf})")
    parser.add_argument("--schedule", choices=("linear", "cosine"), default=d.schedule, help="default linear")
    parser.add_argument("--warmup-epochs", type=float, default=d.warmup_epochs, help=f"default {d.warmup_epochs}")
    parser.add_argument("--close-mosaic", type=int, default=d.close_mosaic, help="no mosaic in the last N epochs")
    parser.add_argument("--no-mosaic", action="store_true", help="never use mosaic")
    parser.add_argument("--eval-every", type=int, default=d.eval_every, help="validate every N epochs")
    parser.add_argument("--checkpoint-batches", type=int, default=d.checkpoint_batches, help=f"also write last.pt within an epoch, every N batches (0: at epoch ends only; default {d.checkpoint_batches})")
    parser.add_argument("--seed", type=int, default=d.seed, help=f"default {d.seed}")
    parser.add_argument("--device", default=d.device, help="cpu | cuda | cuda:N (default cpu)")
    parser.add_argument("--workers", type=int, default=d.workers, help=f"data loader processes (default {d.workers})")
    parser.add_argument("--threads", type=int, help="torch CPU threads (default: the cores available)")
    parser.add_argument("--resume", action="store_true", help="continue OUT/last.pt with its saved options")
    parser.add_argument("--no-progress", action="store_true", help="no progress bars or epoch lines")


def _run_train(args: argparse.Namespace) -> int:
    import torch

    from semchain_train.checkpoint import load_checkpoint
    from semchain_train.data.dataset import load_data_yaml
    from semchain_train.train import TrainOptions, check_device, fit

    check_device(args.device)
    progress = not args.no_progress
    if args.resume:
        last = args.out / "last.pt"
        if not last.exists():
            raise CommandError(f"{last}: nothing to resume (no last.pt in the run folder)")
        checkpoint = load_checkpoint(last)
        saved = checkpoint.raw.get("train_options") or {}
        options = TrainOptions.from_dict(saved)
        # Where and how fast it runs may change; what it computes may not.
        options.device, options.workers, options.threads = args.device, args.workers, args.threads
        options.progress, options.resume, options.out = progress, True, args.out
        model, names = checkpoint.raw["model"], checkpoint.names
        user_extra = (checkpoint.raw.get("extra") or {}).get("user")
    else:
        spec = load_data_yaml(args.data)
        names = spec.names
        options = TrainOptions(
            data=args.data, out=args.out, epochs=args.epochs, batch=args.batch, input_size=args.input,
            optimizer=args.optimizer, lr0=args.lr0, lrf=args.lrf, schedule=args.schedule,
            warmup_epochs=args.warmup_epochs, mosaic=not args.no_mosaic, close_mosaic=args.close_mosaic,
            seed=args.seed, device=args.device, workers=args.workers, threads=args.threads,
            eval_every=args.eval_every, checkpoint_batches=args.checkpoint_batches, progress=progress,
        )
        options.validate()
        torch.manual_seed(args.seed)
        if args.weights is not None and args.weights.suffix == ".onnx":
            model = _model_from_onnx(args, spec, names)
        elif args.weights is not None:
            checkpoint = load_checkpoint(args.weights)
            if checkpoint.names != names:
                raise CommandError(f"{args.weights}: its classes {checkpoint.names} are not {args.data}'s {names}")
            # A checkpoint's model is its EMA copy, whose parameters are frozen.
            model = checkpoint.model.train().requires_grad_(True)
        else:
            from semchain_train.model.config import ModelConfig
            from semchain_train.model.detector import build_detector

            model = build_detector(ModelConfig(scale=args.scale, classes=len(names), gd_neck=args.gd, asf=args.asf))
        user_extra = None
    best = fit(model, options, names, extra_checkpoint=user_extra)
    print(f"best: {best}")
    return 0


def _model_from_onnx(args: argparse.Namespace, spec, names: list[str]):
    """The Detector an exported raw-head ONNX (e.g. models/detector.onnx) computes, to fine-tune."""
    import torch

    from semchain_train.data.dataset import split_images
    from semchain_train.model.config import ModelConfig
    from semchain_train.onnx_import import OnnxImportError, calibration_images, export_input_size, load_detector_from_onnx

    names_file = args.weights.with_suffix(".names")
    if not names_file.is_file():
        raise CommandError(f"{names_file}: missing (the class names of {args.weights})")
    onnx_names = [line.strip() for line in names_file.read_text().splitlines() if line.strip()]
    if onnx_names != names:
        raise CommandError(f"{names_file}: its classes {onnx_names} are not {args.data}'s {names}")
    try:
        input_size = export_input_size(args.weights)
        # Batch-norm statistics from a fixed, seeded sample of the training images.
        images = split_images(spec, "train")
        order = torch.randperm(len(images), generator=torch.Generator().manual_seed(args.seed)).tolist()
        calibration = calibration_images([images[i] for i in order[:64]], input_size)
        config = ModelConfig(scale=args.scale, classes=len(names), gd_neck=args.gd, asf=args.asf)
        return load_detector_from_onnx(args.weights, config, calibration)
    except OnnxImportError as error:
        raise CommandError(str(error)) from None


def _add_val_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--weights", type=Path, required=True, help="checkpoint (.pt) to evaluate (its EMA weights)")
    parser.add_argument("--data", type=Path, required=True, help="data.yaml")
    parser.add_argument("--split", choices=("train", "val", "test"), default="test", help="default test")
    parser.add_argument("--input", type=parse_size, help="WIDTHxHEIGHT (default: the size it was trained at)")
    parser.add_argument("--conf", type=float, default=0.001, help="confidence threshold (default 0.001)")
    parser.add_argument("--iou", type=float, default=0.7, help="NMS IoU threshold (default 0.7)")
    parser.add_argument("--batch", type=int, default=16, help="images per forward pass (default 16)")
    parser.add_argument("--device", default="cpu", help="cpu | cuda | cuda:N (default cpu)")
    parser.add_argument("--workers", type=int, default=0, help="data loader processes (default 0)")
    parser.add_argument("--out", type=Path, help="write the results as JSON here")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")


def _run_val(args: argparse.Namespace) -> int:
    from semchain_train.checkpoint import load_checkpoint
    from semchain_train.data.dataset import load_data_yaml
    from semchain_train.train import check_device
    from semchain_train.val import evaluate

    check_device(args.device)
    if not 0 < args.conf <= 1 or not 0 < args.iou <= 1:
        raise CommandError("--conf and --iou must lie in (0, 1]")
    spec = load_data_yaml(args.data)
    checkpoint = load_checkpoint(args.weights, device=args.device)
    if checkpoint.names != spec.names:
        raise CommandError(f"{args.weights}: its classes {checkpoint.names} are not {args.data}'s {spec.names}")
    input_size = args.input
    if input_size is None:
        saved = (checkpoint.raw.get("train_options") or {}).get("input_size")
        input_size = tuple(saved) if saved else (320, 256)
    result = evaluate(
        checkpoint.model, args.data, split=args.split, input_size=input_size, device=args.device,
        conf=args.conf, iou=args.iou, batch=args.batch, workers=args.workers, progress=not args.no_progress,
    )
    result.update(weights=str(args.weights), data=str(args.data), input=f"{input_size[0]}x{input_size[1]}")
    print(f"{args.split}: {result['images']} images, {result['truths']} objects at {result['input']}")
    print(f"mAP@0.5 {result['map50']:.4f}  mAP@0.5:0.95 {result['map50_95']:.4f}  "
          f"P {result['precision']:.4f}  R {result['recall']:.4f}")
    for name, c in result["classes"].items():
        if c["truths"]:
            print(f"  {name:<12} {c['truths']:>5}  AP50 {c['ap50']:.4f}  AP50-95 {c['ap50_95']:.4f}")
    if args.out is not None:
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(result, indent=2) + "\n")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(prog=PROGRAM, description="Train, validate, prune and export semchain's detector.")
    commands = parser.add_subparsers(dest="command", metavar="{train,val,prune,export,curve}", parser_class=OneLineParser)
    commands.required = True
    train = commands.add_parser("train", help="train a detector on a data.yaml")
    _add_train_arguments(train)
    train.set_defaults(run=_run_train)
    val = commands.add_parser("val", help="mAP of a checkpoint on a split (the C++ bench detector's metrics)")
    _add_val_arguments(val)
    val.set_defaults(run=_run_val)
    for name, module_name, text in (
        ("prune", "semchain_train.prune_cli", "LAMP channel pruning to a FLOPs speed-up, then fine-tuning"),
        ("export", "semchain_train.export", "export to the raw-head ONNX the C++ runtime runs"),
        ("curve", "semchain_train.curve", "the learning curve (val mAP, losses per epoch) of results.csv files as a PNG"),
    ):
        sub = commands.add_parser(name, help=text)
        try:
            module = importlib.import_module(module_name)
        except Exception as error:  # a broken optional module must not take train and val down
            sub.set_defaults(run=_unavailable(name, error))
            continue
        module.add_arguments(sub)
        sub.set_defaults(run=module.run)
    return parser


def _unavailable(name: str, error: Exception):
    def run(_: argparse.Namespace) -> int:
        raise CommandError(f"{name} is not available ({error})")

    return run


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.run(args) or 0)
    except KeyboardInterrupt:
        sys.stderr.write(f"{PROGRAM}: interrupted\n")
        return 130
    except (CommandError, ValueError, FileNotFoundError, OSError) as error:
        # DataError, TrainError and checkpoint errors are ValueErrors whose message names the file.
        message = str(error).splitlines()[0] if str(error) else type(error).__name__
        sys.stderr.write(f"{PROGRAM}: error: {message}\n")
        return 1


if __name__ == "__main__":
    sys.exit(main())
