"""The learning-curve PNG: stages joined epoch after epoch, values drawn where they belong, CPU-hours
summed, bad files refused with the file and line."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest

from semchain_train.curve import COLOURS, CurveError, draw, panels, read_stages

HEADER = "epoch,box_loss,cls_loss,dfl_loss,lr,map50,map50_95,precision,recall,fitness,train_seconds,seconds,cpu_seconds\n"


def _write(path: Path, rows: list[tuple[float, float, str, float]]) -> Path:
    """rows: (box loss, cls loss, map50 or '', cpu seconds)."""
    lines = [HEADER]
    for i, (box, cls, map50, cpu) in enumerate(rows, start=1):
        map50_95 = f"{float(map50) / 2:.3f}" if map50 else ""  # apart from mAP@0.5's line
        lines.append(f"{i},{box},{cls},1.0,0.001,{map50},{map50_95},,,,10,12,{cpu}\n")
    path.write_text("".join(lines))
    return path


def test_stages_are_consecutive_epochs_and_cpu_hours_add_up(tmp_path: Path):
    first = _write(tmp_path / "a.csv", [(3.0, 4.0, "0.1", 1800), (2.5, 3.0, "", 1800)])
    second = _write(tmp_path / "b.csv", [(2.0, 2.0, "0.5", 3600)])
    data = read_stages([first, second])
    assert list(data.epoch) == [1, 2, 3]
    assert data.stage_ends == [2, 3]
    assert data.cpu_hours == pytest.approx(2.0)
    assert np.isnan(data.values["map50"][1])  # not validated that epoch
    assert data.values["map50"][2] == pytest.approx(0.5)


def test_the_map_line_passes_through_its_points(tmp_path: Path):
    rows = [(3.0 - 0.2 * i, 2.0, f"{0.1 * i:.1f}", 60) for i in range(1, 9)]
    data = read_stages([_write(tmp_path / "r.csv", rows)])
    image = draw(data, "test")
    top, _ = panels(data)
    colour = np.array(COLOURS["map50"])
    for epoch, value in zip(data.epoch, data.values["map50"]):
        x, y = top.to_pixel(epoch, value)
        patch = image[y - 2 : y + 3, x - 2 : x + 3].reshape(-1, 3).astype(int)
        assert (np.abs(patch - colour).sum(1) < 60).any(), f"epoch {epoch}: no mAP point at ({x}, {y})"
    # A point where no value lies carries no mAP colour (mAP 0.9 at epoch 1 was never reached).
    x, y = top.to_pixel(1, 0.9)
    patch = image[y - 1 : y + 2, x - 1 : x + 2].reshape(-1, 3).astype(int)
    assert not (np.abs(patch - colour).sum(1) < 60).any()


def test_cli_writes_the_png_and_refuses_bad_numbers(tmp_path: Path):
    good = _write(tmp_path / "r.csv", [(3.0, 4.0, "0.2", 60), (2.0, 3.0, "0.4", 60)])
    out = tmp_path / "curve.png"
    train_dir = Path(__file__).resolve().parents[1]
    run = subprocess.run([sys.executable, "-m", "semchain_train", "curve", str(good), "--out", str(out)],
                         cwd=train_dir, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert cv2.imread(str(out)) is not None
    bad = tmp_path / "bad.csv"
    bad.write_text(HEADER + "1,x,4.0,1.0,0.001,0.1,0.1,,,,10,12,60\n")
    with pytest.raises(CurveError, match=r"bad.csv:2"):
        read_stages([bad])
    run = subprocess.run([sys.executable, "-m", "semchain_train", "curve", str(bad), "--out", str(out)],
                         cwd=train_dir, capture_output=True, text=True)
    assert run.returncode == 1
    assert len(run.stderr.strip().splitlines()) == 1 and "bad.csv:2" in run.stderr
