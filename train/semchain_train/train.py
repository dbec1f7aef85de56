"""The training loop: YOLOv8's recipe (warm-up, linear/cosine decay, mosaic closed for the last epochs,
gradient accumulation to a nominal batch of 64, clipping, EMA) with validation of the EMA model,
best.pt by fitness, last.pt every epoch and every `checkpoint_batches` batches within one, and exact
resumption from last.pt, mid-epoch too.
"""

from __future__ import annotations

import contextlib
import csv
import dataclasses
import io
import math
import os
import random
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable

import numpy as np
import torch
import yaml
from torch import nn

from semchain_train.checkpoint import load_checkpoint, save_checkpoint
from semchain_train.data.augment import AugmentOptions
from semchain_train.data.dataset import DetectionDataset, collate, epoch_order, load_data_yaml, split_images
from semchain_train.ema import ModelEMA
from semchain_train.loss import DetectionLoss, LossWeights
from semchain_train.optimizer import OPTIMIZERS, build_optimizer
from semchain_train.schedule import SCHEDULES, ScheduleOptions, apply_rates, learning_rates, warmup_iterations
from semchain_train.val import EvalOptions, evaluate_images, fitness

RESULT_COLUMNS = (
    "epoch", "box_loss", "cls_loss", "dfl_loss", "lr", "map50", "map50_95", "precision", "recall", "fitness", "train_seconds",
    "seconds", "cpu_seconds",
)


def _cpu_seconds() -> float:
    """CPU time of this process and of its finished children (the data loader's workers end with
    each epoch): what an epoch cost on a shared machine, where wall time says little."""
    import resource

    own, children = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


class TrainError(ValueError):
    """Options or state that make training impossible; the message says what is wrong."""


@dataclass
class TrainOptions:
    """Defaults: YOLOv8's (ultralytics default.yaml) with the paper's AdamW lr 0.001."""

    data: Path = Path("data.yaml")  # data.yaml with train and val splits
    out: Path = Path("runs/train")  # run folder: last.pt, best.pt, results.csv, args.yaml
    epochs: int = 100
    batch: int = 16
    input_size: tuple[int, int] = (320, 256)  # (width, height), multiples of 32
    optimizer: str = "adamw"  # adamw | sgd
    lr0: float = 0.001
    lrf: float = 0.01  # final lr = lr0 * lrf
    schedule: str = "linear"  # linear | cosine
    momentum: float = 0.937  # SGD momentum / AdamW beta1
    weight_decay: float = 5e-4  # on conv/linear weights, scaled by batch * accumulate / nominal_batch
    nominal_batch: int = 64  # gradients are accumulated up to this many images per step
    warmup_epochs: float = 3.0  # at least 100 iterations (YOLOv8)
    warmup_momentum: float = 0.8
    warmup_bias_lr: float | None = None  # None: 0.1 for SGD (YOLOv8), 0.01 for AdamW (ultralytics' cap for Adam)
    mosaic: bool = True
    close_mosaic: int = 10  # no mosaic in the last epochs
    scale: float = 0.5
    translate: float = 0.1
    hsv_h: float = 0.015
    hsv_s: float = 0.7
    hsv_v: float = 0.4
    flip_lr: float = 0.5
    box_gain: float = 7.5
    cls_gain: float = 0.5
    dfl_gain: float = 1.5
    ema_decay: float = 0.9999
    ema_tau: float = 2000.0
    grad_clip: float = 10.0  # max gradient norm
    amp: bool = True  # mixed precision, used on cuda only
    seed: int = 0
    device: str = "cpu"  # cpu | cuda | cuda:N
    workers: int = 2  # DataLoader worker processes
    threads: int | None = None  # torch CPU threads; None: the cores this process may use
    resume: bool = False  # continue from out/last.pt
    eval_every: int = 1  # validate every N epochs (and always after the last)
    # last.pt is also written within an epoch, at the first optimizer step after every N batches
    # (0: at epoch ends only), so that a run stopped mid-epoch loses minutes, not the epoch.
    checkpoint_batches: int = 200
    val_split: str = "val"
    progress: bool = True  # tqdm bars

    @staticmethod
    def from_dict(values: dict[str, Any]) -> "TrainOptions":
        known = {f.name for f in dataclasses.fields(TrainOptions)}
        kwargs = {key: value for key, value in values.items() if key in known}
        for key in ("data", "out"):
            if key in kwargs:
                kwargs[key] = Path(kwargs[key])
        if "input_size" in kwargs:
            kwargs["input_size"] = tuple(kwargs["input_size"])
        return TrainOptions(**kwargs)

    def validate(self) -> None:
        if self.epochs < 1 or self.batch < 1:
            raise TrainError(f"epochs ({self.epochs}) and batch ({self.batch}) must be positive")
        width, height = self.input_size
        if width <= 0 or height <= 0 or width % 32 or height % 32:
            raise TrainError(f"input {width}x{height}: both sides must be positive multiples of 32")
        if self.optimizer not in OPTIMIZERS:
            raise TrainError(f"optimizer '{self.optimizer}': expected one of {', '.join(OPTIMIZERS)}")
        if self.schedule not in SCHEDULES:
            raise TrainError(f"schedule '{self.schedule}': expected one of {', '.join(SCHEDULES)}")
        if self.eval_every < 1 or self.workers < 0:
            raise TrainError("eval_every must be >= 1 and workers >= 0")
        if self.checkpoint_batches < 0:
            raise TrainError(f"checkpoint_batches {self.checkpoint_batches}: must be >= 0 (0: at epoch ends only)")
        if not self.lr0 > 0:
            raise TrainError(f"lr0 {self.lr0}: must be positive")
        check_device(self.device)


