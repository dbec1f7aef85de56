"""Detection accuracy with the exact definitions of the C++ `semchain bench detector`
(src/detection/detection_metrics.{h,cc}), so that Python validation and the C++ benchmark agree.

AP per class at IoU 0.50, 0.55, ..., 0.95: COCO's 101-point interpolation of the precision envelope;
a detection matches the unmatched truth of its class with the highest IoU at or above each
threshold, best-scoring detections first; mAP over the classes that have truths; precision and
recall (means over those classes) at the confidence, on a grid of 1000, that maximises the F1 of
the means.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

THRESHOLDS = 0.5 + 0.05 * np.arange(10)
CONFIDENCE_GRID = 1000


def box_iou_matrix(boxes_a: np.ndarray, boxes_b: np.ndarray) -> np.ndarray:
    """Pairwise IoU of [N, 4] and [M, 4] x1 y1 x2 y2 boxes; 0 when they do not overlap."""
    a = np.asarray(boxes_a, dtype=np.float64).reshape(-1, 4)
    b = np.asarray(boxes_b, dtype=np.float64).reshape(-1, 4)
    w = np.minimum(a[:, None, 2], b[None, :, 2]) - np.maximum(a[:, None, 0], b[None, :, 0])
    h = np.minimum(a[:, None, 3], b[None, :, 3]) - np.maximum(a[:, None, 1], b[None, :, 1])
    overlapping = (w > 0) & (h > 0)
    inter = np.where(overlapping, w * h, 0.0)
    area_a = (a[:, 2] - a[:, 0]) * (a[:, 3] - a[:, 1])
    area_b = (b[:, 2] - b[:, 0]) * (b[:, 3] - b[:, 1])
    union = area_a[:, None] + area_b[None, :] - inter
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(overlapping & (union > 0), inter / np.where(union > 0, union, 1.0), 0.0)


def average_precision(recall: np.ndarray, precision: np.ndarray) -> float:
    """Area under the precision envelope sampled at recall 0, 0.01, ..., 1 (points by decreasing score)."""
    recall = np.asarray(recall, dtype=np.float64)
    if recall.size == 0:
        return 0.0
    envelope = np.maximum.accumulate(np.asarray(precision, dtype=np.float64)[::-1])[::-1]
    total = 0.0
    k = 0
    for i in range(101):
        r = i / 100.0
        while k < recall.size and recall[k] < r - 1e-12:
            k += 1
        if k == recall.size:  # recall never reaches r: precision 0 from here on
            break
        total += envelope[k]
    return total / 101.0


@dataclass
class ClassAccuracy:
    truths: int = 0
    ap50: float = 0.0
    ap50_95: float = 0.0


@dataclass
class DetectionAccuracy:
    map50: float = 0.0
    map50_95: float = 0.0
    precision: float = 0.0
    recall: float = 0.0
    confidence: float = 0.0
    classes: list[ClassAccuracy] = field(default_factory=list)


class DetectionEvaluator:
    def __init__(self, classes: int) -> None:
        self.classes = classes
        self._scores: list[list[float]] = [[] for _ in range(classes)]
        self._true_positive: list[list[np.ndarray]] = [[] for _ in range(classes)]
        self._truths = np.zeros(classes, dtype=np.int64)

    def add_image(self, detections: np.ndarray, truths: np.ndarray) -> None:
        """detections [N, 6]: x1 y1 x2 y2 score class; truths [M, 5]: class x1 y1 x2 y2 (same pixels)."""
        detections = np.asarray(detections, dtype=np.float64).reshape(-1, 6)
        truths = np.asarray(truths, dtype=np.float64).reshape(-1, 5)
        truth_classes = truths[:, 0].astype(np.int64)
        for c in truth_classes:
            if 0 <= c < self.classes:
                self._truths[c] += 1
        order = np.argsort(-detections[:, 4], kind="stable")
        iou = box_iou_matrix(detections[:, :4], truths[:, 1:])
        taken = np.zeros((len(THRESHOLDS), len(truths)), dtype=bool)
        for i in order:
            class_id = int(detections[i, 5])
            if not 0 <= class_id < self.classes:
                continue
            same_class = truth_classes == class_id
            hits = np.zeros(len(THRESHOLDS), dtype=bool)
            for t, threshold in enumerate(THRESHOLDS):
                eligible = same_class & ~taken[t] & (iou[i] >= threshold - 1e-12) & (iou[i] > 0)
                if eligible.any():
                    # The highest IoU; ties go to the first truth, as the C++ loop keeps the first maximum.
                    best = int(np.argmax(np.where(eligible, iou[i], -1.0)))
                    taken[t, best] = True
                    hits[t] = True
            self._scores[class_id].append(float(detections[i, 4]))
            self._true_positive[class_id].append(hits)

    def evaluate(self) -> DetectionAccuracy:
        accuracy = DetectionAccuracy(classes=[ClassAccuracy() for _ in range(self.classes)])
        with_truth = 0
        mean_precision = np.zeros(CONFIDENCE_GRID)
        mean_recall = np.zeros(CONFIDENCE_GRID)
        confidences = np.arange(CONFIDENCE_GRID) / CONFIDENCE_GRID
        for c in range(self.classes):
            result = accuracy.classes[c]
            truths = int(self._truths[c])
            result.truths = truths
            if truths == 0:
                continue
            with_truth += 1
            scores = np.asarray(self._scores[c], dtype=np.float64)
            hits = np.asarray(self._true_positive[c], dtype=bool).reshape(-1, len(THRESHOLDS))
            order = np.argsort(-scores, kind="stable")
            scores, hits = scores[order], hits[order]
            cumulative = np.cumsum(hits, axis=0)
            ranks = np.arange(1, len(scores) + 1)
            for t in range(len(THRESHOLDS)):
                ap = average_precision(cumulative[:, t] / truths, cumulative[:, t] / ranks) if len(scores) else 0.0
                if t == 0:
                    result.ap50 = ap
                result.ap50_95 += ap / len(THRESHOLDS)
            # Detections scoring at least each grid confidence: a prefix of the sorted list.
            predicted = np.searchsorted(-scores, -confidences, side="right")
            tp_at = np.concatenate(([0], cumulative[:, 0]))[predicted] if len(scores) else np.zeros(CONFIDENCE_GRID)
            with np.errstate(divide="ignore", invalid="ignore"):
                mean_precision += np.where(predicted > 0, tp_at / np.maximum(predicted, 1), 1.0)
            mean_recall += tp_at / truths
        if with_truth == 0:
            return accuracy
        p = mean_precision / with_truth
        r = mean_recall / with_truth
        with np.errstate(divide="ignore", invalid="ignore"):
            f1 = np.where(p + r > 0, 2 * p * r / np.where(p + r > 0, p + r, 1.0), 0.0)
        best = int(np.argmax(f1))  # first maximum, as the C++ loop's strict '>'
        accuracy.precision, accuracy.recall, accuracy.confidence = float(p[best]), float(r[best]), float(confidences[best])
        for result in accuracy.classes:
            if result.truths:
                accuracy.map50 += result.ap50 / with_truth
                accuracy.map50_95 += result.ap50_95 / with_truth
        return accuracy
