"""Validation as the C++ runtime detects and `semchain bench detector` scores (src/detection/):
letterbox to the input, raw head decoded (DFL expectation, best class per anchor, sigmoid score >=
conf), class-wise NMS (drop a box overlapping a better one of its class by IoU > iou), at most
max_det boxes, mapped back to the image and clipped; scored against the labels in image pixels.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import torch
from torch import nn

from semchain_train.boxes import decode_outputs
from semchain_train.data.augment import Letterbox, apply_letterbox, fit_letterbox
from semchain_train.data.dataset import label_path_of, load_data_yaml, read_labels, read_rgb, split_images, to_pixel_boxes
from semchain_train.metrics import DetectionEvaluator


@dataclass
class EvalOptions:
    input_size: tuple[int, int] = (320, 256)  # (width, height) of the network input
    conf: float = 0.001  # ultralytics' validation threshold, as `bench detector`
    iou: float = 0.7  # NMS IoU threshold, as `bench detector`
    max_det: int = 300  # detections kept per image, as the C++ YoloOptions
    batch: int = 16


def class_wise_nms(boxes: np.ndarray, scores: np.ndarray, classes: np.ndarray, iou: float, max_count: int) -> np.ndarray:
    """Indices kept, best score first (ties: lower index first); boxes of different classes never
    suppress each other (the C++ ClassWiseNms: OpenCV's NMSBoxes per class)."""
    order = np.argsort(-scores, kind="stable")
    keep: list[int] = []
    suppressed = np.zeros(len(scores), dtype=bool)
    x1, y1, x2, y2 = boxes[:, 0], boxes[:, 1], boxes[:, 2], boxes[:, 3]
    areas = (x2 - x1) * (y2 - y1)
    for i in order:
        if suppressed[i]:
            continue
        keep.append(int(i))
        if len(keep) == max_count:
            break
        w = np.minimum(x2[i], x2) - np.maximum(x1[i], x1)
        h = np.minimum(y2[i], y2) - np.maximum(y1[i], y1)
        inter = np.where((w > 0) & (h > 0), w * h, 0.0)
        union = areas[i] + areas - inter
        overlap = np.where(union > 0, inter / np.where(union > 0, union, 1.0), 0.0)
        suppressed |= (overlap > iou) & (classes == classes[i])
    return np.asarray(keep, dtype=np.int64)


def postprocess(
    boxes: torch.Tensor, scores: torch.Tensor, letterbox: Letterbox, options: EvalOptions
) -> np.ndarray:
    """One image's decoded anchors (input pixels) -> detections [N, 6] x1 y1 x2 y2 score class in image pixels."""
    best_score, best_class = scores.max(dim=-1)
    selected = best_score >= options.conf
    boxes_np = boxes[selected].double().cpu().numpy()
    scores_np = best_score[selected].double().cpu().numpy()
    classes_np = best_class[selected].cpu().numpy()
    keep = class_wise_nms(boxes_np, scores_np, classes_np, options.iou, options.max_det)
    out = np.zeros((len(keep), 6))
    if len(keep) == 0:
        return out
    kept = boxes_np[keep]
    out[:, [0, 2]] = (kept[:, [0, 2]] - letterbox.pad_left) / letterbox.scale_x
    out[:, [1, 3]] = (kept[:, [1, 3]] - letterbox.pad_top) / letterbox.scale_y
    width, height = letterbox.image_size
    out[:, [0, 2]] = out[:, [0, 2]].clip(0, width)
    out[:, [1, 3]] = out[:, [1, 3]].clip(0, height)
    out[:, 4] = scores_np[keep].clip(0, 1)
    out[:, 5] = classes_np[keep]
    return out[(out[:, 2] > out[:, 0]) & (out[:, 3] > out[:, 1])]


class _EvalImages(torch.utils.data.Dataset):
    def __init__(self, images: list[Path], classes: int, input_size: tuple[int, int]) -> None:
        self.images = images
        self.classes = classes
        self.input_size = input_size
        # Read every label first: a bad line is reported before any inference.
        self.truths = []
        for path in images:
            labels = read_labels(label_path_of(path), classes)
            self.truths.append(labels)

    def __len__(self) -> int:
        return len(self.images)

    def __getitem__(self, index: int) -> tuple[np.ndarray, Letterbox, np.ndarray]:
        image = read_rgb(self.images[index])
        h, w = image.shape[:2]
        letterbox = fit_letterbox((w, h), self.input_size)
        return apply_letterbox(image, letterbox), letterbox, to_pixel_boxes(self.truths[index], w, h)


def _collate(batch: list[Any]) -> tuple[torch.Tensor, list[Letterbox], list[np.ndarray]]:
    images = torch.from_numpy(np.stack([item[0] for item in batch])).permute(0, 3, 1, 2).float().div_(255.0)
    return images, [item[1] for item in batch], [item[2] for item in batch]


@torch.no_grad()
def evaluate_images(
    model: nn.Module,
    images: list[Path],
    names: list[str],
    options: EvalOptions,
    device: str = "cpu",
    workers: int = 0,
    progress: bool = False,
) -> dict[str, Any]:
    dataset = _EvalImages(images, len(names), tuple(options.input_size))
    loader = torch.utils.data.DataLoader(dataset, batch_size=options.batch, num_workers=workers, collate_fn=_collate)
    evaluator = DetectionEvaluator(len(names))
    strides = tuple(getattr(model, "strides", (8, 16, 32)))
    reg_max = int(getattr(model, "reg_max", 16))
    was_training = model.training
    model.eval()
    iterator = loader
    if progress:
        from tqdm import tqdm

        iterator = tqdm(loader, desc="val", unit="batch", leave=False)
    truths_total = 0
    try:
        for batch_images, letterboxes, truths in iterator:
            boxes, scores = decode_outputs(model(batch_images.to(device)), strides, reg_max)
            for i, letterbox in enumerate(letterboxes):
                evaluator.add_image(postprocess(boxes[i], scores[i], letterbox, options), truths[i])
                truths_total += len(truths[i])
    finally:
        model.train(was_training)
    accuracy = evaluator.evaluate()
    return {
        "images": len(dataset),
        "truths": truths_total,
        "map50": accuracy.map50,
        "map50_95": accuracy.map50_95,
        "precision": accuracy.precision,
        "recall": accuracy.recall,
        "confidence": accuracy.confidence,
        "classes": {
            name: {"truths": c.truths, "ap50": c.ap50, "ap50_95": c.ap50_95} for name, c in zip(names, accuracy.classes)
        },
        "ap50_per_class": [c.ap50 for c in accuracy.classes],
    }


def evaluate(
    model: nn.Module,
    data_yaml: Path | str,
    split: str = "test",
    input_size: tuple[int, int] = (320, 256),
    device: str = "cpu",
    conf: float = 0.001,
    iou: float = 0.7,
    *,
    max_det: int = 300,
    batch: int = 16,
    workers: int = 0,
    progress: bool = False,
) -> dict[str, Any]:
    """mAP@0.5, mAP@0.5:0.95, precision, recall and per-class AP of `model` on a split of data_yaml."""
    spec = load_data_yaml(data_yaml)
    images = split_images(spec, split)
    options = EvalOptions(input_size=tuple(input_size), conf=conf, iou=iou, max_det=max_det, batch=batch)
    result = evaluate_images(model, images, spec.names, options, device, workers, progress)
    result["split"] = split
    return result


def fitness(result: dict[str, Any]) -> float:
    """YOLOv8's model selection score."""
    return 0.1 * result["map50"] + 0.9 * result["map50_95"]