def check_device(device: str) -> torch.device:
    try:
        parsed = torch.device(device)
    except RuntimeError:
        raise TrainError(f"device '{device}': expected cpu or cuda") from None
    if parsed.type not in ("cpu", "cuda"):
        raise TrainError(f"device '{device}': expected cpu or cuda")
    if parsed.type == "cuda":
        if not torch.cuda.is_available():
            raise TrainError(f"device '{device}': CUDA is not available on this machine")
        if parsed.index is not None and parsed.index >= torch.cuda.device_count():
            raise TrainError(f"device '{device}': only {torch.cuda.device_count()} CUDA device(s)")
    return parsed


def _grad_scaler(enabled: bool):
    if hasattr(torch, "amp") and hasattr(torch.amp, "GradScaler"):  # torch >= 2.3
        return torch.amp.GradScaler("cuda", enabled=enabled)
    return torch.cuda.amp.GradScaler(enabled=enabled)


def _rng_state() -> dict[str, Any]:
    state = {"torch": torch.get_rng_state(), "numpy": np.random.get_state(), "python": random.getstate()}
    if torch.cuda.is_available():
        state["cuda"] = torch.cuda.get_rng_state_all()
    return state


def _set_rng_state(state: dict[str, Any]) -> None:
    torch.set_rng_state(state["torch"].cpu())
    np.random.set_state(state["numpy"])
    random.setstate(state["python"])
    if "cuda" in state and torch.cuda.is_available():
        torch.cuda.set_rng_state_all([s.cpu() for s in state["cuda"]])


def _write_atomically(path: Path, text: str) -> None:
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text)
    os.replace(tmp, path)


