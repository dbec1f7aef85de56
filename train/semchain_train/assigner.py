"""YOLOv8's task-aligned assigner (TOOD, Feng et al., ICCV 2021, as ultralytics uses it).

For each ground-truth box g and anchor a whose centre lies inside g:
  t(a, g) = s(a, class g)^alpha * u(a, g)^beta   (s: predicted class score, u: CIoU of a's box with g, >= 0)
The top-k anchors by t of each g are its candidates; an anchor claimed by several boxes keeps the one it
overlaps most. Targets: g's box, g's class with the score t(a, g) * max_a' u(a', g) / max_a' t(a', g)
(the alignment metric normalized so that each box's best anchor gets its best overlap).
"""

from __future__ import annotations

from dataclasses import dataclass

import torch

from semchain_train.boxes import bbox_ciou


@dataclass
class AssignerOptions:
    topk: int = 10  # candidates per ground-truth box
    alpha: float = 0.5  # weight of the classification score in the alignment metric
    beta: float = 6.0  # weight of the overlap
    eps: float = 1e-9


@dataclass
class Assignment:
    labels: torch.Tensor  # [B, A] long, the class of the assigned box (0 where none)
    boxes: torch.Tensor  # [B, A, 4] the assigned box, x1 y1 x2 y2 in the inputs' units
    scores: torch.Tensor  # [B, A, C] the normalized alignment metric at the assigned class, else 0
    foreground: torch.Tensor  # [B, A] bool, anchors that received a box
    gt_index: torch.Tensor  # [B, A] long, index of the assigned box within its image


def anchors_inside_boxes(anchor_points: torch.Tensor, gt_boxes: torch.Tensor, eps: float = 1e-9) -> torch.Tensor:
    """[A, 2] centres, [B, M, 4] boxes -> [B, M, A] bool: the centre lies strictly inside the box."""
    left_top = anchor_points[None, None] - gt_boxes[..., None, :2]
    right_bottom = gt_boxes[..., None, 2:] - anchor_points[None, None]
    return torch.cat((left_top, right_bottom), dim=-1).amin(dim=-1) > eps


class TaskAlignedAssigner:
    def __init__(self, options: AssignerOptions | None = None, classes: int = 80) -> None:
        self.options = options or AssignerOptions()
        self.classes = classes

    @torch.no_grad()
    def __call__(
        self,
        pred_scores: torch.Tensor,
        pred_boxes: torch.Tensor,
        anchor_points: torch.Tensor,
        gt_labels: torch.Tensor,
        gt_boxes: torch.Tensor,
        gt_mask: torch.Tensor,
    ) -> Assignment:
        """pred_scores [B, A, C] (after sigmoid), pred_boxes [B, A, 4], anchor_points [A, 2] (same units as
        the boxes), gt_labels [B, M] long, gt_boxes [B, M, 4], gt_mask [B, M] bool (padding rows False)."""
        batch, anchors, classes = pred_scores.shape
        gts = gt_boxes.shape[1]
        device = pred_scores.device
        if gts == 0:
            return Assignment(
                labels=torch.zeros(batch, anchors, dtype=torch.long, device=device),
                boxes=torch.zeros(batch, anchors, 4, device=device),
                scores=torch.zeros_like(pred_scores),
                foreground=torch.zeros(batch, anchors, dtype=torch.bool, device=device),
                gt_index=torch.zeros(batch, anchors, dtype=torch.long, device=device),
            )
        opts = self.options
        candidates = anchors_inside_boxes(anchor_points, gt_boxes, opts.eps) & gt_mask[..., None]  # [B, M, A]

        # Alignment metric t = s^alpha * u^beta on the candidates, 0 elsewhere.
        labels = gt_labels.long().clamp(0, classes - 1)
        class_scores = torch.gather(pred_scores.permute(0, 2, 1), 1, labels[..., None].expand(-1, -1, anchors))
        overlaps = bbox_ciou(gt_boxes[:, :, None, :], pred_boxes[:, None, :, :]).clamp(min=0)  # [B, M, A]
        overlaps = torch.where(candidates, overlaps, torch.zeros_like(overlaps))
        metric = class_scores.float().pow(opts.alpha) * overlaps.pow(opts.beta)
        metric = torch.where(candidates, metric, torch.zeros_like(metric))

        # Top-k anchors per box by the metric, kept only where they are candidates.
        k = min(opts.topk, anchors)
        top_index = metric.topk(k, dim=-1).indices  # [B, M, k]
        in_topk = torch.zeros_like(candidates).scatter_(-1, top_index, True)
        positive = in_topk & candidates  # [B, M, A]

        # An anchor claimed by several boxes keeps the one it overlaps most.
        claimed = positive.sum(dim=1)  # [B, A]
        if int(claimed.max()) > 1:
            best = overlaps.argmax(dim=1)  # [B, A]
            only_best = torch.zeros_like(positive).scatter_(1, best[:, None, :], True)
            positive = torch.where((claimed > 1)[:, None, :], only_best & positive, positive)
        foreground = positive.any(dim=1)  # [B, A]
        gt_index = positive.float().argmax(dim=1)  # [B, A]

        batch_index = torch.arange(batch, device=device)[:, None]
        target_labels = labels[batch_index, gt_index]  # [B, A]
        target_boxes = gt_boxes[batch_index, gt_index]  # [B, A, 4]
        one_hot = torch.nn.functional.one_hot(target_labels, classes).float() * foreground[..., None]

        # Normalized metric: t(a, g) * max u(., g) / max t(., g) over g's positives.
        metric = metric * positive
        best_metric = metric.amax(dim=-1, keepdim=True)
        best_overlap = (overlaps * positive).amax(dim=-1, keepdim=True)
        normalized = (metric * best_overlap / (best_metric + opts.eps)).amax(dim=1)  # [B, A]
        return Assignment(
            labels=target_labels,
            boxes=target_boxes,
            scores=one_hot * normalized[..., None],
            foreground=foreground,
            gt_index=gt_index,
        )
