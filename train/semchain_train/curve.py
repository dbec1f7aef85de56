"""The learning curve as a PNG: val mAP@0.5 and mAP@0.5:0.95 (top) and the three training losses
(bottom) per epoch, from one or more results.csv files taken as consecutive stages of one model
(a run, then the fine-tuning runs that went on from its export), with the CPU-hours spent.

    /usr/bin/python3 -m semchain_train curve RUN1/results.csv RUN2/results.csv --out curve.png
"""

from __future__ import annotations

import argparse
import csv
import os
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np

WIDTH, HEIGHT = 900, 640
MARGIN_LEFT, MARGIN_RIGHT, MARGIN_TOP, MARGIN_BOTTOM, GAP = 70, 170, 40, 50, 50
# BGR colours of the series, in the legend's order.
COLOURS = {
    "map50": (200, 90, 20),
    "map50_95": (60, 160, 60),
    "box_loss": (40, 40, 200),
    "cls_loss": (160, 60, 160),
    "dfl_loss": (20, 150, 200),
}
LABELS = {
    "map50": "val mAP@0.5",
    "map50_95": "val mAP@0.5:0.95",
    "box_loss": "box loss",
    "cls_loss": "cls loss",
    "dfl_loss": "dfl loss",
}


class CurveError(ValueError):
    pass


@dataclass
class Epochs:
    """Per epoch (1-based, counted across the stages): the value of each column, NaN where the
    epoch was not validated; stage boundaries as the last epoch of each stage."""

    epoch: np.ndarray
    values: dict[str, np.ndarray]
    stage_ends: list[int]
    cpu_hours: float
    wall_hours: float


def _number(text: str, source: str) -> float:
    if text == "":
        return float("nan")
    try:
        return float(text)
    except ValueError:
        raise CurveError(f"{source}: '{text}' is not a number") from None


def read_stages(paths: list[Path]) -> Epochs:
    epochs: list[int] = []
    values: dict[str, list[float]] = {key: [] for key in COLOURS}
    stage_ends: list[int] = []
    cpu = wall = 0.0
    for path in paths:
        if not path.is_file():
            raise CurveError(f"{path}: no such results file")
        with open(path, newline="") as stream:
            rows = list(csv.DictReader(stream))
        if not rows:
            raise CurveError(f"{path}: no epochs")
        missing = [key for key in ("epoch", *COLOURS) if key not in rows[0]]
        if missing:
            raise CurveError(f"{path}: no column {', '.join(missing)} (not a semchain_train results.csv)")
        for line, row in enumerate(rows, start=2):
            source = f"{path}:{line}"
            epochs.append(len(epochs) + 1)
            for key in COLOURS:
                values[key].append(_number(row[key], source))
            if row.get("cpu_seconds"):  # absent in results.csv written before the column existed
                cpu += _number(row["cpu_seconds"], source)
            wall += _number(row.get("seconds", "") or "0", source)
        stage_ends.append(len(epochs))
    return Epochs(
        np.array(epochs, dtype=float),
        {key: np.array(series) for key, series in values.items()},
        stage_ends,
        cpu / 3600.0,
        wall / 3600.0,
    )


@dataclass
class Panel:
    """A plot area in the image and the data range it shows."""

    left: int
    top: int
    right: int
    bottom: int
    x_max: float
    y_max: float

    def to_pixel(self, x: float, y: float) -> tuple[int, int]:
        """Epoch x in [0, x_max] and value y in [0, y_max] to image pixels (y up)."""
        px = self.left + (self.right - self.left) * x / self.x_max
        py = self.bottom - (self.bottom - self.top) * y / self.y_max
        return int(round(px)), int(round(py))


def panels(data: Epochs) -> tuple[Panel, Panel]:
    x_max = max(float(data.epoch.max()), 1.0)
    losses = np.concatenate([data.values[k] for k in ("box_loss", "cls_loss", "dfl_loss")])
    loss_max = float(np.nanmax(losses)) if np.isfinite(losses).any() else 1.0
    height = (HEIGHT - MARGIN_TOP - MARGIN_BOTTOM - GAP) // 2
    top = Panel(MARGIN_LEFT, MARGIN_TOP, WIDTH - MARGIN_RIGHT, MARGIN_TOP + height, x_max, 1.0)
    bottom_top = MARGIN_TOP + height + GAP
    bottom = Panel(MARGIN_LEFT, bottom_top, WIDTH - MARGIN_RIGHT, bottom_top + height, x_max, loss_max * 1.05)
    return top, bottom


