"""Checkpoints that store the whole module, so that pruned models (other shapes) load as they are.

A checkpoint is a dict written with ``torch.save``:
  format   "semchain_train/1"
  model    the nn.Module itself (float32, on CPU, train mode as saved)
  ema      the EMA module (float32, on CPU) or None; ema_updates its update count
  config   model.config if the module has one (ModelConfig), else None
  names    class names, index = class id
  epoch    last finished epoch (0-based; -1 before the first)
  optimizer, best_fitness, train_options (a plain dict), extra (caller's dict, e.g. RNG states)
"""

from __future__ import annotations

import copy
import dataclasses
import inspect
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import torch
from torch import nn

CHECKPOINT_FORMAT = "semchain_train/1"


@dataclass
class Checkpoint:
    """A loaded checkpoint; ``model`` holds the EMA weights when the file has them, in eval mode."""

    model: nn.Module
    names: list[str]
    epoch: int
    raw: dict[str, Any]


def _cpu_float_copy(module: nn.Module) -> nn.Module:
    # A copy, so that the live (possibly half-precision, on-GPU) model keeps training untouched.
    clone = copy.deepcopy(module)
    return clone.float().cpu()


def _plain(value: Any) -> Any:
    """Options as plain Python data (no Path or dataclass instances) so any reader can unpickle them."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        value = dataclasses.asdict(value)
    if isinstance(value, dict):
        return {str(key): _plain(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return type(value)(_plain(item) for item in value)
    if isinstance(value, Path):
        return str(value)
    return value


def _ema_module(ema: Any) -> nn.Module:
    # Accept the ModelEMA wrapper (ema.module) or a bare module.
    return ema.module if hasattr(ema, "module") and isinstance(ema.module, nn.Module) else ema


def save_checkpoint(
    path: Path | str,
    model: nn.Module,
    *,
    names: list[str],
    epoch: int,
    ema: Any = None,
    optimizer: torch.optim.Optimizer | None = None,
    best_fitness: float | None = None,
    train_options: Any = None,
    extra: dict[str, Any] | None = None,
) -> Path:
    """Write a checkpoint atomically (temporary file in the same folder, then rename)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    ema_module = _ema_module(ema) if ema is not None else None
    state: dict[str, Any] = {
        "format": CHECKPOINT_FORMAT,
        "model": _cpu_float_copy(model),
        "ema": _cpu_float_copy(ema_module) if ema_module is not None else None,
        "ema_updates": int(getattr(ema, "updates", 0)) if ema is not None else 0,
        "config": copy.deepcopy(getattr(model, "config", None)),
        "names": list(names),
        "epoch": int(epoch),
        "optimizer": optimizer.state_dict() if optimizer is not None else None,
        "best_fitness": None if best_fitness is None else float(best_fitness),
        "train_options": _plain(train_options),
        "extra": extra if extra is not None else {},
    }
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        with open(tmp, "wb") as stream:
            torch.save(state, stream)
            stream.flush()
            os.fsync(stream.fileno())
        os.replace(tmp, path)
    finally:
        if tmp.exists():
            tmp.unlink()
    return path


def _torch_load(path: Path, device: str) -> Any:
    kwargs: dict[str, Any] = {"map_location": device}
    # torch >= 2.6 defaults to weights_only=True, which refuses pickled modules; ours are trusted files.
    if "weights_only" in inspect.signature(torch.load).parameters:
        kwargs["weights_only"] = False
    return torch.load(path, **kwargs)


def load_checkpoint(path: Path | str, device: str = "cpu") -> Checkpoint:
    """Load a checkpoint; raise FileNotFoundError or ValueError naming the path on bad input."""
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such checkpoint file")
    try:
        raw = _torch_load(path, device)
    except Exception as error:  # pickle/zip/EOF errors differ by torch version; one message for all
        raise ValueError(f"{path}: not a readable checkpoint ({type(error).__name__}: {error})") from None
    if not isinstance(raw, dict) or raw.get("format") != CHECKPOINT_FORMAT:
        raise ValueError(f"{path}: not a semchain_train checkpoint (format tag missing)")
    if not isinstance(raw.get("model"), nn.Module):
        raise ValueError(f"{path}: checkpoint holds no model")
    model = raw["ema"] if isinstance(raw.get("ema"), nn.Module) else raw["model"]
    model = model.to(device).float().eval()
    return Checkpoint(model=model, names=list(raw.get("names") or []), epoch=int(raw.get("epoch", -1)), raw=raw)
