import math

import pytest
import torch

from semchain_train.assigner import AssignerOptions, TaskAlignedAssigner, anchors_inside_boxes

GT = [0.0, 0.0, 4.0, 2.0]
QUARTER = [1.0, 0.5, 3.0, 1.5]  # concentric with GT, same aspect: CIoU = IoU = 0.25


def _one_image_case(topk: int):
    anchors = torch.tensor([[0.5, 0.5], [1.5, 0.5], [2.5, 0.5], [3.5, 0.5], [4.5, 0.5], [1.5, 1.5]])
    scores = torch.zeros(1, 6, 3)
    scores[0, :, 1] = torch.tensor([0.9, 0.4, 0.81, 0.1, 1.0, 0.64])
    boxes = torch.tensor([[QUARTER] + [GT] * 5])
    assigner = TaskAlignedAssigner(AssignerOptions(topk=topk), classes=3)
    return assigner(scores, boxes, anchors, torch.tensor([[1]]), torch.tensor([[GT]]), torch.tensor([[True]]))


def test_top_k_by_alignment_metric_and_normalized_scores() -> None:
    result = _one_image_case(topk=3)
    # Metrics s^0.5 u^6: a0 0.9^0.5 * 0.25^6, a1 0.632, a2 0.9, a3 0.316, a4 outside the box, a5 0.8.
    assert result.foreground[0].tolist() == [False, True, True, False, False, True]
    expected = torch.zeros(6)
    expected[[1, 2, 5]] = torch.tensor([math.sqrt(0.4) / 0.9, 1.0, 0.8 / 0.9])
    torch.testing.assert_close(result.scores[0, :, 1], expected)
    assert result.scores[0, :, [0, 2]].abs().sum() == 0
    assert result.labels[0, 2] == 1
    torch.testing.assert_close(result.boxes[0, 2], torch.tensor(GT))


def test_normalization_uses_the_best_overlap_of_the_box() -> None:
    result = _one_image_case(topk=10)  # every anchor inside: a0, a1, a2, a3, a5
    assert result.foreground[0].tolist() == [True, True, True, True, False, True]
    # Best overlap 1 (a1..), best metric 0.9 (a2): a0 gets 0.9^0.5 * 0.25^6 / 0.9.
    torch.testing.assert_close(result.scores[0, 0, 1], torch.tensor(math.sqrt(0.9) * 0.25**6 / 0.9))


def test_anchor_claimed_by_two_boxes_keeps_the_one_it_overlaps_most() -> None:
    anchors = torch.tensor([[2.5, 1.0], [0.5, 1.0], [4.5, 1.0]])
    box_a, box_b = [0.0, 0.0, 4.0, 2.0], [1.0, 0.0, 5.0, 2.0]
    pred = torch.tensor([[box_b, box_a, box_b]])
    scores = torch.full((1, 3, 3), 0.5)
    assigner = TaskAlignedAssigner(AssignerOptions(topk=10), classes=3)
    result = assigner(
        scores, pred, anchors, torch.tensor([[0, 2]]), torch.tensor([[box_a, box_b]]), torch.tensor([[True, True]])
    )
    assert result.foreground[0].tolist() == [True, True, True]
    assert result.gt_index[0].tolist() == [1, 0, 1] and result.labels[0].tolist() == [2, 0, 2]
    torch.testing.assert_close(result.scores[0, 0], torch.tensor([0.0, 0.0, 1.0]))


def test_padding_rows_and_empty_images_assign_nothing() -> None:
    anchors = torch.tensor([[0.5, 0.5], [1.5, 0.5]])
    scores = torch.full((2, 2, 2), 0.5)
    pred = torch.tensor([[GT, GT], [GT, GT]])
    gt_boxes = torch.tensor([[GT], [GT]])
    result = TaskAlignedAssigner(classes=2)(
        scores, pred, anchors, torch.tensor([[0], [0]]), gt_boxes, torch.tensor([[True], [False]])
    )
    assert result.foreground.tolist() == [[True, True], [False, False]]
    empty = TaskAlignedAssigner(classes=2)(
        scores, pred, anchors, torch.zeros(2, 0, dtype=torch.long), torch.zeros(2, 0, 4), torch.zeros(2, 0, dtype=torch.bool)
    )
    assert not empty.foreground.any() and empty.scores.sum() == 0


def test_centres_on_the_edge_are_not_inside() -> None:
    inside = anchors_inside_boxes(torch.tensor([[0.0, 1.0], [0.1, 1.0], [4.0, 1.0]]), torch.tensor([[GT]]))
    assert inside[0, 0].tolist() == [False, True, False]