def _axes(image: np.ndarray, panel: Panel, title: str, ticks: list[float]) -> None:
    grey, font = (150, 150, 150), cv2.FONT_HERSHEY_SIMPLEX
    cv2.rectangle(image, (panel.left, panel.top), (panel.right, panel.bottom), (0, 0, 0), 1)
    for y in ticks:
        _, py = panel.to_pixel(0, y)
        cv2.line(image, (panel.left, py), (panel.right, py), (225, 225, 225), 1)
        cv2.putText(image, f"{y:.2f}", (panel.left - 50, py + 4), font, 0.4, grey, 1, cv2.LINE_AA)
    cv2.putText(image, title, (panel.left, panel.top - 10), font, 0.5, (0, 0, 0), 1, cv2.LINE_AA)


def draw(data: Epochs, title: str) -> np.ndarray:
    image = np.full((HEIGHT, WIDTH, 3), 255, np.uint8)
    top, bottom = panels(data)
    _axes(image, top, f"{title}: validation", [0.0, 0.25, 0.5, 0.75, 1.0])
    _axes(image, bottom, "training losses (gains included)", list(np.linspace(0, bottom.y_max, 5)))
    font = cv2.FONT_HERSHEY_SIMPLEX
    for end in data.stage_ends[:-1]:  # where a fine-tuning stage went on from an export
        for panel in (top, bottom):
            x, _ = panel.to_pixel(end + 0.5, 0)
            cv2.line(image, (x, panel.top), (x, panel.bottom), (190, 190, 190), 1)
    for key, colour in COLOURS.items():
        panel = top if key.startswith("map") else bottom
        series = data.values[key]
        points = [panel.to_pixel(x, y) for x, y in zip(data.epoch, series) if np.isfinite(y)]
        if len(points) > 1:
            cv2.polylines(image, [np.array(points, np.int32)], False, colour, 2, cv2.LINE_AA)
        for point in points:
            cv2.circle(image, point, 2, colour, -1, cv2.LINE_AA)
    for row, key in enumerate(COLOURS):
        y = MARGIN_TOP + 20 + 22 * row
        cv2.line(image, (WIDTH - MARGIN_RIGHT + 15, y), (WIDTH - MARGIN_RIGHT + 40, y), COLOURS[key], 2)
        cv2.putText(image, LABELS[key], (WIDTH - MARGIN_RIGHT + 45, y + 4), font, 0.4, (0, 0, 0), 1, cv2.LINE_AA)
    best = np.nanmax(data.values["map50"]) if np.isfinite(data.values["map50"]).any() else float("nan")
    cpu = f"{data.cpu_hours:.1f} CPU-hours, " if data.cpu_hours > 0 else ""
    footer = (
        f"{int(data.epoch.max())} epochs in {len(data.stage_ends)} stage(s), {cpu}{data.wall_hours:.1f} h wall; "
        f"best val mAP@0.5 {best:.3f}"
    )
    cv2.putText(image, footer, (MARGIN_LEFT, HEIGHT - 15), font, 0.45, (0, 0, 0), 1, cv2.LINE_AA)
    cv2.putText(image, "epoch", (bottom.right - 40, bottom.bottom + 18), font, 0.4, (120, 120, 120), 1, cv2.LINE_AA)
    return image


def write_png(path: Path, image: np.ndarray) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp.png")
    if not cv2.imwrite(str(tmp), image):
        raise CurveError(f"{path}: cannot write the image")
    os.replace(tmp, path)


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("results", type=Path, nargs="+", help="results.csv of each stage, in training order")
    parser.add_argument("--out", type=Path, required=True, help="PNG to write")
    parser.add_argument("--title", default="semchain detector", help="title above the validation panel")


def run(args: argparse.Namespace) -> int:
    data = read_stages(args.results)
    write_png(args.out, draw(data, args.title))
    best = np.nanmax(data.values["map50"]) if np.isfinite(data.values["map50"]).any() else float("nan")
    print(f"wrote {args.out}: {int(data.epoch.max())} epochs, {data.cpu_hours:.2f} CPU-hours recorded, best val mAP@0.5 {best:.4f}")
    return 0
