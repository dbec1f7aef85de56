"""YOLOv8's detection loss: BCE on the classes, CIoU and distribution focal loss on the boxes.

  L = B * (7.5 L_box + 0.5 L_cls + 1.5 L_dfl)       (B: batch size, as ultralytics scales it)
  L_cls = sum BCE(class logits, normalized alignment targets) / S
  L_box = sum_fg w (1 - CIoU(pred, target)) / S,    w = the anchor's target score
  L_dfl = sum_fg w DFL / S,   DFL(y) = -((y_r - y) log p_l + (y - y_l) log p_r) averaged over l, t, r, b
with S = max(1, sum of target scores) and y the target distance in strides (Li et al., GFL, NeurIPS 2020).
"""

from __future__ import annotations

from dataclasses import dataclass

import torch
import torch.nn.functional as F

from semchain_train.assigner import AssignerOptions, TaskAlignedAssigner
from semchain_train.boxes import bbox2dist, bbox_ciou, dfl_expectation, dist2bbox, flatten_outputs, make_anchors


@dataclass
class LossWeights:
    box: float = 7.5
    cls: float = 0.5
    dfl: float = 1.5


def distribution_focal_loss(logits: torch.Tensor, target: torch.Tensor) -> torch.Tensor:
    """logits [N, 4, reg_max], target [N, 4] distances in bins (0 <= y < reg_max - 1) -> [N] mean over sides.

    Cross-entropy towards the two bins around y, weighted by their linear interpolation weights.
    """
    left = target.long()
    right = left + 1
    weight_left = right.float() - target
    weight_right = 1 - weight_left
    log_p = F.log_softmax(logits.float(), dim=-1)
    loss = -(log_p.gather(-1, left[..., None])[..., 0] * weight_left + log_p.gather(-1, right[..., None])[..., 0] * weight_right)
    return loss.mean(dim=-1)


def batch_targets(targets: torch.Tensor, batch: int) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
    """[M, 6] (image, class, x1, y1, x2, y2) -> labels [B, K], boxes [B, K, 4], mask [B, K] (K: most per image)."""
    device = targets.device
    counts = torch.bincount(targets[:, 0].long(), minlength=batch) if len(targets) else torch.zeros(batch, dtype=torch.long)
    most = int(counts.max()) if len(targets) else 0
    labels = torch.zeros(batch, most, dtype=torch.long, device=device)
    boxes = torch.zeros(batch, most, 4, device=device)
    mask = torch.zeros(batch, most, dtype=torch.bool, device=device)
    for image in range(batch):
        rows = targets[targets[:, 0].long() == image]
        labels[image, : len(rows)] = rows[:, 1].long()
        boxes[image, : len(rows)] = rows[:, 2:6]
        mask[image, : len(rows)] = True
    return labels, boxes, mask


class DetectionLoss:
    """Callable on (raw head maps, targets [M, 6] in input pixels) -> (scalar to minimize, [box, cls, dfl])."""

    def __init__(
        self,
        classes: int,
        strides: tuple[int, ...] = (8, 16, 32),
        reg_max: int = 16,
        weights: LossWeights | None = None,
        assigner: AssignerOptions | None = None,
    ) -> None:
        self.classes = classes
        self.strides = tuple(strides)
        self.reg_max = reg_max
        self.weights = weights or LossWeights()
        self.assigner = TaskAlignedAssigner(assigner, classes=classes)

    def __call__(self, outputs: list[torch.Tensor], targets: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        batch = outputs[0].shape[0]
        distribution, class_logits = flatten_outputs(outputs, self.reg_max)
        distribution, class_logits = distribution.float(), class_logits.float()
        points, stride_column = make_anchors([tuple(o.shape[2:]) for o in outputs], self.strides, outputs[0].device)
        # Boxes in grid units (strides) around the anchor centres.
        pred_boxes = dist2bbox(dfl_expectation(distribution, self.reg_max), points)

        gt_labels, gt_boxes, gt_mask = batch_targets(targets.to(outputs[0].device).float(), batch)
        assignment = self.assigner(
            class_logits.detach().sigmoid(),
            pred_boxes.detach() * stride_column,
            points * stride_column,
            gt_labels,
            gt_boxes,
            gt_mask,
        )
        target_scores = assignment.scores
        score_sum = target_scores.sum().clamp(min=1.0)

        loss_cls = F.binary_cross_entropy_with_logits(class_logits, target_scores, reduction="sum") / score_sum
        loss_box = torch.zeros((), device=class_logits.device)
        loss_dfl = torch.zeros((), device=class_logits.device)
        foreground = assignment.foreground
        if foreground.any():
            weight = target_scores.sum(-1)[foreground]
            target_grid = assignment.boxes / stride_column  # pixels -> strides
            ciou = bbox_ciou(pred_boxes[foreground], target_grid[foreground])
            loss_box = ((1.0 - ciou) * weight).sum() / score_sum
            target_distances = bbox2dist(points, target_grid, self.reg_max)[foreground]
            logits = distribution[foreground].reshape(-1, 4, self.reg_max)
            loss_dfl = (distribution_focal_loss(logits, target_distances) * weight).sum() / score_sum

        parts = torch.stack((loss_box * self.weights.box, loss_cls * self.weights.cls, loss_dfl * self.weights.dfl))
        return parts.sum() * batch, parts.detach()
