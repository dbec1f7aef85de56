"""Box geometry shared by the assigner, the loss and the evaluation.

Boxes are x1, y1, x2, y2. Anchors follow the C++ runtime (src/detection/yolo_head.cc): per stride
8, 16, 32, row by row, centres at ((i + 0.5) s, (j + 0.5) s) input pixels; the head predicts
left, top, right, bottom distances in strides as the softmax-expected bin of reg_max DFL logits.
"""

from __future__ import annotations

import math

import torch

EPS = 1e-7


def make_anchors(
    feature_sizes: list[tuple[int, int]], strides: tuple[int, ...], device: torch.device | str = "cpu"
) -> tuple[torch.Tensor, torch.Tensor]:
    """Anchor centres in grid units ([A, 2], (i + 0.5, j + 0.5)) and their strides ([A, 1]).

    feature_sizes: (height, width) of each output map, in the strides' order.
    """
    points, stride_column = [], []
    for (height, width), stride in zip(feature_sizes, strides):
        ys = torch.arange(height, device=device, dtype=torch.float32) + 0.5
        xs = torch.arange(width, device=device, dtype=torch.float32) + 0.5
        grid_y, grid_x = torch.meshgrid(ys, xs, indexing="ij")
        points.append(torch.stack((grid_x, grid_y), dim=-1).reshape(-1, 2))
        stride_column.append(torch.full((height * width, 1), float(stride), device=device))
    return torch.cat(points), torch.cat(stride_column)


def dfl_expectation(logits: torch.Tensor, reg_max: int = 16) -> torch.Tensor:
    """[..., 4 * reg_max] logits (l, t, r, b bins) -> [..., 4] expected bins under the softmax."""
    shape = logits.shape[:-1]
    probabilities = logits.reshape(*shape, 4, reg_max).softmax(dim=-1)
    bins = torch.arange(reg_max, device=logits.device, dtype=probabilities.dtype)
    return (probabilities * bins).sum(dim=-1)


def dist2bbox(distances: torch.Tensor, anchor_points: torch.Tensor) -> torch.Tensor:
    """ltrb distances around anchor points -> x1 y1 x2 y2 (same units as both inputs)."""
    left_top, right_bottom = distances[..., :2], distances[..., 2:]
    return torch.cat((anchor_points - left_top, anchor_points + right_bottom), dim=-1)


def bbox2dist(anchor_points: torch.Tensor, boxes: torch.Tensor, reg_max: int = 16) -> torch.Tensor:
    """x1 y1 x2 y2 -> ltrb distances from the anchor, clipped into the DFL's range [0, reg_max - 1)."""
    distances = torch.cat((anchor_points - boxes[..., :2], boxes[..., 2:] - anchor_points), dim=-1)
    return distances.clamp(0, reg_max - 1 - 0.01)


def box_iou(boxes_a: torch.Tensor, boxes_b: torch.Tensor) -> torch.Tensor:
    """Pairwise IoU [N, M] of [N, 4] and [M, 4] boxes (0 where either is empty)."""
    top_left = torch.maximum(boxes_a[:, None, :2], boxes_b[None, :, :2])
    bottom_right = torch.minimum(boxes_a[:, None, 2:], boxes_b[None, :, 2:])
    inter = (bottom_right - top_left).clamp(min=0).prod(dim=-1)
    area_a = (boxes_a[:, 2:] - boxes_a[:, :2]).clamp(min=0).prod(dim=-1)
    area_b = (boxes_b[:, 2:] - boxes_b[:, :2]).clamp(min=0).prod(dim=-1)
    union = area_a[:, None] + area_b[None, :] - inter
    return torch.where(union > 0, inter / union.clamp(min=1e-12), torch.zeros_like(union))


def bbox_ciou(box1: torch.Tensor, box2: torch.Tensor) -> torch.Tensor:
    """Complete IoU (Zheng et al., AAAI 2020) of matching boxes [..., 4] -> [...]:
    IoU - rho^2 / c^2 - alpha v, v = 4 / pi^2 (atan(w2 / h2) - atan(w1 / h1))^2,
    alpha = v / (1 - IoU + v) held constant in the gradient (as YOLOv5/v8 do)."""
    b1_x1, b1_y1, b1_x2, b1_y2 = box1.unbind(-1)
    b2_x1, b2_y1, b2_x2, b2_y2 = box2.unbind(-1)
    w1, h1 = b1_x2 - b1_x1, (b1_y2 - b1_y1).clamp(min=EPS)
    w2, h2 = b2_x2 - b2_x1, (b2_y2 - b2_y1).clamp(min=EPS)
    inter = (torch.minimum(b1_x2, b2_x2) - torch.maximum(b1_x1, b2_x1)).clamp(min=0) * (
        torch.minimum(b1_y2, b2_y2) - torch.maximum(b1_y1, b2_y1)
    ).clamp(min=0)
    union = w1 * h1 + w2 * h2 - inter + EPS
    iou = inter / union
    enclosing_w = torch.maximum(b1_x2, b2_x2) - torch.minimum(b1_x1, b2_x1)
    enclosing_h = torch.maximum(b1_y2, b2_y2) - torch.minimum(b1_y1, b2_y1)
    diagonal_sq = enclosing_w**2 + enclosing_h**2 + EPS
    centre_dist_sq = ((b2_x1 + b2_x2 - b1_x1 - b1_x2) ** 2 + (b2_y1 + b2_y2 - b1_y1 - b1_y2) ** 2) / 4
    v = (4 / math.pi**2) * (torch.atan(w2 / h2) - torch.atan(w1 / h1)) ** 2
    with torch.no_grad():
        alpha = v / (v - iou + (1 + EPS))
    return iou - (centre_dist_sq / diagonal_sq + v * alpha)


def flatten_outputs(outputs: list[torch.Tensor], reg_max: int = 16) -> tuple[torch.Tensor, torch.Tensor]:
    """Three raw maps [B, 4 reg_max + nc, h, w] -> DFL logits [B, A, 4 reg_max], class logits [B, A, nc]."""
    batch = outputs[0].shape[0]
    flat = torch.cat([o.reshape(batch, o.shape[1], -1) for o in outputs], dim=2).permute(0, 2, 1)
    return flat[..., : 4 * reg_max], flat[..., 4 * reg_max :]


def decode_outputs(
    outputs: list[torch.Tensor], strides: tuple[int, ...] = (8, 16, 32), reg_max: int = 16
) -> tuple[torch.Tensor, torch.Tensor]:
    """Raw head maps -> boxes [B, A, 4] (x1 y1 x2 y2 input pixels) and class scores [B, A, nc] (sigmoid)."""
    distribution, class_logits = flatten_outputs(outputs, reg_max)
    points, stride_column = make_anchors([tuple(o.shape[2:]) for o in outputs], strides, outputs[0].device)
    boxes = dist2bbox(dfl_expectation(distribution.float(), reg_max), points) * stride_column
    return boxes, class_logits.float().sigmoid()