def _write_results(path: Path, rows: list[dict[str, Any]]) -> None:
    buffer = io.StringIO()
    writer = csv.DictWriter(buffer, fieldnames=RESULT_COLUMNS, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({key: (f"{value:.6g}" if isinstance(value, float) else value) for key, value in row.items()})
    _write_atomically(path, buffer.getvalue())


def _copy_atomically(source: Path, target: Path) -> None:
    tmp = target.with_name(f".{target.name}.{os.getpid()}.tmp")
    tmp.write_bytes(source.read_bytes())
    os.replace(tmp, target)


@dataclass
class _RunState:
    start_epoch: int = 0
    best_fitness: float | None = None
    rows: list[dict[str, Any]] = field(default_factory=list)
    # Where a checkpoint written within start_epoch left it: batches done, their loss sums and
    # the seconds spent ({} at an epoch's start).
    partial: dict[str, Any] = field(default_factory=dict)


def fit(
    model: nn.Module,
    options: TrainOptions,
    names: list[str],
    *,
    extra_checkpoint: dict[str, Any] | None = None,
    on_batch_end: Callable[[int, int], None] | None = None,
) -> Path:
    """Train `model` on options.data; returns the path of best.pt (highest 0.1 mAP50 + 0.9 mAP50-95).

    extra_checkpoint is stored in every checkpoint under raw["extra"]["user"] (e.g. pruning records).
    on_batch_end(epoch, iteration) is called after every batch (tests interrupt training with it).
    """
    options.validate()
    device = check_device(options.device)
    spec = load_data_yaml(options.data)
    if list(names) != spec.names:
        raise TrainError(f"class names {list(names)} are not {options.data}'s names {spec.names}")
    classes = int(getattr(model, "classes", len(names)))
    if classes != len(names):
        raise TrainError(f"the model has {classes} classes but {options.data} lists {len(names)}")
    augment = AugmentOptions(
        mosaic=options.mosaic,
        scale=options.scale,
        translate=options.translate,
        hsv_h=options.hsv_h,
        hsv_s=options.hsv_s,
        hsv_v=options.hsv_v,
        flip_lr=options.flip_lr,
    )
    train_set = DetectionDataset(spec, "train", options.input_size, augment=augment, seed=options.seed)
    val_images = split_images(spec, options.val_split)

    if device.type == "cpu":
        torch.set_num_threads(options.threads or max(1, len(os.sched_getaffinity(0))))
    torch.manual_seed(options.seed)
    np.random.seed(options.seed % 2**32)
    random.seed(options.seed)

    out = Path(options.out)
    out.mkdir(parents=True, exist_ok=True)
    model.to(device)
    accumulate = max(round(options.nominal_batch / options.batch), 1)
    weight_decay = options.weight_decay * options.batch * accumulate / options.nominal_batch
    optimizer = build_optimizer(model, options.optimizer, options.lr0, options.momentum, weight_decay)
    ema = ModelEMA(model, decay=options.ema_decay, tau=options.ema_tau)
    use_amp = options.amp and device.type == "cuda"
    scaler = _grad_scaler(use_amp)
    state = _RunState()
    if options.resume:
        state = _restore(out / "last.pt", model, ema, optimizer, scaler, device)
    _write_atomically(out / "args.yaml", yaml.safe_dump(_plain_options(options), sort_keys=False))

    schedule = ScheduleOptions(
        lr0=options.lr0,
        lrf=options.lrf,
        schedule=options.schedule,
        warmup_epochs=options.warmup_epochs,
        warmup_momentum=options.warmup_momentum,
        warmup_bias_lr=options.warmup_bias_lr
        if options.warmup_bias_lr is not None
        else (0.1 if options.optimizer == "sgd" else 0.01),
        momentum=options.momentum,
    )
    criterion = DetectionLoss(
        classes,
        strides=tuple(getattr(model, "strides", (8, 16, 32))),
        reg_max=int(getattr(model, "reg_max", 16)),
        weights=LossWeights(box=options.box_gain, cls=options.cls_gain, dfl=options.dfl_gain),
    )
    batches_per_epoch = math.ceil(len(train_set) / options.batch)
    warmup = warmup_iterations(schedule, batches_per_epoch)
    eval_options = EvalOptions(input_size=tuple(options.input_size), batch=options.batch)
    parameters = [p for p in model.parameters() if p.requires_grad]

    def extra_state(partial: dict[str, Any]) -> dict[str, Any]:
        return {
            "rng": _rng_state(),
            "scaler": scaler.state_dict(),
            "results": state.rows,
            "user": extra_checkpoint or {},
            "partial": partial,
        }

    for epoch in range(state.start_epoch, options.epochs):
        partial = state.partial if epoch == state.start_epoch else {}
        done = int(partial.get("batches", 0))
        started = time.time() - float(partial.get("seconds", 0.0))
        cpu_started = _cpu_seconds() - float(partial.get("cpu_seconds", 0.0))
        model.train()
        train_set.set_epoch(epoch, mosaic=epoch < options.epochs - options.close_mosaic)
        # A resumed epoch goes on with the batches it had not reached, in the same order.
        loader = torch.utils.data.DataLoader(
            train_set,
            batch_size=options.batch,
            sampler=epoch_order(options.seed, epoch, len(train_set))[done * options.batch :],
            num_workers=options.workers,
            collate_fn=collate,
            pin_memory=device.type == "cuda",
        )
        bar = _progress(loader, options.progress, f"epoch {epoch + 1}/{options.epochs}")
        loss_sum = torch.tensor(partial.get("loss_sum", [0.0, 0.0, 0.0]))
        last_step = done - 1
        saved_at = done
        optimizer.zero_grad(set_to_none=True)
        rates: dict[str, float] = {}
        for i, (images, targets) in enumerate(bar, start=done):
            iteration = i + epoch * batches_per_epoch
            rates, momentum = learning_rates(schedule, epoch, options.epochs, iteration, batches_per_epoch)
            apply_rates(optimizer, rates, momentum)
            # YOLOv8 ramps the accumulation from 1 to its full value during warm-up.
            step_every = (
                max(1, round(float(np.interp(iteration, [0, warmup], [1, accumulate])))) if iteration < warmup else accumulate
            )
            images = images.to(device, non_blocking=True)
            with _autocast(use_amp):
                outputs = model(images)
            loss, parts = criterion([o.float() for o in outputs], targets.to(device))
            if not torch.isfinite(loss):
                raise TrainError(f"the loss is not finite at epoch {epoch + 1}, batch {i + 1} (lower lr0?)")
            scaler.scale(loss).backward()
            if i - last_step >= step_every or i == batches_per_epoch - 1:
                scaler.unscale_(optimizer)
                torch.nn.utils.clip_grad_norm_(parameters, max_norm=options.grad_clip)
                scaler.step(optimizer)
                scaler.update()
                optimizer.zero_grad(set_to_none=True)
                ema.update(model)
                last_step = i
            loss_sum += parts.cpu()
            if (
                options.checkpoint_batches
                and last_step == i
                and i + 1 - saved_at >= options.checkpoint_batches
                and i + 1 < batches_per_epoch
            ):
                saved_at = i + 1
                save_checkpoint(
                    out / "last.pt", model, names=names, epoch=epoch - 1, ema=ema, optimizer=optimizer,
                    best_fitness=state.best_fitness, train_options=options,
                    extra=extra_state({
                        "batches": i + 1, "loss_sum": loss_sum.tolist(),
                        "seconds": time.time() - started, "cpu_seconds": _cpu_seconds() - cpu_started,
                    }),
                )
            mean = loss_sum / (i + 1)
            if options.progress:
                bar.set_postfix(box=f"{mean[0]:.3f}", cls=f"{mean[1]:.3f}", dfl=f"{mean[2]:.3f}", lr=f"{rates['weights']:.2e}")
            if on_batch_end is not None:
                on_batch_end(epoch, i)
        mean = loss_sum / max(batches_per_epoch, 1)
        row: dict[str, Any] = {
            "epoch": epoch + 1,
            "box_loss": float(mean[0]),
            "cls_loss": float(mean[1]),
            "dfl_loss": float(mean[2]),
            "lr": float(rates.get("weights", 0.0)),
            "map50": "", "map50_95": "", "precision": "", "recall": "", "fitness": "",
        }
        row["train_seconds"] = time.time() - started
        improved = False
        if (epoch + 1) % options.eval_every == 0 or epoch + 1 == options.epochs:
            result = evaluate_images(
                ema.module, val_images, spec.names, eval_options, str(device), options.workers, options.progress
            )
            score = fitness(result)
            row.update(
                map50=result["map50"], map50_95=result["map50_95"], precision=result["precision"],
                recall=result["recall"], fitness=score,
            )
            if state.best_fitness is None or score > state.best_fitness:
                state.best_fitness, improved = score, True
        row["seconds"] = time.time() - started
        row["cpu_seconds"] = _cpu_seconds() - cpu_started
        state.rows.append(row)
        last = save_checkpoint(
            out / "last.pt", model, names=names, epoch=epoch, ema=ema, optimizer=optimizer,
            best_fitness=state.best_fitness, train_options=options, extra=extra_state({}),
        )
        if improved:
            _copy_atomically(last, out / "best.pt")
        _write_results(out / "results.csv", state.rows)
        _report(row, options)
    best = out / "best.pt"
    if not best.exists():  # e.g. a resumed run that had already finished before any validation
        _copy_atomically(out / "last.pt", best)
    return best


def _restore(path: Path, model: nn.Module, ema: ModelEMA, optimizer, scaler, device: torch.device) -> _RunState:
    if not path.exists():
        raise TrainError(f"{path}: nothing to resume (no last.pt in the run folder)")
    checkpoint = load_checkpoint(path, device="cpu")
    raw = checkpoint.raw
    try:
        model.load_state_dict(raw["model"].state_dict())
        if raw.get("ema") is not None:
            ema.module.load_state_dict(raw["ema"].state_dict())
    except RuntimeError as error:
        first = str(error).splitlines()[0]
        raise TrainError(f"{path}: the checkpoint's model does not fit the one being trained ({first})") from None
    model.to(device)
    ema.module.to(device)
    ema.updates = int(raw.get("ema_updates", 0))
    if raw.get("optimizer") is not None:
        optimizer.load_state_dict(raw["optimizer"])
    extra = raw.get("extra") or {}
    if extra.get("scaler"):
        scaler.load_state_dict(extra["scaler"])
    if "rng" in extra:
        _set_rng_state(extra["rng"])
    return _RunState(
        start_epoch=checkpoint.epoch + 1,
        best_fitness=raw.get("best_fitness"),
        rows=list(extra.get("results", [])),
        partial=dict(extra.get("partial") or {}),
    )


def _plain_options(options: TrainOptions) -> dict[str, Any]:
    values = dataclasses.asdict(options)
    values["data"], values["out"] = str(options.data), str(options.out)
    values["input_size"] = list(options.input_size)
    return values


def _autocast(enabled: bool):
    if not enabled:
        return contextlib.nullcontext()
    return torch.autocast(device_type="cuda", dtype=torch.float16)


def _progress(loader, enabled: bool, description: str):
    if not enabled:
        return loader
    from tqdm import tqdm

    return tqdm(loader, desc=description, unit="batch", leave=False, dynamic_ncols=True)


def _report(row: dict[str, Any], options: TrainOptions) -> None:
    if not options.progress:
        return
    text = (
        f"epoch {row['epoch']}/{options.epochs}  box {row['box_loss']:.4f}  cls {row['cls_loss']:.4f}  "
        f"dfl {row['dfl_loss']:.4f}  {row['seconds']:.1f} s"
    )
    if row["map50"] != "":
        text += f"  mAP50 {row['map50']:.4f}  mAP50-95 {row['map50_95']:.4f}  P {row['precision']:.3f}  R {row['recall']:.3f}"
    print(text, flush=True)
