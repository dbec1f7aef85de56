"""Tiny YOLO data sets written to a temporary folder: one filled rectangle per object on black."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np

# One saturated colour per class (RGB), so a class's pixels can be found again after augmentation.
CLASS_COLOURS = [(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 0)]
CLASS_NAMES = ["red", "green", "blue", "yellow"]


def write_dataset(
    root: Path,
    objects: dict[str, list[list[tuple[int, tuple[int, int, int, int]]]]],
    size: tuple[int, int] = (64, 64),
    names: list[str] | None = None,
) -> Path:
    """objects[split][image] = [(class, (x1, y1, x2, y2) in pixels), ...]; returns data.yaml's path."""
    names = names or CLASS_NAMES
    width, height = size
    for split, images in objects.items():
        (root / "images" / split).mkdir(parents=True, exist_ok=True)
        (root / "labels" / split).mkdir(parents=True, exist_ok=True)
        for index, boxes in enumerate(images):
            image = np.zeros((height, width, 3), np.uint8)
            lines = []
            for class_id, (x1, y1, x2, y2) in boxes:
                image[y1:y2, x1:x2] = CLASS_COLOURS[class_id]
                cx, cy = (x1 + x2) / 2 / width, (y1 + y2) / 2 / height
                lines.append(f"{class_id} {cx:.6f} {cy:.6f} {(x2 - x1) / width:.6f} {(y2 - y1) / height:.6f}")
            cv2.imwrite(str(root / "images" / split / f"{index:03d}.png"), cv2.cvtColor(image, cv2.COLOR_RGB2BGR))
            (root / "labels" / split / f"{index:03d}.txt").write_text("\n".join(lines) + "\n")
    splits = "".join(f"{split}: images/{split}\n" for split in objects)
    yaml_path = root / "data.yaml"
    yaml_path.write_text(f"path: {root}\n{splits}nc: {len(names)}\nnames: [{', '.join(names)}]\n")
    return yaml_path


def four_colour_dataset(root: Path, size: tuple[int, int] = (64, 64), splits=("train", "val")) -> Path:
    """Four images, image i holding one rectangle of class i, in each split."""
    w, h = size
    rects = [
        (0, (w // 8, h // 8, w // 2, h // 2)),
        (1, (w // 3, h // 4, w - w // 8, h - h // 3)),
        (2, (w // 5, h // 2, w // 2 + 4, h - h // 10)),
        (3, (w // 2, h // 6, w - w // 6, h // 2 + 3)),
    ]
    return write_dataset(root, {split: [[r] for r in rects] for split in splits}, size)


def class_pixel_box(image: np.ndarray, class_id: int) -> tuple[float, float, float, float] | None:
    """Edge-coordinate bounding box of the pixels nearer class_id's colour than anything else."""
    r, g, b = (image[..., k].astype(int) for k in range(3))
    high, low = 128, 128
    masks = [
        (r >= high) & (g < low) & (b < low),
        (g >= high) & (r < low) & (b < low),
        (b >= high) & (r < low) & (g < low),
        (r >= high) & (g >= high) & (b < low),
    ]
    ys, xs = np.nonzero(masks[class_id])
    if len(xs) == 0:
        return None
    return float(xs.min()), float(ys.min()), float(xs.max() + 1), float(ys.max() + 1)
