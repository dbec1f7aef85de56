import math

import torch

from semchain_train.boxes import bbox_ciou, box_iou, decode_outputs, dfl_expectation, make_anchors
from semchain_train.loss import DetectionLoss, batch_targets, distribution_focal_loss
from stand_in_detector import StandInConfig, StandInDetector


def test_ciou_of_a_hand_computed_pair() -> None:
    # [0,0,2,2] and [1,1,3,4]: intersection 1, union 4 + 6 - 1 = 9; enclosing box 3 x 4 (c^2 = 25);
    # centres (1, 1) and (2, 2.5) (rho^2 = 3.25); aspect term v = 4/pi^2 (atan(2/3) - atan(1))^2.
    iou = 1 / 9
    v = 4 / math.pi**2 * (math.atan(2 / 3) - math.atan(1.0)) ** 2
    alpha = v / (1 - iou + v)
    expected = iou - 3.25 / 25 - alpha * v
    got = bbox_ciou(torch.tensor([0.0, 0.0, 2.0, 2.0]), torch.tensor([1.0, 1.0, 3.0, 4.0]))
    assert abs(got.item() - expected) < 1e-6
    same = bbox_ciou(torch.tensor([1.0, 2.0, 5.0, 3.0]), torch.tensor([1.0, 2.0, 5.0, 3.0]))
    assert abs(same.item() - 1.0) < 1e-6


def test_dfl_is_minimal_at_the_two_bins_around_the_target() -> None:
    target = torch.tensor([[3.3, 0.0, 7.5, 14.2]])
    logits = torch.zeros(1, 4, 16, requires_grad=True)
    optimizer = torch.optim.SGD([logits], lr=5.0)
    for _ in range(300):
        optimizer.zero_grad()
        distribution_focal_loss(logits, target).sum().backward()
        optimizer.step()
    probabilities = logits.detach().softmax(-1)[0]
    torch.testing.assert_close(probabilities[0, 3:5], torch.tensor([0.7, 0.3]), atol=0.02, rtol=0)
    torch.testing.assert_close(probabilities[1, 0], torch.tensor(1.0), atol=0.02, rtol=0)
    torch.testing.assert_close(probabilities[3, 14:16], torch.tensor([0.8, 0.2]), atol=0.02, rtol=0)
    torch.testing.assert_close(dfl_expectation(logits.detach().reshape(1, 64)), target, atol=0.05, rtol=0)
    # At the optimum the loss is the entropy of the two-bin split.
    exact = torch.full((1, 4, 16), -30.0)
    exact[0, 0, 3], exact[0, 0, 4] = math.log(0.7), math.log(0.3)
    entropy = -(0.7 * math.log(0.7) + 0.3 * math.log(0.3))
    loss = distribution_focal_loss(exact[:, :1], target[:, :1])
    assert abs(loss.item() - entropy) < 1e-5


def test_decoding_puts_anchors_at_cell_centres_and_boxes_in_strides() -> None:
    points, strides = make_anchors([(2, 3), (1, 2)], (8, 16))
    assert points.tolist()[:4] == [[0.5, 0.5], [1.5, 0.5], [2.5, 0.5], [0.5, 1.5]]
    assert strides[:, 0].tolist() == [8.0] * 6 + [16.0] * 2
    # All logits equal -> expected bin 7.5 on each side: a 15-stride square around each centre.
    outputs = [torch.zeros(1, 66, 2, 2), torch.zeros(1, 66, 1, 1), torch.zeros(1, 66, 1, 1)]
    boxes, scores = decode_outputs(outputs, (8, 16, 32))
    torch.testing.assert_close(boxes[0, 1], torch.tensor([12 - 60.0, 4 - 60.0, 12 + 60.0, 4 + 60.0]))
    torch.testing.assert_close(boxes[0, 5], torch.tensor([16 - 240.0, 16 - 240.0, 16 + 240.0, 16 + 240.0]))
    assert scores.shape == (1, 6, 2) and torch.allclose(scores, torch.tensor(0.5))


def test_batch_targets_pads_per_image() -> None:
    targets = torch.tensor([[1, 2, 0, 0, 4, 4], [1, 0, 1, 1, 2, 2], [0, 1, 3, 3, 5, 5]], dtype=torch.float32)
    labels, boxes, mask = batch_targets(targets, 3)
    assert labels.tolist() == [[1, 0], [2, 0], [0, 0]]
    assert mask.tolist() == [[True, False], [True, True], [False, False]]
    assert boxes[1, 1].tolist() == [1, 1, 2, 2]


def test_images_without_objects_give_only_a_classification_loss() -> None:
    torch.manual_seed(0)
    model = StandInDetector(StandInConfig(classes=2))
    loss, parts = DetectionLoss(classes=2)(model(torch.rand(2, 3, 64, 64)), torch.zeros(0, 6))
    assert torch.isfinite(loss) and parts[0] == 0 and parts[2] == 0 and parts[1] > 0
    loss.backward()


def test_overfitting_one_image_lowers_the_loss_and_finds_the_boxes() -> None:
    torch.manual_seed(0)
    model = StandInDetector(StandInConfig(classes=2, width=16))
    image = torch.zeros(1, 3, 64, 64)
    image[0, 0, 8:40, 4:28] = 1.0
    image[0, 1, 30:60, 36:60] = 1.0
    targets = torch.tensor([[0, 0, 4, 8, 28, 40], [0, 1, 36, 30, 60, 60]], dtype=torch.float32)
    criterion = DetectionLoss(classes=2)
    optimizer = torch.optim.Adam(model.parameters(), lr=0.01)
    history = []
    for _ in range(60):
        optimizer.zero_grad()
        loss, parts = criterion(model(image), targets)
        loss.backward()
        optimizer.step()
        history.append(parts)
    first, last = history[0], history[-1]
    assert last.sum() < 0.5 * first.sum() and (last < first).all(), (first, last)
    model.eval()
    with torch.no_grad():
        boxes, scores = decode_outputs(model(image))
    for class_id in range(2):
        best = scores[0, :, class_id].argmax()
        assert scores[0, best, class_id] > 0.5
        assert box_iou(boxes[0, best : best + 1], targets[class_id : class_id + 1, 2:]).item() > 0.8
